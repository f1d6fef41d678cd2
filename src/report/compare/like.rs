//! Like with like: what a comparison states instead of testing. Values whose runs return their
//! plans by different rules (the knee of a front against the fittest member) are named with
//! their rules, so that a reader knows the comparison is of the plans each returns; a value
//! whose plans are executable by construction is said to be, and its executability not tested
//! (a test of a property that cannot fail shows nothing about the data).

use crate::thesis::config::SelectionName;
use crate::thesis::scenario::Moves;

/// The value a label stands for: `ga (memetic=true)` is `ga` with a nested setting.
fn raw(label: &str) -> &str {
    label.split_once(" (").map_or(label, |(v, _)| v)
}

/// How runs with `key = value` choose the plan they return, where the key decides it.
pub(super) fn returned_plan(key: &str, value: &str) -> Option<&'static str> {
    match key {
        "thesis.selection" => SelectionName::parse(raw(value)).map(SelectionName::returned_plan),
        _ => None,
    }
}

/// Why every plan of runs with `key = value` is executable, where that holds by construction.
pub(super) fn executable_by_construction(key: &str, value: &str) -> Option<&'static str> {
    match key {
        "thesis.moves" => {
            toml::Value::String(raw(value).to_string()).try_into::<Moves>().ok()?.executable_by_construction()
        }
        _ => None,
    }
}

/// The sentence naming the return rules of `values` against `baseline`'s, where they differ.
pub(super) fn return_rules(key: &str, baseline: &str, values: &[String]) -> Option<String> {
    let base = returned_plan(key, baseline)?;
    let differing: Vec<String> = values
        .iter()
        .filter_map(|v| returned_plan(key, v).filter(|r| *r != base).map(|r| format!("`{v}` returns {r}")))
        .collect();
    if differing.is_empty() {
        return None;
    }
    Some(format!(
        "The values return their plans by different rules: {}, `{baseline}` {base}; each comparison is of the \
         plans the runs return, not of the best plan each run found.",
        differing.join(", ")
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_and_constructions_are_read_from_the_planners_own_types() {
        let table: [(&str, &str, Option<&str>, bool); 6] = [
            ("thesis.selection", "nsga2", Some("the knee of its final first front"), false),
            ("thesis.selection", "elite", Some("its fittest member (highest `f`)"), false),
            ("thesis.selection", "tournament", Some("its fittest member (highest `f`)"), false),
            ("thesis.moves", "routed", None, true),
            ("thesis.moves", "straight", None, false),
            ("cell_order.solver", "ga (cell_order.memetic=true)", None, false),
        ];
        for (key, value, rule, built) in table {
            assert_eq!(returned_plan(key, value), rule, "{key}={value}");
            assert_eq!(executable_by_construction(key, value).is_some(), built, "{key}={value}");
        }
        let text = return_rules("thesis.selection", "elite", &["nsga2".into()]).unwrap();
        assert!(
            text.contains("`nsga2` returns the knee of its final first front, `elite` its fittest member"),
            "{text}"
        );
        assert_eq!(return_rules("thesis.selection", "elite", &["tournament".into()]), None);
        assert_eq!(return_rules("thesis.moves", "straight", &["routed".into()]), None);
    }
}
