//! End-to-end tests of grid studies: expansion counts, resume after kill -9, shards + merge,
//! --jobs independence, the report, and bad grid files.

use crate::common::{assert_success as ok, covga};
use std::path::{Path, PathBuf};
use std::process::Stdio;

mod resilience;
mod shipped;

/// A 12-run grid: elite, and tournament with 2 sizes, x 2 C_len x 2 seeds, 60 iterations.
const GRID: &str = r#"
seed = 5
seeds = 2
[base]
[base.thesis]
pop_min = 30
init_individuals = 60
init_actions = 25
keep = 2
select = 8
[base.budget]
iterations = 60
[axes]
"thesis.selection" = ["elite", "tournament"]
"thesis.c_len" = [0.1, 0.4]
[[conditional]]
when = { "thesis.selection" = "tournament" }
axes = { "thesis.tournament_size" = [2, 5] }
"#;

fn grid_file(dir: &Path) -> PathBuf {
    let p = dir.join("g.toml");
    std::fs::write(&p, GRID).unwrap();
    p
}

/// runs.csv rows without the timing column, keyed by run id.
fn rows_without_timing(file: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(file).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let wall = header.iter().position(|h| *h == "wall_s").unwrap();
    let mut rows: Vec<String> = lines
        .map(|l| l.split(',').enumerate().filter(|(i, _)| *i != wall).map(|(_, v)| v).collect::<Vec<_>>().join(","))
        .collect();
    rows.sort();
    rows
}

#[test]
fn thesis_grids_expand_to_table_4_3() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("grids");
    for (file, runs) in [
        ("thesis-elite.toml", 864),
        ("thesis-turn.toml", 6912),
        ("thesis-prws.toml", 3456),
        ("thesis-rrws.toml", 6912),
        ("thesis-table-4-3.toml", 3 * 18144),
        ("thesis-extended.toml", 27216),
        ("smoke.toml", 36),
        ("thesis-seeding.toml", 24),
    ] {
        let o = crate::common::grid_dry_run(&root.join(file));
        ok(&o);
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(text.contains(&format!(": {runs} runs")), "{file}: {text}");
    }
    let o = crate::common::grid_dry_run(&root.join("thesis-table-4-3.toml"));
    let text = String::from_utf8_lossy(&o.stdout);
    for line in [
        // Three seeds of every configuration.
        "54432 runs (18144 configurations x replicates)",
        "2592 runs  no conditional axes",
        "20736 runs  thesis.selection=tournament",
        "10368 runs  thesis.selection=prws",
        "20736 runs  thesis.selection=rrws",
    ] {
        assert!(text.contains(line), "{line}: {text}");
    }
}

#[test]
fn jobs_one_and_two_give_identical_results_and_a_report() {
    let dir = tempfile::tempdir().unwrap();
    let g = grid_file(dir.path());
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    ok(&covga(&["grid", g.to_str().unwrap(), "--jobs", "1", "--out", a.to_str().unwrap()]));
    ok(&covga(&["grid", g.to_str().unwrap(), "--jobs", "2", "--out", b.to_str().unwrap()]));
    let ra = rows_without_timing(&a.join("runs.csv"));
    assert_eq!(ra.len(), 12);
    assert_eq!(ra, rows_without_timing(&b.join("runs.csv")));
    // The order the runs start in changes nothing either.
    let c = dir.path().join("c");
    ok(&covga(&["grid", g.to_str().unwrap(), "--jobs", "2", "--order", "seeds", "--out", c.to_str().unwrap()]));
    assert_eq!(ra, rows_without_timing(&c.join("runs.csv")));
    // Sorted by run id and written whole: the files differ only in wall_s.
    for f in ["grid.toml", "study.json"] {
        assert!(a.join(f).exists(), "{f}");
    }
    let study: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(a.join("study.json")).unwrap()).unwrap();
    assert!(study["git_commit"].is_string() && study["covga_version"].is_string());
    // A second invocation resumes and runs nothing.
    let again = covga(&["grid", g.to_str().unwrap(), "--out", a.to_str().unwrap()]);
    ok(&again);
    assert!(String::from_utf8_lossy(&again.stdout).contains("12 already recorded, 0 run now"));
    // The report.
    let rep = covga(&["report", a.to_str().unwrap(), "--by", "thesis.selection"]);
    ok(&rep);
    for f in ["pareto.png", "pareto.svg", "best_paths.png", "summary.md", "configurations.csv"] {
        assert!(a.join("report").join(f).metadata().map(|m| m.len() > 100).unwrap_or(false), "{f}");
    }
    let md = std::fs::read_to_string(a.join("report/summary.md")).unwrap();
    // The diversity figure shows the runs on a front of executable plans, where a group has any.
    let diversity = a.join("report/diversity.png");
    assert_eq!(diversity.exists(), md.contains("![Diversity of the front runs](diversity.png)"), "{md}");
    for section in [
        "Best configuration per group",
        "hypervolume",
        "95 % CI",
        "Kruskal–Wallis",
        "thesis.selection=elite",
        "thesis.selection=tournament",
    ] {
        assert!(md.contains(section), "{section}");
    }
    // 6 configurations x 2 replicates.
    assert_eq!(std::fs::read_to_string(a.join("report/configurations.csv")).unwrap().lines().count(), 7);
    let bad = covga(&["report", a.to_str().unwrap(), "--by", "nope"]);
    assert_eq!(bad.status.code(), Some(2));
}

/// `--dry-run --calibrate` keeps its times in the study folder, where a later dry run and the
/// longest-first order read them; the wall time is a list schedule in the order asked for.
#[test]
fn a_calibration_is_kept_for_the_order_and_later_estimates() {
    let dir = tempfile::tempdir().unwrap();
    let g = grid_file(dir.path());
    let out = dir.path().join("s");
    let o = covga(&[
        "grid",
        g.to_str().unwrap(),
        "--dry-run",
        "--calibrate",
        "--jobs",
        "2",
        "--out",
        out.to_str().unwrap(),
    ]);
    ok(&o);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("wall time with --jobs 2 in --order longest-first"), "{text}");
    let cal = std::fs::read_to_string(out.join("calibration.csv")).unwrap();
    assert_eq!(cal.lines().next(), Some("branch,runs,seconds_per_run,samples"));
    assert_eq!(cal.lines().count(), 3, "two branches: {cal}");
    assert!(out.join("study.json").exists());
    let later = covga(&["grid", g.to_str().unwrap(), "--dry-run", "--order", "seeds", "--out", out.to_str().unwrap()]);
    ok(&later);
    let text = String::from_utf8_lossy(&later.stdout);
    assert!(text.contains("from the calibration in the study folder") && text.contains("in --order seeds"), "{text}");
    // The folder holds this study: the runs go in, in any order, with the same results.
    ok(&covga(&["grid", g.to_str().unwrap(), "--jobs", "2", "--out", out.to_str().unwrap()]));
    assert_eq!(rows_without_timing(&out.join("runs.csv")).len(), 12);
}

#[test]
fn shards_merge_to_the_full_study() {
    let dir = tempfile::tempdir().unwrap();
    let g = grid_file(dir.path());
    let (full, sharded) = (dir.path().join("full"), dir.path().join("sharded"));
    ok(&covga(&["grid", g.to_str().unwrap(), "--jobs", "2", "--out", full.to_str().unwrap()]));
    for k in 0..3 {
        ok(&covga(&["grid", g.to_str().unwrap(), "--shard", &format!("{k}/3"), "--out", sharded.to_str().unwrap()]));
    }
    let m = covga(&["merge", sharded.to_str().unwrap()]);
    ok(&m);
    assert!(String::from_utf8_lossy(&m.stdout).contains("(12 runs)"));
    assert_eq!(rows_without_timing(&sharded.join("runs.csv")), rows_without_timing(&full.join("runs.csv")));
    // A conflicting duplicate is refused.
    let shard0 = sharded.join("runs-shard-0-of-3.csv");
    let text = std::fs::read_to_string(&shard0).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let header: Vec<&str> = lines[0].split(',').collect();
    let cov = header.iter().position(|h| *h == "cov_final_free").unwrap();
    let mut fields: Vec<String> = lines[1].split(',').map(str::to_string).collect();
    fields[cov] = "0.123".into();
    lines[1] = fields.join(",");
    std::fs::write(&shard0, lines.join("\n") + "\n").unwrap();
    let conflict = covga(&["merge", sharded.to_str().unwrap()]);
    assert_eq!(conflict.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&conflict.stderr).contains("recorded differently"));
}

#[test]
fn killed_study_resumes_to_the_same_results() {
    let dir = tempfile::tempdir().unwrap();
    let g = grid_file(dir.path());
    let (reference, killed) = (dir.path().join("reference"), dir.path().join("killed"));
    ok(&covga(&["grid", g.to_str().unwrap(), "--jobs", "2", "--out", reference.to_str().unwrap()]));
    // Killed deterministically after 4 recorded runs (the runner's fault-injection switch aborts
    // the process like SIGKILL would: no clean-up, the lock released by the OS).
    let killed_run = crate::common::command()
        .args(["grid", g.to_str().unwrap(), "--jobs", "1", "--order", "seeds", "--out", killed.to_str().unwrap()])
        .args(["--abort-after-runs", "4"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .unwrap();
    assert!(!killed_run.success());
    let runs = killed.join("runs.csv");
    let recorded = std::fs::read_to_string(&runs).unwrap().lines().count() - 1;
    assert_eq!(recorded, 4, "the study stopped after its fourth run");
    // Seeds come one after the other: the first runs are all of the first replicate.
    let text = std::fs::read_to_string(&runs).unwrap();
    let rep = text.lines().next().unwrap().split(',').position(|h| h == "replicate").unwrap();
    assert!(text.lines().skip(1).all(|l| l.split(',').nth(rep) == Some("0")), "{text}");
    // Simulate a torn write of the next row.
    let mut f = std::fs::OpenOptions::new().append(true).open(&runs).unwrap();
    std::io::Write::write_all(&mut f, b"deadbeef00000000,half").unwrap();
    drop(f);
    // Killed again after 3 more runs (with two jobs), then resumed to the end.
    let again = crate::common::command()
        .args(["grid", g.to_str().unwrap(), "--jobs", "2", "--out", killed.to_str().unwrap()])
        .args(["--abort-after-runs", "3"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .unwrap();
    assert!(!again.success());
    let recorded = std::fs::read_to_string(&runs).unwrap().lines().count() - 1;
    assert!((7..12).contains(&recorded), "{recorded} runs after the second kill");
    let resumed = covga(&["grid", g.to_str().unwrap(), "--jobs", "2", "--out", killed.to_str().unwrap()]);
    ok(&resumed);
    assert!(String::from_utf8_lossy(&resumed.stdout).contains(&format!("{recorded} already recorded")));
    let rows = rows_without_timing(&runs);
    let ids: std::collections::BTreeSet<&str> = rows.iter().map(|r| r.split(',').next().unwrap()).collect();
    assert_eq!(ids.len(), 12, "every run exactly once");
    assert_eq!(rows, rows_without_timing(&reference.join("runs.csv")));
}

fn expect_grid_error(text: &str, needle: &str) {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("bad.toml");
    std::fs::write(&p, text).unwrap();
    let o = covga(&["grid", p.to_str().unwrap(), "--dry-run"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{text}: {err}");
    assert!(err.contains(needle) && err.contains("bad.toml"), "expected `{needle}` in {err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
}

#[test]
fn bad_grid_files_are_rejected() {
    let base = "[base]\n[base.budget]\niterations = 10\n";
    expect_grid_error(&format!("{base}[axes]\n\"thesis.c_lenn\" = [0.1]\n"), "is not an experiment key");
    expect_grid_error(&format!("{base}[axes]\n\"thesis.c_len\" = []\n"), "empty value list");
    expect_grid_error(&format!("{base}[axes]\n\"thesis.c_len\" = 0.1\n"), "must be a list");
    expect_grid_error(
        &format!(
            "{base}[[conditional]]\nwhen = {{ \"thesis.colour\" = \"red\" }}\naxes = {{ \"thesis.keep\" = [1] }}\n"
        ),
        "neither in the base experiment nor swept",
    );
    expect_grid_error(&format!("seeds = 0\n{base}"), "at least 1 replicate");
    expect_grid_error("[axes]\n\"thesis.c_len\" = [0.1]\n", "missing field `base`");
    expect_grid_error(&format!("{base}[axes]\n\"thesis.p_c\" = [1.5]\n"), "`thesis.p_c` = 1.5 is out of range");
    expect_grid_error(
        &format!(
            "{base}[[base.robots]]\nname = \"a\"\nwidth = 0.9\nstart = [1.5, 1.5]\n[base.fleet]\nmode = \"waypoint\"\n[base.waypoint]\ngenerations = 5\n[axes]\n\"planner\" = [\"waypoint\"]\n"
        ),
        "differs from [robot]",
    );
}

#[test]
fn a_fleet_grid_runs_every_method_and_reports_them() {
    let dir = tempfile::tempdir().unwrap();
    let grid = dir.path().join("fleets.toml");
    std::fs::write(
        &grid,
        "seeds = 2\n[base]\nplanner = \"thesis\"\n[base.map]\nsource = \"thesis-1\"\n[base.stations]\nstart = [1.3, 1.3]\n\
         [base.thesis]\npop_min = 20\n[base.fleet]\nround_iterations = 10\n\
         [base.waypoint]\ngenerations = 1000\nl_init = 100\nobjective = \"footprint\"\nalpha_cov = 1.0\nuav_width = 0.6\n\
         [base.budget]\niterations = 100000\nevaluations = 1500\n\
         [[base.robots]]\nname = \"a\"\nstart = [1.3, 1.3]\n[[base.robots]]\nname = \"b\"\nstart = [9.7, 9.7]\n\
         [axes]\n\"fleet.name\" = [\"pair\"]\n\"fleet.mode\" = [\"central\", \"negotiate\", \"divide\", \"waypoint\"]\n\
         [[conditional]]\nwhen = { \"fleet.mode\" = \"waypoint\" }\naxes = { \"planner\" = [\"waypoint\"] }\n",
    )
    .unwrap();
    let out = dir.path().join("study");
    let dry = covga(&["grid", grid.to_str().unwrap(), "--dry-run"]);
    ok(&dry);
    assert!(String::from_utf8_lossy(&dry.stdout).contains("7 runs (4 configurations"), "division runs once");
    ok(&covga(&["grid", grid.to_str().unwrap(), "--jobs", "2", "--out", out.to_str().unwrap()]));
    let text = std::fs::read_to_string(out.join("runs.csv")).unwrap();
    let mut r = csv::Reader::from_reader(text.as_bytes());
    let header: Vec<String> = r.headers().unwrap().iter().map(str::to_string).collect();
    let col = |name: &str| header.iter().rposition(|h| h == name).unwrap_or_else(|| panic!("{name}"));
    let rows: Vec<Vec<String>> = r.records().map(|x| x.unwrap().iter().map(str::to_string).collect()).collect();
    assert_eq!(rows.len(), 7);
    // Every id and metric column holds what its declared kind says (or nothing).
    for (i, name) in header.iter().enumerate() {
        use covga::study::records::{ColumnKind, column_kind};
        let Some(kind) = column_kind(name) else { continue };
        for v in rows.iter().map(|r| &r[i]).filter(|v| !v.is_empty()) {
            let fits = match kind {
                ColumnKind::Integer => v.parse::<i64>().is_ok(),
                ColumnKind::Unsigned => v.parse::<u64>().is_ok(),
                ColumnKind::Float => v.parse::<f64>().is_ok(),
                ColumnKind::Flag => v == "true" || v == "false",
                ColumnKind::Text => true,
            };
            assert!(fits, "{name} = {v:?} is not {}", kind.name());
        }
    }
    let planners: std::collections::BTreeSet<&str> = rows.iter().map(|r| r[col("planner")].as_str()).collect();
    assert_eq!(
        planners.into_iter().collect::<Vec<_>>(),
        ["fleet-central", "fleet-divide", "fleet-negotiate", "fleet-waypoint"]
    );
    for row in &rows {
        assert_eq!((row[col("fleet_name")].as_str(), row[col("fleet_robots")].as_str()), ("pair", "2"));
        let union: f64 = row[col("union_reach")].parse().unwrap();
        assert!(union > 0.0 && union <= 1.0, "{row:?}");
        let evaluations: u64 = row[col("evaluations")].parse().unwrap();
        let budget = if row[col("planner")] == "fleet-divide" { 0..=0 } else { 1500..=1700 };
        assert!(budget.contains(&evaluations), "{}: {evaluations}", row[col("planner")]);
        let rounds = &row[col("negotiation_rounds")];
        if row[col("planner")] == "fleet-negotiate" {
            assert!(rounds.parse::<u32>().unwrap() >= 1, "{row:?}");
            assert!(["true", "false"].contains(&row[col("negotiation_settled")].as_str()));
            assert!(row[col("negotiation_last_change")].parse::<f64>().unwrap() >= 0.0);
        } else {
            assert_eq!(rounds, "", "only a negotiation has rounds");
        }
    }
    // The report reads runs.csv: the raw run folders are not needed.
    std::fs::remove_dir_all(out.join("runs")).unwrap();
    ok(&covga(&["report", out.to_str().unwrap()]));
    let md = std::fs::read_to_string(out.join("report/summary.md")).unwrap();
    for needle in
        ["# Fleet study", "| pair | central | 2 |", "| pair | divide | 1 |", "## Pairwise tests", "## Convergence"]
    {
        assert!(md.contains(needle), "{needle} in\n{md}");
    }
    let convergence = md.lines().find(|l| l.starts_with("| thesis-1 | pair | 2 |")).expect("a convergence row");
    assert!(!convergence.contains('–') && !convergence.contains("0/0"), "{convergence}");
}

#[test]
fn ablation_smoke_runs_every_planner_with_the_same_columns() {
    let dir = tempfile::tempdir().unwrap();
    let grid = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("grids/ablation-smoke.toml");
    let out = dir.path().join("abl");
    let dry = covga(&["grid", grid.to_str().unwrap(), "--dry-run"]);
    ok(&dry);
    // (2 thesis GA + 2 waypoint + random search) x 2 seeds + 2 deterministic patterns once each.
    assert!(
        String::from_utf8_lossy(&dry.stdout).contains("12 runs (7 configurations"),
        "{}",
        String::from_utf8_lossy(&dry.stdout)
    );
    ok(&covga(&["grid", grid.to_str().unwrap(), "--jobs", "2", "--out", out.to_str().unwrap()]));
    let text = std::fs::read_to_string(out.join("runs.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let rows: Vec<Vec<String>> = lines.map(|l| l.split(',').map(str::to_string).collect()).collect();
    assert_eq!(rows.len(), 12);
    // The swept `planner` is the planner column itself, not a second column of that name.
    assert_eq!(header.iter().filter(|h| **h == "planner").count(), 1, "{header:?}");
    let col = |name: &str| header.iter().rposition(|h| *h == name).unwrap_or_else(|| panic!("{name}"));
    let planners: std::collections::BTreeSet<&str> = rows.iter().map(|r| r[col("planner")].as_str()).collect();
    assert_eq!(planners.len(), 5, "{planners:?}");
    for metric in [
        "cov_final_free",
        "cov_final_reach",
        "t_final",
        "f_reach",
        "cam_walls_free",
        "length_m",
        "time_s",
        "makespan_s",
        "evaluations",
        "executable",
        "planner_feasible",
    ] {
        for r in &rows {
            assert!(!r[col(metric)].is_empty(), "{metric} empty for {}", r[col("planner")]);
        }
    }
    // One executability rule for every planner: a row whose plan sweeps obstacle cells is not
    // executable, whatever its planner's own constraints say; every plan starts and ends at
    // the start station (1.3, 1.3).
    for r in &rows {
        let obstacles: u64 = r[col("obstacle_cells")].parse().unwrap();
        assert_eq!(r[col("executable")] == "true", obstacles == 0, "{}", r[col("planner")]);
        let path = std::fs::read_to_string(out.join("runs").join(&r[0]).join("best_path.csv")).unwrap();
        let points: Vec<&str> = path.lines().skip(1).collect();
        for p in [points[0], points[points.len() - 1]] {
            assert!(p.ends_with(",1.3,1.3"), "{}: {p}", r[col("planner")]);
        }
    }
    // The GAs respect the evaluation budget (they stop at the first iteration past it).
    for r in rows.iter().filter(|r| ["thesis", "random_search", "waypoint"].contains(&r[col("planner")].as_str())) {
        let e: u64 = r[col("evaluations")].parse().unwrap();
        assert!((3000..3000 + 1200).contains(&e), "{}: {e} evaluations", r[col("planner")]);
        assert_eq!(r[col("stop")], "evaluations");
    }
    // The 2 x 2 of search and objective is reported, its four cells in one table.
    ok(&covga(&["report", out.to_str().unwrap()]));
    let md = std::fs::read_to_string(out.join("report/summary.md")).unwrap();
    assert!(md.contains("## Search versus objective"), "{md}");
    let section = md.split("## Search versus objective").nth(1).unwrap().split("\n## ").next().unwrap();
    assert_eq!(section.lines().filter(|l| l.starts_with("| thesis-1 | ")).count(), 2, "{md}");
    // Every planner's plans have their time-to-coverage curves, one series per planner.
    assert!(out.join("report/coverage_curves.png").is_file());
    let curves = md.split("## Time to coverage").nth(1).unwrap().split("\n## ").next().unwrap();
    assert!(curves.lines().filter(|l| l.starts_with("| thesis-1 | ")).count() >= 2, "{curves}");
    // Each time beside its area bound (the study's grid file gives the robots and the map).
    assert!(curves.contains("×)") && !curves.contains("not given"), "{curves}");
    // Each pair of cells that differs in one factor gets a finding: the comparison, or why it
    // cannot be made on executable plans (the thesis GA's plans often touch a wall with the
    // robot's body at a vertex, which 003's penalty does not see).
    assert!(
        md.contains("the thesis GA (Elite) optimising the footprint against the same search optimising the camera")
            || md.contains(
                "the thesis GA (Elite) optimising the footprint and the same search optimising the camera cannot be compared"
            ),
        "{md}"
    );
    assert!(md.contains("with the footprint objective for both"), "{md}");
    // The common scorer gives a plan the same metrics whoever scores it: `covga eval` on a
    // waypoint plan agrees with the study's row.
    let wp = rows.iter().find(|r| r[col("planner")] == "waypoint").unwrap();
    let ev = covga(&[
        "eval",
        "--map",
        "thesis-1",
        "--projection",
        "f2",
        "--path",
        out.join("runs").join(&wp[0]).join("best_path.csv").to_str().unwrap(),
        "--json",
        "--out",
        dir.path().join("ev").to_str().unwrap(),
    ]);
    ok(&ev);
    let v: serde_json::Value = serde_json::from_slice(&ev.stdout).unwrap();
    for metric in ["cov_final_free", "cov_final_reach", "t_final", "f_reach", "cam_walls_free", "time_s"] {
        let a = v["common"][metric].as_f64().unwrap();
        let b: f64 = wp[col(metric)].parse().unwrap();
        assert!((a - b).abs() < 1e-12, "{metric}: eval {a} vs study {b}");
    }
    let rep = covga(&["report", out.to_str().unwrap()]);
    ok(&rep);
    let md = std::fs::read_to_string(out.join("report/summary.md")).unwrap();
    for section in ["## Planner comparison", "Mann–Whitney", "## Findings", "thesis", "random_search", "spiral"] {
        assert!(md.contains(section), "{section}");
    }
    for f in ["boxplots_cov.png", "convergence.png", "planner_paths.png", "planners.csv", "pairwise.csv"] {
        assert!(out.join("report").join(f).metadata().map(|m| m.len() > 100).unwrap_or(false), "{f}");
    }
}

#[test]
fn bad_planner_sections_are_rejected_with_the_key() {
    let dir = tempfile::tempdir().unwrap();
    for (text, needle) in [
        ("planner = \"random_search\"\n", "`budget.evaluations`"),
        ("planner = \"spiral\"\n[pattern]\nangle_deg = 1e9\n", "`pattern.angle_deg`"),
        ("planner = \"boustrophedon\"\n[pattern]\nlanes = 3\n", "lanes"),
        ("planner = \"genetic\"\n", "unknown variant `genetic`"),
        ("planner = \"waypoint\"\n[scorer.camera]\nsections = 0\n", "`scorer.camera.sections`"),
        // A key under its old name is checked under its new one, and the message says both.
        ("planner = \"waypoint\"\n[waypoint]\nsections = 0\n", "`scorer.camera.sections`"),
        ("planner = \"waypoint\"\n[waypoint]\nsections = 0\n", "`waypoint.sections`"),
    ] {
        let p = dir.path().join("bad.toml");
        std::fs::write(&p, text).unwrap();
        let o = covga(&["run", p.to_str().unwrap(), "--out", dir.path().join("o").to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{text}: {err}");
        assert!(err.contains(needle) && err.contains("bad.toml"), "{text}: expected `{needle}` in {err}");
    }
}

#[test]
fn a_study_folder_keeps_its_identity_and_one_writer() {
    let dir = tempfile::tempdir().unwrap();
    let g = grid_file(dir.path());
    let out = dir.path().join("s");
    ok(&covga(&["grid", g.to_str().unwrap(), "--out", out.to_str().unwrap(), "--jobs", "2"]));
    // Another grid (fewer iterations) into the same folder is refused and nothing changes.
    let other = dir.path().join("other.toml");
    std::fs::write(&other, GRID.replace("iterations = 60", "iterations = 30")).unwrap();
    let before = std::fs::read(out.join("runs.csv")).unwrap();
    let o = covga(&["grid", other.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("another study") && err.contains("g.toml") && err.contains("other.toml"), "{err}");
    assert_eq!(std::fs::read(out.join("runs.csv")).unwrap(), before);
    assert!(std::fs::read_to_string(out.join("grid.toml")).unwrap().contains("iterations = 60"));
    // While another process holds the study's lock, a second runner is refused.
    let fresh = dir.path().join("locked");
    std::fs::create_dir_all(&fresh).unwrap();
    let lock = covga::study::runner::StudyLock::take(&fresh.join("runs.csv")).unwrap();
    let o = covga(&["grid", g.to_str().unwrap(), "--out", fresh.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("another covga process"));
    assert!(!fresh.join("runs.csv").exists(), "nothing written while locked");
    drop(lock);
    ok(&covga(&["grid", g.to_str().unwrap(), "--out", fresh.to_str().unwrap()]));
    // A report of a folder that is not a study is refused.
    let o = covga(&["report", dir.path().to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("not a study folder"));
}

#[test]
fn merge_refuses_missing_shards_unless_partial() {
    let dir = tempfile::tempdir().unwrap();
    let g = grid_file(dir.path());
    let out = dir.path().join("sh");
    for k in [0, 2] {
        ok(&covga(&["grid", g.to_str().unwrap(), "--shard", &format!("{k}/3"), "--out", out.to_str().unwrap()]));
    }
    let m = covga(&["merge", out.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&m.stderr);
    assert_eq!(m.status.code(), Some(2), "{err}");
    assert!(err.contains("runs-shard-1-of-3.csv") && err.contains("of 12 runs"), "{err}");
    assert!(!out.join("runs.csv").exists(), "nothing merged");
    let m = covga(&["merge", out.to_str().unwrap(), "--allow-partial"]);
    ok(&m);
    assert!(String::from_utf8_lossy(&m.stderr).contains("partial merge, missing runs-shard-1-of-3.csv"));
    // The missing shard taken from another study (30 iterations): as many runs, not this
    // study's; refused, nothing merged.
    std::fs::remove_file(out.join("runs.csv")).unwrap();
    let other = dir.path().join("other.toml");
    std::fs::write(&other, GRID.replace("iterations = 60", "iterations = 30")).unwrap();
    let foreign = dir.path().join("foreign");
    ok(&covga(&["grid", other.to_str().unwrap(), "--shard", "1/3", "--out", foreign.to_str().unwrap()]));
    std::fs::copy(foreign.join("runs-shard-1-of-3.csv"), out.join("runs-shard-1-of-3.csv")).unwrap();
    let m = covga(&["merge", out.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&m.stderr);
    assert_eq!(m.status.code(), Some(2), "{err}");
    assert!(err.contains("runs of another study"), "{err}");
    assert!(!out.join("runs.csv").exists(), "nothing merged");
}
