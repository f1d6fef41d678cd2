//! The values of a `runs.csv` a report reads, checked before anything is computed from them: a
//! hand-edited or damaged file (a time that is no number, a share above 1, a count with a
//! fraction, a replicate or swept value the study's grid never ran) is refused with its run,
//! line and column, rather than printed as `NaN ± NaN` or silently dropped from a comparison.

use crate::study::records::{ColumnKind, FAILED_STOP, RunsTable, column_kind};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Columns that hold a share of cells, time or change: allowed [0, 1].
const SHARES: [&str; 13] = [
    "cov_final_free",
    "cov_final_reach",
    "t_final",
    "cam_walls_free",
    "cam_open_free",
    "cam_walls_reach",
    "cam_open_reach",
    "union_free",
    "union_reach",
    "overlap_fraction",
    "fleet_cov_final",
    "fleet_t_final",
    "negotiation_last_change",
];

/// The line of row `r` of a runs file (its header is line 1).
fn line(r: usize) -> usize {
    r + 2
}

/// Refuses a runs table whose values a report cannot take as results: a run id recorded
/// twice, a number column (counts, seeds, metrics, times) holding no number of its kind or a
/// value out of its range, a yes/no column holding anything but `true` or `false`, and a run
/// that did not fail with a common metric left empty.
pub(crate) fn check_finite(t: &RunsTable) -> Result<(), String> {
    let id = t.col("run_id");
    if let Some(i) = id {
        let mut seen = BTreeSet::new();
        for row in &t.rows {
            if !seen.insert(row[i].as_str()) {
                return Err(format!(
                    "run {} is recorded twice: every run id appears once (was the file edited by hand?)",
                    row[i]
                ));
            }
        }
    }
    let failed = t.col("stop");
    let common = crate::coverage::score::Score::column_names();
    for (c, name) in t.header.iter().enumerate() {
        let Some(kind) = column_kind(name) else { continue };
        for (r, row) in t.rows.iter().enumerate() {
            let run_failed = failed.is_some_and(|f| row[f] == FAILED_STOP);
            let run = id.map_or("?", |i| row[i].as_str());
            // An empty yes/no cell is checked as any other value of it.
            if row[c].is_empty() && kind != ColumnKind::Flag {
                if !run_failed && common.contains(&name.as_str()) {
                    return Err(format!(
                        "run {run} has `{name}` empty (line {}): a run that did not fail has every metric (was the file edited by hand?)",
                        line(r)
                    ));
                }
                continue;
            }
            if let Some((what, allowed)) = check_cell(kind, name, &row[c], run_failed) {
                return Err(format!("run {run} has {what} (line {}): {allowed}", line(r)));
            }
        }
    }
    Ok(())
}

/// Checks one cell of column `name` of `kind`; on failure, the cell in words (`` `name` = value ``)
/// and what is allowed.
fn check_cell(kind: ColumnKind, name: &str, cell: &str, run_failed: bool) -> Option<(String, String)> {
    let hand = "(was the file edited by hand?)";
    let quoted = || format!("`{name}` = `{cell}`");
    match kind {
        ColumnKind::Text => None,
        // Yes/no columns hold `true` or `false`: read as anything else they would count as "no".
        ColumnKind::Flag if ["executable", "planner_feasible"].contains(&name) && !run_failed => {
            (cell != "true" && cell != "false").then(|| (quoted(), format!("allowed `true` or `false` {hand}")))
        }
        ColumnKind::Flag => None,
        ColumnKind::Integer | ColumnKind::Unsigned => {
            cell.parse::<u64>().is_err().then(|| (quoted(), format!("expected a whole number, 0 or more {hand}")))
        }
        ColumnKind::Float => {
            let plain = || format!("`{name}` = {cell}");
            match cell.parse::<f64>() {
                Err(_) => Some((quoted(), format!("expected a number {hand}"))),
                Ok(v) if !v.is_finite() => Some((plain(), format!("every metric must be a finite number {hand}"))),
                Ok(v) => {
                    // Shares lie in [0, 1]; lengths, times and counts are not negative.
                    let (lo, hi) = if SHARES.contains(&name) { (0.0, 1.0) } else { (0.0, f64::INFINITY) };
                    (!(lo..=hi).contains(&v)).then(|| (plain(), format!("allowed [{lo}, {hi}] {hand}")))
                }
            }
        }
    }
}

/// The values each swept key of a grid file's text takes (its unconditional and conditional
/// axes, by the key's current name) and its replicates per configuration; `None` where the
/// text is no grid file.
fn grid_values(text: &str) -> Option<(BTreeMap<String, BTreeSet<String>>, u32)> {
    let grid: crate::study::grid::GridFile = toml::from_str(text).ok()?;
    let mut values: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for axes in std::iter::once(&grid.axes).chain(grid.conditional.iter().map(|c| &c.axes)) {
        for (key, v) in axes {
            let list = match v {
                toml::Value::Array(a) => a.iter().map(crate::study::grid::scalar_text).collect(),
                other => vec![crate::study::grid::scalar_text(other)],
            };
            values.entry(crate::experiment::renamed::current_key(key).to_string()).or_default().extend(list);
        }
    }
    Some((values, grid.seeds))
}

/// Refuses runs of `t` that the grid of study folder `dir` (its `grid.toml`) never ran: a
/// replicate past its `seeds`, a swept key's value none of its axes lists (a comparison would
/// silently leave such a run out). Without a readable grid file there is nothing to check.
pub(crate) fn check_against_grid(dir: &Path, t: &RunsTable) -> Result<(), String> {
    let grid_file = dir.join("grid.toml");
    let Some((values, seeds)) = std::fs::read_to_string(&grid_file).ok().and_then(|text| grid_values(&text)) else {
        return Ok(());
    };
    let id = t.col("run_id");
    let run = |row: &[String]| id.map_or("?".to_string(), |i| row[i].clone());
    if let Some(c) = t.col("replicate") {
        for (r, row) in t.rows.iter().enumerate() {
            if row[c].parse::<u64>().is_ok_and(|k| k >= u64::from(seeds)) {
                return Err(format!(
                    "run {} has `replicate` = {} (line {}): {} runs replicates 0 to {} (seeds = {seeds}) (was the file edited by hand?)",
                    run(row),
                    row[c],
                    line(r),
                    grid_file.display(),
                    seeds.saturating_sub(1)
                ));
            }
        }
    }
    // A swept key named like a metric column (`planner`) records there what the run reports
    // (`fleet-negotiate` for a fleet's method), not the swept value: only the swept keys' own
    // columns are checked.
    for (key, allowed) in values.iter().filter(|(key, _)| column_kind(key).is_none()) {
        let Some(c) = t.col(key) else { continue };
        for (r, row) in t.rows.iter().enumerate() {
            if !row[c].is_empty() && !allowed.contains(&row[c]) {
                let listed: Vec<&str> = allowed.iter().map(String::as_str).collect();
                return Err(format!(
                    "run {} has `{key}` = `{}` (line {}): not a value {} sweeps (it sweeps {}) (was the file edited by hand?)",
                    run(row),
                    row[c],
                    line(r),
                    grid_file.display(),
                    listed.join(", ")
                ));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(header: &str, rows: &[&str]) -> RunsTable {
        let text = std::iter::once(header).chain(rows.iter().copied()).collect::<Vec<_>>().join("\n") + "\n";
        RunsTable::parse(&text).unwrap()
    }

    #[test]
    fn values_of_the_wrong_kind_or_range_are_refused_with_run_line_and_column() {
        for (header, row, needle) in [
            ("run_id,time_s", "a,abc", "run a has `time_s` = `abc` (line 2): expected a number"),
            ("run_id,wall_s", "a,-1", "run a has `wall_s` = -1 (line 2): allowed [0, inf]"),
            ("run_id,wall_s", "a,nan", "run a has `wall_s` = nan (line 2): every metric must be a finite number"),
            ("run_id,t_final", "a,2", "run a has `t_final` = 2 (line 2): allowed [0, 1]"),
            ("run_id,unique_cells", "a,2.5", "run a has `unique_cells` = `2.5` (line 2): expected a whole number"),
            ("run_id,replicate", "a,abc", "run a has `replicate` = `abc` (line 2): expected a whole number"),
            ("run_id,stop,time_s", "a,evaluations,", "run a has `time_s` empty (line 2)"),
        ] {
            let err = check_finite(&table(header, &[row])).unwrap_err();
            assert!(err.contains(needle), "{row}: {err}");
        }
        // A failed run has no metrics; a single robot no fleet columns.
        check_finite(&table("run_id,stop,time_s,fleet_makespan_s", &["a,failed,,", "b,budget,5,"])).unwrap();
    }

    /// Every committed study passes the checks its report makes.
    #[test]
    fn committed_studies_pass() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("results");
        for e in std::fs::read_dir(&root).unwrap().flatten() {
            let Ok(text) = std::fs::read_to_string(e.path().join("runs.csv")) else { continue };
            let t = RunsTable::parse(&text).unwrap();
            check_finite(&t).unwrap_or_else(|m| panic!("{}: {m}", e.path().display()));
            check_against_grid(&e.path(), &t).unwrap_or_else(|m| panic!("{}: {m}", e.path().display()));
        }
    }

    #[test]
    fn a_replicate_or_a_swept_value_the_grid_never_ran_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let grid = "seeds = 3\n[base]\n[axes]\n\"thesis.c_len\" = [0.1, 0.4]\n[[conditional]]\nwhen = { \"thesis.c_len\" = 0.1 }\naxes = { \"thesis.selection\" = [\"elite\"] }\n";
        std::fs::write(dir.path().join("grid.toml"), grid).unwrap();
        let header = "run_id,replicate,thesis.c_len,thesis.selection";
        check_against_grid(dir.path(), &table(header, &["a,2,0.1,elite", "b,0,0.4,"])).unwrap();
        for (row, needle) in [
            ("a,3,0.1,elite", "run a has `replicate` = 3 (line 2):"),
            ("a,0,0.2,elite", "run a has `thesis.c_len` = `0.2` (line 2): not a value"),
            ("a,0,0.1,rrws", "run a has `thesis.selection` = `rrws` (line 2): not a value"),
        ] {
            let err = check_against_grid(dir.path(), &table(header, &[row])).unwrap_err();
            assert!(err.contains(needle) && err.contains("grid.toml"), "{row}: {err}");
        }
    }
}
