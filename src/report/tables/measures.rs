//! `covga report DIR --measure KEY …`: any figure the runs record, per group of `--by`.
//!
//! The standard report summarises the common scorer's columns. A planner records more: the
//! waypoint planner its waypoints, set-up time, its own wall coverage and whether a team's
//! graph stays connected (`summary.json`), every GA its best values per iteration
//! (`history.csv`). `--measure` names such figures; `measures.md` gives each group's median
//! with its range (numbers) or the count of runs where it holds (yes/no figures), and
//! `measures.csv` records the per-run values read from the run folders. A study whose run
//! folders are gone (a committed results folder) is reported from that `measures.csv`, so the
//! committed `measures.md` re-makes byte for byte from committed files.
//!
//! A key is read from, in order: a column of runs.csv of that name; `history.COLUMN@ITERATION`,
//! the column of `history.csv` in the row of that iteration; else a dotted path into
//! `summary.json` (`objectives.wall_coverage`).

use crate::report::analysis::ReportError;
use crate::report::analysis::rendered::Rendered;
use crate::report::analysis::runs::{Group, run_folder};
use crate::study::records::RunsTable;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

/// The file stem of what `--measure` writes (`measures.md`, `measures.csv`).
pub const STEM: &str = "measures";

/// Where a measure's value is read.
#[derive(Clone, Debug, PartialEq)]
enum Source {
    /// A column of runs.csv.
    Column(usize),
    /// A column of the run's `history.csv` at an iteration.
    History { column: String, iteration: u64 },
    /// A dotted path into the run's `summary.json`.
    Summary(Vec<String>),
}

/// One run's value of a measure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    /// A number.
    Num(f64),
    /// A yes/no figure.
    Bool(bool),
    /// No value: a figure the run records as `null` (a coverage it never reached, say).
    Null,
    /// Not recorded: a `summary.json` figure the run's planner does not write (a coverage goal's
    /// time of a planner that has no goal, in a study of several planners).
    Missing,
}

impl Value {
    /// The value as a cell of runs.csv or `measures.csv` writes it.
    fn cell(self) -> String {
        match self {
            Value::Num(x) => x.to_string(),
            Value::Bool(b) => b.to_string(),
            Value::Null => "null".into(),
            Value::Missing => "missing".into(),
        }
    }

    /// Reads a cell: `true`/`false`, `null` or empty for no value, else a finite number.
    fn parse(cell: &str) -> Option<Self> {
        match cell {
            "true" => Some(Value::Bool(true)),
            "false" => Some(Value::Bool(false)),
            "null" | "" => Some(Value::Null),
            "missing" => Some(Value::Missing),
            _ => cell.parse::<f64>().ok().filter(|x| x.is_finite()).map(Value::Num),
        }
    }
}

/// Where `key` is read, or why it cannot be.
fn source(t: &RunsTable, key: &str) -> Result<Source, String> {
    if let Some(c) = t.col(key) {
        return Ok(Source::Column(c));
    }
    if let Some(rest) = key.strip_prefix("history.") {
        let Some((column, at)) = rest.split_once('@') else {
            return Err(format!(
                "--measure {key}: a history measure is history.COLUMN@ITERATION, e.g. history.best_walls@50"
            ));
        };
        let iteration = at.parse::<u64>().map_err(|_| {
            format!("--measure {key}: the iteration `{at}` is not a whole number of iterations (0 or more)")
        })?;
        if column.is_empty() {
            return Err(format!("--measure {key}: no history column named before `@`"));
        }
        return Ok(Source::History { column: column.to_string(), iteration });
    }
    let path: Vec<String> = key.split('.').map(str::to_string).collect();
    if path.iter().any(String::is_empty) {
        return Err(format!("--measure {key}: not a runs.csv column, and an empty step in a summary.json path"));
    }
    Ok(Source::Summary(path))
}

/// Reads the measures whose source is a run's folder from `folder`.
fn read_folder(folder: &Path, keys: &[(String, Source)]) -> Result<BTreeMap<String, Value>, ReportError> {
    let bad = |p: &Path, m: String| ReportError::Input(format!("{}: {m}", p.display()));
    let mut out = BTreeMap::new();
    let mut summary: Option<serde_json::Value> = None;
    let mut history: Option<RunsTable> = None;
    for (key, src) in keys {
        let value = match src {
            Source::Column(_) => continue,
            Source::Summary(path) => {
                let file = folder.join("summary.json");
                if summary.is_none() {
                    let text = std::fs::read_to_string(&file).map_err(|e| bad(&file, e.to_string()))?;
                    summary = Some(serde_json::from_str(&text).map_err(|e| bad(&file, e.to_string()))?);
                }
                match path.iter().try_fold(summary.as_ref().expect("read above"), |v, step| v.get(step)) {
                    // Counted apart: another planner's runs of the study may record it.
                    None => Value::Missing,
                    Some(serde_json::Value::Bool(b)) => Value::Bool(*b),
                    Some(serde_json::Value::Number(n)) => Value::Num(n.as_f64().unwrap_or(f64::NAN)),
                    Some(serde_json::Value::Null) => Value::Null,
                    Some(other) => {
                        return Err(bad(&file, format!("`{key}` is {other}, not a number, true/false or null")));
                    }
                }
            }
            Source::History { column, iteration } => {
                let file = folder.join("history.csv");
                if history.is_none() {
                    let text = std::fs::read_to_string(&file).map_err(|e| bad(&file, e.to_string()))?;
                    history = Some(RunsTable::parse(&text).map_err(|m| bad(&file, m))?);
                }
                let h = history.as_ref().expect("read above");
                let (Some(it), Some(c)) = (h.col("iteration"), h.col(column)) else {
                    return Err(bad(&file, format!("no column `{column}` (its columns: {})", h.header.join(", "))));
                };
                let row = h.rows.iter().find(|r| r[it].parse::<u64>().ok() == Some(*iteration)).ok_or_else(|| {
                    bad(&file, format!("no row of iteration {iteration} (the run recorded {} rows)", h.rows.len()))
                })?;
                Value::parse(&row[c]).ok_or_else(|| {
                    bad(&file, format!("`{column}` at iteration {iteration} is `{}`, not a number", row[c]))
                })?
            }
        };
        if matches!(value, Value::Num(x) if !x.is_finite()) {
            return Err(bad(folder, format!("`{key}` is not a finite number")));
        }
        out.insert(key.clone(), value);
    }
    Ok(out)
}

/// Reads a `measures.csv` back: what the run folders said when the report was made.
fn from_csv(file: &Path, keys: &[(String, Source)]) -> Result<BTreeMap<String, BTreeMap<String, Value>>, ReportError> {
    let bad = |m: String| {
        ReportError::Input(format!(
            "{}: {m} (the study holds no run folders, so the report reads what it recorded)",
            file.display()
        ))
    };
    let text = std::fs::read_to_string(file).map_err(|e| bad(e.to_string()))?;
    let t = RunsTable::parse(&text).map_err(bad)?;
    let id = t.col("run_id").ok_or_else(|| bad("no column run_id".into()))?;
    let mut out = BTreeMap::new();
    for row in &t.rows {
        let mut values = BTreeMap::new();
        for (key, src) in keys {
            if matches!(src, Source::Column(_)) {
                continue;
            }
            let c = t.col(key).ok_or_else(|| bad(format!("`{key}` is not recorded")))?;
            let v =
                Value::parse(&row[c]).ok_or_else(|| bad(format!("run {}: `{}` cannot be read", row[id], row[c])))?;
            values.insert(key.clone(), v);
        }
        out.insert(row[id].clone(), values);
    }
    Ok(out)
}

/// Four significant digits, the way the table prints a number.
fn significant(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    if x.fract() == 0.0 && x.abs() < 1e15 {
        return format!("{x:.0}");
    }
    let decimals = (3 - x.abs().log10().floor() as i32).clamp(0, 8) as usize;
    format!("{x:.decimals$}")
}

/// One group's cell of a measure: `median [min, max]` of numbers, `k/n` of yes/no figures;
/// runs that record no value (`null`) are counted beside them, never taken as a number.
fn summarise(values: &[Value]) -> String {
    let mut nums = Vec::new();
    let (mut yes, mut bools, mut nulls, mut missing) = (0, 0, 0, 0);
    for v in values {
        match v {
            Value::Num(x) => nums.push(*x),
            Value::Bool(b) => {
                yes += usize::from(*b);
                bools += 1;
            }
            Value::Null => nulls += 1,
            Value::Missing => missing += 1,
        }
    }
    let apart: Vec<String> = [(nulls, "null"), (missing, "missing")]
        .into_iter()
        .filter(|(n, _)| *n > 0)
        .map(|(n, what)| format!("{n} {what}"))
        .collect();
    if nulls + missing == values.len() && !values.is_empty() {
        return format!("no value ({})", apart.join(", "));
    }
    let without = if apart.is_empty() { String::new() } else { format!("; {}", apart.join("; ")) };
    if !nums.is_empty() && bools > 0 {
        return "numbers and yes/no mixed".into();
    }
    if nums.is_empty() {
        return format!("{yes}/{bools}{without}");
    }
    let (lo, hi) = nums.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    format!("{} [{}, {}]{without}", significant(crate::stats::median(&mut nums)), significant(lo), significant(hi))
}

/// Makes `measures.md` and `measures.csv` of `keys` over `groups` of `t`, reading the run
/// folders of `dir` or, where the study holds none, `previous/measures.csv`; writes nothing.
pub(crate) fn render(
    dir: &Path,
    t: &RunsTable,
    groups: &[Group],
    selected: &[String],
    keys: &[String],
    previous: &Path,
) -> Result<Rendered, ReportError> {
    let file = dir.join("runs.csv");
    let id = t.col("run_id").ok_or_else(|| ReportError::Input(format!("{}: no column run_id", file.display())))?;
    let sources: Vec<(String, Source)> = keys
        .iter()
        .map(|k| source(t, k).map(|s| (k.clone(), s)))
        .collect::<Result<_, _>>()
        .map_err(ReportError::Input)?;
    let from_folders = sources.iter().any(|(_, s)| !matches!(s, Source::Column(_)));
    let folders = if !from_folders {
        BTreeMap::new()
    } else if dir.join("runs").is_dir() {
        let mut all = BTreeMap::new();
        for row in &t.rows {
            let folder = run_folder(dir, &row[id], "--measure reads it there")?;
            all.insert(row[id].clone(), read_folder(&folder, &sources)?);
        }
        all
    } else {
        from_csv(&previous.join(format!("{STEM}.csv")), &sources)?
    };
    // Every run's values, in the order of `keys`.
    let mut values: BTreeMap<&str, Vec<Value>> = BTreeMap::new();
    for row in &t.rows {
        let mut v = Vec::with_capacity(sources.len());
        for (key, src) in &sources {
            let value = match src {
                Source::Column(c) => Value::parse(&row[*c]).ok_or_else(|| {
                    ReportError::Input(format!(
                        "{}: run {}: `{key}` is `{}`, not a number or true/false",
                        file.display(),
                        row[id],
                        row[*c]
                    ))
                })?,
                _ => *folders.get(&row[id]).and_then(|m| m.get(key)).ok_or_else(|| {
                    ReportError::Input(format!(
                        "{}: run {} is not recorded, and the study holds no run folders",
                        previous.join(format!("{STEM}.csv")).display(),
                        row[id]
                    ))
                })?,
            };
            v.push(value);
        }
        values.insert(row[id].as_str(), v);
    }
    let nowhere = (0..sources.len()).find(|&k| values.values().all(|v| v[k] == Value::Missing));
    if let Some(k) = nowhere.filter(|_| !values.is_empty()) {
        return Err(ReportError::Input(format!(
            "--measure {}: no run of {} records it (not a runs.csv column, and no run's summary.json has it)",
            sources[k].0,
            dir.display()
        )));
    }
    let mut md = String::from("# Measures per group\n\n");
    if !selected.is_empty() {
        let _ = writeln!(md, "Runs with {} only.\n", selected.join(", "));
    }
    md.push_str(&markdown(t, id, groups, &sources, &values));
    Ok(Rendered { stem: STEM.into(), markdown: md, csv: csv(keys, &values), design: None, forest: None })
}

/// The body of `measures.md`: one row per group, one column per measure.
fn markdown(
    t: &RunsTable,
    id: usize,
    groups: &[Group],
    sources: &[(String, Source)],
    values: &BTreeMap<&str, Vec<Value>>,
) -> String {
    let mut md = String::new();
    let from = |want: fn(&Source) -> bool| {
        sources.iter().filter(|(_, s)| want(s)).map(|(k, _)| format!("`{k}`")).collect::<Vec<_>>().join(", ")
    };
    let mut read = Vec::new();
    for (what, keys) in [
        ("runs.csv", from(|s| matches!(s, Source::Column(_)))),
        ("each run's `summary.json`", from(|s| matches!(s, Source::Summary(_)))),
        ("each run's `history.csv` at the iteration after `@`", from(|s| matches!(s, Source::History { .. }))),
    ] {
        if !keys.is_empty() {
            read.push(format!("{what} ({keys})"));
        }
    }
    let _ = writeln!(
        md,
        "What each run recorded, read from {}. Numbers: the median of the group's runs with the least and the \
         greatest [min, max]; yes/no figures: the runs where it holds, of the group's runs.{}\n",
        read.join("; "),
        apart_note(values)
    );
    let _ =
        writeln!(md, "| group | runs | {} |", sources.iter().map(|(k, _)| k.as_str()).collect::<Vec<_>>().join(" | "));
    let _ = writeln!(md, "|---|---|{}", "---|".repeat(sources.len()));
    for g in groups {
        let cells: Vec<String> = (0..sources.len())
            .map(|k| summarise(&g.rows.iter().map(|&r| values[t.rows[r][id].as_str()][k]).collect::<Vec<_>>()))
            .collect();
        let _ = writeln!(md, "| {} | {} | {} |", g.label, g.rows.len(), cells.join(" | "));
    }
    md
}

/// What the table says of runs counted apart: those that record `null` and those that do not
/// record the figure at all.
fn apart_note(values: &BTreeMap<&str, Vec<Value>>) -> String {
    let mut note = String::new();
    if values.values().flatten().any(|v| *v == Value::Null) {
        note.push_str(" Runs that record no value (`null`: a coverage never reached, say) are counted apart.");
    }
    if values.values().flatten().any(|v| *v == Value::Missing) {
        note.push_str(
            " Runs whose `summary.json` does not record the figure (`missing`: a planner without it) are counted apart.",
        );
    }
    note
}

/// `measures.csv`: one row per run, by run id.
fn csv(keys: &[String], values: &BTreeMap<&str, Vec<Value>>) -> String {
    let mut s = format!("run_id,{}\n", keys.join(","));
    for (id, v) in values {
        let _ = writeln!(s, "{id},{}", v.iter().map(|x| x.cell()).collect::<Vec<_>>().join(","));
    }
    s
}

#[cfg(test)]
mod tests;
