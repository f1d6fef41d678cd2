//! The measures' sources, group summaries and folder reads.

use super::*;

fn table() -> RunsTable {
    RunsTable::parse("run_id,wall_s,executable\na,1.5,true\nb,2.5,false\n").unwrap()
}

#[test]
fn keys_are_read_from_runs_csv_history_or_summary_in_that_order() {
    let t = table();
    let cases = [
        ("wall_s", Ok(Source::Column(1))),
        ("history.best_walls@50", Ok(Source::History { column: "best_walls".into(), iteration: 50 })),
        ("objectives.wall_coverage", Ok(Source::Summary(vec!["objectives".into(), "wall_coverage".into()]))),
    ];
    for (key, want) in cases {
        assert_eq!(source(&t, key), want, "{key}");
    }
    for bad in ["history.best_walls", "history.best_walls@-1", "history.@5", "objectives..x"] {
        assert!(source(&t, bad).is_err(), "{bad} must be refused");
    }
}

#[test]
fn groups_summarise_numbers_as_median_and_range_and_yes_no_as_counts() {
    let cases: [(&[Value], &str); 11] = [
        (&[Value::Num(1.0), Value::Num(3.0), Value::Num(2.0)], "2 [1, 3]"),
        (&[Value::Num(0.877), Value::Num(0.9634), Value::Num(0.7731)], "0.8770 [0.7731, 0.9634]"),
        (&[Value::Num(382.0), Value::Num(180.0)], "281 [180, 382]"),
        (&[Value::Num(382.0), Value::Num(179.0)], "280.5 [179, 382]"),
        (&[Value::Bool(true), Value::Bool(false), Value::Bool(true)], "2/3"),
        (&[Value::Num(0.0055)], "0.005500 [0.005500, 0.005500]"),
        (&[Value::Num(1.0), Value::Null, Value::Num(3.0)], "2 [1, 3]; 1 null"),
        (&[Value::Null, Value::Null], "no value (2 null)"),
        (&[Value::Bool(true), Value::Null], "1/1; 1 null"),
        (&[Value::Num(1.0), Value::Missing, Value::Num(3.0), Value::Null], "2 [1, 3]; 1 null; 1 missing"),
        (&[Value::Missing, Value::Null], "no value (1 null, 1 missing)"),
    ];
    for (values, want) in cases {
        assert_eq!(summarise(values), want);
    }
}

#[test]
fn folder_values_are_read_and_a_missing_one_is_named() {
    let dir = std::env::temp_dir().join(format!("covga-measures-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("summary.json"),
        r#"{"waypoints": 382, "connected": true, "objectives": {"wall_coverage": 0.9}}"#,
    )
    .unwrap();
    std::fs::write(dir.join("history.csv"), "iteration,best_walls\n0,0.5\n50,0.75\n").unwrap();
    let t = table();
    let keys: Vec<(String, Source)> = ["waypoints", "connected", "objectives.wall_coverage", "history.best_walls@50"]
        .iter()
        .map(|k| (k.to_string(), source(&t, k).unwrap()))
        .collect();
    let got = read_folder(&dir, &keys).unwrap();
    assert_eq!(got["waypoints"], Value::Num(382.0));
    assert_eq!(got["connected"], Value::Bool(true));
    assert_eq!(got["objectives.wall_coverage"], Value::Num(0.9));
    assert_eq!(got["history.best_walls@50"], Value::Num(0.75));
    // A summary figure the run does not record is counted apart, not an error.
    let k = [("objectives.open_coverage".to_string(), source(&t, "objectives.open_coverage").unwrap())];
    assert_eq!(read_folder(&dir, &k).unwrap()["objectives.open_coverage"], Value::Missing);
    for missing in ["history.best_walls@100", "history.mean_walls@0"] {
        let k = [(missing.to_string(), source(&t, missing).unwrap())];
        let e = read_folder(&dir, &k).unwrap_err().to_string();
        assert!(e.contains("summary.json") || e.contains("history.csv"), "{missing}: {e}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
