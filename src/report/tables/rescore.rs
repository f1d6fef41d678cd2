//! What a re-run changed: a study's `runs.csv` against an earlier `runs.csv` of the same study
//! (`covga report DIR --previous OLD.csv` writes it as `rescore.md`), so that a study README can
//! say, from the data, which plans changed executability and which columns moved when a rule
//! or a planner changed.
//!
//! Runs are matched by `run_id` (a hash of the configuration and replicate: a run present in
//! both is the same run). Per planner and map it counts the matched runs, the executable ones
//! before and after and the status changes each way; then, per column present in both tables
//! (timings left out), how many matched runs differ. Runs present in one table only and
//! columns present in one table only are named.

use crate::study::records::{RunsTable, TIMING_COLUMNS};
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// Executable counts of one (planner, map) over the runs matched in both tables.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
struct StatusCounts {
    matched: usize,
    before: usize,
    after: usize,
    lost: usize,
    gained: usize,
}

/// The metric `planner` column (the last of that name: a swept `planner` key comes first).
fn planner_col(t: &RunsTable) -> Option<usize> {
    t.header.iter().rposition(|h| h == "planner")
}

/// The `rescore.md` text: `new` (today's runs) against `old` (named `old_label`).
pub fn rescore_markdown(new: &RunsTable, old: &RunsTable, old_label: &str) -> String {
    let (new_ids, old_ids) = (new.by_id(), old.by_id());
    let matched: Vec<&String> = new_ids.keys().filter(|id| old_ids.contains_key(*id)).collect();
    let only_new = new_ids.len() - matched.len();
    let only_old = old_ids.len() - matched.len();
    let mut md = format!(
        "# Re-run against {old_label}\n\n{} runs now, {} before; {} matched by run id, {} only now, {} only before.\n\n",
        new_ids.len(),
        old_ids.len(),
        matched.len(),
        only_new,
        only_old
    );
    md.push_str(&shares_table(new, old));
    if !matched.is_empty() {
        md.push_str(&status_table(new, old, &matched));
    }
    md.push_str(&column_changes(new, old, &matched));
    md
}

/// Executable plans per (planner, map) out of all runs of each table, matched or not (a
/// re-run whose configurations changed, and so its run ids, is compared this way alone).
fn shares_table(new: &RunsTable, old: &RunsTable) -> String {
    let count = |t: &RunsTable| -> BTreeMap<(String, String), (usize, usize)> {
        let (p, m, e) = (planner_col(t), t.col("map"), t.col("executable"));
        let mut out: BTreeMap<(String, String), (usize, usize)> = BTreeMap::new();
        for r in &t.rows {
            let key = (p.map_or(String::new(), |c| r[c].clone()), m.map_or(String::new(), |c| r[c].clone()));
            let slot = out.entry(key).or_default();
            slot.0 += 1;
            slot.1 += usize::from(e.is_some_and(|c| r[c] == "true"));
        }
        out
    };
    let (now, before) = (count(new), count(old));
    let mut keys: Vec<&(String, String)> = now.keys().chain(before.keys()).collect();
    keys.sort();
    keys.dedup();
    let cell = |c: Option<&(usize, usize)>| c.map_or("–".to_string(), |(n, e)| format!("{e} of {n}"));
    let mut md = String::from(
        "## Executable plans per planner and map, all runs

| planner | map | executable before | executable now |
|---|---|---|---|
",
    );
    for k in keys {
        let _ = writeln!(md, "| {} | {} | {} | {} |", k.0, k.1, cell(before.get(k)), cell(now.get(k)));
    }
    md.push('\n');
    md
}

/// Per (planner, map): executable plans before and after among the matched runs.
fn status_table(new: &RunsTable, old: &RunsTable, matched: &[&String]) -> String {
    let (Some(ne), Some(oe)) = (new.col("executable"), old.col("executable")) else {
        return "No `executable` column in both tables: no status changes to count.\n\n".into();
    };
    let (new_ids, old_ids) = (new.by_id(), old.by_id());
    let (np, nm) = (planner_col(new), new.col("map"));
    let mut counts: BTreeMap<(String, String), StatusCounts> = BTreeMap::new();
    for id in matched {
        let (n, o) = (new_ids[*id], old_ids[*id]);
        let key = (np.map_or(String::new(), |c| n[c].clone()), nm.map_or(String::new(), |c| n[c].clone()));
        let c = counts.entry(key).or_default();
        let (b, a) = (o[oe] == "true", n[ne] == "true");
        c.matched += 1;
        c.before += usize::from(b);
        c.after += usize::from(a);
        c.lost += usize::from(b && !a);
        c.gained += usize::from(!b && a);
    }
    let mut md = String::from(
        "## Executable plans of the runs in both tables, before and after\n\n| planner | map | runs | executable before | executable now | lost | gained |\n|---|---|---|---|---|---|---|\n",
    );
    let mut total = StatusCounts::default();
    for ((planner, map), c) in &counts {
        let _ = writeln!(
            md,
            "| {planner} | {map} | {} | {} | {} | {} | {} |",
            c.matched, c.before, c.after, c.lost, c.gained
        );
        total.matched += c.matched;
        total.before += c.before;
        total.after += c.after;
        total.lost += c.lost;
        total.gained += c.gained;
    }
    let _ = writeln!(
        md,
        "| all | | {} | {} | {} | {} | {} |\n\n{} of the {} matched runs changed status: {} are no longer executable, {} became executable.\n",
        total.matched,
        total.before,
        total.after,
        total.lost,
        total.gained,
        total.lost + total.gained,
        total.matched,
        total.lost,
        total.gained
    );
    md
}

/// Per column in both tables (timings left out): how many matched runs differ in it.
fn column_changes(new: &RunsTable, old: &RunsTable, matched: &[&String]) -> String {
    let (new_ids, old_ids) = (new.by_id(), old.by_id());
    let mut md = String::from("## Columns that changed\n\n");
    let mut rows = Vec::new();
    for (ni, name) in new.header.iter().enumerate() {
        if TIMING_COLUMNS.contains(&name.as_str()) {
            continue;
        }
        // The first column of that name in both (a swept key can share a metric's name).
        let Some(oi) = old.col(name) else { continue };
        if new.col(name) != Some(ni) {
            continue;
        }
        let differ = matched.iter().filter(|id| new_ids[**id][ni] != old_ids[**id][oi]).count();
        if differ > 0 {
            rows.push(format!("| {name} | {differ} |"));
        }
    }
    if rows.is_empty() {
        md.push_str("Every column present in both tables is equal in every matched run (timings left out).\n\n");
    } else {
        md.push_str("| column | matched runs that differ |\n|---|---|\n");
        md.push_str(&rows.join("\n"));
        md.push_str("\n\n");
    }
    let only = |a: &RunsTable, b: &RunsTable| -> Vec<String> {
        a.header.iter().filter(|h| b.col(h).is_none()).map(|h| format!("`{h}`")).collect()
    };
    let (added, removed) = (only(new, old), only(old, new));
    if !added.is_empty() {
        let _ = writeln!(md, "Columns only now: {}.\n", added.join(", "));
    }
    if !removed.is_empty() {
        let _ = writeln!(md, "Columns only before: {}.\n", removed.join(", "));
    }
    md
}

/// Writes `rescore.md` into the report folder `out`: the runs of the study folder `dir`
/// against the earlier `runs.csv` at `previous`.
pub fn write(
    dir: &std::path::Path,
    previous: &std::path::Path,
    out: &std::path::Path,
) -> Result<std::path::PathBuf, crate::report::analysis::ReportError> {
    use crate::report::analysis::ReportError;
    let read = |p: &std::path::Path| -> Result<RunsTable, ReportError> {
        let text = std::fs::read_to_string(p).map_err(|e| ReportError::Input(format!("{}: {e}", p.display())))?;
        RunsTable::parse(&text).map_err(|m| ReportError::Input(format!("{}: {m}", p.display())))
    };
    let (new, old) = (read(&dir.join("runs.csv"))?, read(previous)?);
    let md = rescore_markdown(&new, &old, &format!("`{}`", previous.display()));
    let file = out.join("rescore.md");
    crate::io::write_atomic(&file, md.as_bytes()).map_err(|e| ReportError::Io(format!("{}: {e}", file.display())))?;
    Ok(file)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(text: &str) -> RunsTable {
        RunsTable::parse(text).unwrap()
    }

    #[test]
    fn status_changes_and_changed_columns_are_counted_per_planner_and_map() {
        let old = table(
            "run_id,planner,map,executable,obstacle_cells,cov_final_free,wall_s\n\
             a,thesis,m1,true,0,0.5,1\nb,thesis,m1,true,0,0.6,1\nc,spiral,m1,false,3,0.7,1\nd,thesis,m2,true,0,0.2,1\n",
        );
        let new = table(
            "run_id,planner,map,executable,obstacle_cells,obstacle_sweeps,cov_final_free,wall_s\n\
             a,thesis,m1,false,4,0,0.5,2\nb,thesis,m1,true,0,0,0.6,2\nc,spiral,m1,true,0,3,0.7,2\ne,thesis,m2,true,0,0,0.3,2\n",
        );
        let md = rescore_markdown(&new, &old, "the committed runs.csv");
        assert!(md.contains("4 runs now, 4 before; 3 matched by run id, 1 only now, 1 only before."), "{md}");
        assert!(md.contains("| spiral | m1 | 1 | 0 | 1 | 0 | 1 |"), "{md}");
        assert!(md.contains("| thesis | m1 | 2 | 2 | 1 | 1 | 0 |"), "{md}");
        assert!(md.contains("| all | | 3 | 2 | 2 | 1 | 1 |"), "{md}");
        assert!(
            md.contains("2 of the 3 matched runs changed status: 1 are no longer executable, 1 became executable.")
        );
        assert!(md.contains("| executable | 2 |") && md.contains("| obstacle_cells | 2 |"), "{md}");
        assert!(!md.contains("| cov_final_free |") && !md.contains("| wall_s |"), "{md}");
        assert!(md.contains("Columns only now: `obstacle_sweeps`."), "{md}");
        assert!(
            md.contains("| thesis | m1 | 2 of 2 | 1 of 2 |") && md.contains("| thesis | m2 | 1 of 1 | 1 of 1 |"),
            "{md}"
        );
    }

    #[test]
    fn identical_tables_report_no_change() {
        let t = table("run_id,planner,map,executable,x,wall_s\na,p,m,true,1,3\n");
        let md = rescore_markdown(&t, &t, "itself");
        assert!(md.contains("0 of the 1 matched runs changed status"), "{md}");
        assert!(md.contains("Every column present in both tables is equal"), "{md}");
    }
}
