//! End-to-end tests of the waypoint planner through `covga run`: improvement, determinism
//! across thread counts, outputs, and bad input.

use crate::common::covga_threads;
use std::path::Path;

/// A small single-agent run on the office preset.
fn small(extra: &str) -> String {
    format!(
        "seed = 3\nplanner = \"waypoint\"\n[map]\nsource = \"office\"\n[stations]\nstart = [2.0, 2.0]\n[waypoint]\npopulation = 20\ngenerations = 25\n{extra}\n"
    )
}

fn write(dir: &Path, text: &str) -> std::path::PathBuf {
    let p = dir.join("w.toml");
    std::fs::write(&p, text).unwrap();
    p
}

fn summary_without_time(dir: &Path) -> serde_json::Value {
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let o = v.as_object_mut().unwrap();
    o.remove("wall_s");
    o.remove("precompute_s");
    v
}

#[test]
fn single_agent_run_improves_and_is_deterministic() {
    let dir = tempfile::tempdir().unwrap();
    let exp = write(dir.path(), &small("l_init = 120"));
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    for (out, threads) in [(&a, "1"), (&b, "2")] {
        let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], threads);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    for f in ["config.toml", "history.csv", "best_path.csv"] {
        assert_eq!(
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
            "{f} differs between 1 and 2 threads"
        );
    }
    assert_eq!(summary_without_time(&a), summary_without_time(&b));
    for f in ["paths.png", "paths.svg", "coverage.png", "pareto_snapshots.png", "objectives.png"] {
        assert!(a.join(f).metadata().map(|m| m.len() > 1000).unwrap_or(false), "{f}");
    }
    let s = summary_without_time(&a);
    for key in ["wall_coverage", "open_coverage", "flight_time", "loop_closures_ok", "connected", "agents", "seed"] {
        assert!(s.get(key).is_some(), "{key}");
    }
    // Mean coverage rises over the first generations (the ramp forces it up from 0.3).
    let hist = std::fs::read_to_string(a.join("history.csv")).unwrap();
    let header: Vec<&str> = hist.lines().next().unwrap().split(',').collect();
    let k = header.iter().position(|h| *h == "mean_coverage").unwrap();
    let mean: Vec<f64> = hist.lines().skip(1).map(|l| l.split(',').nth(k).unwrap().parse().unwrap()).collect();
    assert_eq!(mean.len(), 26);
    assert!(mean[25] > mean[0] + 0.05, "mean coverage {} -> {}", mean[0], mean[25]);
    // The best path CSV has an agent column and starts at the entry waypoint region.
    let path = std::fs::read_to_string(a.join("best_path.csv")).unwrap();
    assert!(path.starts_with("agent,index,x_m,y_m"));
}

#[test]
fn three_agents_share_loop_closures() {
    let dir = tempfile::tempdir().unwrap();
    let exp = write(dir.path(), &small("agents = 3\nl_init = 80\nlc_separation = 15"));
    let out = dir.path().join("o");
    let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], "2");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s = summary_without_time(&out);
    assert_eq!(s["agents"], 3);
    // The loop-closure matrix of this seed, pinned: every pair of agents shares closures, so
    // the closure graph has one component (one zero eigenvalue of its Laplacian, 000 eq. 5).
    let closures: Vec<Vec<u64>> = serde_json::from_value(s["closures"].clone()).unwrap();
    assert_eq!(closures, vec![vec![3, 3, 26], vec![3, 2, 4], vec![26, 4, 15]]);
    for (i, row) in closures.iter().enumerate() {
        for (j, &c) in row.iter().enumerate() {
            assert_eq!(c, closures[j][i], "symmetric");
        }
    }
    assert_eq!(s["laplacian_zero_eigenvalues"], 1);
    assert_eq!(s["connected"], true);
    // Feasible means: every agent ≥ lc_min = 2 self closures, connected, coverage ≥ C_end = 0.8.
    let loops_ok = (0..3).all(|i| closures[i][i] >= 2);
    assert_eq!(s["loop_closures_ok"], loops_ok);
    let coverage = s["coverage"].as_f64().unwrap();
    assert_eq!(s["planner_feasible"], loops_ok && coverage >= 0.8);
    assert_eq!(s["planner_feasible"], true);
    assert!(s["violations"].as_array().unwrap().is_empty());
    let initial = s["initial_feasible"].as_u64().unwrap();
    assert!(initial <= 20, "at most the population: {initial}");
    let paths = std::fs::read_to_string(out.join("best_path.csv")).unwrap();
    let agents: std::collections::BTreeSet<&str> =
        paths.lines().skip(1).map(|l| l.split(',').next().unwrap()).collect();
    assert_eq!(agents.len(), 3);
    // The team is scored as a fleet of three of the experiment's robot; its union is the
    // common scorer's coverage and its makespan the common makespan.
    let f = &s["fleet"];
    assert_eq!(f["robots"], serde_json::json!(["agent 0", "agent 1", "agent 2"]));
    assert_eq!(f["cov_final"], s["score"]["cov_final_free"]);
    assert_eq!(f["makespan_s"], s["score"]["makespan_s"]);
    assert!(f["overlap_fraction"].as_f64().unwrap() > 0.0, "loop closures re-fly shared edges");
}

#[test]
fn bad_waypoint_settings_are_rejected() {
    for (extra, needle) in [
        // The camera's keys under their old names (in [waypoint]) are checked as [scorer.camera]'s.
        ("d_min = 8.0", "`scorer.camera.d_max` = 7 must exceed d_min"),
        ("fov_deg = 0.0", "`scorer.camera.fov_deg` = 0 is out of range (0, 360]"),
        ("fov_deg = 400.0", "`waypoint.fov_deg`, its name before the move"),
        ("hallway = 0.1", "below the cell size"),
        ("agents = 0", "`waypoint.agents` = 0 is out of range"),
        ("starts = [[0.1, 0.1]]", "inside an obstacle"),
        ("l_init = 10", "l_min"),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let exp = write(dir.path(), &small(extra));
        let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", dir.path().join("o").to_str().unwrap()], "1");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{extra}: {err}");
        assert!(err.contains(needle) && err.contains("w.toml"), "{extra}: expected `{needle}` in {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
    }
    // A start inside an obstacle through [stations].
    let dir = tempfile::tempdir().unwrap();
    let exp = write(dir.path(), &small("l_init = 120").replace("start = [2.0, 2.0]", "start = [15.0, 9.7]"));
    let o = covga_threads(&["run", exp.to_str().unwrap()], "1");
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("inside an obstacle"));
}

/// A camera depth far beyond the map sees what one reaching just past it sees, and costs no
/// more: views are computed with `d_max` capped at the map (thesis-1 is 11 m square, 15.6 m
/// across).
#[test]
fn a_camera_depth_beyond_the_map_sees_the_same_and_runs_quickly() {
    let dir = tempfile::tempdir().unwrap();
    let text = |d_max: &str| {
        format!(
            "seed = 5\nplanner = \"waypoint\"\n[map]\nsource = \"thesis-1\"\n[stations]\nstart = [1.3, 1.3]\n[waypoint]\npopulation = 10\ngenerations = 5\nl_init = 40\nl_min = 20\n[scorer.camera]\nd_max = {d_max}\n"
        )
    };
    let mut outs = Vec::new();
    for d_max in ["16.0", "1000.0"] {
        let sub = dir.path().join(d_max);
        std::fs::create_dir_all(&sub).unwrap();
        let exp = write(&sub, &text(d_max));
        let out = sub.join("out");
        let started = std::time::Instant::now();
        let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], "2");
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(started.elapsed().as_secs() < 30, "d_max = {d_max} took {:?}", started.elapsed());
        outs.push(out);
    }
    for f in ["history.csv", "best_path.csv"] {
        assert_eq!(std::fs::read(outs[0].join(f)).unwrap(), std::fs::read(outs[1].join(f)).unwrap(), "{f}");
    }
    let (mut a, mut b) = (summary_without_time(&outs[0]), summary_without_time(&outs[1]));
    for s in [&mut a, &mut b] {
        s.as_object_mut().unwrap().remove("config");
    }
    assert_eq!(a, b);
}

/// The waypoint planner reads `stations.end`: its plan ends there (the return leg is flown and
/// paid for like every other planner's), and no warning calls the key ignored.
#[test]
fn the_plan_ends_at_the_end_station_without_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let text = "seed = 3\nplanner = \"waypoint\"\n[map]\nsource = \"thesis-1\"\n[stations]\nstart = [2.0, 2.0]\nend = [8.0, 8.0]\n[waypoint]\npopulation = 10\ngenerations = 3\n";
    let file = write(dir.path(), text);
    let out = dir.path().join("out");
    let o = covga_threads(&["run", file.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], "1");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(!err.contains("stations.end"), "{err}");
    let path = std::fs::read_to_string(out.join("best_path.csv")).unwrap();
    let last: Vec<f64> = path.lines().last().unwrap().split(',').skip(2).map(|v| v.parse().unwrap()).collect();
    assert_eq!(last, vec![8.0, 8.0], "the plan ends at {last:?}");
    let first: Vec<f64> = path.lines().nth(1).unwrap().split(',').skip(2).map(|v| v.parse().unwrap()).collect();
    assert_eq!(first, vec![2.0, 2.0], "the plan starts at {first:?}");
}
