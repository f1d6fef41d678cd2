//! The units a pooled comparison tests: what varies independently across the strata.
//!
//! Within a stratum the seeds are the units: each seed is a run of its own, and a control that
//! reads no seed is one fixed value the seeds are compared with. Pooled over the strata, the
//! question is whether the value helps across the settings, so one stratum is one observation;
//! its pairs measure only the spread of its own seeds (counting them as units would count a
//! control's one run ten times). Strata that differ only in the problem posed on a floor plan
//! — the robot, the start station, the map's noise (a generated plan's clean and noisy twins,
//! [`crate::map::generate::clean_twin`]) — stand on one floor plan and are not independent
//! either. Nor are strata of one floor plan that differ in the planner's settings (a search
//! seeded with a control's tours can return the control's plan on that floor plan): wherever
//! runs on one floor plan are pooled with runs on others, whatever differs among them, the
//! unit is the floor plan, and its effect the median of every pair on it.

use std::collections::BTreeMap;

/// Sections of the parameters that pose the problem on a floor plan rather than set the planner.
const PROBLEM_SECTIONS: [&str; 3] = ["map.", "robot.", "stations."];

/// What one unit of a pooled comparison is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum UnitKind {
    /// A stratum: one combination of the other parameters.
    Stratum,
    /// A floor plan: every stratum on it together (over several floor plans, whatever else
    /// differs; on one, the strata that differ only in the problem posed on it).
    FloorPlan,
}

impl UnitKind {
    /// The unit's name in a table, singular and plural.
    pub(super) fn names(self) -> (&'static str, &'static str) {
        match self {
            UnitKind::Stratum => ("stratum", "strata"),
            UnitKind::FloorPlan => ("floor plan", "floor plans"),
        }
    }
}

/// The units of a pooled comparison: which unit each stratum belongs to, and why.
#[derive(Clone, Debug)]
pub(super) struct Units {
    pub kind: UnitKind,
    /// Stratum label → unit label.
    pub of: BTreeMap<String, String>,
    /// The one sentence a comparison says about its units.
    pub reason: String,
}

/// The units of strata `strata` (label → `(column, value)` of each stratum parameter); `once_run`
/// says whether a compared side ran once per stratum.
pub(super) fn choose(strata: &BTreeMap<String, Vec<(String, String)>>, once_run: bool) -> Units {
    let is_problem = |column: &str| PROBLEM_SECTIONS.iter().any(|s| column.starts_with(s));
    let unit_of = |params: &[(String, String)]| -> String {
        let mut parts: Vec<String> = Vec::new();
        for (column, value) in params {
            if column == "map.source" {
                parts.push(format!("{column}={}", crate::map::generate::clean_twin(value)));
            } else if !is_problem(column) {
                parts.push(format!("{column}={value}"));
            }
        }
        parts.join(", ")
    };
    if let Some(units) = by_floor_plan(strata) {
        return units;
    }
    let of: BTreeMap<String, String> = strata.iter().map(|(s, p)| (s.clone(), unit_of(p))).collect();
    let units = of.values().collect::<std::collections::BTreeSet<_>>().len();
    if units < strata.len() {
        let shared: Vec<&str> = {
            let mut c: Vec<&str> = strata
                .values()
                .flatten()
                .map(|(c, _)| c.as_str())
                .filter(|c| is_problem(c) && *c != "map.source")
                .collect();
            c.sort_unstable();
            c.dedup();
            c
        };
        let twins = strata
            .values()
            .flatten()
            .any(|(c, v)| c == "map.source" && crate::map::generate::clean_twin(v) != v.as_str());
        let mut what: Vec<String> = shared.iter().map(|c| format!("`{c}`")).collect();
        if twins {
            what.push("the map's noise (a generated plan's clean and noisy twins)".into());
        }
        return Units {
            kind: UnitKind::FloorPlan,
            of,
            reason: format!(
                "The pooled unit is the floor plan under one setting of the planner ({units} units from {} strata): \
                 strata that differ only in {} pose one floor plan and are not independent; a unit's effect is \
                 the median of its pairs' effects.",
                strata.len(),
                what.join(" or ")
            ),
        };
    }
    let why = if once_run {
        "a side ran once per stratum, so its one run pairs with every seed of the other and a stratum's \
         pairs share that run"
    } else {
        "the pooled question is whether the value helps across the settings, and a stratum's seeds measure \
         only the spread within it"
    };
    Units {
        kind: UnitKind::Stratum,
        of: strata.keys().map(|s| (s.clone(), s.clone())).collect(),
        reason: format!(
            "The pooled unit is the stratum ({} units), because {why}; a stratum's effect is the median of its \
             pairs' effects.",
            strata.len()
        ),
    }
}

/// Over several floor plans, the floor plans as units, whatever else tells the strata on one
/// apart; `None` where the strata stand on one floor plan (or do not name their map).
fn by_floor_plan(strata: &BTreeMap<String, Vec<(String, String)>>) -> Option<Units> {
    let plan_of = |params: &[(String, String)]| {
        params.iter().find(|(c, _)| c == "map.source").map(|(_, v)| crate::map::generate::clean_twin(v).to_string())
    };
    let of: BTreeMap<String, String> = strata
        .iter()
        .map(|(s, p)| plan_of(p).map(|plan| (s.clone(), format!("map.source={plan}"))))
        .collect::<Option<_>>()?;
    let plans = of.values().collect::<std::collections::BTreeSet<_>>().len();
    if plans < 2 || plans == strata.len() {
        return None;
    }
    let mut differ: Vec<String> = strata
        .values()
        .flatten()
        .filter(|(c, _)| c != "map.source")
        .map(|(c, _)| format!("`{c}`"))
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    if strata.values().flatten().any(|(c, v)| c == "map.source" && crate::map::generate::clean_twin(v) != v.as_str()) {
        differ.push("the map's noise (a generated plan's clean and noisy twins)".into());
    }
    Some(Units {
        kind: UnitKind::FloorPlan,
        of,
        reason: format!(
            "The pooled unit is the floor plan ({plans} units from {} strata): the strata on one floor plan, \
             whatever tells them apart ({}), are not independent (they share the plan's rooms, clutter and \
             start, and a search seeded with another plan can return it there), so each floor plan counts \
             once; a unit's effect is the median of every pair on it.",
            strata.len(),
            differ.join(", ")
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    type Strata = BTreeMap<String, Vec<(String, String)>>;

    fn strata(rows: &[&[(&str, &str)]]) -> Strata {
        rows.iter()
            .map(|r| {
                let params: Vec<(String, String)> = r.iter().map(|(c, v)| (c.to_string(), v.to_string())).collect();
                let label = params.iter().map(|(c, v)| format!("{c}={v}")).collect::<Vec<_>>().join(", ");
                (label, params)
            })
            .collect()
    }

    /// Each design and the units it gets: (strata, a side ran once, kind, units).
    #[test]
    fn the_unit_follows_the_design() {
        let maps_and_robots = strata(&[
            &[("map.source", "a.yaml"), ("robot.rot_speed", "0")],
            &[("map.source", "a.yaml"), ("robot.rot_speed", "0.5")],
            &[("map.source", "b.yaml"), ("robot.rot_speed", "0")],
            &[("map.source", "b.yaml"), ("robot.rot_speed", "0.5")],
        ]);
        let twins = strata(&[
            &[("map.source", "gen/house-1.yaml")],
            &[("map.source", "gen/house-1-noisy.yaml")],
            &[("map.source", "office")],
        ]);
        let settings = strata(&[
            &[("map.source", "a"), ("thesis.moves", "straight")],
            &[("map.source", "a"), ("thesis.moves", "routed")],
            &[("map.source", "b"), ("thesis.moves", "straight")],
        ]);
        let one_map = strata(&[&[("thesis.c_len", "0.1")], &[("thesis.c_len", "0.2")]]);
        let one_plan_robots = strata(&[
            &[("map.source", "a.yaml"), ("robot.rot_speed", "0"), ("thesis.moves", "straight")],
            &[("map.source", "a.yaml"), ("robot.rot_speed", "0.5"), ("thesis.moves", "straight")],
            &[("map.source", "a.yaml"), ("robot.rot_speed", "0"), ("thesis.moves", "routed")],
        ]);
        let table: [(&Strata, bool, UnitKind, usize); 7] = [
            (&maps_and_robots, true, UnitKind::FloorPlan, 2),
            (&maps_and_robots, false, UnitKind::FloorPlan, 2),
            (&twins, true, UnitKind::FloorPlan, 2),
            (&settings, false, UnitKind::FloorPlan, 2),
            (&settings, true, UnitKind::FloorPlan, 2),
            (&one_map, false, UnitKind::Stratum, 2),
            (&one_plan_robots, true, UnitKind::FloorPlan, 2),
        ];
        for (i, (design, once, kind, count)) in table.into_iter().enumerate() {
            let u = choose(design, once);
            let units = u.of.values().collect::<std::collections::BTreeSet<_>>().len();
            assert_eq!((u.kind, units), (kind, count), "design {i}: {}", u.reason);
        }
        let u = choose(&maps_and_robots, true);
        assert!(u.reason.contains("(`robot.rot_speed`)"), "{}", u.reason);
        assert_eq!(u.of["map.source=a.yaml, robot.rot_speed=0.5"], "map.source=a.yaml");
        let u = choose(&twins, true);
        assert!(u.reason.contains("clean and noisy twins"), "{}", u.reason);
        assert_eq!(u.of["map.source=gen/house-1-noisy.yaml"], "map.source=gen/house-1.yaml");
        let u = choose(&settings, true);
        assert_eq!(u.of["map.source=a, thesis.moves=routed"], "map.source=a", "a setting does not split a floor plan");
        assert!(u.reason.contains("`thesis.moves`"), "{}", u.reason);
        let u = choose(&one_plan_robots, true);
        assert!(u.reason.contains("differ only in `robot.rot_speed`"), "{}", u.reason);
        assert!(choose(&one_map, true).reason.contains("a side ran once per stratum"));
        assert!(choose(&one_map, false).reason.contains("across the settings"));
    }
}
