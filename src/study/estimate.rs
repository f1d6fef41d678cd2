//! Run-time estimates for `covga grid --dry-run`: from runs already recorded in the study
//! folder, or from a calibration of three short runs per branch, timed on one thread and
//! extrapolated as `t_init + (t_short − t_init)·full / short`, where `full / short` is the
//! ratio of evaluation budgets when the study fixes evaluations, else of iterations
//! (deterministic planners are timed whole).

use super::grid::Study;
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

/// Wall seconds with `jobs` runs in parallel (each run on one core).
pub fn wall_seconds(times: &[BranchTime], jobs: usize) -> f64 {
    cpu_seconds(times) / jobs.max(1) as f64
}

/// Mean `wall_s` per branch over runs already recorded in `dir` (any runs file).
pub fn from_records(study: &Study, dir: &Path) -> Option<Vec<BranchTime>> {
    let branch_of: BTreeMap<&str, &str> = study.runs.iter().map(|r| (r.id.as_str(), r.branch.as_str())).collect();
    let mut acc: BTreeMap<String, (f64, usize)> = BTreeMap::new();
    for entry in std::fs::read_dir(dir).ok()?.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if !(name == "runs.csv" || name.starts_with("runs-shard-")) {
            continue;
        }
        let table = RunsTable::parse(&std::fs::read_to_string(entry.path()).ok()?).ok()?;
        for row in &table.rows {
            let id = &row[table.col("run_id")?];
            if let (Some(b), Some(w)) = (branch_of.get(id.as_str()), table.num(row, "wall_s")) {
                let e = acc.entry(b.to_string()).or_default();
                e.0 += w;
                e.1 += 1;
            }
        }
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

/// Times three short runs per branch (one thread) and extrapolates to the full budget.
pub fn calibrate(study: &Study) -> Result<Vec<BranchTime>, StudyError> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .map_err(|e| StudyError::Run { id: String::new(), message: e.to_string() })?;
    let maps = MapCache::default();
    let mut out = Vec::new();
    for (branch, runs) in study.branches() {
        let members: Vec<_> = study.runs.iter().filter(|r| r.branch == branch).collect();
        let picks = [members.len() / 6, members.len() / 2, (5 * members.len()) / 6];
        let mut total = 0.0;
        for &k in &picks {
            let run = members[k.min(members.len() - 1)];
            let exp = experiment_of(study, run, &maps)?;
            let planner = exp.planner.planner();
            let time = |budget: crate::planner::Budget| {
                let t = Instant::now();
                pool.install(|| planner.run(&exp.scenario, exp.seed, &budget, &mut []))
                    .map(|_| t.elapsed().as_secs_f64())
            };
            let io = |e: crate::planner::PlannerError| StudyError::Run { id: run.id.clone(), message: e.to_string() };
            if planner.deterministic() {
                total += time(exp.budget).map_err(io)?;
                continue;
            }
            // Set-up and initial population: a budget of one evaluation stops every GA there.
            let init = crate::planner::Budget { iterations: 0, evaluations: Some(1), ..exp.budget };
            let t_init = time(init).map_err(io)?;
            // A tenth of the budget (evaluations when the study fixes them, else iterations),
            // extrapolated linearly beyond the set-up.
            let (short, scale) = match exp.budget.evaluations {
                Some(e) => {
                    let short = (e / 10).max(1);
                    (crate::planner::Budget { evaluations: Some(short), ..exp.budget }, e as f64 / short as f64)
                }
                None => {
                    let full = exp.budget.iterations;
                    let short = (full / 10).clamp(1, 200).min(full.max(1));
                    (crate::planner::Budget { iterations: short, ..exp.budget }, f64::from(full) / f64::from(short))
                }
            };
            let t_short = time(short).map_err(io)?;
            total += t_init + (t_short - t_init).max(0.0) * scale;
        }
        out.push(BranchTime { branch, runs, seconds_per_run: total / picks.len() as f64, samples: picks.len() });
    }
    Ok(out)
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
