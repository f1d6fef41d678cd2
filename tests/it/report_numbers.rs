//! The numbers `covga report` publishes, checked on a six-run fixture study against values
//! worked out by hand (hypervolumes, best runs) or computed independently (means with t-based
//! 95 % intervals and the tie-corrected Kruskal–Wallis H with its χ²₁ p-value = erfc(√(H/2)),
//! worked in a short script outside the project and written down here).

use std::collections::HashMap;

/// (run id, config id, replicate, C_len, cov_final, t_final, wall s).
const RUNS: [(&str, &str, u32, &str, f64, f64, f64); 6] = [
    ("a1", "cfgA", 0, "0.1", 0.50, 0.60, 1.0),
    ("a2", "cfgA", 1, "0.1", 0.62, 0.50, 2.0),
    ("a3", "cfgA", 2, "0.1", 0.70, 0.40, 3.0),
    ("b1", "cfgB", 0, "0.4", 0.80, 0.50, 4.0),
    ("b2", "cfgB", 1, "0.4", 0.60, 0.70, 5.0),
    ("b3", "cfgB", 2, "0.4", 0.72, 0.60, 6.0),
];

/// Writes a study folder's `runs.csv` (one row per map of column values; a column not given is
/// 0) and `study.json` into `dir`.
fn write_study(dir: &std::path::Path, params: &[String], rows: &[HashMap<&str, String>]) {
    let header = covga::study::records::header(params);
    let mut csv = header.join(",") + "\n";
    for values in rows {
        let row: Vec<String> = header.iter().map(|h| values.get(h.as_str()).cloned().unwrap_or("0".into())).collect();
        csv += &(row.join(",") + "\n");
    }
    std::fs::write(dir.join("runs.csv"), csv).unwrap();
    let study = format!("{{\"grid_hash\": \"fixture\", \"runs\": {}}}", rows.len());
    std::fs::write(dir.join("study.json"), study).unwrap();
}

fn fixture(dir: &std::path::Path) {
    let params = vec!["thesis.c_len".to_string()];
    let mut rows = Vec::new();
    for (id, config, rep, c_len, cov, t, wall) in RUNS {
        let values: HashMap<&str, String> = [
            ("run_id", id.to_string()),
            ("config_id", config.to_string()),
            ("replicate", rep.to_string()),
            ("seed", "1".to_string()),
            ("thesis.c_len", c_len.to_string()),
            ("planner", "thesis".to_string()),
            ("map", "thesis-1".to_string()),
            // One run a robot cannot drive: counted in its group's row, left out of its means.
            ("executable", (id != "a3").to_string()),
            ("planner_feasible", (id != "a3").to_string()),
            ("violations", if id == "a3" { "the path sweeps 1 obstacle cells".to_string() } else { String::new() }),
            ("cov_final_free", cov.to_string()),
            ("cov_final_reach", cov.to_string()),
            ("t_final", t.to_string()),
            ("f_free", (cov * t).to_string()),
            ("f_reach", (cov * t).to_string()),
            ("wall_s", wall.to_string()),
        ]
        .into_iter()
        .collect();
        rows.push(values);
    }
    write_study(dir, &params, &rows);
}

#[test]
fn report_numbers_match_hand_and_independent_computations() {
    let dir = tempfile::tempdir().unwrap();
    fixture(dir.path());
    let o = crate::common::command()
        .args(["report", dir.path().to_str().unwrap(), "--by", "thesis.c_len"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(dir.path().join("report/summary.md")).unwrap();
    for line in [
        "6 runs, 2 configurations, 3 replicate(s); grouped by thesis.c_len.",
        // Best run per group by f = t·cov: a2 (0.31 against 0.30 and 0.28), b3 (0.432).
        "| thesis.c_len=0.1 | a2 | 0.1 | 0.620000 | 0.500000 | 0.310000 |",
        "| thesis.c_len=0.4 | b3 | 0.4 | 0.720000 | 0.600000 | 0.432000 |",
        // Every executable point is on its group's front (a3, not executable, is on none).
        // Hypervolume from (0, 0), by t ascending: A: 0.5·0.62 + 0.1·0.5 = 0.36;
        // B: 0.5·0.8 + 0.1·0.72 + 0.1·0.6 = 0.532.
        "| thesis.c_len=0.1 | 3 | 2 | 0.3600 | 2.000 | 1.000 | 3.000 |",
        "| thesis.c_len=0.4 | 3 | 3 | 0.5320 | 5.000 | 4.000 | 6.000 |",
        // Best configuration per group over seeds (each group here is one configuration).
        "| thesis.c_len=0.4 | 0.4 | 3 | 0.7067 ± 0.2501 | 0.6000 ± 0.2484 | 0.4173 |",
        // Means ± t(0.975, 2)·s/√3, best mean f first.
        "| 0.4 | 3 | 0.7067 ± 0.2501 | 0.6000 ± 0.2484 | 0.4173 |",
        "| 0.1 | 3 | 0.6067 ± 0.2501 | 0.5000 ± 0.2484 | 0.2967 |",
        // Kruskal–Wallis: cov without ties (rank sums 8 and 13), t with two tied pairs, f with
        // every A below every B (rank sums 6 and 15: H = 12/42·(36/3 + 225/3) − 21 = 27/7,
        // p = erfc(√(H/2)) = 0.0495); the medians are each group's middle run. Executable plans
        // (a3 left out): reachable coverage ranks A 1, 3 and B 2, 4, 5, H = 0.4·(16/2 + 121/3) − 18
        // = 4/3; time_s is 0 in every run, not tested. Holm over the four tests: 4·0.0495,
        // then 3·0.2482 for the rest (0.2612·2 and 0.2752 fall below it).
        "| thesis.c_len | executable | cov_final_reach | 5 | 2 | 1.333 | 1 | 2.482e-1 | 7.446e-1 | 0.3333 | 0.1: 0.5600 · 0.4: 0.7200 |",
        "| thesis.c_len | executable | time_s | 5 | 2 | – | – | – | – | – | 0.1: 0.0000 · 0.4: 0.0000 |",
        "| thesis.c_len | every | cov_final_free | 6 | 2 | 1.190 | 1 | 2.752e-1 | 7.446e-1 | 0.2381 | 0.1: 0.6200 · 0.4: 0.7200 |",
        "| thesis.c_len | every | t_final | 6 | 2 | 1.263 | 1 | 2.612e-1 | 7.446e-1 | 0.2525 | 0.1: 0.5000 · 0.4: 0.6000 |",
        "| thesis.c_len | every | f_free | 6 | 2 | 3.857 | 1 | 4.953e-2 | 1.981e-1 | 0.7714 | 0.1: 0.3000 · 0.4: 0.4200 |",
        "Holm–Bonferroni over the 4 tests of this section (every tested parameter and measure).",
        // Per group over the executable runs (a1 and a2 of group A: cov 0.56 ± t(0.975, 1)·0.06 =
        // 12.7062·0.06, t 0.55 ± 12.7062·0.05, f = cov·t 0.305 ± 12.7062·0.005), then cov over
        // all three runs (0.6067 ± 0.2501, as in the configuration rows).
        "| thesis.c_len=0.1 | 3 | 2/3 | 0.5600 ± 0.7624 | 0.5500 ± 0.6353 | 0.3050 ± 0.0635 | 0.6067 ± 0.2501 |",
        "| thesis.c_len=0.4 | 3 | 3/3 | 0.7067 ± 0.2501 | 0.6000 ± 0.2484 | 0.4173 ± ",
        // One-way ANOVA of cov: SS_between = 6·0.05² = 0.015, SS_within = 2·0.020267 = 0.040533,
        // η² = 0.015/0.055533, F = 0.015/(0.040533/4) = 1.48; P(F(1, 4) > F) = P(|T₄| > √F),
        // from the closed form of Student's t with 4 df: 0.2906. On ranks (A 1, 3, 4; B 6, 2, 5):
        // F = 4.1667/(13.333/4) = 1.25, p = 0.3262. The model has every configuration, so the
        // residual is all between replicates.
        "| thesis.c_len | 1 | 0.2701 | 1.48 | 2.91e-1 | 3.26e-1 |",
        "| residual | 4 | 0.7299 | | | |",
        "| of which between replicates of one configuration | | 0.7299 | | | |",
    ] {
        assert!(md.contains(line), "missing `{line}` in\n{md}");
    }
    // The per-configuration table holds the same means.
    let conf = std::fs::read_to_string(dir.path().join("report/configurations.csv")).unwrap();
    let first = conf.lines().nth(1).unwrap();
    assert!(conf.starts_with("config_id,planner,thesis.c_len,n,cov_final_mean,"), "{conf}");
    assert!(first.starts_with("cfgB,thesis,0.4,3,0.706666"), "{first}");
}

#[test]
fn where_filters_the_runs_and_name_keeps_reports_apart() {
    let dir = tempfile::tempdir().unwrap();
    fixture(dir.path());
    let report = |extra: &[&str]| {
        let mut args = vec!["report", dir.path().to_str().unwrap()];
        args.extend(extra);
        crate::common::command().args(&args).output().unwrap()
    };
    // `0.40` equals `0.4` as a number.
    let o = report(&["--where", "thesis.c_len=0.40", "--name", "c-len-04"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(dir.path().join("report-c-len-04/summary.md")).unwrap();
    assert!(md.contains("Runs with thesis.c_len = 0.40 only."), "{md}");
    assert!(md.contains("3 runs, 1 configurations, 3 replicate(s)"), "{md}");
    assert!(md.contains("| all runs | 3 | 3/3 | 0.7067 ± 0.2501 | 0.6000 ± 0.2484 |"), "{md}");
    assert!(!dir.path().join("report").exists(), "the default report folder is left alone");
    for (args, needle) in [
        (vec!["--where", "nothing=1"], "--where `nothing` is not a column"),
        (vec!["--where", "thesis.c_len=0.7"], "no recorded run"),
        (vec!["--where", "thesis.c_len"], "expected KEY=VALUE"),
        (vec!["--name", "../x"], "--name `../x`"),
    ] {
        let o = report(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

/// A thesis study of 40 Elite and 40 tournament runs on map 1 (and one on map 2, which the
/// claims leave out), with histories whose final diversity is known: Elite 100–139,
/// tournament 200–239 with TS 7 on the lower half.
#[test]
fn the_claims_of_section_5_1_get_their_verdicts() {
    let dir = tempfile::tempdir().unwrap();
    let params: Vec<String> = [
        "map.source",
        "robot.rot_speed",
        "thesis.selection",
        "scorer.projection",
        "thesis.c_len",
        "thesis.c_child",
        "thesis.p_ma",
        "thesis.p_mi",
        "thesis.tournament_size",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let header = covga::study::records::header(&params);
    let mut csv = header.join(",") + "\n";
    let mut add = |id: String, map: &str, selection: &str, ts: &str, diversity: f64| {
        let values: HashMap<&str, String> = [
            ("run_id", id.clone()),
            ("config_id", id.clone()),
            ("map.source", map.to_string()),
            ("robot.rot_speed", "0".to_string()),
            ("thesis.selection", selection.to_string()),
            ("scorer.projection", "f2".to_string()),
            ("thesis.c_len", "0.2".to_string()),
            ("thesis.c_child", "2".to_string()),
            ("thesis.p_ma", "0.01".to_string()),
            ("thesis.p_mi", "0".to_string()),
            ("thesis.tournament_size", ts.to_string()),
            ("planner", "thesis".to_string()),
            ("executable", "true".to_string()),
            ("planner_feasible", "true".to_string()),
            ("cov_final_free", "0.7".to_string()),
            ("t_final", "0.8".to_string()),
            ("f_free", "0.56".to_string()),
        ]
        .into_iter()
        .collect();
        let row: Vec<String> = header.iter().map(|h| values.get(h.as_str()).cloned().unwrap_or("0".into())).collect();
        csv += &(row.join(",") + "\n");
        let run = dir.path().join("runs").join(&id);
        std::fs::create_dir_all(&run).unwrap();
        let history: String = std::iter::once("iteration,diversity\n".to_string())
            .chain((0..10).map(|i| format!("{i},{diversity}\n")))
            .collect();
        std::fs::write(run.join("history.csv"), history).unwrap();
    };
    for k in 0..40 {
        add(format!("e{k:02}"), "thesis-1", "elite", "", 100.0 + f64::from(k));
        add(format!("t{k:02}"), "thesis-1", "tournament", if k < 20 { "7" } else { "3" }, 200.0 + f64::from(k));
    }
    add("m2".into(), "thesis-2", "elite", "", 1000.0);
    std::fs::write(dir.path().join("runs.csv"), csv).unwrap();
    std::fs::write(dir.path().join("study.json"), "{\"grid_hash\": \"fixture\", \"runs\": 81}").unwrap();
    let o = crate::common::command().args(["report", dir.path().to_str().unwrap()]).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(dir.path().join("report/summary.md")).unwrap();
    for line in [
        "On the 80 runs of map 1 without rotation cost (80 with a history for the diversity).",
        // Every Elite value below every tournament value: A₁₂ = 0.
        "| Elite loses the most diversity | final diversity, Elite vs tournament | 40 / 40 | A₁₂ = 0.000 (large) |",
        "| Elite loses the most diversity | final diversity, Elite vs prws | 40 / 0 | – | – | cannot say |",
        // TS 7 holds the 20 lowest tournament values.
        "| Higher TS lowers diversity | final diversity, TS 7 vs TS 3 | 20 / 20 | A₁₂ = 0.000 (large) |",
        // Identical best individuals: every deviation is 0, all tied, no test → cannot say.
        "| Elite's best individuals lie in a small distribution | distance of cov_final from the group median, Elite vs tournament | 40 / 40 | – | – | cannot say |",
    ] {
        assert!(md.contains(line), "missing `{line}` in\n{md}");
    }
    let holds = md.lines().filter(|l| l.starts_with("| Elite loses") && l.ends_with("| holds |")).count();
    assert_eq!(holds, 1, "only the tournament comparison has data");
    assert!(md.lines().any(|l| l.starts_with("| Higher TS lowers") && l.ends_with("| holds |")));
}

/// The library's `write_report` writes what `covga report --by` writes, and returns the path
/// of its summary.
#[test]
fn the_library_call_writes_the_report_the_command_writes() {
    let (lib, cli) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    fixture(lib.path());
    fixture(cli.path());
    let path = covga::report::write_report(lib.path(), &["thesis.c_len".to_string()]).unwrap();
    assert_eq!(path, lib.path().join("report/summary.md"));
    let o = crate::common::command()
        .args(["report", cli.path().to_str().unwrap(), "--by", "thesis.c_len"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let read = |dir: &std::path::Path| {
        std::fs::read_to_string(dir.join("report/summary.md")).unwrap().replace(dir.to_str().unwrap(), "<study>")
    };
    let summary = read(lib.path());
    assert!(summary.contains("0.4"), "grouped by C_len: {summary}");
    assert_eq!(summary, read(cli.path()));
}

/// A study with no run recorded yet says so, with or without `--where` (whose own message is
/// for a value no recorded run has).
#[test]
fn an_empty_study_says_no_runs_are_recorded_yet() {
    let dir = tempfile::tempdir().unwrap();
    let header = covga::study::records::header(&["thesis.c_len".to_string()]);
    std::fs::write(dir.path().join("runs.csv"), header.join(",") + "\n").unwrap();
    std::fs::write(dir.path().join("study.json"), "{\"grid_hash\": \"fixture\", \"runs\": 0}").unwrap();
    for filter in [&[][..], &["--where", "thesis.c_len=0.1"][..]] {
        let o = crate::common::command().arg("report").arg(dir.path()).args(filter).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains("no runs recorded yet"), "{filter:?}: {err}");
    }
}

/// Grouped by two columns, the Pareto panels are laid out as the first column's values (rows)
/// by the second's (columns): C_len's two values over one map give two rows of one panel
/// (480 px wide, 2·440 px of panels below the title), not the default two panels side by side.
#[test]
fn two_grouping_columns_lay_the_panels_out_as_rows_by_columns() {
    let dir = tempfile::tempdir().unwrap();
    fixture(dir.path());
    let o = crate::common::command()
        .args(["report", dir.path().to_str().unwrap(), "--by", "thesis.c_len", "--by", "map"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let size = image::image_dimensions(dir.path().join("report/pareto.png")).unwrap();
    assert_eq!(size.0, 480, "one column: {size:?}");
    assert!(size.1 > 2 * 440 && size.1 < 2 * 440 + 100, "two rows and a title: {size:?}");
}

/// f1 and f2 are different functions: where a study sweeps the projection, the best run, the
/// best configuration and the mean of f are given per projection, never across them.
#[test]
fn f_is_ranked_and_averaged_within_one_projection() {
    let dir = tempfile::tempdir().unwrap();
    let params = vec!["scorer.projection".to_string()];
    let mut rows = Vec::new();
    // (run, config, projection, cov_final, t_final): f1 = (c + t)/2 is larger than f2 = c·t,
    // so a ranking across projections would put every f1 run first.
    for (id, config, projection, cov, t) in [
        ("p1", "cfg1", "f1", 0.40, 0.50),
        ("p2", "cfg1", "f1", 0.50, 0.50),
        ("q1", "cfg2", "f2", 0.90, 0.90),
        ("q2", "cfg2", "f2", 0.70, 0.90),
    ] {
        let f = if projection == "f1" { (cov + t) / 2.0 } else { cov * t };
        let values: HashMap<&str, String> = [
            ("run_id", id.to_string()),
            ("config_id", config.to_string()),
            ("seed", "1".to_string()),
            ("scorer.projection", projection.to_string()),
            ("planner", "thesis".to_string()),
            ("map", "thesis-1".to_string()),
            ("executable", "true".to_string()),
            ("planner_feasible", "true".to_string()),
            ("cov_final_free", cov.to_string()),
            ("cov_final_reach", cov.to_string()),
            ("t_final", t.to_string()),
            ("f_free", f.to_string()),
            ("f_reach", f.to_string()),
            ("wall_s", "1".to_string()),
        ]
        .into_iter()
        .collect();
        rows.push(values);
    }
    write_study(dir.path(), &params, &rows);
    let o = crate::common::command().args(["report", dir.path().to_str().unwrap()]).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(dir.path().join("report/summary.md")).unwrap();
    for line in [
        // The best run of each projection: p2 (f1 0.5) and q1 (f2 0.81).
        "| all runs, scorer.projection=f1 | p2 | f1 | 0.500000 | 0.500000 | 0.500000 |",
        "| all runs, scorer.projection=f2 | q1 | f2 | 0.900000 | 0.900000 | 0.810000 |",
        // The best configuration of each projection over its seeds.
        "| all runs, scorer.projection=f1 | f1 | 2 |",
        "| all runs, scorer.projection=f2 | f2 | 2 |",
        // Means of f per projection: f1 (0.45 + 0.5)/2, f2 (0.81 + 0.63)/2.
        "| group | runs | executable | cov_final | t_final | f (f1) | f (f2) | cov_final (all) |",
    ] {
        assert!(md.contains(line), "missing `{line}` in\n{md}");
    }
    let means = md.lines().find(|l| l.starts_with("| all runs | 4 | 4/4 |")).expect("the group's means");
    assert!(means.contains("| 0.4750 ± ") && means.contains("| 0.7200 ± "), "{means}");
}

/// A row of runs.csv under `header`: `values`, over a thesis run on thesis-1 that is executable
/// and feasible, 0 in every other column.
fn runs_row(header: &[String], values: &[(&str, &str)]) -> String {
    let defaults = [
        ("seed", "1"),
        ("planner", "thesis"),
        ("map", "thesis-1"),
        ("executable", "true"),
        ("planner_feasible", "true"),
        ("wall_s", "1"),
    ];
    let cell = |h: &str| values.iter().chain(&defaults).find(|(k, _)| *k == h).map_or("0", |(_, v)| *v).to_string();
    header.iter().map(|h| cell(h)).collect::<Vec<_>>().join(",") + "\n"
}

/// A `--by` column a conditional sets for some runs only labels the groups that have a value:
/// the Elite group is `thesis.selection=elite`, not `…, thesis.tournament_size=`.
#[test]
fn an_empty_by_column_does_not_label_its_group() {
    let dir = tempfile::tempdir().unwrap();
    let params = vec!["thesis.selection".to_string(), "thesis.tournament_size".to_string()];
    let header = covga::study::records::header(&params);
    let mut csv = header.join(",") + "\n";
    for (id, selection, size) in [("e1", "elite", ""), ("t1", "tournament", "3")] {
        let cov = [("cov_final_free", "0.5"), ("cov_final_reach", "0.5"), ("t_final", "0.5")];
        let keys =
            [("run_id", id), ("config_id", id), ("thesis.selection", selection), ("thesis.tournament_size", size)];
        csv += &runs_row(&header, &[&keys[..], &cov[..]].concat());
    }
    std::fs::write(dir.path().join("runs.csv"), csv).unwrap();
    std::fs::write(dir.path().join("study.json"), "{\"grid_hash\": \"fixture\", \"runs\": 2}").unwrap();
    let o = crate::common::command()
        .args(["report", dir.path().to_str().unwrap(), "--by", "thesis.selection", "--by", "thesis.tournament_size"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(dir.path().join("report/summary.md")).unwrap();
    assert!(md.contains("| thesis.selection=elite |"), "{md}");
    assert!(md.contains("| thesis.selection=tournament, thesis.tournament_size=3 |"), "{md}");
    assert!(!md.contains("tournament_size= "), "{md}");
}

/// (run id, config id, replicate, planner, reachable coverage, mission time s).
const MIXED: [(&str, &str, u32, &str, f64, f64); 4] = [
    ("p1", "cfgP", 0, "spiral", 0.950, 900.0),
    ("c1", "cfgC", 0, "cell_order", 0.901, 400.0),
    ("c2", "cfgC", 1, "cell_order", 0.903, 500.0),
    ("c3", "cfgC", 2, "cell_order", 0.899, 350.0),
];

/// A study that runs planners other than the thesis GA is tabled on the common scorer's
/// measures: the best run covers most, the fastest of those within 0.005 of it; means of
/// `cov_final_reach` and `time_s` with t-based intervals; no `t_final` or `f`.
#[test]
fn a_study_of_other_planners_is_tabled_on_mission_time_and_reachable_coverage() {
    let dir = tempfile::tempdir().unwrap();
    let mut rows = Vec::new();
    for (id, config, rep, planner, cov, time) in MIXED {
        let values: HashMap<&str, String> = [
            ("run_id", id.to_string()),
            ("config_id", config.to_string()),
            ("replicate", rep.to_string()),
            ("seed", "1".to_string()),
            ("planner", planner.to_string()),
            ("map", "thesis-1".to_string()),
            ("executable", "true".to_string()),
            ("planner_feasible", "true".to_string()),
            ("violations", String::new()),
            ("cov_final_free", (cov - 0.05).to_string()),
            ("cov_final_reach", cov.to_string()),
            ("time_s", time.to_string()),
            // 003's f would pick c2 (the highest) as the cell-order group's best.
            ("t_final", "0.5".to_string()),
            ("f_free", cov.to_string()),
            ("f_reach", cov.to_string()),
            ("wall_s", "1".to_string()),
        ]
        .into_iter()
        .collect();
        rows.push(values);
    }
    write_study(dir.path(), &[], &rows);
    let o =
        crate::common::command().args(["report", dir.path().to_str().unwrap(), "--by", "planner"]).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(dir.path().join("report/summary.md")).unwrap();
    for line in [
        "## Best run per group (highest cov_final_reach; of those within 0.005 of it, the shortest time_s)",
        // c3 lies within 0.005 of c2's 0.903 and is the fastest of the three.
        "| planner=cell_order | c3 | cell_order | 0.8990 | 350.0 |",
        "| planner=spiral | p1 | spiral | 0.9500 | 900.0 |",
        // Means ± t(0.975, 2)·s/√3: coverage s = 0.002, time s = 76.376.
        "| planner=cell_order | cell_order | 3 | 0.9010 ± 0.0050 | 416.7 ± 189.7 s |",
        "| planner=spiral | spiral | 1 | 0.9500 (1 run) | 900.0 s (1 run) |",
        // c3 is the fastest, and the others cover no more than 0.005 above it: it dominates them.
        "| planner=cell_order | 3 | 3 | 1 | 1.000 | 1.000 | 1.000 |",
        "| planner=cell_order | 3 | 3/3 | 0.9010 ± 0.0050 | 416.7 ± 189.7 s | 0.9010 ± 0.0050 |",
        "![Mission time against reachable coverage, every plan](pareto.png)",
    ] {
        assert!(md.contains(line), "missing {line:?} in\n{md}");
    }
    assert!(!md.contains("highest f over") && !md.contains("| mean f |"), "{md}");
}
