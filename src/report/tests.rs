use super::{
    FRONT_MIN_COVERAGE, cell_matches, cmp_group_values, coverage_front, median, param_columns, read_history_diversity,
};
use crate::study::records::{RunsTable, metric_columns};
use std::cmp::Ordering::{Equal, Greater, Less};

#[test]
fn medians_of_odd_and_even_counts_by_hand() {
    let cases: &[(&[f64], f64)] =
        &[(&[3.0], 3.0), (&[5.0, 1.0, 3.0], 3.0), (&[4.0, 1.0, 3.0, 2.0], 2.5), (&[7.0, -1.0], 3.0)];
    for (values, want) in cases {
        assert_eq!(median(&mut values.to_vec()), *want, "{values:?}");
    }
}

#[test]
fn where_values_match_numbers_as_numbers_and_text_as_text() {
    let cases = [
        ("0.10", "0.1", true),
        ("1e-2", "0.01", true),
        ("2", "3", false),
        ("elite", "elite", true),
        ("elite", "rrws", false),
        ("1", "one", false),
    ];
    for (cell, want, matches) in cases {
        assert_eq!(cell_matches(cell, want), matches, "{cell} vs {want}");
    }
}

#[test]
fn swept_columns_lie_between_the_seed_and_the_metrics() {
    let metrics = metric_columns();
    let table = |params: &[&str]| RunsTable {
        header: ["run", "seed"].iter().chain(params).map(|s| s.to_string()).chain(metrics.iter().cloned()).collect(),
        rows: Vec::new(),
    };
    assert_eq!(param_columns(&table(&["thesis.c_len", "planner"])), vec!["thesis.c_len", "planner"]);
    assert!(param_columns(&table(&[])).is_empty());
    let mut short = table(&[]);
    short.header.pop();
    assert!(param_columns(&short).is_empty(), "a table without the whole metric block has no swept columns");
    assert!(param_columns(&RunsTable { header: vec!["run".into()], rows: Vec::new() }).is_empty());
}

#[test]
fn history_diversity_is_read_by_column_name() {
    let dir = std::env::temp_dir().join(format!("covga-report-history-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("history.csv");
    std::fs::write(&path, "evaluations,diversity,iteration\n10,4.5,0\n20,2.25,1\n").unwrap();
    assert_eq!(read_history_diversity(&path), Some(vec![(0, 4.5), (1, 2.25)]));
    std::fs::write(&path, "iteration,diversity\n0,\n").unwrap();
    assert_eq!(read_history_diversity(&path), None, "an unmeasured diversity is not a value");
    std::fs::write(&path, "iteration,diversity\n0,4\n1,\n2,3\n").unwrap();
    assert_eq!(read_history_diversity(&path), Some(vec![(0, 4.0), (2, 3.0)]), "rows between measurements");
    std::fs::write(&path, "iteration,diversity\n0,4\n1,x\n").unwrap();
    assert_eq!(read_history_diversity(&path), None, "a malformed value is not passed over");
    assert_eq!(read_history_diversity(&dir.join("missing.csv")), None);
    std::fs::remove_dir_all(&dir).unwrap();
}

fn values(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

#[test]
fn group_values_order_numbers_by_magnitude_and_text_as_text() {
    let cases: &[(&[&str], &[&str], std::cmp::Ordering)] = &[
        (&["2"], &["10"], Less),
        (&["10"], &["3"], Greater),
        (&["0.01"], &["0.1"], Less),
        (&["-1"], &["0"], Less),
        (&["1e3"], &["50"], Greater),
        (&["rrws"], &["elite"], Greater),
        (&["5"], &["elite"], Less),
        (&["f2"], &["3"], Greater),
        (&["7", "f1"], &["7", "f2"], Less),
        (&["10", "f1"], &["9", "f2"], Greater),
        (&["3"], &["3"], Equal),
        // Equal numbers written differently stay distinct groups, in text order.
        (&["1.0"], &["1"], Greater),
    ];
    for (a, b, want) in cases {
        assert_eq!(cmp_group_values(&values(a), &values(b)), *want, "{a:?} vs {b:?}");
    }
    let mut sizes = vec![values(&["10"]), values(&["2"]), values(&["5"]), values(&["3"])];
    sizes.sort_by(|a, b| cmp_group_values(a, b));
    assert_eq!(sizes, vec![values(&["2"]), values(&["3"]), values(&["5"]), values(&["10"])]);
}

#[test]
fn a_plan_that_has_not_begun_to_cover_is_off_the_front() {
    // (t_final, coverage): a one-move plan at t_final 1 dominates nothing the front needs.
    let points = [(1.0, 0.003), (0.9, 0.5), (0.8, 0.7), (0.7, 0.6), (1.0, 0.0)];
    assert_eq!(coverage_front(&points), vec![1, 2]);
    let at_limit = [(1.0, FRONT_MIN_COVERAGE), (0.5, 0.9)];
    assert_eq!(coverage_front(&at_limit), vec![0, 1], "1 % is on the front");
}
