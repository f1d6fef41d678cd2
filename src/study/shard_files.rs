//! What a study folder's shard files (`runs-shard-K-of-N.csv`) allow: a folder holds one
//! study, run either whole or in shards of one count, so a run that would split the runs
//! another way, or run again what a shard recorded, is refused before it starts.

use super::records::RunsTable;
use super::runner::{Shard, StudyError};
use std::collections::HashSet;
use std::path::Path;

/// The shard files of `out` with their index and count, in name order.
fn shard_files(out: &Path) -> Vec<(String, usize, usize)> {
    let Ok(entries) = std::fs::read_dir(out) else { return Vec::new() };
    let mut files: Vec<(String, usize, usize)> = entries
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter_map(|name| {
            let (k, n) = name.strip_prefix("runs-shard-")?.strip_suffix(".csv")?.split_once("-of-")?;
            let (k, n) = (k.parse().ok()?, n.parse().ok()?);
            Some((name, k, n))
        })
        .collect();
    files.sort();
    files
}

/// Refuses shard `shard` in a folder that holds shard files of another shard count: shards of
/// two counts split the runs differently, so some runs would be computed twice and others by
/// neither split's merge.
pub fn check_shard_count(out: &Path, shard: Shard) -> Result<(), StudyError> {
    if let Some((name, _, count)) = shard_files(out).into_iter().find(|&(_, _, c)| c != shard.count) {
        return Err(StudyError::Mismatch {
            path: out.join(&name),
            message: format!(
                "holds shards of {count}, and this is shard {}/{}: every shard of a study uses one count (the \
                 runs are split by it); use --shard I/{count}, or another --out folder",
                shard.index, shard.count
            ),
        });
    }
    Ok(())
}

/// The run ids a runs file records (none where it is missing or unreadable: the runner reads
/// and checks its own file; a shard file's half-written last line is not counted).
fn ids_in(file: &Path) -> HashSet<String> {
    let Ok(text) = std::fs::read_to_string(file) else { return HashSet::new() };
    let Ok(table) = RunsTable::parse(&text) else { return HashSet::new() };
    let Some(id) = table.col("run_id") else { return HashSet::new() };
    table.rows.into_iter().map(|mut r| std::mem::take(&mut r[id])).collect()
}

/// The runs a shard need not run again: those the folder's `runs.csv` records (a whole-study
/// run's, or the merge of shards), less its failed runs when they are to be retried. Read
/// without changing the file: another shard may be reading it too.
pub fn ids_in_whole_study_file(out: &Path, retry_failed: bool) -> HashSet<String> {
    let Ok(text) = std::fs::read_to_string(out.join("runs.csv")) else { return HashSet::new() };
    let Ok(table) = RunsTable::parse(&text) else { return HashSet::new() };
    let (Some(id), stop) = (table.col("run_id"), table.col("stop")) else { return HashSet::new() };
    let failed = |r: &Vec<String>| retry_failed && stop.is_some_and(|s| r[s] == super::records::FAILED_STOP);
    table.rows.iter().filter(|r| !failed(r)).map(|r| r[id].clone()).collect()
}

/// Refuses a whole-study run in a folder whose shard files record runs that its `runs.csv`
/// does not: it would run them again into a second runs file of the one study. Once the
/// shards are merged (`covga merge`, which writes their union into `runs.csv`), resuming the
/// whole study there runs only what no file records.
pub fn check_no_unmerged_shards(out: &Path) -> Result<(), StudyError> {
    let shards = shard_files(out);
    if shards.is_empty() {
        return Ok(());
    }
    let merged = ids_in(&out.join("runs.csv"));
    for (name, index, count) in shards {
        let unmerged = ids_in(&out.join(&name)).difference(&merged).count();
        if unmerged > 0 {
            let dir = out.display();
            return Err(StudyError::Mismatch {
                path: out.join(&name),
                message: format!(
                    "records {unmerged} runs of shard {index}/{count} of this study that {dir}/runs.csv does not: \
                     this folder's study is run in shards of {count}, and a whole-study run here would run them \
                     again; run the other shards (--shard K/{count}) and `covga merge {dir}`, or merge what is \
                     there first (`covga merge {dir} --allow-partial`) and then resume the whole study"
                ),
            });
        }
    }
    Ok(())
}
