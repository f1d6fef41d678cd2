//! The fourth hardening pass (merge under the lock, report inputs, smaller findings): one case
//! per finding, each failing on the code before it.

use std::path::Path;
use std::process::{Output, Stdio};

use crate::common::covga_in as run;

/// The output of a command that succeeded.
pub(super) fn ok(o: &Output) -> String {
    assert!(o.status.success(), "{}\n{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The error output of a command that ended with exit code `code`.
pub(super) fn refused(o: &Output, code: i32) -> String {
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(code), "{err}");
    err
}

/// Writes `text` to `dir/name`, making its folder.
pub(super) fn write(dir: &Path, name: &str, text: &str) {
    let path = dir.join(name);
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, text).unwrap();
}

/// Waits (at most 20 s) until `file` exists and is not empty.
fn wait_for(file: &Path) {
    let begun = std::time::Instant::now();
    while !std::fs::read_to_string(file).is_ok_and(|t| !t.trim().is_empty()) {
        assert!(begun.elapsed().as_secs() < 20, "no {}", file.display());
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
}

/// Item 5: merge takes the study folder's lock, so it is refused (exit 2, naming the folder)
/// while a grid runs there, and leaves the grid's runs file alone.
#[test]
fn merge_is_refused_while_a_grid_runs_in_the_folder() {
    let dir = tempfile::tempdir().unwrap();
    let grid = "[base]\n[base.thesis]\npop_min = 40\ninit_actions = 30\n[base.budget]\niterations = 1000000\nwall_clock_s = 3\n[axes]\n\"thesis.c_len\" = [0.1, 0.4]\n";
    write(dir.path(), "g.toml", grid);
    let mut grid = crate::common::command()
        .current_dir(dir.path())
        .args(["grid", "g.toml", "--jobs", "1", "--out", "sl"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    wait_for(&dir.path().join("sl/.covga.lock"));
    // The grid writes its runs file's header before its first run: merge must leave it alone.
    let runs = dir.path().join("sl/runs.csv");
    wait_for(&runs);
    let before = std::fs::read(&runs).unwrap();
    let err = refused(&run(dir.path(), &["merge", "sl", "--allow-partial"]), 2);
    grid.kill().unwrap();
    grid.wait().unwrap();
    assert!(err.contains("sl: in use") && err.contains("another covga process"), "{err}");
    assert_eq!(std::fs::read(&runs).unwrap(), before, "merge wrote the runs file of a running grid");
}

/// Item 9: a merge of an unsharded study with runs still missing says to resume the study, not
/// to rerun shards it never had.
#[test]
fn merge_of_an_unsharded_study_says_to_resume_it() {
    let dir = tempfile::tempdir().unwrap();
    let header = covga::study::records::header(&[]);
    let row: Vec<String> = header.iter().map(|h| if h == "run_id" { "a".into() } else { String::new() }).collect();
    write(dir.path(), "S/runs.csv", &format!("{}\n{}\n", header.join(","), row.join(",")));
    write(dir.path(), "S/study.json", "{\"runs\": 3, \"grid_hash\": \"x\"}");
    let err = refused(&run(dir.path(), &["merge", "S"]), 2);
    assert!(err.contains("missing 2 of 3 runs") && err.contains("covga grid"), "{err}");
    assert!(!err.contains("shard"), "{err}");
}

/// Item 9: `covga gtsp` refuses one file for both the instance and its nodes.
#[test]
fn gtsp_refuses_one_file_for_the_instance_and_the_nodes() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "c.toml", "planner = \"cell_order\"\n");
    let err = refused(&run(dir.path(), &["gtsp", "c.toml", "--out", "x.gtsp", "--nodes", "./x.gtsp"]), 2);
    assert!(err.contains("--out x.gtsp and --nodes ./x.gtsp name the same file"), "{err}");
    assert!(!dir.path().join("x.gtsp").exists());
}

/// Item 9: a reference page that cannot be written is an error (exit 1), not a panic (101).
#[test]
fn a_reference_page_into_a_full_device_is_an_error_not_a_panic() {
    let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") else { return };
    let o = crate::common::command().args(["reference", "keys"]).stdout(full).output().unwrap();
    let err = refused(&o, 1);
    assert!(err.contains("cannot write the page to standard output") && !err.contains("panicked"), "{err}");
}

/// Item 9: a path of one point covers no area and has no multiple of its bound (not `NaN`).
#[test]
fn a_single_point_path_has_no_nan_multiple_of_the_bound() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "p.csv", "x_m,y_m\n5,5\n");
    let table = ok(&run(dir.path(), &["eval", "--map", "thesis-1", "--path", "p.csv", "--out", "E"]));
    let line = table.lines().find(|l| l.starts_with("× the bound")).expect("a bound line");
    assert!(!line.contains("NaN") && !line.contains("inf"), "{line}");
}

/// Item 10: `covga eval` without `--out` writes into a folder named after the map, so that a
/// second map's check keeps the first one's files.
#[test]
fn eval_writes_each_map_into_its_own_default_folder() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "p.csv", "x_m,y_m\n1.3,1.3\n3,1.3\n");
    for map in ["thesis-1", "thesis-2"] {
        let out = ok(&run(dir.path(), &["eval", "--map", map, "--path", "p.csv"]));
        assert!(out.contains(&format!("wrote out/eval-{map}/path.png")), "{out}");
    }
    for map in ["thesis-1", "thesis-2"] {
        let metrics = std::fs::read_to_string(dir.path().join(format!("out/eval-{map}/metrics.json"))).unwrap();
        assert!(metrics.contains(map), "{map}: {metrics}");
    }
}

/// Item 9: a coverage goal the scored plan does not reach is warned about (the cell-order
/// plan without a completion pass covers 0.977 of thesis map 1, short of a goal of 0.99).
#[test]
fn a_missed_coverage_goal_is_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let file = "planner = \"cell_order\"\nrobot.rot_speed = 0.52\n[cell_order]\nsolver = \"nearest\"\ncompletion = \"none\"\ncoverage_goal = 0.99\n";
    write(dir.path(), "a.toml", file);
    let o = run(dir.path(), &["run", "a.toml", "--out", "o", "--quiet"]);
    ok(&o);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("short of its coverage goal (cell_order.coverage_goal = 0.99)"), "{err}");
}
