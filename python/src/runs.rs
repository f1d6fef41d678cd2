//! Experiments, grid studies and reports, run with the interpreter released; Ctrl-C stops them.
//!
//! The work runs on a thread of its own while the calling thread waits with the interpreter
//! released, waking every few milliseconds to let Python see its signals. On Ctrl-C a stop flag
//! is set: a run ends at its next generation and writes nothing more; a study starts no
//! further run, stops the runs in progress unrecorded, keeps the rows of the runs it finished,
//! and resumes when run again.

use crate::{config_error, guarded, panic_error};
use covga::planner::executor::Interrupt;
use covga::study::runner::{RunDone, RunnerOptions, StudyError, run_study};
use covga::usecase::UseCaseError;
use covga::usecase::run::{ExperimentText, prepare, run_in_folder};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Runs `work` on its own thread until it ends or Python raises a signal's exception (Ctrl-C's
/// `KeyboardInterrupt`); then `stop` is called, the work is waited for, and the exception
/// returned.
pub(crate) fn interruptible<T: Send>(
    py: Python<'_>,
    stop: &(dyn Fn() + Sync),
    work: impl FnOnce() -> T + Send,
) -> PyResult<T> {
    std::thread::scope(|scope| {
        let handle = scope.spawn(work);
        let mut signal = None;
        while !handle.is_finished() {
            py.detach(|| std::thread::sleep(Duration::from_millis(10)));
            if signal.is_none()
                && let Err(e) = py.check_signals()
            {
                stop();
                signal = Some(e);
            }
        }
        let result = handle.join().map_err(panic_error)?;
        match signal {
            Some(e) => Err(e),
            None => Ok(result),
        }
    })
}

/// The experiment text of `payload` read as `kind` (`path`, `text` or `json`), with its origin
/// in messages and its default folder name.
fn experiment_text(kind: &str, payload: &str) -> PyResult<ExperimentText> {
    let inline = |text: String, origin: &str| ExperimentText { text, origin: origin.into(), stem: "experiment".into() };
    match kind {
        "path" => ExperimentText::read(Path::new(payload)).map_err(use_case_error),
        "text" => Ok(inline(payload.to_string(), "experiment text")),
        "json" => {
            let origin = "experiment dict";
            let value: toml::Value =
                serde_json::from_str(payload).map_err(|e| config_error(format!("{origin}: {e}")))?;
            let text = toml::to_string(&value).map_err(|e| config_error(format!("{origin}: {e}")))?;
            Ok(inline(text, origin))
        }
        other => Err(config_error(format!("experiment kind '{other}': expected path, text or json"))),
    }
}

/// A use case's failure as Python sees it: the user's input a `ValueError` (`ConfigError`),
/// anything else a `RuntimeError`.
fn use_case_error(e: UseCaseError) -> PyErr {
    match e {
        UseCaseError::Input(m) => config_error(m),
        UseCaseError::Internal(m) | UseCaseError::Interrupted(m) => PyRuntimeError::new_err(m),
    }
}

/// Runs one experiment into `out` (with figures when `figures`); returns the warnings about it
/// in words. `summary.json`, `history.csv` and `best_path.csv` are in `out` afterwards.
#[pyfunction]
#[pyo3(signature = (kind, payload, seed, out, figures, threads=None))]
pub fn run_experiment(
    py: Python<'_>,
    kind: &str,
    payload: &str,
    seed: Option<u64>,
    out: &str,
    figures: bool,
    threads: Option<usize>,
) -> PyResult<Vec<String>> {
    let mut prepared = guarded(|| prepare(&experiment_text(kind, payload)?, seed, None).map_err(use_case_error))?;
    // Ctrl-C raises the run's interrupt: it ends at its next iteration and writes nothing.
    let interrupt = Interrupt::new();
    prepared.experiment.budget.interrupt = Some(interrupt.clone());
    let dir = PathBuf::from(out);
    let (summary, _) = interruptible(py, &|| interrupt.raise(), || {
        crate::with_threads(threads, || run_in_folder(&prepared, Some(&dir), figures, &mut []))
    })
    .and_then(|run| run?.map_err(use_case_error))?;
    let mut warnings = prepared.warnings;
    warnings.extend(summary.warnings.iter().map(|w| format!("{}: {w}", prepared.origin)));
    Ok(warnings)
}

/// Runs (or resumes) the grid study `file` into `out` with `jobs` runs at a time, started in
/// `order` (`longest-first` or `seeds`, as `covga grid --order`); returns the runs selected,
/// already recorded and completed now.
#[pyfunction]
#[pyo3(signature = (file, jobs, out, order))]
pub fn run_grid(py: Python<'_>, file: &str, jobs: usize, out: &str, order: &str) -> PyResult<(usize, usize, usize)> {
    let (study, order) = guarded(|| {
        if jobs == 0 {
            return Err(config_error("jobs = 0 is out of range: at least 1"));
        }
        let order = covga::study::order::RunOrder::from_name(order)
            .ok_or_else(|| config_error(format!("order = {order:?} is not one of \"longest-first\", \"seeds\"")))?;
        Ok((covga::study::grid::Study::load(Path::new(file)).map_err(config_error)?, order))
    })?;
    for w in &study.warnings {
        PyErr::warn(py, &py.get_type::<pyo3::exceptions::PyUserWarning>(), &std::ffi::CString::new(w.as_str())?, 1)?;
    }
    // Ctrl-C raises the flag: no further run starts, and the runs in progress stop at their
    // next iteration, unrecorded (they run again when the study resumes).
    let stop = Interrupt::new();
    let on_done = |_: RunDone| {};
    let opts = RunnerOptions {
        jobs,
        shard: None,
        out: PathBuf::from(out),
        max_memory: None,
        on_done: &on_done,
        stop: Some(&stop),
        order,
        abort_after_runs: None,
        retry_failed: false,
    };
    match interruptible(py, &|| stop.raise(), || run_study(&study, &opts))? {
        Ok(o) => match o.first_failure {
            Some((id, why)) => Err(config_error(format!(
                "{out}/runs.csv: {} of {} runs failed while running and are recorded as such (stop = failed, the \
                 reason in violations); the first, run {id}: {why}",
                o.failed, o.selected
            ))),
            None => Ok((o.selected, o.skipped, o.completed)),
        },
        Err(e @ (StudyError::Config(_) | StudyError::Mismatch { .. } | StudyError::Folder { .. })) => {
            Err(config_error(e))
        }
        Err(e @ (StudyError::Io { .. } | StudyError::Run { .. } | StudyError::Stopped { .. })) => {
            Err(PyRuntimeError::new_err(e.to_string()))
        }
    }
}

/// `covga report`: writes the report of study folder `dir` (with the comparisons `compare` of
/// executable plans and `compare_every_plan` of every plan, each `KEY=BASELINE`, made first so
/// that one that cannot be made writes nothing; with `anova_condensed`, `anova-condensed.md`
/// too; with `design`, each comparison's `design-KEY.md`) and returns the path of its `summary.md`.
#[pyfunction]
#[pyo3(signature = (dir, by, filter, name, compare, compare_every_plan, anova_condensed=false, plans=false, reference=None, seed_to_seed=false, measures=Vec::new(), design=false))]
#[allow(clippy::too_many_arguments)]
pub fn write_report(
    py: Python<'_>,
    dir: &str,
    by: Vec<String>,
    filter: Vec<(String, String)>,
    name: Option<String>,
    compare: Vec<String>,
    compare_every_plan: Vec<String>,
    anova_condensed: bool,
    plans: bool,
    reference: Option<String>,
    seed_to_seed: bool,
    measures: Vec<String>,
    design: bool,
) -> PyResult<String> {
    use covga::report::ReportError;
    let error = |e: ReportError| match e {
        ReportError::Input(m) => config_error(m),
        other => PyRuntimeError::new_err(other.to_string()),
    };
    let comparisons = compare
        .iter()
        .map(|c| covga::report::compare::Comparison::parse(c))
        .chain(compare_every_plan.iter().map(|c| covga::report::compare::Comparison::parse_every_plan(c)))
        .collect::<Result<Vec<_>, _>>()
        .map_err(config_error)?;
    crate::released(py, || {
        let dir = Path::new(dir);
        let out = match &name {
            Some(n) => dir.join(format!("report-{n}")),
            None => dir.join("report"),
        };
        let rendered = covga::report::compare::render_all(dir, &filter, &comparisons, &out).map_err(error)?;
        let opts = covga::report::ReportOptions {
            by,
            filter,
            name,
            anova_condensed,
            plans,
            reference: reference.map(std::path::PathBuf::from),
            seed_to_seed,
            measures,
        };
        let path = covga::report::write_report_with(dir, &opts).map_err(error)?;
        let folder = path.parent().unwrap_or(dir);
        for r in &rendered {
            r.save(folder).map_err(error)?;
            if design {
                r.save_design(folder).map_err(error)?;
            }
        }
        Ok(path.display().to_string())
    })
}

/// Panics inside the guard, for the tests that prove a panic reaches Python as a
/// `RuntimeError` and leaves the interpreter running.
#[pyfunction]
pub fn raise_panic(py: Python<'_>) -> PyResult<()> {
    crate::released(py, || -> PyResult<()> { panic!("a deliberate panic to test the guard") })
}

/// The planners an experiment may name (`planner = "…"`), from covga's one registry of
/// planners, in the order studies list them: covga's own, then those registered from outside
/// by the program covga runs in.
#[pyfunction]
pub fn planners() -> Vec<&'static str> {
    covga::experiment::registry::PlannerKind::all().into_iter().map(|k| k.name()).collect()
}
