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
    /// Shards or runs are missing.
    #[error("{0}")]
    Incomplete(String),
    /// Another covga process (a grid, a shard, a merge) is writing the folder now.
    #[error("{0}")]
    Busy(String),
}

/// Shard files `runs-shard-K-of-N.csv` that should be there but are not.
fn missing_shards(names: &[String]) -> Vec<String> {
    let mut counts: BTreeMap<usize, std::collections::BTreeSet<usize>> = BTreeMap::new();
    for n in names {
        let Some(rest) = n.strip_prefix("runs-shard-").and_then(|r| r.strip_suffix(".csv")) else { continue };
        if let Some((k, n)) = rest.split_once("-of-")
            && let (Ok(k), Ok(n)) = (k.parse::<usize>(), n.parse::<usize>())
        {
            counts.entry(n).or_default().insert(k);
        }
    }
    counts
        .iter()
        .flat_map(|(&n, have)| (0..n).filter(|k| !have.contains(k)).map(move |k| format!("runs-shard-{k}-of-{n}.csv")))
        .collect()
}

/// What to do about the `missing` files and runs of a study whose runs files are `names`:
/// rerun the missing shards where shard files are missing or the study is sharded, else resume
/// the study, which runs only the runs not yet recorded.
fn what_to_rerun(names: &[String], missing: &[String]) -> &'static str {
    let sharded = names.iter().any(|n| n.starts_with("runs-shard-"));
    if sharded || missing.iter().any(|m| m.starts_with("runs-shard-")) {
        "rerun the missing shards"
    } else {
        "resume the study with `covga grid` into this folder, which runs only the runs not yet recorded"
    }
}

/// Merges the runs files of `dir` into `dir/runs.csv`; returns (files, runs, what is missing).
/// A missing shard file, or fewer runs than `study.json` records, is an error unless
/// `allow_partial`, when it is reported in the third value instead.
///
/// Refused while a grid (or a shard of one) writes the folder: merge takes the folder's lock
/// exclusively, as a whole-study grid does, so that it never replaces a `runs.csv` a running
/// grid still appends to.
pub fn merge(dir: &Path, allow_partial: bool) -> Result<(usize, usize, Vec<String>), MergeError> {
    if !dir.join("study.json").is_file() {
        // No study folder: refused as the listing refuses it, with no lock file left there.
        runs_files(dir)?;
    }
    let lock_existed = dir.join(".covga.lock").exists();
    let lock = crate::io::FolderLock::take(dir, true).map_err(MergeError::Busy)?;
    let merged = merge_locked(dir, allow_partial);
    drop(lock);
    if !lock_existed {
        // A merge leaves the folder as it was but for runs.csv: its lock file goes too.
        let _ = std::fs::remove_file(dir.join(".covga.lock"));
    }
    merged
}

/// [`merge`] once the folder's lock is held.
fn merge_locked(dir: &Path, allow_partial: bool) -> Result<(usize, usize, Vec<String>), MergeError> {
    // Listed under the lock: a shard may have written its first file meanwhile.
    let files = runs_files(dir)?;
    let table = merged_rows(&files)?;
    let names: Vec<String> =
        files.iter().filter_map(|f| f.file_name().map(|n| n.to_string_lossy().into_owned())).collect();
    let mut missing = missing_shards(&names);
    missing.extend(check_against_study(dir, &table)?);
    if !missing.is_empty() && !allow_partial {
        return Err(MergeError::Incomplete(format!(
            "{}: the study is incomplete, missing {}; {} (or merge with --allow-partial)",
            dir.display(),
            missing.join(", "),
            what_to_rerun(&names, &missing)
        )));
    }
    let out = dir.join("runs.csv");
    crate::io::write_atomic(&out, &table.to_csv_sorted())
        .map_err(|e| MergeError::File { path: out.display().to_string(), message: e.to_string() })?;
    Ok((files.len(), table.rows.len(), missing))
}

/// The runs files of study folder `dir` (`runs.csv` and `runs-shard-*.csv`), sorted; refused
/// when there are none or the folder is no study folder.
fn runs_files(dir: &Path) -> Result<Vec<std::path::PathBuf>, MergeError> {
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
    if !dir.join("study.json").is_file() {
        return Err(MergeError::File {
            path: dir.display().to_string(),
            message: "not a study folder (no study.json): merge only folders that `covga grid` wrote".into(),
        });
    }
    Ok(files)
}

/// Reads `file` as a covga runs file: the run's identity first, the common metrics last.
fn read_runs_file(file: &Path) -> Result<RunsTable, MergeError> {
    let name = file.display().to_string();
    let text =
        std::fs::read_to_string(file).map_err(|e| MergeError::File { path: name.clone(), message: e.to_string() })?;
    let t = RunsTable::parse(&text).map_err(|m| MergeError::File { path: name.clone(), message: m })?;
    let metrics = super::records::metric_columns();
    let identity = ["run_id", "config_id", "replicate", "seed"];
    if t.header.len() < identity.len() + metrics.len()
        || t.header[..identity.len()] != identity
        || t.header[t.header.len() - metrics.len()..] != metrics[..]
    {
        return Err(MergeError::File {
            path: name,
            message: format!(
                "not a covga runs file: its header must start with {} and end with the metric columns ({} … {})",
                identity.join(","),
                metrics[0],
                metrics[metrics.len() - 1]
            ),
        });
    }
    Ok(t)
}

/// The rows of every file, one per run id; a run recorded twice must be recorded alike (timings
/// aside), and every file must have the same columns.
fn merged_rows(files: &[std::path::PathBuf]) -> Result<RunsTable, MergeError> {
    let mut merged: BTreeMap<String, (Vec<String>, String)> = BTreeMap::new();
    let mut table = RunsTable::default();
    for (k, f) in files.iter().enumerate() {
        let name = f.display().to_string();
        let t = read_runs_file(f)?;
        if k > 0 && t.header != table.header {
            return Err(MergeError::File {
                path: name,
                message: "its columns differ from the other runs files".into(),
            });
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
    Ok(table)
}

/// The merged rows against the study's `study.json`: refused when they hold runs of another
/// study (more runs than it has, or as many but not its runs: a study's identity is the hash of
/// its sorted run ids); the runs still missing, in words, otherwise.
fn check_against_study(dir: &Path, table: &RunsTable) -> Result<Option<String>, MergeError> {
    let meta = std::fs::read_to_string(dir.join("study.json"))
        .ok()
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
        .unwrap_or_default();
    let Some(n) = meta["runs"].as_u64() else { return Ok(None) };
    let hash = super::runner::ids_hash(table.rows.iter().map(|r| r[0].as_str()).collect());
    let recorded = meta["grid_hash"].as_str().unwrap_or_default();
    let foreign = table.rows.len() as u64 > n || (table.rows.len() as u64 == n && hash != recorded);
    if foreign && !recorded.is_empty() {
        return Err(MergeError::Incomplete(format!(
            "{}: the runs files hold runs of another study ({} runs where study.json records {n} with hash {recorded}); remove the foreign shard files",
            dir.display(),
            table.rows.len()
        )));
    }
    Ok(((table.rows.len() as u64) < n).then(|| format!("{} of {n} runs", n - table.rows.len() as u64)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_shards_are_named() {
        let names: Vec<String> =
            ["runs-shard-0-of-3.csv", "runs-shard-2-of-3.csv", "runs.csv"].iter().map(|s| s.to_string()).collect();
        assert_eq!(missing_shards(&names), vec!["runs-shard-1-of-3.csv".to_string()]);
        assert!(missing_shards(&["runs.csv".to_string()]).is_empty());
    }

    #[test]
    fn an_unsharded_study_is_resumed_not_rerun_by_shard() {
        let unsharded = what_to_rerun(&["runs.csv".to_string()], &["3 of 8 runs".to_string()]);
        assert!(!unsharded.contains("shard"), "{unsharded}");
        assert!(unsharded.contains("covga grid"), "{unsharded}");
        let sharded = what_to_rerun(&["runs-shard-0-of-2.csv".to_string()], &["3 of 8 runs".to_string()]);
        assert!(sharded.contains("missing shards"), "{sharded}");
    }
}
