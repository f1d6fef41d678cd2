//! `covga.stats`: the statistics of `covga report` (`covga::stats`), for notebooks. Inputs
//! arrive checked by `python/covga/stats.py` (finite numbers, one-dimensional); results go
//! out as tuples that module names.

use covga::stats::{self, Contrast};
use pyo3::prelude::*;

/// `(U, p, method)` of the two-sided Mann–Whitney test, or `None` (every value tied).
#[pyfunction]
pub fn stats_mann_whitney(a: Vec<f64>, b: Vec<f64>) -> Option<(f64, f64, &'static str)> {
    stats::mann_whitney(&a, &b).map(|t| (t.u, t.p_value, t.method.name()))
}

/// `(W+, pairs, p, method)` of the two-sided signed-rank test, or `None` (every pair tied).
#[pyfunction]
pub fn stats_wilcoxon(a: Vec<f64>, b: Vec<f64>) -> Option<(f64, usize, f64, &'static str)> {
    stats::wilcoxon_signed_rank(&a, &b).map(|t| (t.w_plus, t.pairs, t.p_value, t.method.name()))
}

/// The two-sided sign test's p of `values` against `c`, or `None` (every value ties).
#[pyfunction]
pub fn stats_sign_test(values: Vec<f64>, c: f64) -> Option<f64> {
    stats::sign_test(&values, c)
}

/// `A₁₂`: P(a > b) + ½ P(a = b).
#[pyfunction]
pub fn stats_a12(a: Vec<f64>, b: Vec<f64>) -> f64 {
    stats::vargha_delaney_a12(&a, &b)
}

/// Holm-adjusted p-values, in the input order.
#[pyfunction]
pub fn stats_holm(p: Vec<f64>) -> Vec<f64> {
    stats::holm(&p)
}

/// `(H, df, p, ε²)` of the Kruskal–Wallis test, or `None`.
#[pyfunction]
pub fn stats_kruskal_wallis(groups: Vec<Vec<f64>>) -> Option<(f64, usize, f64, f64)> {
    stats::kruskal_wallis(&groups).map(|t| (t.h, t.df, t.p_value, t.epsilon_squared))
}

/// `(estimate, low, high)` of the percentile bootstrap, or `None`; `contrast` is
/// `"median_difference"` or `"median_ratio"` (checked by the Python layer).
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub fn stats_bootstrap_ci(
    a: Vec<f64>,
    b: Vec<f64>,
    contrast: &str,
    paired: bool,
    level: f64,
    resamples: usize,
    seed: u64,
) -> PyResult<Option<(f64, f64, f64)>> {
    let contrast = match contrast {
        "median_difference" => Contrast::MedianDifference,
        "median_ratio" => Contrast::MedianRatio,
        other => {
            return Err(crate::config_error(format!(
                "contrast = {other:?}: expected \"median_difference\" or \"median_ratio\""
            )));
        }
    };
    Ok(stats::bootstrap_ci(&a, &b, contrast, paired, level, resamples, seed).map(|i| (i.estimate, i.low, i.high)))
}

/// `(estimate, low, high)` of the median over clustered values, whole clusters resampled, or
/// `None` (an empty cluster, no cluster, a NaN).
#[pyfunction]
pub fn stats_cluster_bootstrap_ci(
    clusters: Vec<Vec<f64>>,
    level: f64,
    resamples: usize,
    seed: u64,
) -> Option<(f64, f64, f64)> {
    stats::design::cluster_bootstrap_ci(&clusters, stats::median, level, resamples, seed)
        .map(|i| (i.estimate, i.low, i.high))
}

/// The smallest Holm-adjusted p of a family of `tests` paired comparisons of `units` units each.
#[pyfunction]
pub fn stats_smallest_p(units: usize, tests: usize) -> f64 {
    stats::design::holm_min_p(stats::design::signed_rank_min_p(units), tests)
}

/// Units a paired comparison needs to show the standardised effect `d` (`None` where out of range).
#[pyfunction]
pub fn stats_units_for_effect(d: f64, alpha: f64, power: f64, tests: usize) -> Option<usize> {
    stats::design::units_for_effect(d, alpha, power, tests)
}
