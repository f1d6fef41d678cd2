//! `covga._covga`: the compiled part of the `covga` Python package.
//!
//! The bindings only convert: numpy arrays and Python values in, the covga library's calls,
//! numpy arrays and JSON-shaped values out. The pure-Python layer (`python/covga/`) adds the
//! pandas conversions and reads result folders. Every error of the user's input is raised as
//! `covga.ConfigError` (a `ValueError`) with the command line's message; a panic inside covga is
//! raised as `RuntimeError` and never crosses into the interpreter.

mod maps;
mod runs;
mod scoring;
mod stats;

use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use std::panic::{AssertUnwindSafe, catch_unwind};

create_exception!(
    covga,
    ConfigError,
    PyValueError,
    "Bad input to covga: the message names the file, key or argument and the allowed range."
);

/// A `ConfigError` with `message`.
pub(crate) fn config_error(message: impl std::fmt::Display) -> PyErr {
    ConfigError::new_err(message.to_string())
}

/// The `RuntimeError` of a panic inside covga.
pub(crate) fn panic_error(payload: Box<dyn std::any::Any + Send>) -> PyErr {
    let what = payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown cause".into());
    PyRuntimeError::new_err(format!("internal error in covga (please report it): {what}"))
}

/// Runs `work` with the interpreter released; a panic becomes a `RuntimeError`.
pub(crate) fn released<T: Send>(py: Python<'_>, work: impl FnOnce() -> PyResult<T> + Send) -> PyResult<T> {
    py.detach(|| catch_unwind(AssertUnwindSafe(work))).unwrap_or_else(|p| Err(panic_error(p)))
}

/// Runs `work` while holding the interpreter; a panic becomes a `RuntimeError`.
pub(crate) fn guarded<T>(work: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    catch_unwind(AssertUnwindSafe(work)).unwrap_or_else(|p| Err(panic_error(p)))
}

/// The most threads a call may ask for.
pub(crate) const MAX_THREADS: usize = 1024;

/// Runs `work` on a pool of `threads` worker threads, or on rayon's global pool (one thread
/// per CPU, or `RAYON_NUM_THREADS`) when `None`. Results do not depend on the count.
pub(crate) fn with_threads<T: Send>(threads: Option<usize>, work: impl FnOnce() -> T + Send) -> PyResult<T> {
    match threads {
        None => Ok(work()),
        Some(n) if !(1..=MAX_THREADS).contains(&n) => {
            Err(config_error(format!("threads = {n} is out of range: allowed [1, {MAX_THREADS}]")))
        }
        Some(n) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| PyRuntimeError::new_err(format!("cannot start {n} threads: {e}")))?;
            Ok(pool.install(work))
        }
    }
}

/// The module.
#[pymodule]
fn _covga(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("ConfigError", m.py().get_type::<ConfigError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<maps::Map>()?;
    m.add_function(wrap_pyfunction!(maps::load_map, m)?)?;
    m.add_function(wrap_pyfunction!(maps::map_from_states, m)?)?;
    m.add_function(wrap_pyfunction!(maps::experiment_map, m)?)?;
    m.add_function(wrap_pyfunction!(scoring::score, m)?)?;
    m.add_function(wrap_pyfunction!(scoring::pattern, m)?)?;
    m.add_function(wrap_pyfunction!(scoring::thesis_evaluate, m)?)?;
    m.add_function(wrap_pyfunction!(scoring::thesis_decode, m)?)?;
    m.add("THESIS_COLUMNS", covga::thesis::batch::COLUMNS.to_vec())?;
    m.add("MAX_THREADS", MAX_THREADS)?;
    m.add("MAX_MAP_CELLS", covga::map::ros::MAX_MAP_CELLS)?;
    // map_server's default thresholds, as the map reader applies them, in occupancy percent.
    let rule = covga::map::ros::PixelRule::default();
    m.add("OCCUPIED_ABOVE_PERCENT", 100.0 * rule.occupied_thresh)?;
    m.add("FREE_BELOW_PERCENT", 100.0 * rule.free_thresh)?;
    // What each id and metric column of runs.csv holds, so that a study reads with the same
    // dtypes whatever its values happen to be.
    let kinds: std::collections::BTreeMap<String, &str> = covga::study::records::header(&[])
        .into_iter()
        .filter_map(|c| covga::study::records::column_kind(&c).map(|k| (c, k.name())))
        .collect();
    m.add("RUNS_COLUMN_KINDS", kinds)?;
    m.add_function(wrap_pyfunction!(runs::planners, m)?)?;
    m.add_function(wrap_pyfunction!(runs::run_experiment, m)?)?;
    m.add_function(wrap_pyfunction!(runs::run_grid, m)?)?;
    m.add_function(wrap_pyfunction!(runs::write_report, m)?)?;
    m.add_function(wrap_pyfunction!(runs::raise_panic, m)?)?;
    m.add_function(wrap_pyfunction!(stats::stats_mann_whitney, m)?)?;
    m.add_function(wrap_pyfunction!(stats::stats_wilcoxon, m)?)?;
    m.add_function(wrap_pyfunction!(stats::stats_sign_test, m)?)?;
    m.add_function(wrap_pyfunction!(stats::stats_a12, m)?)?;
    m.add_function(wrap_pyfunction!(stats::stats_holm, m)?)?;
    m.add_function(wrap_pyfunction!(stats::stats_kruskal_wallis, m)?)?;
    m.add_function(wrap_pyfunction!(stats::stats_bootstrap_ci, m)?)?;
    m.add_function(wrap_pyfunction!(stats::stats_cluster_bootstrap_ci, m)?)?;
    m.add_function(wrap_pyfunction!(stats::stats_smallest_p, m)?)?;
    m.add_function(wrap_pyfunction!(stats::stats_units_for_effect, m)?)?;
    Ok(())
}
