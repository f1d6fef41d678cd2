//! The ablation's 2 × 2 of search and objective: the waypoint-graph search of 000 and the
//! thesis GA of 003 (Elite), each optimising the robot's swept footprint and 000's camera
//! coverage, so that a difference between the planners can be put down to the search or to
//! what it optimises. A table of the four cells per map and the findings that compare cells
//! differing in one factor only.

use crate::stats::{a12_magnitude, quartiles};
use std::fmt::Write as _;

/// The two searches, as the table names them.
const SEARCHES: [&str; 2] = ["waypoint graph (000)", "thesis GA, Elite (003)"];

/// The cell of the 2 × 2 a run belongs to, `(search, objective)`, from its swept values
/// (`value(column)`, `None` where the study has no such column or the key does not apply):
/// the waypoint planner with its `waypoint.objective`, and the thesis GA as 003 runs it (Elite,
/// straight moves, a random initial population) with its `thesis.objective` (the footprint
/// where it is not swept); `None` for every other run.
pub fn cell_of(value: &dyn Fn(&str) -> Option<String>) -> Option<(&'static str, &'static str)> {
    let given = |c: &str| value(c).filter(|v| !v.is_empty());
    let objective = |c: &str| match given(c).as_deref() {
        None | Some("footprint") => Some("footprint"),
        Some("camera") => Some("camera"),
        Some(_) => None,
    };
    match given("planner").as_deref() {
        Some("waypoint") => Some((SEARCHES[0], objective("waypoint.objective")?)),
        Some("thesis") => {
            let plain = given("thesis.selection").is_none_or(|s| s == "elite")
                && given("thesis.moves").is_none_or(|m| m == "straight")
                && given("thesis.seed_population").is_none_or(|p| p == "[]");
            plain.then_some(())?;
            Some((SEARCHES[1], objective("thesis.objective")?))
        }
        _ => None,
    }
}

/// All runs of a variant (by label), and its executable runs.
pub type RowsOf<'a> = &'a dyn Fn(&str) -> (Vec<usize>, Vec<usize>);

/// The Holm-corrected p and A₁₂ of a tested pair (first, second, metric), if tested.
pub type PairTest<'a> = &'a dyn Fn(&str, &str, &str) -> Option<(f64, f64)>;

/// What the 2 × 2 reads of one map's runs.
pub struct MapRuns<'a> {
    /// The map's short name.
    pub name: &'a str,
    /// The variants present on the map with their cell of the 2 × 2 ([`cell_of`]).
    pub cells: &'a [(&'a String, Option<(&'static str, &'static str)>)],
    /// All runs of a variant, and its executable runs.
    pub rows: RowsOf<'a>,
    /// A run's metric.
    pub num: &'a dyn Fn(usize, &str) -> f64,
    /// The Holm-corrected p and A₁₂ = P(first > second) of a tested pair on a metric, over
    /// executable plans.
    pub pair: PairTest<'a>,
}

impl MapRuns<'_> {
    /// The label of a cell on this map, if its runs are present.
    fn label(&self, search: &str, objective: &str) -> Option<&str> {
        self.cells.iter().find(|(_, c)| *c == Some((search, objective))).map(|(l, _)| l.as_str())
    }

    /// Whether all four cells are present.
    pub fn complete(&self) -> bool {
        SEARCHES.iter().all(|s| ["footprint", "camera"].iter().all(|o| self.label(s, o).is_some()))
    }

    /// One table row per search: each cell's medians over executable plans (footprint coverage
    /// of the reachable cells, camera wall coverage) with the executable share, and over all
    /// plans.
    pub fn table_rows(&self, md: &mut String) {
        for search in SEARCHES {
            let cells: Vec<String> = ["footprint", "camera"]
                .iter()
                .map(|objective| {
                    let Some(label) = self.label(search, objective) else { return "–".to_string() };
                    let (all, exec) = (self.rows)(label);
                    let med = |rows: &[usize], c: &str| {
                        let v: Vec<f64> = rows.iter().map(|&r| (self.num)(r, c)).collect();
                        if v.is_empty() { "–".to_string() } else { format!("{:.3}", quartiles(&v).1) }
                    };
                    format!(
                        "{} / {} ({}/{} executable; all plans {} / {})",
                        med(&exec, "cov_final_reach"),
                        med(&exec, "cam_walls_free"),
                        exec.len(),
                        all.len(),
                        med(&all, "cov_final_reach"),
                        med(&all, "cam_walls_free")
                    )
                })
                .collect();
            let _ = writeln!(md, "| {} | {search} | {} |", self.name, cells.join(" | "));
        }
    }

    /// Sentences comparing cells that differ in one factor, from the pairwise tests.
    pub fn findings(&self) -> Vec<String> {
        let name = self.name;
        let effect = |(p, a12): (f64, f64)| format!("A₁₂ = {a12:.2} ({}, p = {p:.1e})", a12_magnitude(a12));
        let mut out = Vec::new();
        let cell = |s: &str, o: &str| self.label(s, o);
        let (wf, wc) = (cell(SEARCHES[0], "footprint"), cell(SEARCHES[0], "camera"));
        let (tf, tc) = (cell(SEARCHES[1], "footprint"), cell(SEARCHES[1], "camera"));
        // One search, two objectives: A₁₂ = P(footprint-optimised > camera-optimised).
        for (search, f, c) in [("the waypoint search", wf, wc), ("the thesis GA (Elite)", tf, tc)] {
            let (Some(f), Some(c)) = (f, c) else { continue };
            if let Some(cov) = (self.pair)(f, c, "cov_final_reach") {
                let cam = (self.pair)(f, c, "cam_walls_free");
                out.push(format!(
                    "On {name}, {search} optimising the footprint against the same search optimising the camera (A₁₂ = P(footprint-optimised plan higher)): footprint coverage {}{}.",
                    effect(cov),
                    cam.map_or(String::new(), |x| format!(", camera wall coverage {}", effect(x)))
                ));
            } else {
                let n = |l: &str| (self.rows)(l).1.len();
                out.push(format!(
                    "On {name}, {search} optimising the footprint and the same search optimising the camera cannot be compared on executable plans: {} and {} of their plans are executable (at least 2 each are needed).",
                    n(f),
                    n(c)
                ));
            }
        }
        // One objective, two searches: A₁₂ = P(waypoint search > thesis GA) on the objective.
        for (objective, metric, what, w, t) in [
            ("footprint", "cov_final_reach", "footprint coverage", wf, tf),
            ("camera", "cam_walls_free", "camera wall coverage", wc, tc),
        ] {
            let (Some(w), Some(t)) = (w, t) else { continue };
            if let Some(x) = (self.pair)(w, t, metric) {
                let t_final = |l: &str| {
                    let v: Vec<f64> = (self.rows)(l).1.iter().map(|&r| (self.num)(r, "t_final")).collect();
                    quartiles(&v).1
                };
                out.push(format!(
                    "On {name}, with the {objective} objective for both, the waypoint-graph search against the thesis GA (Elite) (A₁₂ = P(waypoint-graph plan higher)): {} for {what}; t_final medians {:.3} and {:.3}.",
                    effect(x),
                    t_final(w),
                    t_final(t)
                ));
            } else {
                let n = |l: &str| (self.rows)(l).1.len();
                out.push(format!(
                    "On {name}, with the {objective} objective for both, the two searches cannot be compared on executable plans: {} of the waypoint search's and {} of the thesis GA's plans are executable (at least 2 each are needed).",
                    n(w),
                    n(t)
                ));
            }
        }
        out
    }
}

/// The 2 × 2 section's heading, note and table head.
pub fn table_head(md: &mut String) {
    let _ = writeln!(md, "## Search versus objective\n");
    let _ = writeln!(
        md,
        "The waypoint-graph search of 000 and the thesis GA of 003 (Elite), each optimising the robot's swept footprint and 000's camera coverage (eq. 2, `waypoint.alpha_cov`). Each cell: median footprint coverage of the reachable cells / median camera wall coverage, over the executable plans, then over all plans.\n"
    );
    let _ = writeln!(md, "| map | search | footprint objective | camera objective |\n|---|---|---|---|");
}
