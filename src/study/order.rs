//! The order a study's runs are started in (`covga grid --order`).
//!
//! Workers take the runs one after another, so a study's wall time is a list schedule: when
//! a long run starts last, the other cores idle while it finishes. Starting the runs by
//! decreasing estimated time (longest processing time first) keeps that tail short; on the
//! ablation's recorded times the seed-by-seed order ends 1.31 times its lower bound on 16
//! cores and longest-first 1.001 times (`examples/schedule_simulation.rs`). The order never
//! changes a result: each run depends on its configuration and seed only, and `runs.csv` is
//! sorted by run id when the study completes.

use super::estimate::BranchTime;
use super::grid::{RunSpec, Study};
use super::runner::MapCache;
use std::collections::BTreeMap;
use std::path::Path;

/// The file `covga grid --dry-run --calibrate` writes its per-branch times to, in the study
/// folder, for a later `--order longest-first` to read.
pub const CALIBRATION_FILE: &str = "calibration.csv";

/// How the runs of a study are ordered (`--order`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum RunOrder {
    /// By decreasing estimated run time (ties: by replicate, then id), so that the last runs
    /// to start are short and few cores idle at the end. A study stopped part-way holds its
    /// longest configurations first.
    #[default]
    LongestFirst,
    /// Replicate by replicate, in id order within each: a study stopped part-way holds whole
    /// seeds first and, of the seed in progress, a uniform random sample of the configurations.
    Seeds,
}

impl RunOrder {
    /// The order `name` names as `--order` does (`longest-first`, `seeds`).
    pub fn from_name(name: &str) -> Option<Self> {
        use clap::ValueEnum;
        Self::value_variants().iter().copied().find(|o| o.to_possible_value().is_some_and(|v| v.get_name() == name))
    }
}

/// Where the estimates [`estimates`] gives come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EstimateSource {
    /// Recorded `wall_s` of the study folder's runs files and its calibration, in seconds.
    Records,
    /// No time is recorded: fitness evaluations (or iterations) times the map's free cells, a
    /// unitless work figure that ranks runs only.
    Budget,
}

/// An estimated cost per run id, and its source.
#[derive(Clone, Debug)]
pub struct Estimates {
    /// Cost of each run, by id.
    pub cost: BTreeMap<String, f64>,
    /// What the figures are.
    pub source: EstimateSource,
}

/// Estimated costs of `runs`: from the times recorded in `dir` (runs files of earlier sittings
/// or shards, and [`CALIBRATION_FILE`]) when there are any — the mean `wall_s` of the run's
/// configuration, else of its branch, else its [`budget_work`] at the recorded runs' seconds
/// per unit of work (a configuration run once, as a pattern is, may be the longest of a
/// study; the mean of all records would start it last) — and otherwise [`budget_work`].
pub fn estimates(study: &Study, runs: &[&RunSpec], dir: &Path, maps: &MapCache) -> Estimates {
    match recorded_means(study, dir, maps) {
        Some(means) => Estimates {
            cost: runs
                .iter()
                .map(|r| {
                    let t = means.config.get(&r.config_id).or_else(|| means.branch.get(&r.branch)).copied();
                    (r.id.clone(), t.unwrap_or_else(|| budget_work(r, maps) * means.seconds_per_work))
                })
                .collect(),
            source: EstimateSource::Records,
        },
        None => Estimates {
            cost: runs.iter().map(|r| (r.id.clone(), budget_work(r, maps))).collect(),
            source: EstimateSource::Budget,
        },
    }
}

/// Mean recorded seconds per configuration and per branch, and recorded seconds per unit of
/// [`budget_work`].
struct Means {
    config: BTreeMap<String, f64>,
    branch: BTreeMap<String, f64>,
    seconds_per_work: f64,
}

/// Means of the `wall_s` recorded in `dir`'s runs files, with the calibration's per-branch
/// means for branches no run of which is recorded; `None` when nothing is recorded.
fn recorded_means(study: &Study, dir: &Path, maps: &MapCache) -> Option<Means> {
    let (mut config, mut branch): (Sums, Sums) = Default::default();
    let (mut seconds, mut work) = (0.0, 0.0);
    for (run, w) in super::estimate::recorded_times(study, dir).unwrap_or_default() {
        add(&mut config, &run.config_id, w);
        add(&mut branch, &run.branch, w);
        seconds += w;
        work += budget_work(run, maps);
    }
    for b in read_calibration(&dir.join(CALIBRATION_FILE)) {
        if let Some(run) = study.runs.iter().find(|r| r.branch == b.branch)
            && !branch.contains_key(&b.branch)
        {
            seconds += b.seconds_per_run;
            work += budget_work(run, maps);
            branch.insert(b.branch, (b.seconds_per_run, 1));
        }
    }
    if branch.is_empty() {
        return None;
    }
    let mean = |m: Sums| m.into_iter().map(|(k, (s, n))| (k, s / n as f64)).collect();
    Some(Means { config: mean(config), branch: mean(branch), seconds_per_work: seconds / work.max(f64::MIN_POSITIVE) })
}

/// Sums of recorded seconds and their counts, by key.
type Sums = BTreeMap<String, (f64, usize)>;

fn add(m: &mut Sums, key: &str, w: f64) {
    let e = m.entry(key.to_string()).or_default();
    e.0 += w;
    e.1 += 1;
}

/// The work figure of a run when no time is recorded: the fitness evaluations it may spend
/// (else its iterations) times the free cells of its map, for the planners that search; the
/// map's free cells alone for the patterns, which plan once. It ranks runs of one study roughly (a
/// larger map or budget takes longer); a calibration or an earlier sitting ranks them better.
pub fn budget_work(run: &RunSpec, maps: &MapCache) -> f64 {
    let f = &run.file;
    let cells = maps.load(&f.map.source, &f.map.bare_image()).map_or(1.0, |m| m.free_count() as f64);
    let searched = if f.budget.evaluations > 0 { f.budget.evaluations as f64 } else { f64::from(f.budget.iterations) };
    // A planner that ignores the seed plans once, without a search.
    if f.planner.is_deterministic() { cells } else { searched.max(1.0) * cells }
}

/// Sorts `runs` into `order`; `cost` gives each run's estimate (longest first only).
pub fn sort_runs(runs: &mut [&RunSpec], order: RunOrder, cost: impl Fn(&RunSpec) -> f64) {
    let seeds = |a: &RunSpec, b: &RunSpec| a.replicate.cmp(&b.replicate).then_with(|| a.id.cmp(&b.id));
    match order {
        RunOrder::Seeds => runs.sort_by(|a, b| seeds(a, b)),
        RunOrder::LongestFirst => runs.sort_by(|a, b| cost(b).total_cmp(&cost(a)).then_with(|| seeds(a, b))),
    }
}

/// The wall time of running tasks of `times` (in the order given) on `jobs` workers, each
/// taking the next task as soon as it is free: what `covga grid --jobs` does.
pub fn list_schedule(times: &[f64], jobs: usize) -> f64 {
    let mut free = vec![0.0f64; jobs.max(1)];
    for &t in times {
        let first = free.iter().enumerate().min_by(|a, b| a.1.total_cmp(b.1)).map_or(0, |(i, _)| i);
        free[first] += t;
    }
    free.into_iter().fold(0.0, f64::max)
}

/// Writes per-branch times as [`CALIBRATION_FILE`] reads them.
pub fn calibration_csv(times: &[BranchTime]) -> String {
    let mut out = String::from("branch,runs,seconds_per_run,samples\n");
    for b in times {
        out.push_str(&format!(
            "\"{}\",{},{},{}\n",
            b.branch.replace('"', "\"\""),
            b.runs,
            b.seconds_per_run,
            b.samples
        ));
    }
    out
}

/// Per-branch times of a calibration file (none when it is absent or unreadable).
pub fn read_calibration(path: &Path) -> Vec<BranchTime> {
    let Ok(text) = std::fs::read_to_string(path) else { return Vec::new() };
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    reader
        .records()
        .flatten()
        .filter_map(|r| {
            Some(BranchTime {
                branch: r.get(0)?.to_string(),
                runs: r.get(1)?.parse().ok()?,
                seconds_per_run: r.get(2)?.parse().ok()?,
                samples: r.get(3)?.parse().ok()?,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests;
