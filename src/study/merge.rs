//! Merging shard outputs: the union of `runs.csv` and every `runs-shard-K-of-N.csv` in a study
//! folder, written as `runs.csv` sorted by run id. A run recorded twice must agree on every
//! column except timing; otherwise the merge fails and writes nothing.

use super::records::RunsTable;
use std::collections::BTreeMap;
use std::path::Path;

/// Merge failures.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    /// Nothing to merge.
    #[error("{0}: no runs.csv or runs-shard-*.csv files")]
    Empty(String),
    /// A file could not be read or written, or is malformed.
    #[error("{path}: {message}")]
    File {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// The same run id with different results.
    #[error("{0}")]
    Conflict(String),
}

/// Merges the runs files of `dir` into `dir/runs.csv`; returns (files, runs).
pub fn merge(dir: &Path) -> Result<(usize, usize), MergeError> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .map_err(|e| MergeError::File { path: dir.display().to_string(), message: e.to_string() })?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n == "runs.csv" || (n.starts_with("runs-shard-") && n.ends_with(".csv")))
        })
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(MergeError::Empty(dir.display().to_string()));
    }
    let mut header: Option<Vec<String>> = None;
    let mut merged: BTreeMap<String, (Vec<String>, String)> = BTreeMap::new();
    let mut table = RunsTable::default();
    for f in &files {
        let name = f.display().to_string();
        let text =
            std::fs::read_to_string(f).map_err(|e| MergeError::File { path: name.clone(), message: e.to_string() })?;
        let t = RunsTable::parse(&text).map_err(|m| MergeError::File { path: name.clone(), message: m })?;
        match &header {
            None => header = Some(t.header.clone()),
            Some(h) if *h != t.header => {
                return Err(MergeError::File {
                    path: name,
                    message: "its columns differ from the other runs files".into(),
                });
            }
            _ => {}
        }
        table.header = t.header.clone();
        for (id, row) in t.by_id() {
            if let Some((prev, prev_file)) = merged.get(&id) {
                let (a, b) = (t.without_timing(prev), t.without_timing(row));
                if let Some(k) = (0..a.len()).find(|&k| a[k] != b[k]) {
                    let cols: Vec<&String> =
                        t.header.iter().filter(|h| !super::records::TIMING_COLUMNS.contains(&h.as_str())).collect();
                    return Err(MergeError::Conflict(format!(
                        "run {id} is recorded differently in {prev_file} and {name} (column `{}`: {} vs {})",
                        cols[k], a[k], b[k]
                    )));
                }
                continue;
            }
            merged.insert(id, (row.clone(), name.clone()));
        }
    }
    table.rows = merged.into_values().map(|(r, _)| r).collect();
    let out = dir.join("runs.csv");
    crate::io::write_atomic(&out, &table.to_csv_sorted())
        .map_err(|e| MergeError::File { path: out.display().to_string(), message: e.to_string() })?;
    Ok((files.len(), table.rows.len()))
}
