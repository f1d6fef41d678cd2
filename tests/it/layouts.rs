//! The idealised lane control (`planner = "layouts"`, issue 102 item 1) end to end: it runs on
//! a small floor plan, its plan is executable by the body rule (the common scorer says so,
//! read back with `covga eval`), reaches its coverage goal, is the same plan for any seed, and
//! a setting out of range is refused with its key, its range and exit status 2.

use crate::common::{covga, run_text, summary};
use std::path::Path;

/// The lane control on the office preset, a turning robot, stopping at 90 % of the reachable
/// cells.
fn experiment(seed: u64) -> String {
    format!(
        "planner = \"layouts\"\nseed = {seed}\n[map]\nsource = \"office\"\n[robot]\nwidth = 0.6\nspeed = 0.3\n\
         rot_speed = 0.52\n[stations]\nstart = [2.0, 2.0]\n[layouts]\ncoverage_goal = 0.9\nlane_offsets = 4\n"
    )
}

fn run(text: &str) -> tempfile::TempDir {
    let tmp = tempfile::tempdir().unwrap();
    run_text(text, Path::new("."), tmp.path());
    tmp
}

#[test]
fn the_lane_control_is_executable_reaches_its_goal_and_reads_no_seed() {
    let (a, b, c) = (run(&experiment(1)), run(&experiment(1)), run(&experiment(7)));
    let s = summary(a.path());
    assert_eq!(s["score"]["executable"], true, "{s}");
    let reach = s["score"]["cov_final_reach"].as_f64().unwrap();
    assert!(reach >= 0.9 - 1e-9, "the plan stops at its goal, not short of it: {reach}");
    let to_goal = s["time_to_goal_s"].as_f64().expect("the goal is reached");
    let total = s["score"]["time_s"].as_f64().unwrap();
    assert!(to_goal > 0.0 && to_goal <= total, "{to_goal} of {total}");
    // The time to the goal is the fastest of the finalists the common scorer read.
    let finalists: Vec<f64> = s["finalists_time_s"].as_array().unwrap().iter().filter_map(|v| v.as_f64()).collect();
    assert!(!finalists.is_empty());
    assert!(finalists.iter().all(|&t| to_goal <= t + 1e-6), "{to_goal} vs {finalists:?}");
    let read = |d: &tempfile::TempDir, file: &str| std::fs::read(d.path().join(file)).unwrap();
    assert!(read(&a, "config.toml") == read(&b, "config.toml"), "config.toml differs for the same seed");
    for (other, what) in [(&b, "the same seed"), (&c, "another seed")] {
        for file in ["best_path.csv", "coverage_curve.csv"] {
            assert!(read(&a, file) == read(other, file), "{file} differs for {what}");
        }
    }
    // The common scorer, run on its own, agrees that a robot can drive it.
    let eval = covga(&[
        "eval",
        "--map",
        "office",
        "--start",
        "2.0,2.0",
        "--width",
        "0.6",
        "--json",
        "--path",
        a.path().join("best_path.csv").to_str().unwrap(),
    ]);
    assert!(eval.status.success(), "{}", String::from_utf8_lossy(&eval.stderr));
    let eval: serde_json::Value = serde_json::from_slice(&eval.stdout).unwrap();
    assert_eq!(eval["common"]["executable"], true);
    assert_eq!(eval["common"]["obstacle_cells"], 0);
}

#[test]
fn a_layouts_setting_out_of_range_is_refused_with_its_key() {
    for (key, value, needle) in [
        ("lane_spacing", "0.9", "layouts.lane_spacing"),
        ("lane_offsets", "0", "layouts.lane_offsets"),
        ("coverage_goal", "1.5", "layouts.coverage_goal"),
        ("directions", "[]", "layouts.directions"),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("bad.toml");
        let text = format!(
            "planner = \"layouts\"\n[map]\nsource = \"thesis-2\"\n[stations]\nstart = [1.3, 1.3]\n[layouts]\n{key} = {value}\n"
        );
        std::fs::write(&file, text).unwrap();
        let o = covga(&["run", file.to_str().unwrap(), "--out", dir.path().join("o").to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{key}: {err}");
        assert!(err.contains(needle) && err.contains("bad.toml"), "{key}: {err}");
        assert!(!dir.path().join("o").exists(), "no results for a bad file");
    }
}
