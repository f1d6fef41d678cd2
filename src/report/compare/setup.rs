//! What a comparison compares, before any test: the compared key's values (refused where the
//! key is not swept or the baseline is none of them), the baseline as `runs.csv` records it, and
//! the strata that hold the baseline and another value, their runs paired by seed.

use super::strata::{Design, seed_pairs};
use super::{Comparison, metrics, strongest};
use crate::report::analysis::ReportError;
use crate::report::analysis::design::followed_by;
use crate::report::analysis::runs::{cell_matches, cmp_group_values, param_columns};
use crate::study::records::RunsTable;
use std::collections::BTreeMap;

/// `cmp` with each control of its baseline written as runs.csv records it where they are equal
/// as numbers (`thesis.c_len=0.10` finds the runs of `0.1`), as `--where` matches.
pub(super) fn numeric_baseline(t: &RunsTable, cmp: &Comparison) -> Comparison {
    let Some(c) = t.col(&cmp.key) else { return cmp.clone() };
    let recorded = |want: &str| {
        if t.rows.iter().any(|r| r[c] == want) {
            return want.to_string();
        }
        t.rows.iter().map(|r| &r[c]).find(|v| cell_matches(v, want)).cloned().unwrap_or_else(|| want.to_string())
    };
    let baseline = strongest::controls(&cmp.baseline).into_iter().map(recorded).collect::<Vec<_>>().join("|");
    Comparison { baseline, ..cmp.clone() }
}

/// The column of `cmp`'s key and its values (sorted), refused when the key is not swept, the
/// baseline is none of its values, or runs.csv lacks a compared metric.
pub(super) fn compared_values(t: &RunsTable, cmp: &Comparison) -> Result<(usize, Vec<String>), ReportError> {
    let input = |m: String| ReportError::Input(m);
    let mut params = param_columns(t);
    // A grid that sweeps `planner` records it in the planner column, not among the parameters.
    if let Some(c) = t.col("planner")
        && t.rows.iter().any(|r| r[c] != t.rows[0][c])
    {
        params.push("planner".into());
    }
    let key = match t.col(&cmp.key) {
        Some(c) if params.contains(&cmp.key) => c,
        _ => return Err(input(format!("--compare {}: not a swept parameter; swept: {}", cmp.key, params.join(", ")))),
    };
    let mut values: Vec<String> = t.rows.iter().map(|r| r[key].clone()).collect();
    values.sort_by(|a, b| cmp_group_values(std::slice::from_ref(a), std::slice::from_ref(b)));
    values.dedup();
    let controls = strongest::controls(&cmp.baseline);
    if let Some(missing) = controls.iter().find(|c| !values.iter().any(|v| v == *c)) {
        let which = if controls.len() > 1 { format!("the value {missing}") } else { "that value".to_string() };
        let set: Vec<&str> = values.iter().map(String::as_str).filter(|v| !v.is_empty()).collect();
        let unset = if set.len() < values.len() { " (and runs that do not set it)" } else { "" };
        return Err(input(format!(
            "--compare {}={}: no run has {which}; values: {}{unset}",
            cmp.key,
            cmp.baseline,
            set.join(", ")
        )));
    }
    for m in &metrics("time_s") {
        if t.col(m.column).is_none() {
            return Err(input(format!("--compare: runs.csv has no `{}` column (written by an older covga)", m.column)));
        }
    }
    Ok((key, values))
}

/// Why no stratum of `d` holds both the baseline and another value of `cmp`'s key (column
/// `key`): the key follows another parameter, or the grid never crosses it with the others.
pub(super) fn no_stratum(t: &RunsTable, key: usize, d: &Design, cmp: &Comparison) -> ReportError {
    let why = match followed_by(t, key, &d.kept) {
        Some(of) => format!("`{}` follows {of} (confounded with it)", cmp.key),
        None => "the grid never crosses it with the other parameters".to_string(),
    };
    ReportError::Input(format!(
        "--compare {}={}: no stratum of the other parameters holds both the baseline and another value: {why}",
        cmp.key, cmp.baseline
    ))
}

/// Per stratum and compared value: the stratum, the value, the runs and executable runs on
/// each side (baseline first), and the paired runs (row indices).
pub(super) type StratumPairs = (String, String, (usize, usize), (usize, usize), Vec<(usize, usize)>);

/// The strata that hold the baseline and another of `values`, with their runs paired by seed.
pub(super) fn stratum_pairs(
    d: &Design,
    cmp: &Comparison,
    values: &[String],
    executable: &dyn Fn(usize) -> bool,
) -> Vec<StratumPairs> {
    let mut rows = Vec::new();
    let mut strata: Vec<&String> = d.cells.keys().map(|(s, _)| s).collect();
    strata.dedup();
    for stratum in strata {
        let Some(base) = d.cells.get(&(stratum.clone(), cmp.baseline.clone())) else { continue };
        for value in values.iter().filter(|v| **v != cmp.baseline) {
            let Some(other) = d.cells.get(&(stratum.clone(), value.clone())) else { continue };
            let exec = |m: &BTreeMap<String, usize>| m.values().filter(|&&r| executable(r)).count();
            let pairs = seed_pairs(base, other, d.once_run_pairs);
            rows.push((stratum.clone(), value.clone(), (base.len(), other.len()), (exec(base), exec(other)), pairs));
        }
    }
    rows
}
