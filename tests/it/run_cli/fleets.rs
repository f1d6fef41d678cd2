//! Fleets from an experiment file: negotiated and central plans repeat on any thread count and
//! write their results; bad fleets exit 2.

use super::*;

/// A small fleet experiment (two robots on map 1, 40 individuals each, 200 iterations).
fn fleet(extra: &str) -> String {
    format!(
        "{}[fleet]\nround_iterations = 50\n[[robots]]\nname = \"narrow\"\nwidth = 0.4\nstart = [1.3, 1.3]\n\
         [[robots]]\nname = \"wide\"\nwidth = 0.9\nspeed = 0.5\nstart = [9.55, 9.55]\n{extra}",
        small("")
    )
}

/// Runs `exp` with 1 and 2 threads into `dir/one` and `dir/two`, checks that the history, plan
/// and configuration files are identical, and returns both folders.
fn run_on_one_and_two_threads(dir: &Path, exp: &Path) -> (PathBuf, PathBuf) {
    let run = |threads: &str, out: &str| {
        let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", dir.join(out).to_str().unwrap()], threads);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        dir.join(out)
    };
    let (one, two) = (run("1", "one"), run("2", "two"));
    for file in ["history.csv", "best_path.csv", "config.toml"] {
        assert_eq!(read(&one.join(file)), read(&two.join(file)), "{file} with 1 and 2 threads");
    }
    (one, two)
}

#[test]
fn a_fleet_negotiates_deterministically_and_writes_its_results() {
    let dir = tempfile::tempdir().unwrap();
    let exp = write(dir.path(), "fleet.toml", &fleet(""));
    let (one, two) = run_on_one_and_two_threads(dir.path(), &exp);
    assert_eq!(summary_without_time(&one), summary_without_time(&two));
    let s = summary_without_time(&one);
    assert_eq!(s["fleet"]["robots"], serde_json::json!(["narrow", "wide"]));
    assert_eq!(s["rounds"].as_u64(), Some(4), "200 iterations in rounds of 50");
    let hist = read(&one.join("history.csv"));
    assert!(hist.starts_with("round,robot,iteration,evaluations,best_fitness,cov_final,t_final,change\n"));
    assert_eq!(hist.lines().count(), 1 + 4 * 2, "one row per round and robot");
    assert!(read(&one.join("best_path.csv")).starts_with("agent,robot,index,x_m,y_m\n"));
    assert!(one.join("path.png").exists());
}

#[test]
fn a_fleet_plans_centrally_deterministically_and_writes_its_results() {
    let dir = tempfile::tempdir().unwrap();
    let text = fleet("").replace("[fleet]\n", "[fleet]\nmode = \"central\"\n");
    let exp = write(dir.path(), "central.toml", &text);
    let (one, two) = run_on_one_and_two_threads(dir.path(), &exp);
    let s = summary_without_time(&one);
    assert_eq!(s, summary_without_time(&two));
    assert_eq!(s["planner"], "fleet-central");
    assert_eq!(s["fleet"]["robots"], serde_json::json!(["narrow", "wide"]));
    assert_eq!(s["iterations"].as_u64(), Some(200));
    assert_eq!(s["genome_len"].as_array().map(Vec::len), Some(2), "one genome per robot");
    let f = &s["fleet"];
    assert!(f["union_reach"].as_f64().unwrap() > 0.5, "{f}");
    assert_eq!(f["robot_time_s"].as_array().map(Vec::len), Some(2));
    assert_eq!(read(&one.join("history.csv")).lines().count(), 1 + 201, "one row per iteration");
    // Per generation and robot of the best crew; the last generation's genomes are the plan's.
    let robots = read(&one.join("robots_history.csv"));
    assert_eq!(robots.lines().next(), Some("iteration,robot,genome_len,swept_cells,t_actual_s"));
    assert_eq!(robots.lines().count(), 1 + 201 * 2);
    let last: Vec<Vec<&str>> = robots.lines().rev().take(2).map(|l| l.split(',').collect()).collect();
    assert_eq!((last[1][0], last[1][1], last[0][0], last[0][1]), ("200", "narrow", "200", "wide"));
    assert_eq!(last[1][2].parse::<u64>().ok(), s["genome_len"][0].as_u64());
    assert_eq!(last[0][2].parse::<u64>().ok(), s["genome_len"][1].as_u64());
    assert_eq!(robots, read(&two.join("robots_history.csv")));
    let paths = read(&one.join("best_path.csv"));
    assert!(paths.contains(",narrow,") && paths.contains(",wide,"));
    assert!(one.join("path.png").exists());
}

#[test]
fn bad_fleets_are_rejected_with_exit_2() {
    expect_error(&fleet("[[robots]]\nname = \"narrow\"\n"), "`robots[2].name`");
    expect_error(&fleet("[[robots]]\nname = \"x\"\nstart = [0.5, 5.0]\n"), "robots[2].start (robot \"x\")");
    expect_error(&fleet("").replace("round_iterations = 50", "round_iterations = 0"), "fleet.round_iterations");
    expect_error(&format!("planner = \"spiral\"\n{}", fleet("")), "cannot plan for [[robots]]");
    expect_error(&fleet("").replace("[fleet]\n", "[fleet]\nmode = \"waypoint\"\n"), "cannot plan for [[robots]]");
    expect_error(&fleet("").replace("[fleet]\n", "[fleet]\nname = \"a,b\"\n"), "fleet.name");
    expect_error(&fleet("").replace("[fleet]\n", "[fleet]\nmode = \"teleport\"\n"), "teleport");
    expect_error(&small("[fleet]\nround_iterations = 5"), "no [[robots]]");
}
