//! Running a study: `--jobs` runs at once (worker threads, each run on one thread of its
//! own), each finished run's files under `runs/<id>/` and its row appended to the runs file
//! (write, flush, fsync), resumable (recorded ids are skipped, a half-written last line
//! dropped), shardable (`--shard K/N` takes every N-th id in sorted order and writes
//! `runs-shard-K-of-N.csv`). When all of a study's (or shard's) runs are recorded the file is
//! rewritten sorted by run id, so its bytes do not depend on the number of jobs. Nothing is
//! printed; progress goes to a callback.

use super::grid::{RunSpec, Study};
use super::records::{RunsTable, csv_line, failed_row, header, row};
use crate::config::ConfigError;
use crate::experiment::file::Experiment;
use crate::planner::Checks;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// Failure of a study.
#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    /// Bad grid or experiment values.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// The existing runs file does not belong to this grid.
    #[error("{path}: {message}")]
    Mismatch {
        /// The file.
        path: PathBuf,
        /// What does not match.
        message: String,
    },
    /// The study folder cannot be made (a file is in the way, no permission: the user's
    /// environment, not an internal fault).
    #[error("{path}: cannot create the study folder: {source}")]
    Folder {
        /// The folder.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A run failed.
    #[error("run {id}: {message}")]
    Run {
        /// The run id.
        id: String,
        /// What failed.
        message: String,
    },
    /// The caller asked the runner to stop (`RunnerOptions::stop`); the runs finished before
    /// are recorded, and running the study again resumes it.
    #[error("stopped after {recorded} new runs; run the study again to resume it")]
    Stopped {
        /// Runs recorded by this invocation before it stopped.
        recorded: usize,
    },
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> StudyError + '_ {
    move |source| StudyError::Io { path: path.to_path_buf(), source }
}

/// A shard: `index` of `count`, 0-based.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// This shard, `0 ≤ index < count`.
    pub index: usize,
    /// Number of shards.
    pub count: usize,
}

impl Shard {
    /// Parses `K/N` with `0 ≤ K < N`.
    pub fn parse(s: &str) -> Result<Self, String> {
        let (k, n) = s.split_once('/').ok_or_else(|| format!("--shard `{s}` is not K/N"))?;
        let (index, count) = (k.trim().parse::<usize>(), n.trim().parse::<usize>());
        match (index, count) {
            (Ok(index), Ok(count)) if count > 0 && index < count => Ok(Self { index, count }),
            _ => Err(format!("--shard `{s}`: expected K/N with 0 <= K < N (Slurm's array task id and count)")),
        }
    }
    /// The runs file of this shard.
    pub fn file_name(&self) -> String {
        format!("runs-shard-{}-of-{}.csv", self.index, self.count)
    }
}

/// Progress of a study, handed to the caller after every run.
pub struct RunDone<'a> {
    /// The run.
    pub run: &'a RunSpec,
    /// Runs finished in this invocation so far.
    pub done: usize,
    /// Runs to do in this invocation.
    pub total: usize,
    /// Already recorded before this invocation.
    pub skipped: usize,
    /// `cov_final_reach`, `t_final`, wall seconds.
    pub result: (f64, f64, f64),
    /// Why the run failed, when it failed while running (its row records it).
    pub failure: Option<&'a str>,
}

/// How a study is run.
pub struct RunnerOptions<'a> {
    /// Parallel runs.
    pub jobs: usize,
    /// Optional shard.
    pub shard: Option<Shard>,
    /// Study folder.
    pub out: PathBuf,
    /// The memory limit in bytes (`--max-memory`); `None`: the memory available.
    pub max_memory: Option<u64>,
    /// Called after each finished run (from worker threads).
    pub on_done: &'a (dyn Fn(RunDone) + Sync),
    /// When raised (from another thread: Ctrl-C), no further run starts and the runs in
    /// progress stop at their next iteration, unrecorded, their folders removed; the runs
    /// finished before stay recorded, and the runner returns [`StudyError::Stopped`].
    pub stop: Option<&'a crate::planner::executor::Interrupt>,
    /// The order the runs start in (results never depend on it).
    pub order: super::order::RunOrder,
    /// Fault injection for crash-and-resume tests: abort the process, as a kill would, right
    /// after this many runs were recorded by this invocation (`covga grid --abort-after-runs`,
    /// hidden). `None` in every real use.
    pub abort_after_runs: Option<usize>,
    /// Run again the runs recorded as failed (`stop` = failed): their rows are taken out of
    /// the runs file first (`covga grid --retry-failed`), after a fix to what made them fail.
    pub retry_failed: bool,
}

/// What a study invocation did.
#[derive(Debug, Clone)]
pub struct StudyOutcome {
    /// Runs in the study or shard.
    pub selected: usize,
    /// Runs already recorded.
    pub skipped: usize,
    /// Runs completed now.
    pub completed: usize,
    /// Rows of the runs file, now and before, of runs that failed while running.
    pub failed: usize,
    /// The first of them by run id, with its reason.
    pub first_failure: Option<(String, String)>,
}

/// A recorded run's `cov_final_reach`, `t_final` and wall seconds, and why it failed if it did.
type RunResult = ((f64, f64, f64), Option<String>);

/// Maps loaded once per study and shared by its runs.
#[derive(Default)]
pub struct MapCache(Mutex<std::collections::HashMap<MapKey, crate::map::GridMap>>);

/// A map's source with the bits of its bare-image resolution and its free threshold.
type MapKey = (String, Option<u64>, Option<u8>);

impl MapCache {
    /// Loads a map, or clones the one loaded before.
    pub fn load(
        &self,
        source: &str,
        image: &crate::map::ros::BareImage,
    ) -> Result<crate::map::GridMap, crate::map::MapError> {
        let key = (source.to_string(), image.resolution.map(f64::to_bits), image.free_threshold);
        if let Some(m) = self.0.lock().expect("map cache").get(&key) {
            return Ok(m.clone());
        }
        let m = crate::map::ros::load_map(source, image)?;
        self.0.lock().expect("map cache").insert(key, m.clone());
        Ok(m)
    }
}

/// Validates a run's experiment.
pub fn experiment_of(study: &Study, run: &RunSpec, maps: &MapCache) -> Result<Experiment, ConfigError> {
    checked_experiment_of(study, run, maps, Checks::Full)
}

/// Validates a run's experiment as deep as `checks` asks.
fn checked_experiment_of(
    study: &Study,
    run: &RunSpec,
    maps: &MapCache,
    checks: Checks,
) -> Result<Experiment, ConfigError> {
    let origin = format!("{} (run {})", study.path.display(), run.id);
    run.file.clone().validate_with(&origin, Path::new("."), &run.id, &|s, r| maps.load(s, r), checks)
}

/// Validates the experiments of `runs` (maps loaded once through `maps`; one replicate per
/// configuration) and checks that
/// `parallel` of the largest of them, each on one thread (as [`run_study`] runs them), fit in
/// the memory `limit` (see [`crate::experiment::memory`]).
/// Returns the largest run's memory estimate in bytes.
pub fn validate_runs(
    study: &Study,
    runs: &[&RunSpec],
    maps: &MapCache,
    limit: Option<&crate::experiment::memory::MemoryLimit>,
    parallel: usize,
    checks: Checks,
) -> Result<f64, ConfigError> {
    let parallel = parallel.min(runs.len());
    // Replicates differ only in their seed, which no check reads (run seeds are kept below
    // 2^63): one run per configuration is validated, so a pattern-seeded GA plans its seed
    // once per configuration, not once per replicate.
    let mut seen = std::collections::HashSet::new();
    runs.iter().filter(|run| seen.insert(run.config_id.as_str())).try_fold(0.0f64, |largest, run| {
        let exp = checked_experiment_of(study, run, maps, checks)?;
        let origin = format!("{} (run {})", study.path.display(), run.id);
        Ok(largest.max(exp.check_memory(&origin, limit, parallel, 1)?.bytes))
    })
}

/// The identity of a study: a hash of its sorted run ids (each the hash of a fully resolved
/// configuration and replicate), so two grids that expand to the same runs are one study.
pub fn grid_hash(study: &Study) -> String {
    ids_hash(study.runs.iter().map(|r| r.id.as_str()).collect())
}

/// The identity hash of a set of run ids (see [`grid_hash`]).
pub fn ids_hash(mut ids: Vec<&str>) -> String {
    ids.sort_unstable();
    format!("{:016x}", super::grid::fnv1a(ids.join("\n").as_bytes()))
}

/// Refuses a folder that holds another study (a different `grid_hash` in its `study.json`).
pub fn check_identity(study: &Study, out: &Path) -> Result<(), StudyError> {
    let path = out.join("study.json");
    let Ok(text) = std::fs::read_to_string(&path) else { return Ok(()) };
    let meta: serde_json::Value = serde_json::from_str(&text)
        .map_err(|e| StudyError::Mismatch { path: path.clone(), message: format!("not a study description: {e}") })?;
    let recorded = meta["grid_hash"].as_str().unwrap_or_default();
    let ours = grid_hash(study);
    if !recorded.is_empty() && recorded != ours {
        return Err(StudyError::Mismatch {
            path,
            message: format!(
                "this folder holds another study (grid {}, {} runs, hash {recorded}); {} expands to {} runs with hash {ours}: use another --out folder",
                meta["grid_file"].as_str().unwrap_or("?"),
                meta["runs"],
                study.path.display(),
                study.runs.len()
            ),
        });
    }
    Ok(())
}

/// An advisory lock on a study's runs file, held while a process writes it and released by
/// the operating system when the process ends, however it ends.
pub struct StudyLock {
    _file: std::fs::File,
}

impl StudyLock {
    /// Takes the lock of `runs_file` (a `.lock` file beside it), or says who holds it.
    pub fn take(runs_file: &Path) -> Result<Self, StudyError> {
        let name = runs_file.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let path = runs_file.with_file_name(format!(".{name}.lock"));
        let file =
            std::fs::OpenOptions::new().create(true).truncate(false).write(true).open(&path).map_err(io(&path))?;
        #[cfg(unix)]
        {
            use std::os::fd::AsRawFd;
            // SAFETY: flock on a file descriptor this function owns; no memory is shared.
            let rc = unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) };
            if rc != 0 {
                return Err(StudyError::Mismatch {
                    path: runs_file.to_path_buf(),
                    message: "another covga process is running this study (or shard) in this folder now; wait for it to finish".into(),
                });
            }
        }
        Ok(Self { _file: file })
    }
}

/// Writes `grid.toml` and `study.json` (version, commit, counts, identity) into the study
/// folder.
pub fn write_study_files(study: &Study, out: &Path) -> Result<(), StudyError> {
    std::fs::create_dir_all(out).map_err(io(out))?;
    let text = super::standalone::grid_text(study);
    crate::io::write_atomic(&out.join("grid.toml"), text.as_bytes()).map_err(io(out))?;
    let meta = serde_json::json!({
        "grid_file": study.path.display().to_string(),
        "grid_hash": grid_hash(study),
        "covga_version": env!("CARGO_PKG_VERSION"),
        "git_commit": env!("COVGA_GIT_COMMIT"),
        "runs": study.runs.len(),
        "columns": study.columns,
    });
    crate::io::write_atomic(&out.join("study.json"), serde_json::to_string_pretty(&meta).expect("json").as_bytes())
        .map_err(io(out))
}

/// Runs (or resumes) a study.
pub fn run_study(study: &Study, opts: &RunnerOptions) -> Result<StudyOutcome, StudyError> {
    let selected: Vec<&RunSpec> = match opts.shard {
        Some(s) => study.shard(s.index, s.count),
        None => study.runs.iter().collect(),
    };
    // Validate everything before the first run starts: bad input loses nothing. The validated
    // experiments are not kept (memory stays flat); each worker validates its run again.
    let maps = MapCache::default();
    // More workers than runs would only start idle threads (and count their memory).
    let jobs = opts.jobs.clamp(1, selected.len().max(1));
    validate_runs(
        study,
        &selected,
        &maps,
        crate::experiment::memory::memory_limit(opts.max_memory).as_ref(),
        jobs,
        Checks::Full,
    )?;
    check_identity(study, &opts.out)?;
    std::fs::create_dir_all(&opts.out).map_err(|source| StudyError::Folder { path: opts.out.clone(), source })?;
    let file = opts.out.join(opts.shard.map_or("runs.csv".to_string(), |s| s.file_name()));
    let _folder = crate::io::FolderLock::take(&opts.out, opts.shard.is_none()).map_err(|message| {
        // The lock's message names the folder, as the error does: once is enough.
        let message = message.strip_prefix(&format!("{}: ", opts.out.display())).unwrap_or(&message).to_string();
        StudyError::Mismatch { path: opts.out.clone(), message }
    })?;
    match opts.shard {
        Some(shard) => super::shard_files::check_shard_count(&opts.out, shard)?,
        None => super::shard_files::check_no_unmerged_shards(&opts.out)?,
    }
    let _lock = StudyLock::take(&file)?;
    write_study_files(study, &opts.out)?;
    let head = header(&study.columns);
    if opts.retry_failed {
        drop_failed_rows(&file, &head)?;
    }
    let mut done_ids = recorded_ids(&file, &head)?;
    let fresh_file = done_ids.is_empty();
    if opts.shard.is_some() {
        // A shard in a folder whose `runs.csv` already records some of its runs (the study was
        // run whole there, or shards were merged) runs only the rest; the merge unites them.
        let whole = super::shard_files::ids_in_whole_study_file(&opts.out, opts.retry_failed);
        let mine: Vec<String> = selected.iter().filter(|r| whole.contains(&r.id)).map(|r| r.id.clone()).collect();
        done_ids.extend(mine);
    }
    let mut pending: Vec<&RunSpec> = selected.iter().filter(|r| !done_ids.contains(&r.id)).copied().collect();
    // Handed out one at a time in the order asked for (results never depend on it).
    let cost = match opts.order {
        super::order::RunOrder::LongestFirst => super::order::estimates(study, &pending, &opts.out, &maps).cost,
        super::order::RunOrder::Seeds => Default::default(),
    };
    super::order::sort_runs(&mut pending, opts.order, |r| cost.get(&r.id).copied().unwrap_or(0.0));
    let skipped = selected.len() - pending.len();
    let writer = std::fs::OpenOptions::new().create(true).append(true).open(&file).map_err(io(&file))?;
    if fresh_file {
        let mut w = &writer;
        w.set_len(0).map_err(io(&file))?;
        w.write_all(&csv_line(&head)).map_err(io(&file))?;
        w.sync_data().map_err(io(&file))?;
    }
    let execution =
        Execution { study, opts, maps: &maps, file: &file, writer: Mutex::new(writer), written: AtomicUsize::new(0) };
    let completed = execution.run_all(&pending, skipped, jobs)?;
    if opts.stop.is_some_and(|s| s.is_raised()) && completed < pending.len() {
        return Err(StudyError::Stopped { recorded: completed });
    }
    complete(&file, selected.len(), skipped, pending.len())
}

/// The runs of a study being made: what each worker needs to run one and record its row.
struct Execution<'a> {
    study: &'a Study,
    opts: &'a RunnerOptions<'a>,
    maps: &'a MapCache,
    file: &'a Path,
    writer: Mutex<std::fs::File>,
    /// Rows written so far (for the fault injection of the crash-and-resume tests).
    written: AtomicUsize,
}

impl Execution<'_> {
    /// Runs `run` and appends its row. A run its planner refuses while planning (what
    /// validation cannot see without planning) is recorded with its reason and the study goes
    /// on; a run the stop flag interrupts is not recorded (`None`: it runs again on resuming);
    /// any other failure stops the study.
    fn run_one(&self, run: &RunSpec) -> Result<Option<RunResult>, StudyError> {
        let (study, file) = (self.study, self.file);
        let dir = self.opts.out.join("runs").join(&run.id);
        let mut exp = experiment_of(study, run, self.maps)?;
        // The flag is not part of the experiment: its id, files and results do not change.
        exp.budget.interrupt = self.opts.stop.cloned();
        let started = std::time::Instant::now();
        let (fields, result) = match crate::experiment::output::run_experiment(&exp, &dir, false, &mut []) {
            Ok(summary) => {
                let s = &summary.score;
                (row(&study.columns, run, &summary), ((s.cov_final_reach, s.t_final, summary.wall_s), None))
            }
            Err(crate::experiment::output::OutputError::Planner(message)) => {
                let wall_s = started.elapsed().as_secs_f64();
                // A failed run has no files; its empty folder goes (a non-empty one stays).
                let _ = std::fs::remove_dir(&dir);
                (failed_row(&study.columns, run, &message, wall_s), ((f64::NAN, f64::NAN, wall_s), Some(message)))
            }
            Err(crate::experiment::output::OutputError::Interrupted { .. }) => {
                // An interrupted run wrote nothing; its empty folder goes.
                let _ = std::fs::remove_dir(&dir);
                return Ok(None);
            }
            Err(other) => return Err(StudyError::Run { id: run.id.clone(), message: other.to_string() }),
        };
        let line = csv_line(&fields);
        let mut w = self.writer.lock().expect("writer");
        w.write_all(&line).map_err(io(file))?;
        w.flush().map_err(io(file))?;
        w.sync_data().map_err(io(file))?;
        let recorded = self.written.fetch_add(1, Ordering::SeqCst) + 1;
        if self.opts.abort_after_runs == Some(recorded) {
            // Fault injection for crash-and-resume tests: die like a killed process,
            // with this run's row on disk and nothing cleaned up.
            std::process::abort();
        }
        Ok(Some(result))
    }

    /// Runs `pending` on `jobs` workers until done, stopped or failed; returns how many ran.
    ///
    /// The workers take the runs in order, each run on one thread: the runs are what a study
    /// runs in parallel. A run given a pool of several threads keeps an evaluation scratch (with
    /// its segment cache, `thesis::segments::CACHE_BYTES`) per thread of the pool, `jobs²` in
    /// all. Each worker is a plain thread with a one-thread pool of its own, which the run's
    /// parallel loops see; results do not depend on the threads.
    fn run_all(&self, pending: &[&RunSpec], skipped: usize, jobs: usize) -> Result<usize, StudyError> {
        let failed = AtomicBool::new(false);
        let first_error: Mutex<Option<StudyError>> = Mutex::new(None);
        let counter = AtomicUsize::new(0);
        let fail = |e: StudyError| {
            failed.store(true, Ordering::Relaxed);
            first_error.lock().expect("error slot").get_or_insert(e);
        };
        let next = AtomicUsize::new(0);
        let opts = self.opts;
        std::thread::scope(|scope| {
            for _ in 0..jobs {
                scope.spawn(|| {
                    let pool = match rayon::ThreadPoolBuilder::new().num_threads(1).build() {
                        Ok(pool) => pool,
                        Err(e) => return fail(StudyError::Run { id: String::new(), message: e.to_string() }),
                    };
                    let stopped = || opts.stop.is_some_and(|s| s.is_raised());
                    while !failed.load(Ordering::Relaxed) && !stopped() {
                        let Some(&run) = pending.get(next.fetch_add(1, Ordering::SeqCst)) else { break };
                        match pool.install(|| self.run_one(run)) {
                            Ok(None) => break,
                            Ok(Some((result, failure))) => {
                                let done = counter.fetch_add(1, Ordering::SeqCst) + 1;
                                let failure = failure.as_deref();
                                (opts.on_done)(RunDone { run, done, total: pending.len(), skipped, result, failure });
                            }
                            Err(e) => fail(e),
                        }
                    }
                });
            }
        });
        match first_error.into_inner().expect("error slot") {
            Some(e) => Err(e),
            None => Ok(counter.load(Ordering::SeqCst)),
        }
    }
}

/// A study run to its end: `runs.csv` rewritten sorted by run id (atomically), and the outcome
/// with its failed rows counted.
fn complete(file: &Path, selected: usize, skipped: usize, completed: usize) -> Result<StudyOutcome, StudyError> {
    let text = std::fs::read_to_string(file).map_err(io(file))?;
    let table = RunsTable::parse(&text).map_err(|m| StudyError::Mismatch { path: file.to_path_buf(), message: m })?;
    crate::io::write_atomic(file, &table.to_csv_sorted()).map_err(io(file))?;
    let mut failures: Vec<&Vec<String>> = table.failed_rows();
    let (id, why) = (table.col("run_id").unwrap_or(0), table.col("violations").unwrap_or(0));
    failures.sort_by(|a, b| a[id].cmp(&b[id]));
    let first_failure = failures.first().map(|r| (r[id].clone(), r[why].clone()));
    Ok(StudyOutcome { selected, skipped, completed, failed: failures.len(), first_failure })
}

/// Takes the rows of failed runs out of the runs file `file` (whose columns are `head`), so
/// that they run again; the file is replaced atomically, the other rows kept as they were.
fn drop_failed_rows(file: &Path, head: &[String]) -> Result<(), StudyError> {
    recorded_ids(file, head)?;
    let Ok(text) = std::fs::read_to_string(file) else { return Ok(()) };
    let mut table =
        RunsTable::parse(&text).map_err(|m| StudyError::Mismatch { path: file.to_path_buf(), message: m })?;
    let Some(stop) = table.col("stop") else { return Ok(()) };
    let before = table.rows.len();
    table.rows.retain(|r| r[stop] != super::records::FAILED_STOP);
    if table.rows.len() == before {
        return Ok(());
    }
    let mut bytes = csv_line(&table.header);
    for row in &table.rows {
        bytes.extend(csv_line(row));
    }
    crate::io::write_atomic(file, &bytes).map_err(io(file))
}

/// Ids recorded in an existing runs file; drops a half-written last line in place.
fn recorded_ids(file: &Path, head: &[String]) -> Result<std::collections::HashSet<String>, StudyError> {
    let Ok(bytes) = std::fs::read(file) else { return Ok(Default::default()) };
    let text = String::from_utf8_lossy(&bytes).into_owned();
    if text.is_empty() {
        return Ok(Default::default());
    }
    let keep = text.rfind('\n').map_or(0, |i| i + 1);
    if keep < text.len() {
        let f = std::fs::OpenOptions::new().write(true).open(file).map_err(io(file))?;
        f.set_len(keep as u64).map_err(io(file))?;
        f.sync_data().map_err(io(file))?;
    }
    let table =
        RunsTable::parse(&text[..keep]).map_err(|m| StudyError::Mismatch { path: file.to_path_buf(), message: m })?;
    if table.header.is_empty() && table.rows.is_empty() {
        return Ok(Default::default());
    }
    if table.header != head {
        return Err(StudyError::Mismatch {
            path: file.to_path_buf(),
            message: "its columns differ from this grid's; use another --out folder or remove the file".into(),
        });
    }
    let id = table.col("run_id").unwrap_or(0);
    let mut ids = std::collections::HashSet::with_capacity(table.rows.len());
    for row in &table.rows {
        if !ids.insert(row[id].clone()) {
            return Err(StudyError::Mismatch {
                path: file.to_path_buf(),
                message: format!(
                    "run {} is recorded twice (a runs file holds each run once: was it edited or concatenated?); \
                     remove one of its rows",
                    row[id]
                ),
            });
        }
    }
    Ok(ids)
}
