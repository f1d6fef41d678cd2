//! A study's runs as every part of a report reads them: the swept columns, the groups and their
//! order, the `--where` filters, the runs that failed and the notes that say so, the fronts,
//! and the run folders' histories.

use super::ReportError;
use super::values::{check_against_grid, check_finite};
use crate::ga::pareto::non_dominated;
use crate::study::records::RunsTable;
use std::path::Path;

/// One configuration over its replicates: id, rows, cov (mean, CI), t (mean, CI), mean f.
pub(crate) type ConfigRow = (String, Vec<usize>, (f64, f64), (f64, f64), f64);

pub(crate) struct Group {
    pub(crate) label: String,
    pub(crate) rows: Vec<usize>,
}

/// The swept-parameter columns of a runs table: between `seed` and the metric columns (a swept
/// `planner` key has the same name as the metric column `planner`, so the metric block is found
/// by its length).
pub fn param_columns(t: &RunsTable) -> Vec<String> {
    // The report's own columns (the times to coverage, [`super::level`]) follow the metrics.
    let added = t.header.iter().rev().take_while(|h| super::level::LEVEL_COLUMNS.contains(&h.as_str())).count();
    let metrics = crate::study::records::metric_columns().len() + added;
    match t.col("seed") {
        Some(a) if t.header.len() >= a + 1 + metrics => t.header[a + 1..t.header.len() - metrics].to_vec(),
        _ => Vec::new(),
    }
}

/// Orders two groups' values parameter by parameter: numbers by magnitude (so the panels of
/// `tournament_size` run 2, 3, 5, 10 and not 10, 2, 3, 5), anything else as text, and a number
/// before a text.
pub(crate) fn cmp_group_values(a: &[String], b: &[String]) -> std::cmp::Ordering {
    use std::cmp::Ordering;
    for (x, y) in a.iter().zip(b) {
        let order = match (x.parse::<f64>(), y.parse::<f64>()) {
            (Ok(p), Ok(q)) => p.total_cmp(&q).then_with(|| x.cmp(y)),
            (Ok(_), Err(_)) => Ordering::Less,
            (Err(_), Ok(_)) => Ordering::Greater,
            (Err(_), Err(_)) => x.cmp(y),
        };
        if order != Ordering::Equal {
            return order;
        }
    }
    a.len().cmp(&b.len())
}

/// The `(iteration, diversity)` pairs of a run's `history.csv`: rows where the diversity was
/// not measured (`output.diversity_every`) are passed over; `None` when no row has one.
pub(crate) fn read_history_diversity(path: &Path) -> Option<Vec<(u32, f64)>> {
    let t = RunsTable::parse(&std::fs::read_to_string(path).ok()?).ok()?;
    let (i, d) = (t.col("iteration")?, t.col("diversity")?);
    let pairs: Option<Vec<(u32, f64)>> =
        t.rows.iter().filter(|r| !r[d].is_empty()).map(|r| Some((r[i].parse().ok()?, r[d].parse().ok()?))).collect();
    pairs.filter(|p| !p.is_empty())
}

/// The least coverage of a plan on a drawn front: 1 % of the free cells.
///
/// `t_final` scores how much of a plan's time goes to new cells, so a plan of one or two short
/// moves that overlaps nothing scores 1: nothing dominates it, and it would anchor every front
/// at `t_final` = 1 with almost no coverage (1 126 of Table 4.3's 54 432 runs, mostly collapsed
/// `C_child` = 0 runs, end below 5 %). Such a plan has not begun to cover; it is drawn as a
/// point, not put on the front.
pub const FRONT_MIN_COVERAGE: f64 = 0.01;

/// The non-dominated points of `(t_final, coverage)` that cover at least [`FRONT_MIN_COVERAGE`].
pub(crate) fn coverage_front(points: &[(f64, f64)]) -> Vec<usize> {
    non_dominated(points).into_iter().filter(|&k| points[k].1 >= FRONT_MIN_COVERAGE).collect()
}

/// `dir`'s runs.csv as the parts of a report that read it apart from the summary do: the runs
/// that failed while running left out and the `--where` pairs of `filter` applied; with the
/// number of runs recorded (failed and filtered ones included).
pub(crate) fn read_filtered_runs(
    dir: &Path,
    filter: &[(String, String)],
) -> Result<(RunsTable, usize, Vec<String>), ReportError> {
    let file = dir.join("runs.csv");
    let text = std::fs::read_to_string(&file).map_err(|e| ReportError::Input(format!("{}: {e}", file.display())))?;
    let input = |m: String| ReportError::Input(format!("{}: {m}", file.display()));
    let mut t = RunsTable::parse(&text).map_err(input)?;
    check_finite(&t).map_err(input)?;
    check_against_grid(dir, &t).map_err(input)?;
    let recorded = t.rows.len();
    let failed = take_failed(&mut t);
    for (key, wants) in where_keys(filter) {
        if let Some(c) = t.col(key) {
            t.rows.retain(|r| wants.iter().any(|want| cell_matches(&r[c], want)));
        }
    }
    Ok((t, recorded, failed))
}

/// `md` (a report file's markdown, its title first) with the failed-runs note of `failed`
/// after the title, so that no file of a report leaves failed runs out without a word.
pub(crate) fn with_failed_note(md: String, failed: &[String]) -> String {
    let Some(note) = failed_note(failed) else { return md };
    match md.find("\n\n") {
        Some(i) => format!("{}{note}\n\n{}", &md[..i + 2], &md[i + 2..]),
        None => format!("{md}\n\n{note}\n"),
    }
}

/// The `--where` pairs by key, in the order the keys first appear: a key given more than once
/// keeps the runs with any of its values (an OR); different keys must all hold (an AND).
pub(crate) fn where_keys(filter: &[(String, String)]) -> Vec<(&str, Vec<&str>)> {
    let mut keys: Vec<(&str, Vec<&str>)> = Vec::new();
    for (key, want) in filter {
        match keys.iter_mut().find(|(k, _)| k == key) {
            Some((_, wants)) => wants.push(want),
            None => keys.push((key, vec![want])),
        }
    }
    keys
}

/// The folder of run `id` in study `dir`, or the error that names it missing and says what
/// the report reads there (`reads`).
pub(crate) fn run_folder(dir: &Path, id: &str, reads: &str) -> Result<std::path::PathBuf, ReportError> {
    let folder = dir.join("runs").join(id);
    if folder.is_dir() {
        Ok(folder)
    } else {
        Err(ReportError::Input(format!("{}: no folder for run {id}: {reads}", dir.join("runs").display())))
    }
}

/// Whether a cell of runs.csv equals a `--where` value: as numbers when both parse, else as text.
pub(crate) fn cell_matches(cell: &str, want: &str) -> bool {
    match (cell.parse::<f64>(), want.parse::<f64>()) {
        (Ok(a), Ok(b)) => a == b,
        _ => cell == want,
    }
}

/// Takes the rows of runs that failed while running out of `t` and returns them as
/// `run <id>: <reason>` lines, by run id: they have no metrics to summarise.
pub fn take_failed(t: &mut RunsTable) -> Vec<String> {
    let (Some(stop), Some(why), Some(id)) = (t.col("stop"), t.col("violations"), t.col("run_id")) else {
        return Vec::new();
    };
    let mut failed = Vec::new();
    t.rows.retain(|r| {
        let ok = r[stop] != crate::study::records::FAILED_STOP;
        if !ok {
            failed.push(format!("run {}: {}", r[id], r[why]));
        }
        ok
    });
    failed.sort();
    failed
}

/// The note a report with failed runs begins with: how many, and the first reasons.
pub fn failed_note(failed: &[String]) -> Option<String> {
    const SHOWN: usize = 3;
    (!failed.is_empty()).then(|| {
        let more = failed.len().saturating_sub(SHOWN);
        format!(
            "**{} recorded runs failed while running** (`stop` = failed in runs.csv, the reason in `violations`) and are \
             left out of every table and figure below: {}{}",
            failed.len(),
            failed.iter().take(SHOWN).cloned().collect::<Vec<_>>().join("; "),
            if more > 0 { format!("; and {more} more") } else { String::new() }
        )
    })
}

/// The note a report of a study with fewer recorded runs than its grid holds begins with.
pub fn incomplete_note(dir: &Path, recorded: usize) -> Option<String> {
    let meta: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(dir.join("study.json")).ok()?).ok()?;
    let total = meta.get("runs")?.as_u64()? as usize;
    (recorded < total).then(|| {
        format!(
            "**Incomplete: {recorded} of {total} runs recorded.** Every table and figure below covers the recorded runs only; \
             resume the study (the same `covga grid` command) for the rest."
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::median;
    use crate::study::records::metric_columns;
    use std::cmp::Ordering::{Equal, Greater, Less};

    #[test]
    fn medians_of_odd_and_even_counts_by_hand() {
        let cases: &[(&[f64], f64)] =
            &[(&[3.0], 3.0), (&[5.0, 1.0, 3.0], 3.0), (&[4.0, 1.0, 3.0, 2.0], 2.5), (&[7.0, -1.0], 3.0)];
        for (values, want) in cases {
            assert_eq!(median(&mut values.to_vec()), *want, "{values:?}");
        }
    }

    #[test]
    fn where_values_match_numbers_as_numbers_and_text_as_text() {
        let cases = [
            ("0.10", "0.1", true),
            ("1e-2", "0.01", true),
            ("2", "3", false),
            ("elite", "elite", true),
            ("elite", "rrws", false),
            ("1", "one", false),
        ];
        for (cell, want, matches) in cases {
            assert_eq!(cell_matches(cell, want), matches, "{cell} vs {want}");
        }
    }

    #[test]
    fn swept_columns_lie_between_the_seed_and_the_metrics() {
        let metrics = metric_columns();
        let table = |params: &[&str]| RunsTable {
            header: ["run", "seed"]
                .iter()
                .chain(params)
                .map(|s| s.to_string())
                .chain(metrics.iter().cloned())
                .collect(),
            rows: Vec::new(),
        };
        assert_eq!(param_columns(&table(&["thesis.c_len", "planner"])), vec!["thesis.c_len", "planner"]);
        assert!(param_columns(&table(&[])).is_empty());
        let mut short = table(&[]);
        short.header.pop();
        assert!(param_columns(&short).is_empty(), "a table without the whole metric block has no swept columns");
        assert!(param_columns(&RunsTable { header: vec!["run".into()], rows: Vec::new() }).is_empty());
    }

    #[test]
    fn history_diversity_is_read_by_column_name() {
        let dir = std::env::temp_dir().join(format!("covga-report-history-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("history.csv");
        std::fs::write(&path, "evaluations,diversity,iteration\n10,4.5,0\n20,2.25,1\n").unwrap();
        assert_eq!(read_history_diversity(&path), Some(vec![(0, 4.5), (1, 2.25)]));
        std::fs::write(&path, "iteration,diversity\n0,\n").unwrap();
        assert_eq!(read_history_diversity(&path), None, "an unmeasured diversity is not a value");
        std::fs::write(&path, "iteration,diversity\n0,4\n1,\n2,3\n").unwrap();
        assert_eq!(read_history_diversity(&path), Some(vec![(0, 4.0), (2, 3.0)]), "rows between measurements");
        std::fs::write(&path, "iteration,diversity\n0,4\n1,x\n").unwrap();
        assert_eq!(read_history_diversity(&path), None, "a malformed value is not passed over");
        assert_eq!(read_history_diversity(&dir.join("missing.csv")), None);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    fn values(v: &[&str]) -> Vec<String> {
        v.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn group_values_order_numbers_by_magnitude_and_text_as_text() {
        let cases: &[(&[&str], &[&str], std::cmp::Ordering)] = &[
            (&["2"], &["10"], Less),
            (&["10"], &["3"], Greater),
            (&["0.01"], &["0.1"], Less),
            (&["-1"], &["0"], Less),
            (&["1e3"], &["50"], Greater),
            (&["rrws"], &["elite"], Greater),
            (&["5"], &["elite"], Less),
            (&["f2"], &["3"], Greater),
            (&["7", "f1"], &["7", "f2"], Less),
            (&["10", "f1"], &["9", "f2"], Greater),
            (&["3"], &["3"], Equal),
            // Equal numbers written differently stay distinct groups, in text order.
            (&["1.0"], &["1"], Greater),
        ];
        for (a, b, want) in cases {
            assert_eq!(cmp_group_values(&values(a), &values(b)), *want, "{a:?} vs {b:?}");
        }
        let mut sizes = vec![values(&["10"]), values(&["2"]), values(&["5"]), values(&["3"])];
        sizes.sort_by(|a, b| cmp_group_values(a, b));
        assert_eq!(sizes, vec![values(&["2"]), values(&["3"]), values(&["5"]), values(&["10"])]);
    }

    #[test]
    fn a_plan_that_has_not_begun_to_cover_is_off_the_front() {
        // (t_final, coverage): a one-move plan at t_final 1 dominates nothing the front needs.
        let points = [(1.0, 0.003), (0.9, 0.5), (0.8, 0.7), (0.7, 0.6), (1.0, 0.0)];
        assert_eq!(coverage_front(&points), vec![1, 2]);
        let at_limit = [(1.0, FRONT_MIN_COVERAGE), (0.5, 0.9)];
        assert_eq!(coverage_front(&at_limit), vec![0, 1], "1 % is on the front");
    }
}
