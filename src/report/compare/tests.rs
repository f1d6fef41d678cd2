//! Unit tests of the comparison: designs, pairs, statistics and the files' text.

use super::*;
use crate::study::records::metric_columns;

/// A runs table of `a` (a, b) × `map` (m1, m2, with `budget` following it) × 6 seeds; `b`
/// covers `shift` more and takes 20 s longer; one `b` plan on m2 is not executable.
fn table(shift: f64) -> RunsTable {
    let metrics = metric_columns();
    let mut text = format!("run_id,config_id,replicate,seed,a,map,budget,{}\n", metrics.join(","));
    for (ai, a) in ["a", "b"].iter().enumerate() {
        for (mi, map) in ["m1", "m2"].iter().enumerate() {
            for s in 0..6 {
                let cov = 0.5 + 0.01 * s as f64 + if ai == 1 { shift } else { 0.0 };
                let time = 100.0 + s as f64 * 3.0 + if ai == 1 { 20.0 } else { 0.0 };
                let exec = !(ai == 1 && mi == 1 && s == 0);
                let fields: Vec<String> = metrics
                    .iter()
                    .map(|m| match m.as_str() {
                        "planner" => "thesis".into(),
                        "executable" => exec.to_string(),
                        "cov_final_reach" => cov.to_string(),
                        "time_s" => time.to_string(),
                        _ => "0".into(),
                    })
                    .collect();
                let budget = 1000 * (mi + 1);
                let _ =
                    writeln!(text, "r{ai}{mi}{s},c{ai}{mi},{s},{},{a},{map},{budget},{}", 100 + s, fields.join(","));
            }
        }
    }
    RunsTable::parse(&text).unwrap()
}

/// The metric fields of an executable cell-order run that takes `time` and covers 0.9.
fn executable_cell_order_run(time: f64) -> String {
    let fields: Vec<String> = metric_columns()
        .iter()
        .map(|m| match m.as_str() {
            "planner" => "cell_order".into(),
            "executable" => "true".into(),
            "cov_final_reach" => "0.9".into(),
            "time_s" => time.to_string(),
            _ => "0".into(),
        })
        .collect();
    fields.join(",")
}

/// A control run once (it reads no seed) against a GA over 6 seeds, with and without a
/// step (`memetic`) that is set under `solver = "ga"` only.
fn control_table() -> RunsTable {
    let metrics = metric_columns();
    let mut text = format!("run_id,config_id,replicate,seed,solver,memetic,{}\n", metrics.join(","));
    let mut line = |id: String, rep: usize, solver: &str, memetic: &str, time: f64| {
        let fields = executable_cell_order_run(time);
        let _ = writeln!(text, "{id},c{solver}{memetic},{rep},{},{solver},{memetic},{fields}", 100 + rep);
    };
    line("n".into(), 0, "nearest", "", 100.0);
    for s in 0..6 {
        line(format!("t{s}"), s, "ga", "true", 90.0 - s as f64);
        line(format!("f{s}"), s, "ga", "false", 110.0 + s as f64);
    }
    RunsTable::parse(&text).unwrap()
}

/// Every search variant against a baseline search that is always seeded: the GA alone and the
/// seeded GA both meet the seeded local search, seed by seed.
#[test]
fn every_search_variant_meets_a_baseline_whose_setting_is_fixed() {
    let metrics = metric_columns();
    let mut text = format!("run_id,config_id,replicate,seed,solver,seeded,{}\n", metrics.join(","));
    for s in 0..6 {
        for (solver, seeded, time) in [("ils", "true", 100.0), ("ga", "true", 101.0), ("ga", "false", 120.0)] {
            let fields = executable_cell_order_run(time + s as f64);
            let _ = writeln!(text, "{solver}{seeded}{s},c{solver}{seeded},{s},{},{solver},{seeded},{fields}", 100 + s);
        }
    }
    let t = RunsTable::parse(&text).unwrap();
    let r = render(&t, &Comparison::parse("solver=ils").unwrap()).unwrap();
    assert!(r.markdown.contains("`seeded` is `true` on every run of the baseline"), "{}", r.markdown);
    let csv = RunsTable::parse(&r.csv).unwrap();
    let get = |r: &Vec<String>, c: &str| r[csv.col(c).unwrap()].clone();
    for value in ["ga (seeded=false)", "ga (seeded=true)"] {
        let row = csv.rows.iter().find(|r| get(r, "metric") == "time_s" && get(r, "value") == value);
        assert_eq!(row.map(|r| get(r, "pairs")), Some("6".to_string()), "{value}: {}", r.csv);
    }
}

#[test]
fn a_control_run_once_pairs_with_every_seed_and_nested_settings_label_the_values() {
    let dir = tempfile::tempdir().unwrap();
    let md = write(&control_table(), &Comparison::parse("solver=nearest").unwrap(), dir.path()).unwrap();
    let text = std::fs::read_to_string(&md).unwrap();
    assert!(text.contains("`memetic` is set under some values of `solver` only"), "{text}");
    assert!(text.contains("its one run pairs with every seed of the other"), "{text}");
    let csv = RunsTable::parse(&std::fs::read_to_string(dir.path().join("compare-solver.csv")).unwrap()).unwrap();
    let get = |r: &Vec<String>, c: &str| r[csv.col(c).unwrap()].clone();
    let time = |value: &str| {
        csv.rows.iter().find(|r| get(r, "metric") == "time_s" && get(r, "value") == value).cloned().unwrap()
    };
    let (with, without) = (time("ga (memetic=true)"), time("ga (memetic=false)"));
    assert_eq!((get(&with, "pairs"), get(&without, "pairs")), ("6".into(), "6".into()));
    assert_eq!((get(&with, "runs_baseline"), get(&with, "runs_value")), ("1".into(), "6".into()));
    // Faster in all six pairs, slower in all six: exact p = 2/2⁶ each.
    assert_eq!((get(&with, "value_better"), get(&without, "value_worse")), ("6".into(), "6".into()));
    assert_eq!(get(&with, "p").parse::<f64>().unwrap(), 2.0 / 64.0);
    assert_eq!(get(&with, "estimate").parse::<f64>().unwrap(), 87.5 / 100.0);
    // A study not yet finished pairs by seed only: the control's one run meets replicate 0.
    let part = render_with(&control_table(), &Comparison::parse("solver=nearest").unwrap(), false).unwrap();
    assert!(part.markdown.contains("The study is not finished"), "{}", part.markdown);
    let csv = RunsTable::parse(&part.csv).unwrap();
    let time = csv.rows.iter().find(|r| get(r, "metric") == "time_s" && get(r, "stratum") != "pooled").unwrap();
    assert_eq!(get(time, "pairs"), "1");
}

#[test]
fn pairs_by_seed_within_strata_corrects_the_family_and_names_the_confounded_column() {
    let dir = tempfile::tempdir().unwrap();
    let t = table(0.1);
    let md = write(&t, &Comparison::parse("a=a").unwrap(), dir.path()).unwrap();
    let text = std::fs::read_to_string(&md).unwrap();
    assert!(text.contains("within each combination of map"), "{text}");
    assert!(text.contains("`budget` follows map"), "{text}");
    let csv = RunsTable::parse(&std::fs::read_to_string(dir.path().join("compare-a.csv")).unwrap()).unwrap();
    let get = |r: &Vec<String>, c: &str| r[csv.col(c).unwrap()].clone();
    assert_eq!(csv.rows.len(), 10, "pooled and two strata × executability and two metrics, and the margin");
    let exec_m2 = csv.rows.iter().find(|r| get(r, "metric") == "executable" && get(r, "stratum") == "map=m2").unwrap();
    // Seed 0 of b on m2 is the only discordant pair: McNemar's exact p = 1.
    assert_eq!((get(exec_m2, "value_better"), get(exec_m2, "value_worse")), ("0".into(), "1".into()));
    assert_eq!((get(exec_m2, "test"), get(exec_m2, "p")), ("mcnemar exact".into(), "1".into()));
    let time_m1 = csv.rows.iter().find(|r| get(r, "metric") == "time_s" && get(r, "stratum") == "map=m1").unwrap();
    // Six pairs, b slower in each: exact p = 2/2⁶; m2 has five pairs (2/2⁵). Holm over the
    // two: 2 · 1/32 and 1/16, both 0.0625 — nothing shown.
    assert_eq!(get(time_m1, "pairs"), "6");
    assert_eq!(get(time_m1, "value_worse"), "6");
    assert_eq!(get(time_m1, "p").parse::<f64>().unwrap(), 2.0 / 64.0);
    assert_eq!(get(time_m1, "p_holm").parse::<f64>().unwrap(), 0.0625);
    assert_eq!(get(time_m1, "estimate").parse::<f64>().unwrap(), 127.5 / 107.5);
    let time_m2 = csv.rows.iter().find(|r| get(r, "metric") == "time_s" && get(r, "stratum") == "map=m2").unwrap();
    assert_eq!((get(time_m2, "pairs"), get(time_m2, "executable_value")), ("5".into(), "5".into()));
    assert!(get(time_m2, "note").contains("5 pairs cannot reach p < 0.05"), "{:?}", get(time_m2, "note"));
    // No difference in coverage: every pair ties, not tested.
    let same = table(0.0);
    write(&same, &Comparison::parse("a=a").unwrap(), dir.path()).unwrap();
    let csv = RunsTable::parse(&std::fs::read_to_string(dir.path().join("compare-a.csv")).unwrap()).unwrap();
    let cov = |stratum: &str| {
        csv.rows.iter().find(|r| get(r, "metric") == "cov_final_reach" && get(r, "stratum") == stratum).unwrap()
    };
    assert_eq!(
        (get(cov("map=m1"), "p"), get(cov("map=m1"), "note")),
        (String::new(), "equal in every pair: not tested".into())
    );
    assert_eq!(get(cov("pooled"), "note"), "equal in every unit: not tested");
}

#[test]
fn pooled_over_the_strata_pairs_every_strata_pair_in_one_test() {
    let dir = tempfile::tempdir().unwrap();
    let md = write(&table(0.1), &Comparison::parse("a=a").unwrap(), dir.path()).unwrap();
    let text = std::fs::read_to_string(&md).unwrap();
    assert!(text.contains("## `time_s`, pooled over the strata"), "{text}");
    assert!(text.contains("One test of `time_s` pooled over the strata (1 value against `a`)"), "{text}");
    let csv = RunsTable::parse(&std::fs::read_to_string(dir.path().join("compare-a.csv")).unwrap()).unwrap();
    let get = |r: &Vec<String>, c: &str| r[csv.col(c).unwrap()].clone();
    let pooled = |metric: &str| {
        csv.rows.iter().find(|r| get(r, "metric") == metric && get(r, "stratum") == "pooled").unwrap().clone()
    };
    // Six pairs on m1 and five on m2 (one plan of b there is not executable), b covers 0.1
    // more in each. The units are the two maps: both better gives the exact p = 2/2², which no
    // design of two units can beat, and the family says so.
    let cov = pooled("cov_final_reach");
    assert_eq!(
        (get(&cov, "pairs"), get(&cov, "unit"), get(&cov, "units")),
        ("11".into(), "stratum".into(), "2".into())
    );
    assert_eq!(get(&cov, "value_better"), "2");
    assert_eq!(get(&cov, "contrast"), "pair difference");
    assert!((get(&cov, "estimate").parse::<f64>().unwrap() - 0.1).abs() < 1e-12);
    assert_eq!(get(&cov, "p").parse::<f64>().unwrap(), 0.5);
    assert_eq!(get(&cov, "p_holm"), get(&cov, "p"));
    assert_eq!((get(&cov, "p_floor_holm"), get(&cov, "note")), ("0.5".into(), "cannot show by design".into()));
    assert!(
        text.contains("By design this family cannot show anything at the 0.05 level**: at best (its largest comparison, 2 strata, all pointing one way) its p is 0.5000"),
        "{text}"
    );
    assert!(text.contains("| b | 2 | 11 | +0.1000 ["), "the pairs are described: {text}");
    // Time: the ratio within each pair, (120 + 3s)/(100 + 3s); the median of the eleven is
    // seed 3's.
    let time = pooled("time_s");
    assert_eq!((get(&time, "contrast"), get(&time, "value_worse")), ("pair ratio".into(), "2".into()));
    assert_eq!(get(&time, "estimate").parse::<f64>().unwrap(), 129.0 / 109.0);
    // The forest plot beside the files: a panel for b, a row per map with its pairs' ratios
    // (seeds 0–5 on m1: (120 + 3s)/(100 + 3s), from 1.2 down to 135/115), linked from the text.
    let forest = dir.path().join("compare-a-forest.png");
    assert!(forest.exists() && text.contains("(compare-a-forest.png)"), "{text}");
    let rendered = render(&table(0.1), &Comparison::parse("a=a").unwrap()).unwrap();
    let panel = &rendered.forest.as_ref().expect("a forest plot").panels[0];
    assert!(panel.rows.len() == 2 && panel.rows[0].name.contains("m1") && panel.rows[1].name.contains("m2"));
    assert!((panel.rows[0].high - 1.2).abs() < 1e-12 && (panel.rows[0].low - 135.0 / 115.0).abs() < 1e-12);
    assert!(panel.rows.iter().all(|r| r.low <= r.ratio && r.ratio <= r.high) && panel.margin == 0.95);
    // Executability: m1 ties (effect 0), m2 one plan in six fewer: one unit differs.
    let exec = pooled("executable");
    assert_eq!(
        (get(&exec, "pairs"), get(&exec, "value_worse"), get(&exec, "p")),
        ("12".into(), "1".into(), "1".into())
    );
    // Every plan: the pair with b's plan not executable counts too, in a file of its own.
    let every = Comparison::parse_every_plan("a=a").unwrap();
    write(&table(0.1), &every, dir.path()).unwrap();
    let text = std::fs::read_to_string(dir.path().join("compare-a-every-plan.md")).unwrap();
    assert!(text.contains("every pair counts, executable or not"), "{text}");
    let csv = RunsTable::parse(&std::fs::read_to_string(dir.path().join("compare-a-every-plan.csv")).unwrap()).unwrap();
    let time = csv.rows.iter().find(|r| get(r, "metric") == "time_s" && get(r, "stratum") == "pooled").unwrap();
    assert_eq!(get(time, "pairs"), "12");
    // One stratum: nothing to pool.
    let one: Vec<Vec<String>> = table(0.1).rows.into_iter().filter(|r| r[5] == "m1").collect();
    let mut t = table(0.1);
    t.rows = one;
    write(&t, &Comparison::parse("a=a").unwrap(), dir.path()).unwrap();
    let text = std::fs::read_to_string(dir.path().join("compare-a.md")).unwrap();
    assert!(!text.contains("pooled"), "{text}");
}

#[test]
fn comparisons_that_cannot_be_made_are_refused_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    let t = table(0.1);
    let err = |text: &str| match write(&t, &Comparison::parse(text).unwrap(), dir.path()) {
        Err(ReportError::Input(m)) => m,
        other => panic!("{text}: {other:?}"),
    };
    assert!(err("budget=1000").contains("`budget` follows map (confounded with it)"), "{}", err("budget=1000"));
    assert!(err("a=c").contains("no run has that value; values: a, b"), "{}", err("a=c"));
    assert!(err("a=a|c").contains("no run has the value c; values: a, b"), "{}", err("a=a|c"));
    assert!(err("time_s=1").contains("not a swept parameter; swept: a, map, budget"), "{}", err("time_s=1"));
    assert!(Comparison::parse("a").is_err() && Comparison::parse("=x").is_err());
    assert!(Comparison::parse_every_plan("a").unwrap_err().starts_with("--compare-every-plan a:"));
}

/// The issue a reviewer raised: a control run once per stratum, paired with each of a search's
/// seeds, turns four settings into forty "units". Pooling the pairs would give p ≈ 2 · 2⁻⁴⁰; with
/// the strata as units the best four can give is 2 · 2⁻⁴ = 0.125, and the report says the design
/// cannot show anything instead of "shown".
#[test]
fn a_once_run_control_is_tested_over_its_strata_not_over_the_pairs() {
    let metrics = metric_columns();
    let mut text = format!("run_id,config_id,replicate,seed,solver,map,{}\n", metrics.join(","));
    let mut line = |id: String, rep: usize, solver: &str, map: usize, time: f64| {
        let fields = executable_cell_order_run(time);
        let _ = writeln!(text, "{id},c{solver}{map},{rep},{},{solver},m{map},{fields}", 100 + rep);
    };
    for map in 0..4 {
        line(format!("n{map}"), 0, "nearest", map, 100.0);
        for s in 0..10 {
            line(format!("g{map}{s}"), s, "ga", map, 90.0 - s as f64);
        }
    }
    let t = RunsTable::parse(&text).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let md = write(&t, &Comparison::parse("solver=nearest").unwrap(), dir.path()).unwrap();
    let text = std::fs::read_to_string(&md).unwrap();
    // The pairs pooled as units: every one of the forty faster.
    let pairs: Vec<f64> = (0..40).map(|i| 90.0 - (i % 10) as f64).collect();
    let pooled_pairs = crate::stats::wilcoxon_signed_rank(&pairs, &[100.0; 40]).unwrap().p_value;
    assert!(pooled_pairs < 1e-6, "{pooled_pairs}");
    let csv = RunsTable::parse(&std::fs::read_to_string(dir.path().join("compare-solver.csv")).unwrap()).unwrap();
    let get = |r: &Vec<String>, c: &str| r[csv.col(c).unwrap()].clone();
    let time = csv.rows.iter().find(|r| get(r, "metric") == "time_s" && get(r, "stratum") == "pooled").unwrap();
    assert_eq!(
        (get(time, "pairs"), get(time, "units"), get(time, "value_better")),
        ("40".into(), "4".into(), "4".into())
    );
    assert_eq!(get(time, "p").parse::<f64>().unwrap(), 0.125);
    assert_eq!(get(time, "note"), "cannot show by design");
    assert!(text.contains("The pooled unit is the stratum (4 units), because a side ran once per stratum"), "{text}");
    assert!(
        text.contains("**By design this family cannot show anything at the 0.05 level**: at best (its largest comparison, 4 strata, all pointing one way) its p is 0.1250"),
        "{text}"
    );
    assert!(text.contains("time, pooled over the 4 strata: median pair ratio 0.855× [0.855×, 0.855×] over 40 pairs; better in 4 and worse in 0 of the strata; cannot show by design."), "{text}");
}
