//! A study asked to stop (`RunnerOptions::stop`, set from another thread as the Python
//! package does on Ctrl-C) starts no further run, keeps the rows of the runs it finished, and
//! resumes to the same rows a study run at once records.

use crate::common::runner_options;
use covga::planner::executor::Interrupt;
use covga::study::grid::Study;
use covga::study::runner::{RunDone, RunnerOptions, StudyError, run_study};
use std::path::Path;

const GRID: &str = "seed = 2\n[base]\nplanner = \"boustrophedon\"\n[axes]\n\"map.source\" = [\"thesis-1\", \"thesis-2\"]\n\
                    \"pattern.angle_deg\" = [0.0, 45.0, 90.0]\n";

/// The rows of `runs.csv` without the wall-time column.
fn rows(dir: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(dir.join("runs.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let wall = header.iter().position(|h| *h == "wall_s").unwrap();
    lines.map(|l| l.split(',').enumerate().filter(|(i, _)| *i != wall).map(|(_, v)| v).collect()).collect()
}

#[test]
fn a_stopped_study_keeps_its_finished_runs_and_resumes_to_the_same_rows() {
    let tmp = tempfile::tempdir().unwrap();
    let grid = tmp.path().join("angles.toml");
    std::fs::write(&grid, GRID).unwrap();
    let study = Study::load(&grid).unwrap();
    assert_eq!(study.runs.len(), 6);
    let stop = Interrupt::new();
    let stop_after_first = |_: RunDone| stop.raise();
    let quiet = |_: RunDone| {};
    let folder = tmp.path().join("stopped");
    let opts = |out: &Path| runner_options(out, 1, &quiet);
    let stopping = RunnerOptions { on_done: &stop_after_first, stop: Some(&stop), ..opts(&folder) };
    match run_study(&study, &stopping) {
        Err(StudyError::Stopped { recorded }) => assert_eq!(recorded, 1),
        other => panic!("expected a stop, got {other:?}"),
    }
    assert_eq!(rows(&folder).len(), 1, "the finished run is recorded, the others are not");
    let resumed = run_study(&study, &opts(&folder)).unwrap();
    assert_eq!((resumed.skipped, resumed.completed), (1, 5));
    let at_once = tmp.path().join("at-once");
    run_study(&study, &opts(&at_once)).unwrap();
    assert_eq!(rows(&folder), rows(&at_once));
}

const LONG_GRID: &str = "seed = 4\nseeds = 2\n[base]\nplanner = \"thesis\"\n[base.map]\nsource = \"thesis-1\"\n\
                         [base.budget]\niterations = 1000000\n[axes]\n\"thesis.selection\" = [\"elite\", \"tournament\"]\n";

#[test]
fn a_stop_ends_the_runs_in_progress_unrecorded_and_leaves_no_run_folder() {
    let tmp = tempfile::tempdir().unwrap();
    let grid = tmp.path().join("long.toml");
    std::fs::write(&grid, LONG_GRID).unwrap();
    let study = Study::load(&grid).unwrap();
    let stop = Interrupt::new();
    let quiet = |_: RunDone| {};
    let folder = tmp.path().join("study");
    let opts = RunnerOptions { stop: Some(&stop), ..runner_options(&folder, 2, &quiet) };
    let started = std::time::Instant::now();
    let outcome = std::thread::scope(|scope| {
        // Raised once both runs are under way (their folders exist), so that the stop meets
        // runs in progress, not runs yet to start.
        let raiser = scope.spawn(|| {
            let in_progress = || std::fs::read_dir(folder.join("runs")).map_or(0, |d| d.count());
            while in_progress() < 2 && started.elapsed().as_secs() < 20 {
                std::thread::sleep(std::time::Duration::from_millis(10));
            }
            std::thread::sleep(std::time::Duration::from_millis(200));
            stop.raise();
        });
        let outcome = run_study(&study, &opts);
        raiser.join().unwrap();
        outcome
    });
    // Each run would take minutes (a million generations); the stop ends both within moments.
    assert!(started.elapsed().as_secs_f64() < 25.0, "stopped after {:?}", started.elapsed());
    match outcome {
        Err(StudyError::Stopped { recorded }) => assert_eq!(recorded, 0),
        other => panic!("expected a stop, got {other:?}"),
    }
    assert!(rows(&folder).is_empty(), "no interrupted run is recorded");
    let left: Vec<_> = std::fs::read_dir(folder.join("runs")).map(|d| d.flatten().collect()).unwrap_or_default();
    assert!(left.is_empty(), "no folder of an interrupted run is left: {left:?}");
}
