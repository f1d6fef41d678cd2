//! The settings the book recommends for the fastest executable plan to a coverage goal on a
//! real floor plan (the first row of the planner table of "Plan your own floor plan"): one
//! list, which `covga init` writes, the shipped floor-plan examples use and the book's table of
//! recommended settings shows. `tests/it/floor_plan_recommendation.rs` keeps the four equal.

/// One recommended setting: a dotted key, its value as TOML, and why (the comment `covga init`
/// writes beside it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Recommended {
    /// The dotted key (`cell_order.solver`).
    pub key: &'static str,
    /// Its value, as TOML text (`"ils"`, `true`, `0.9`).
    pub value: &'static str,
    /// Why, in a few words.
    pub why: &'static str,
}

/// The recommended settings for a real floor plan, in the order a file writes them.
pub const FLOOR_PLAN: [Recommended; 6] = [
    Recommended {
        key: "planner",
        value: "\"cell_order\"",
        why: "lanes per cell of the map, the cells' order searched",
    },
    Recommended {
        key: "cell_order.solver",
        value: "\"ils\"",
        why: "the iterated local search over the cells' order, lane direction and entry",
    },
    Recommended {
        key: "cell_order.seed_directions",
        value: "true",
        why: "seeded with the no-search control's tours, one per lane direction",
    },
    Recommended {
        key: "cell_order.classical_finalists",
        value: "true",
        why: "the classical control's plans among the finalists: never slower than it",
    },
    Recommended {
        key: "cell_order.completion",
        value: "\"quota_search\"",
        why: "what the lanes leave: wall pieces chosen, ordered and turned by search",
    },
    Recommended {
        key: "cell_order.coverage_goal",
        value: "0.9",
        why: "the goal: 90 % of the reachable cells, as soon as possible",
    },
];

/// Whether the experiment table `table` (a parsed file) sets every recommended key to its
/// value; the keys it does not, each with what it sets instead (`None`: nothing).
pub fn departures(table: &toml::Table) -> Vec<(&'static str, Option<String>)> {
    FLOOR_PLAN
        .iter()
        .filter_map(|r| {
            let (head, last) = r.key.rsplit_once('.').unwrap_or(("", r.key));
            let section = if head.is_empty() { Some(table) } else { table.get(head).and_then(toml::Value::as_table) };
            let set = section.and_then(|s| s.get(last));
            let wanted: toml::Value = toml::from_str::<toml::Table>(&format!("v = {}", r.value))
                .expect("a recommended value is TOML")
                .remove("v")
                .expect("the value");
            (set != Some(&wanted)).then(|| (r.key, set.map(toml::Value::to_string)))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_with_every_recommended_key_departs_from_none() {
        let file = "planner = \"cell_order\"\n[cell_order]\nsolver = \"ils\"\nseed_directions = true\n\
                    classical_finalists = true\ncompletion = \"quota_search\"\ncoverage_goal = 0.9\n";
        assert_eq!(departures(&file.parse().unwrap()), vec![]);
        let quota = file.replace("\"quota_search\"", "\"quota\"").replace("seed_directions = true\n", "");
        assert_eq!(
            departures(&quota.parse().unwrap()),
            vec![("cell_order.seed_directions", None), ("cell_order.completion", Some("\"quota\"".to_string()))]
        );
    }
}
