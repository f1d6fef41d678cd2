//! Helpers every integration test shares: the `covga` binary run with arguments (in a folder,
//! with a thread count), the repository root, an experiment run in-process from TOML text and
//! its `summary.json`. Included by both test binaries (`tests/it`, `tests/replays`); a binary
//! that uses only some of them allows the rest to go unused.
#![allow(dead_code)]

use covga::experiment::file::ExperimentFile;
use covga::experiment::output::run_experiment;
use std::collections::HashMap;
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::{Arc, Mutex, OnceLock};

/// The repository root (where `results/`, `grids/` and `experiments/` lie).
pub fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every file under `dir` (at any depth) whose name ends in `.ext`, sorted.
pub fn files_with_extension(dir: &Path, ext: &str) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut folders = vec![dir.to_path_buf()];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).unwrap_or_else(|e| panic!("{}: {e}", folder.display())) {
            let path = entry.unwrap().path();
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|e| e == ext) {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// The `covga` binary under test, not yet started.
pub fn command() -> Command {
    Command::new(env!("CARGO_BIN_EXE_covga"))
}

/// `covga grid GRID --dry-run` (GRID relative to the repository root, or absolute) into an
/// empty folder, run once per test process and remembered: several tests read the dry runs of
/// the shipped grids, some of which check tens of thousands of runs.
pub fn grid_dry_run(grid: &Path) -> Output {
    type Slots = Mutex<HashMap<PathBuf, Arc<OnceLock<Output>>>>;
    static RUNS: OnceLock<Slots> = OnceLock::new();
    let path = repo().join(grid);
    let slot = RUNS.get_or_init(Slots::default).lock().expect("dry runs").entry(path.clone()).or_default().clone();
    slot.get_or_init(|| {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let out = dir.path().join("study");
        command()
            .current_dir(repo())
            .args([OsStr::new("grid"), path.as_os_str(), OsStr::new("--dry-run"), OsStr::new("--out"), out.as_os_str()])
            .output()
            .expect("covga runs")
    })
    .clone()
}

/// `covga ARGS` in the test's working directory (the repository root), run to the end.
pub fn covga<S: AsRef<OsStr>>(args: &[S]) -> Output {
    command().args(args).output().expect("covga runs")
}

/// `covga ARGS` run in `dir`.
pub fn covga_in<S: AsRef<OsStr>>(dir: &Path, args: &[S]) -> Output {
    command().current_dir(dir).args(args).output().expect("covga runs")
}

/// `covga ARGS` with `RAYON_NUM_THREADS = threads`.
pub fn covga_threads<S: AsRef<OsStr>>(args: &[S], threads: &str) -> Output {
    command().args(args).env("RAYON_NUM_THREADS", threads).output().expect("covga runs")
}

/// Fails the test with both streams unless the command succeeded.
pub fn assert_success(o: &Output) {
    assert!(
        o.status.success(),
        "stdout: {}\nstderr: {}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
}

/// Runs the experiment written as TOML `text` (relative paths read from `base`) in-process,
/// writing its files into `out`.
pub fn run_text(text: &str, base: &Path, out: &Path) {
    let exp = ExperimentFile::parse(text, "test.toml").unwrap().validate("test.toml", base, "t").unwrap();
    run_experiment(&exp, out, false, &mut []).unwrap();
}

/// The `summary.json` of the run folder `dir`.
pub fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

/// The options of an in-process study run into `out`: `jobs` at a time, each finished run handed
/// to `on_done`, started in seed order, no shard, stop or memory limit.
pub fn runner_options<'a>(
    out: &Path,
    jobs: usize,
    on_done: &'a (dyn Fn(covga::study::runner::RunDone) + Sync),
) -> covga::study::runner::RunnerOptions<'a> {
    covga::study::runner::RunnerOptions {
        jobs,
        shard: None,
        out: out.to_path_buf(),
        max_memory: None,
        on_done,
        stop: None,
        order: covga::study::order::RunOrder::Seeds,
        abort_after_runs: None,
        retry_failed: false,
    }
}
pub mod raster_cases;
pub mod sweepable;
