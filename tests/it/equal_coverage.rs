//! Plans that stop at different coverage are compared at a common level: a newcomer's grid of
//! the boustrophedon pattern (which sweeps on to 97 % of the office) against the cell-order
//! planner stopped at a coverage goal of 0.9, run through `covga grid`, then `covga report`
//! with a comparison of the planners. Its findings, tests, box plots and comparison read the
//! time to 90 % of the reachable cells and say so; none sets the mission times of the two
//! plans against each other.

use crate::common::covga;

const GRID: &str = "seed = 7\nseeds = 2\n[base]\nplanner = \"boustrophedon\"\n[base.map]\nsource = \"office\"\n\
                    [base.stations]\nstart = [2.0, 2.0]\n[base.robot]\nwidth = 0.6\nspeed = 0.3\nrot_speed = 0.52\n\
                    [base.cell_order]\ncoverage_goal = 0.9\nsolver = \"nearest\"\n[base.budget]\niterations = 1000\n\
                    evaluations = 200\n[axes]\n\"planner\" = [\"boustrophedon\", \"cell_order\"]\n";

#[test]
fn a_goal_against_a_full_sweep_is_compared_at_the_goal() {
    let dir = tempfile::tempdir().unwrap();
    let grid = dir.path().join("grid.toml");
    std::fs::write(&grid, GRID).unwrap();
    let out = dir.path().join("out");
    let o = covga(&["grid", grid.to_str().unwrap(), "--jobs", "1", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // The progress names the coverage it prints: the common scorer's, of the reachable cells.
    let progress = String::from_utf8_lossy(&o.stderr);
    assert!(progress.contains(" cov_final_reach 0.") && !progress.contains(" cov_final 0."), "{progress}");
    let o = covga(&["report", out.to_str().unwrap(), "--by", "planner", "--compare", "planner=boustrophedon"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary = std::fs::read_to_string(out.join("report/summary.md")).unwrap();
    let findings = &summary[summary.find("## Findings").expect("a findings section")..];
    let line = findings.lines().find(|l| l.starts_with("- On office")).expect("the leaders' line");
    assert!(line.contains("time to 90 % of the reachable cells"), "{line}");
    assert!(!line.contains("shortest median time (") && !line.contains("shortest median mission time"), "{line}");
    assert!(
        summary.contains("time is the time to 90 % of the reachable cells (`time_to_90_s`"),
        "the table says which"
    );
    assert!(summary.contains("| time to 90 % [s] |"), "the planner table gives the time to the level");
    let compared = std::fs::read_to_string(out.join("report/compare-planner.md")).unwrap();
    assert!(compared.contains("time is `time_to_90_s`"), "{compared}");
    assert!(compared.contains("  - time to 90 %, stratum by stratum"), "{compared}");
    assert!(!compared.contains("## `time_s`"), "no section compares the whole missions");
    let csv = std::fs::read_to_string(out.join("report/compare-planner.csv")).unwrap();
    assert!(csv.lines().any(|l| l.contains(",time_to_90_s,")), "{csv}");
    assert!(!csv.lines().any(|l| l.contains(",time_s,")), "{csv}");
    assert!(out.join("report/boxplots_time.png").is_file());
    // The configurations' means on the summary's measures, each configuration's planner named.
    let conf = std::fs::read_to_string(out.join("report/configurations.csv")).unwrap();
    assert!(conf.starts_with("config_id,planner,n,cov_final_reach_mean,cov_final_reach_ci95,time_s_mean,"), "{conf}");
    assert!(conf.lines().skip(1).any(|l| l.split(',').nth(1) == Some("cell_order")), "{conf}");
}
