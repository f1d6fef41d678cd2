//! Studies that meet trouble: jobs clamped, shards and Slurm apart, incomplete studies reported, a run
//! that fails while planning recorded, a runs file with a run twice refused.

use super::*;

/// A grid of two boustrophedon runs on thesis-1 (deterministic, well under a second).
const TWO_PATTERN_RUNS: &str = "seed = 1\n[base]\nplanner = \"boustrophedon\"\n[base.map]\nsource = \"thesis-1\"\n[base.stations]\nstart = [1.3, 1.3]\n[axes]\n\"pattern.angle_deg\" = [0.0, 90.0]\n";

/// `--jobs` far above the run count starts no idle workers (clamped), `--shard` with `--slurm`
/// is refused (the array tasks are the shards), an `--array-size` above the run count is
/// clamped to it, and one above Slurm's default `MaxArraySize` warns.
#[test]
fn jobs_are_clamped_shards_and_slurm_exclude_each_other_and_large_arrays_warn() {
    let dir = tempfile::tempdir().unwrap();
    let grid = dir.path().join("tiny.toml");
    std::fs::write(&grid, TWO_PATTERN_RUNS).unwrap();
    let g = grid.to_str().unwrap();
    let out = dir.path().join("out");
    let started = std::time::Instant::now();
    ok(&covga(&["grid", g, "--jobs", "100000", "--out", out.to_str().unwrap()]));
    assert!(started.elapsed().as_secs_f64() < 5.0, "{:?}", started.elapsed());
    let both = covga(&["grid", g, "--shard", "0/2", "--slurm", "--out", dir.path().join("s").to_str().unwrap()]);
    assert_eq!(both.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&both.stderr).contains("cannot be used with"), "{both:?}");
    // More tasks than runs: clamped to one task per run.
    let small = covga(&["grid", g, "--slurm", "--array-size", "2000", "--out", dir.path().join("a").to_str().unwrap()]);
    ok(&small);
    assert!(String::from_utf8_lossy(&small.stderr).contains("clamped to the study's 2 runs"), "{small:?}");
    let script = std::fs::read_to_string(dir.path().join("a/study.sbatch")).unwrap();
    assert!(script.contains("#SBATCH --array=0-1\n"), "{script}");
    // A study of 1 200 runs asked for 1 100 tasks: beyond Slurm's default limit, warned.
    let many = dir.path().join("many.toml");
    std::fs::write(&many, "seeds = 1200\n[base]\n[base.thesis]\npop_min = 20\ninit_actions = 20\n[base.budget]\niterations = 3\n[axes]\n\"thesis.c_len\" = [0.1]\n").unwrap();
    let large = covga(&[
        "grid",
        many.to_str().unwrap(),
        "--slurm",
        "--array-size",
        "1100",
        "--out",
        dir.path().join("b").to_str().unwrap(),
    ]);
    ok(&large);
    assert!(String::from_utf8_lossy(&large.stderr).contains("MaxArraySize of 1001"), "{large:?}");
}

/// A report of a study with runs missing says so first; a runs.csv with a metric that is not a
/// finite number is refused, naming the run and the column.
#[test]
fn reports_mark_incomplete_studies_and_refuse_non_finite_metrics() {
    let dir = tempfile::tempdir().unwrap();
    let grid = dir.path().join("tiny.toml");
    std::fs::write(&grid, TWO_PATTERN_RUNS).unwrap();
    let out = dir.path().join("out");
    let o = out.to_str().unwrap();
    ok(&covga(&["grid", grid.to_str().unwrap(), "--out", o]));
    ok(&covga(&["report", o]));
    let summary = std::fs::read_to_string(out.join("report/summary.md")).unwrap();
    assert!(!summary.contains("Incomplete") && !summary.contains("No `runs/` folder"), "{summary}");
    // Without the runs' folders the report says that it has tables only.
    std::fs::rename(out.join("runs"), dir.path().join("runs-away")).unwrap();
    ok(&covga(&["report", o]));
    let summary = std::fs::read_to_string(out.join("report/summary.md")).unwrap();
    assert!(summary.contains("**No `runs/` folder in"), "{summary}");
    std::fs::rename(dir.path().join("runs-away"), out.join("runs")).unwrap();
    // One run lost (as after kill -9 before it was recorded).
    let runs = std::fs::read_to_string(out.join("runs.csv")).unwrap();
    let lines: Vec<&str> = runs.lines().collect();
    std::fs::write(out.join("runs.csv"), format!("{}\n{}\n", lines[0], lines[1])).unwrap();
    ok(&covga(&["report", o]));
    let summary = std::fs::read_to_string(out.join("report/summary.md")).unwrap();
    assert!(summary.contains("**Incomplete: 1 of 2 runs recorded.**"), "{summary}");
    // A metric that is not a number.
    let header: Vec<&str> = lines[0].split(',').collect();
    let k = header.iter().position(|h| *h == "time_s").unwrap();
    let mut cells: Vec<String> = lines[1].split(',').map(String::from).collect();
    cells[k] = "NaN".into();
    std::fs::write(out.join("runs.csv"), format!("{}\n{}\n", lines[0], cells.join(","))).unwrap();
    let bad = covga(&["report", o]);
    assert_eq!(bad.status.code(), Some(2), "{bad:?}");
    assert!(String::from_utf8_lossy(&bad.stderr).contains("`time_s` = NaN"), "{bad:?}");
}

/// Two fleet runs on thesis map 1 whose second robot ends beside the first one's start: the
/// centralised GA plans it; area division finds the end outside robot b's region only while
/// planning (a refusal validation cannot make without dividing the map).
const ONE_RUN_FAILS_WHILE_PLANNING: &str = r#"
[base]
planner = "thesis"
[base.thesis]
pop_min = 10
init_actions = 10
[base.budget]
iterations = 2
[[base.robots]]
name = "a"
start = [1.3, 1.3]
[[base.robots]]
name = "b"
start = [9.7, 9.5]
end = [1.6, 1.3]
[axes]
"fleet.mode" = ["central", "divide"]
"#;

#[test]
fn a_run_that_fails_while_planning_is_recorded_and_the_study_goes_on() {
    let dir = tempfile::tempdir().unwrap();
    let grid = dir.path().join("g.toml");
    std::fs::write(&grid, ONE_RUN_FAILS_WHILE_PLANNING).unwrap();
    let out = dir.path().join("out");
    let o = out.to_str().unwrap();
    let first = covga(&["grid", grid.to_str().unwrap(), "--out", o]);
    // Exit 2 after the other run is recorded, naming the runs file and the reason.
    assert_eq!(first.status.code(), Some(2), "{first:?}");
    let err = String::from_utf8_lossy(&first.stderr);
    assert!(
        err.contains("runs.csv: 1 of 2 runs failed while running") && err.contains("lies outside its region"),
        "{err}"
    );
    let runs = std::fs::read_to_string(out.join("runs.csv")).unwrap();
    assert_eq!(runs.lines().count(), 3, "{runs}");
    let failed: Vec<&str> = runs.lines().filter(|l| l.contains(",failed,")).collect();
    assert_eq!(failed.len(), 1, "{runs}");
    assert!(failed[0].contains("fleet-divide") || failed[0].contains(",divide,"), "{}", failed[0]);
    // The failed run leaves no folder behind; the other run has its files.
    assert_eq!(std::fs::read_dir(out.join("runs")).unwrap().count(), 1);
    // A resume runs nothing again and still says that a run failed.
    let again = covga(&["grid", grid.to_str().unwrap(), "--out", o]);
    assert_eq!(again.status.code(), Some(2), "{again:?}");
    assert!(String::from_utf8_lossy(&again.stdout).contains("2 already recorded, 0 run now"), "{again:?}");
    assert_eq!(std::fs::read_to_string(out.join("runs.csv")).unwrap(), runs);
    // The report counts the failed run and summarises the other.
    ok(&covga(&["report", o]));
    let summary = std::fs::read_to_string(out.join("report/summary.md")).unwrap();
    assert!(summary.contains("**1 recorded runs failed while running**"), "{summary}");
}

#[test]
fn a_resume_refuses_a_runs_file_holding_a_run_twice() {
    let dir = tempfile::tempdir().unwrap();
    let grid = dir.path().join("g.toml");
    std::fs::write(&grid, "[base]\nplanner = \"boustrophedon\"\n[axes]\n\"robot.speed\" = [0.2, 0.3]\n").unwrap();
    let out = dir.path().join("out");
    let args = ["grid", grid.to_str().unwrap(), "--out", out.to_str().unwrap()];
    ok(&covga(&args));
    let runs = std::fs::read_to_string(out.join("runs.csv")).unwrap();
    let last = runs.lines().last().unwrap();
    std::fs::write(out.join("runs.csv"), format!("{runs}{last}\n")).unwrap();
    let again = covga(&args);
    assert_eq!(again.status.code(), Some(2), "{again:?}");
    assert!(String::from_utf8_lossy(&again.stderr).contains("is recorded twice"), "{again:?}");
    // Nothing was rewritten.
    assert_eq!(std::fs::read_to_string(out.join("runs.csv")).unwrap(), format!("{runs}{last}\n"));
}
