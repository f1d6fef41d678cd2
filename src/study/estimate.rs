//! Run-time estimates for `covga grid --dry-run`: from runs already recorded in the study
//! folder, or from a calibration that runs a sample of each branch at full length, exactly as
//! the study would (same output files, history and diversity included, no figures), one run
//! at a time on one thread.
//!
//! Short runs extrapolated linearly under-predicted by half: a GA's cost per iteration is not
//! constant over a run, and the per-generation work of the history writer was not timed.

use super::grid::{RunSpec, Study};
use super::records::RunsTable;
use super::runner::{MapCache, StudyError, experiment_of};
use std::collections::BTreeMap;
use std::path::Path;
use std::time::Instant;

/// Seconds per run for each branch, and where the figure comes from.
#[derive(Clone, Debug)]
pub struct BranchTime {
    /// Branch label.
    pub branch: String,
    /// Runs in the branch.
    pub runs: usize,
    /// Estimated seconds for one run on one core.
    pub seconds_per_run: f64,
    /// Runs the figure is based on.
    pub samples: usize,
}

/// Total CPU seconds of the estimate.
pub fn cpu_seconds(times: &[BranchTime]) -> f64 {
    times.iter().map(|b| b.seconds_per_run * b.runs as f64).sum()
}

/// Wall seconds with `jobs` runs in parallel (each run on one core), if the work divided
/// evenly: the lower bound of any order but for the longest run.
pub fn wall_seconds(times: &[BranchTime], jobs: usize) -> f64 {
    cpu_seconds(times) / jobs.max(1) as f64
}

/// Wall seconds of the study's runs, each taking its branch's time, started in `order` on
/// `jobs` workers ([`super::order::list_schedule`]).
pub fn scheduled_wall_seconds(study: &Study, times: &[BranchTime], jobs: usize, order: super::order::RunOrder) -> f64 {
    let per: BTreeMap<&str, f64> = times.iter().map(|b| (b.branch.as_str(), b.seconds_per_run)).collect();
    let of = |r: &super::grid::RunSpec| per.get(r.branch.as_str()).copied().unwrap_or(0.0);
    let mut runs: Vec<&super::grid::RunSpec> = study.runs.iter().collect();
    super::order::sort_runs(&mut runs, order, of);
    super::order::list_schedule(&runs.iter().map(|r| of(r)).collect::<Vec<_>>(), jobs)
}

/// The `wall_s` of every run of `study` recorded in `dir`'s runs files (`runs.csv` and the
/// shards' `runs-shard-*.csv`, in name order); `None` when a runs file cannot be read.
pub fn recorded_times<'a>(study: &'a Study, dir: &Path) -> Option<Vec<(&'a RunSpec, f64)>> {
    let spec: BTreeMap<&str, &RunSpec> = study.runs.iter().map(|r| (r.id.as_str(), r)).collect();
    let mut names: Vec<std::path::PathBuf> = std::fs::read_dir(dir)
        .ok()?
        .flatten()
        .filter(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            name == "runs.csv" || name.starts_with("runs-shard-")
        })
        .map(|e| e.path())
        .collect();
    names.sort();
    let mut out = Vec::new();
    for path in names {
        let table = RunsTable::parse(&std::fs::read_to_string(path).ok()?).ok()?;
        let id = table.col("run_id")?;
        for row in &table.rows {
            if let (Some(run), Some(w)) = (spec.get(row[id].as_str()), table.num(row, "wall_s")) {
                out.push((*run, w));
            }
        }
    }
    Some(out)
}

/// Mean `wall_s` per branch over runs already recorded in `dir` (any runs file).
pub fn from_records(study: &Study, dir: &Path) -> Option<Vec<BranchTime>> {
    let mut acc: BTreeMap<String, (f64, usize)> = BTreeMap::new();
    for (run, w) in recorded_times(study, dir)? {
        let e = acc.entry(run.branch.clone()).or_default();
        e.0 += w;
        e.1 += 1;
    }
    let overall = acc.values().fold((0.0, 0), |(s, n), (a, b)| (s + a, n + b));
    if overall.1 == 0 {
        return None;
    }
    Some(
        study
            .branches()
            .into_iter()
            .map(|(branch, runs)| {
                let (s, n) = acc.get(&branch).copied().unwrap_or(overall);
                BranchTime { branch, runs, seconds_per_run: s / n as f64, samples: n }
            })
            .collect(),
    )
}

/// Fewest runs [`calibrate`] times per branch.
pub const CALIBRATION_MIN_RUNS: usize = 5;
/// Most runs [`calibrate`] times per branch.
pub const CALIBRATION_MAX_RUNS: usize = 30;
/// [`calibrate`] stops sampling a branch once the standard error of its mean run time is at
/// most this fraction of the mean (run times within a Table 4.3 grid spread by about half
/// their mean, so a fixed sample of three missed by 30 %).
pub const CALIBRATION_REL_ERROR: f64 = 0.08;
/// …or once it has spent this many seconds on the branch.
pub const CALIBRATION_BRANCH_SECONDS: f64 = 300.0;

/// Times runs of every branch at full length, one at a time on one thread, exactly as the
/// study runs them (outputs in a temporary folder that is removed). Runs are drawn at random
/// with a fixed seed, so the sample spreads over the axes and is the same every time; each
/// branch is sampled until the mean is known to [`CALIBRATION_REL_ERROR`] (at least
/// [`CALIBRATION_MIN_RUNS`], at most [`CALIBRATION_MAX_RUNS`] runs or
/// [`CALIBRATION_BRANCH_SECONDS`]).
pub fn calibrate(study: &Study) -> Result<Vec<BranchTime>, StudyError> {
    use rand::seq::SliceRandom;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .map_err(|e| StudyError::Run { id: String::new(), message: e.to_string() })?;
    let maps = MapCache::default();
    let scratch = std::env::temp_dir().join(format!("covga-calibrate-{}", std::process::id()));
    let mut rng = crate::ga::rng::stream(0xCA1B, crate::ga::rng::Purpose::Main, &[]);
    let mut out = Vec::new();
    for (branch, runs) in study.branches() {
        let mut members: Vec<_> = study.runs.iter().filter(|r| r.branch == branch).collect();
        members.shuffle(&mut rng);
        let mut times: Vec<f64> = Vec::new();
        for run in members.into_iter().take(CALIBRATION_MAX_RUNS) {
            let exp = experiment_of(study, run, &maps)?;
            let dir = scratch.join(&run.id);
            let started = Instant::now();
            let result = pool.install(|| crate::experiment::output::run_experiment(&exp, &dir, false, &mut []));
            times.push(started.elapsed().as_secs_f64());
            let _ = std::fs::remove_dir_all(&dir);
            result.map_err(|e| StudyError::Run { id: run.id.clone(), message: e.to_string() })?;
            if times.len() >= CALIBRATION_MIN_RUNS
                && (relative_standard_error(&times) <= CALIBRATION_REL_ERROR
                    || times.iter().sum::<f64>() >= CALIBRATION_BRANCH_SECONDS)
            {
                break;
            }
        }
        let mean = times.iter().sum::<f64>() / times.len() as f64;
        out.push(BranchTime { branch, runs, seconds_per_run: mean, samples: times.len() });
    }
    let _ = std::fs::remove_dir_all(&scratch);
    Ok(out)
}

/// Standard error of the mean over the mean (0 for fewer than two values or a zero mean).
fn relative_standard_error(x: &[f64]) -> f64 {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    if x.len() < 2 || mean <= 0.0 {
        return 0.0;
    }
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (var / n).sqrt() / mean
}

/// Human-readable duration.
pub fn human(seconds: f64) -> String {
    if seconds < 120.0 {
        format!("{seconds:.1} s")
    } else if seconds < 7200.0 {
        format!("{:.1} min", seconds / 60.0)
    } else {
        format!("{:.2} h", seconds / 3600.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_standard_error_by_hand() {
        // mean 2, sample sd 1, n 4: se = 0.5, relative 0.25.
        assert!((relative_standard_error(&[1.0, 2.0, 3.0, 2.0]) - (2.0f64 / 3.0).sqrt() / 2.0 / 2.0).abs() < 1e-12);
        assert_eq!(relative_standard_error(&[5.0]), 0.0);
        assert_eq!(relative_standard_error(&[3.0, 3.0, 3.0]), 0.0);
    }

    /// Per-branch means of the recorded run times; a branch without records takes the mean
    /// of all records. Two Elite runs and four tournament runs (2 sizes × 2 C_len).
    #[test]
    fn estimates_from_records_by_hand() {
        let grid = "[base]\n[base.thesis]\npop_min = 20\n[axes]\n\"thesis.selection\" = [\"elite\", \"tournament\"]\n\"thesis.c_len\" = [0.1, 0.4]\n[[conditional]]\nwhen = { \"thesis.selection\" = \"tournament\" }\naxes = { \"thesis.tournament_size\" = [2, 5] }\n";
        let study = Study::parse(grid, Path::new("g.toml")).unwrap();
        let of = |branch: &str| -> Vec<&str> {
            study.runs.iter().filter(|r| r.branch == branch).map(|r| r.id.as_str()).collect()
        };
        let (elite, turn) = (of("no conditional axes"), of("thesis.selection=tournament"));
        assert_eq!((elite.len(), turn.len()), (2, 4));
        let dir = tempfile::tempdir().unwrap();
        assert!(from_records(&study, dir.path()).is_none(), "nothing recorded: no estimate");
        let write = |rows: &[(&str, f64)]| {
            let mut csv = String::from("run_id,wall_s\n");
            for (id, w) in rows {
                csv.push_str(&format!("{id},{w}\n"));
            }
            std::fs::write(dir.path().join("runs.csv"), csv).unwrap();
        };
        write(&[(elite[0], 2.0), (turn[0], 1.0), (turn[1], 3.0)]);
        let times = from_records(&study, dir.path()).unwrap();
        let by: BTreeMap<&str, &BranchTime> = times.iter().map(|b| (b.branch.as_str(), b)).collect();
        let (e, t) = (by["no conditional axes"], by["thesis.selection=tournament"]);
        assert_eq!((e.runs, e.seconds_per_run, e.samples), (2, 2.0, 1));
        assert_eq!((t.runs, t.seconds_per_run, t.samples), (4, 2.0, 2));
        assert_eq!(cpu_seconds(&times), 12.0);
        assert_eq!(wall_seconds(&times, 2), 6.0);
        // Only tournament runs recorded: Elite takes the overall mean (1 + 5) / 2 = 3.
        write(&[(turn[0], 1.0), (turn[1], 5.0)]);
        let times = from_records(&study, dir.path()).unwrap();
        assert_eq!(cpu_seconds(&times), 2.0 * 3.0 + 4.0 * 3.0);
        assert_eq!(human(90.0), "90.0 s");
        assert_eq!(human(600.0), "10.0 min");
        assert_eq!(human(10800.0), "3.00 h");
    }
}
