//! `covga report DIR --compare KEY=BASELINE`: every other value of one swept parameter against
//! a baseline value, within each combination of the other parameters (a *stratum*), on the
//! plans a robot can drive.
//!
//! Runs of one stratum are paired by their seed: a grid gives replicate `i` of every
//! configuration the same seed, so a pair differs in the compared parameter only. A pair counts
//! where both plans are executable. Per pair and metric: reachable coverage as a difference
//! (higher is better), mission time as a ratio (lower is better). Each comparison reports the
//! medians, the median contrast with its seeded paired bootstrap interval, how many pairs went
//! which way, `A₁₂`, and the two-sided Wilcoxon signed-rank test, Holm-corrected over the
//! family of all comparisons of that metric in the file (the family is stated). A comparison
//! whose pairs all tie is reported as such and not tested. Parameters whose value follows
//! from the others (a budget set per map) are not strata of their own and are named.

mod findings;
mod forest;
mod like;
mod margin;
mod pooled;
mod power;
mod setup;
mod strata;
mod strongest;
mod text;
mod units;

use setup::{compared_values, no_stratum, numeric_baseline, stratum_pairs};
use strata::{Design, design};
use text::{executability, intro, p_text, section};

use crate::report::analysis::ReportError;
use crate::report::analysis::folder_record::FolderRecords;
use crate::report::analysis::level::{LEVEL_COLUMNS, TimeMeasure, add_level_columns};
use crate::report::analysis::rendered::Rendered;
use crate::report::analysis::runs::{cmp_group_values, read_filtered_runs, with_failed_note};
use crate::stats::{Contrast, Family, bootstrap_ci, vargha_delaney_a12, wilcoxon_signed_rank};
use crate::study::records::RunsTable;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Bootstrap resamples of each interval.
const RESAMPLES: usize = 10_000;
/// Seed of the bootstrap streams: fixed, so that a report re-makes its intervals exactly.
const BOOTSTRAP_SEED: u64 = 1;
/// Level of the comparisons' intervals and of the Holm-corrected tests.
const LEVEL: f64 = 0.95;

/// One parameter's values against a baseline value.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Comparison {
    /// The swept key (a column of runs.csv), e.g. `thesis.moves`.
    pub key: String,
    /// Its value the others are compared with, e.g. `straight`.
    pub baseline: String,
    /// Which plans the metrics compare.
    pub plans: Plans,
}

/// Which plans a comparison's metrics are read from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Plans {
    /// Pairs where both plans are executable: what a robot can drive (the default).
    Executable,
    /// Every pair, executable or not: what the planner optimised, whether a robot can drive it
    /// or not (`--compare-every-plan`). Reported under its own file name, beside the default.
    Every,
}

impl Comparison {
    /// Parses `KEY=BASELINE`, comparing executable plans.
    pub fn parse(text: &str) -> Result<Self, String> {
        match text.split_once('=') {
            Some((k, v)) if !k.trim().is_empty() => {
                Ok(Self { key: k.trim().into(), baseline: v.trim().into(), plans: Plans::Executable })
            }
            _ => Err(format!("--compare {text}: expected KEY=BASELINE, e.g. thesis.moves=straight")),
        }
    }

    /// Parses `KEY=BASELINE`, comparing every plan.
    pub fn parse_every_plan(text: &str) -> Result<Self, String> {
        Self::parse(text)
            .map(|c| Self { plans: Plans::Every, ..c })
            .map_err(|m| m.replacen("--compare", "--compare-every-plan", 1))
    }
}

/// A metric compared pair by pair.
struct Metric {
    column: &'static str,
    higher_is_better: bool,
    contrast: Contrast,
    /// Decimals of its medians.
    decimals: usize,
}

/// The metrics compared: reachable coverage, and time as `time` (the comparison's
/// [`TimeMeasure`]: mission time between plans of equal coverage, else the time to a common level).
fn metrics(time: &'static str) -> [Metric; 2] {
    [
        Metric { column: "cov_final_reach", higher_is_better: true, contrast: Contrast::MedianDifference, decimals: 4 },
        Metric { column: time, higher_is_better: false, contrast: Contrast::MedianRatio, decimals: 1 },
    ]
}

/// One value against the baseline in one stratum, for one metric.
struct Row {
    stratum: String,
    value: String,
    runs: (usize, usize),
    executable: (usize, usize),
    /// `(baseline, value)` of each pair where both plans are executable.
    pairs: Vec<(f64, f64)>,
}

impl Row {
    /// The table cells every section starts a row with: stratum, value, executable runs of
    /// each side, pairs.
    fn lead_md(&self) -> String {
        format!(
            "| {} | {} | {}/{}, {}/{} | {} |",
            if self.stratum.is_empty() { "all" } else { &self.stratum },
            self.value,
            self.executable.0,
            self.runs.0,
            self.executable.1,
            self.runs.1,
            self.pairs.len()
        )
    }

    /// The CSV fields every section starts a row with, `metric` among them, and the `unit` its
    /// test counts with their number.
    fn lead_csv(&self, metric: &str, unit: &str, units: usize) -> String {
        format!(
            "{},{},{metric},{},{},{},{},{},{unit},{units}",
            quoted(&self.stratum),
            quoted(&self.value),
            self.runs.0,
            self.runs.1,
            self.executable.0,
            self.executable.1,
            self.pairs.len()
        )
    }
}

/// `text` as one CSV field: in double quotes, a quote inside doubled (a stratum such as
/// `thesis.seed_population=["boustrophedon"]` holds some).
fn quoted(text: &str) -> String {
    format!("\"{}\"", text.replace('"', "\"\""))
}

/// Reads `dir`'s runs.csv (failed runs left out, the `--where` pairs of `filter` applied as
/// the report applies them) and makes each comparison, writing nothing: a comparison that
/// cannot be made is refused before the report folder is touched. The plans' times to
/// coverage come from the run folders, else from the record in the report folder `out`
/// ([`FolderRecords`]).
pub fn render_all(
    dir: &Path,
    filter: &[(String, String)],
    comparisons: &[Comparison],
    out: &Path,
) -> Result<Vec<Rendered>, ReportError> {
    if comparisons.is_empty() {
        return Ok(Vec::new());
    }
    let (mut t, recorded, failed) = read_filtered_runs(dir, filter)?;
    add_level_columns(&mut t, &FolderRecords::open(dir, out)?);
    // A configuration recorded once pairs with every seed only in a finished study: in one
    // stopped part-way it may be a seeded configuration whose other seeds have not run.
    let expected = std::fs::read_to_string(dir.join("study.json"))
        .ok()
        .and_then(|j| serde_json::from_str::<serde_json::Value>(&j).ok())
        .and_then(|v| v["runs"].as_u64());
    let complete = expected.is_none_or(|n| recorded as u64 >= n);
    let mut rendered: Vec<Rendered> = comparisons
        .iter()
        .map(|c| {
            render_with(&t, c, complete).map(|r| Rendered { markdown: with_failed_note(r.markdown, &failed), ..r })
        })
        .collect::<Result<_, _>>()?;
    // Several baselines of one key (and kind of plans) would share a file: each then names its
    // baseline.
    let shared: Vec<bool> = rendered.iter().map(|r| rendered.iter().filter(|o| o.stem == r.stem).count() > 1).collect();
    for i in 0..rendered.len() {
        if shared[i] {
            let safe = safe_name(&comparisons[i].baseline);
            rendered[i].stem = match comparisons[i].plans {
                Plans::Executable => format!("{}-{safe}", rendered[i].stem),
                Plans::Every => format!("{}-{safe}-every-plan", rendered[i].stem.trim_end_matches("-every-plan")),
            };
        }
    }
    Ok(rendered)
}

/// `text` with characters other than letters, digits, `.` and `-` as `_`, for a file name.
fn safe_name(text: &str) -> String {
    text.chars().map(|c| if c.is_ascii_alphanumeric() || c == '.' || c == '-' { c } else { '_' }).collect()
}

/// Writes `compare-KEY.md` and `compare-KEY.csv` into `out` and returns the markdown's path.
pub fn write(t: &RunsTable, cmp: &Comparison, out: &Path) -> Result<PathBuf, ReportError> {
    render(t, cmp)?.save(out)
}

/// The columns of `compare-KEY.csv`: `unit` is what its test counts (`seed` within a stratum,
/// `stratum` or `floor plan` pooled), `units` how many; `p_floor_holm` the smallest p its family
/// can reach after Holm.
const CSV_HEADER: &str = "stratum,value,metric,runs_baseline,runs_value,executable_baseline,executable_value,pairs,\
                          unit,units,median_baseline,median_value,contrast,estimate,ci_low,ci_high,value_better,\
                          value_worse,a12_value_greater,test,p,p_holm,p_floor_holm,note\n";

/// Makes the comparison `cmp` of the runs `t` of a finished study.
pub fn render(t: &RunsTable, cmp: &Comparison) -> Result<Rendered, ReportError> {
    render_with(t, cmp, true)
}

/// [`render`]; `complete` says whether the study is finished (else a configuration recorded
/// once is paired by seed like any other).
fn render_with(t: &RunsTable, cmp: &Comparison, complete: bool) -> Result<Rendered, ReportError> {
    let cmp = &numeric_baseline(t, cmp);
    let (key, _) = compared_values(t, cmp)?;
    let mut d = design(t, cmp, key);
    d.once_run_pairs = complete;
    // The compared values as labelled (with the parameters nested in them), in order.
    let mut values: Vec<String> = d.cells.keys().map(|(_, v)| v.clone()).collect();
    values.sort_by(|a, b| cmp_group_values(std::slice::from_ref(a), std::slice::from_ref(b)));
    values.dedup();
    let executable = |r: usize| t.col("executable").is_none_or(|c| t.rows[r][c] == "true");
    let rows = stratum_pairs(&d, cmp, &values, &executable);
    if rows.is_empty() {
        return Err(no_stratum(t, key, &d, cmp));
    }
    let num = |r: usize, c: &str| t.col(c).and_then(|i| t.rows[r][i].parse::<f64>().ok()).unwrap_or(f64::NAN);
    let mut md = String::new();
    let mut csv = String::from(CSV_HEADER);
    let every = match cmp.plans {
        Plans::Executable => "",
        Plans::Every => ", every plan",
    };
    let _ = writeln!(md, "# `{}`: each value against `{}`{every}\n", cmp.key, cmp.baseline);
    let compared: Vec<String> = values.iter().filter(|v| **v != cmp.baseline).cloned().collect();
    let units = d.pooled().then(|| units::choose(&d.params, d.once_run()));
    let measure = time_measure(t, &d, cmp.plans);
    let metrics = metrics(measure.column);
    let _ = writeln!(md, "{}\n", intro(&d, (cmp, &measure), units.as_ref(), &compared));
    md.push_str(&strongest_table(&d));
    let findings_at = md.len();
    let as_rows = |value_of: &dyn Fn(usize) -> f64, both_executable: bool| -> Vec<Row> {
        rows.iter()
            .map(|(stratum, value, runs, exec, pairs)| Row {
                stratum: stratum.clone(),
                value: value.clone(),
                runs: *runs,
                executable: *exec,
                pairs: pairs
                    .iter()
                    .filter(|&&(b, o)| !both_executable || (executable(b) && executable(o)))
                    .map(|&(b, o)| (value_of(b), value_of(o)))
                    .collect(),
            })
            .collect()
    };
    let both_executable = cmp.plans == Plans::Executable;
    let executable_rows = as_rows(&|r| f64::from(u8::from(executable(r))), false);
    let built = |value: &str| like::executable_by_construction(&cmp.key, value);
    let mut forest = None;
    if let Some(units) = &units {
        pooled::executability(&mut md, &mut csv, &pooled::pool(&executable_rows, units), (cmp, units), &built);
        for m in &metrics {
            let rows = as_rows(&|r| num(r, m.column), both_executable);
            let pooled = pooled::pool(&rows, units);
            pooled::section(&mut md, &mut csv, m, &pooled, (cmp, units));
            if m.contrast == Contrast::MedianRatio {
                forest = forest::figure(&pooled, units, cmp, m);
            }
        }
    }
    executability(&mut md, &mut csv, &executable_rows, cmp, &built);
    for m in &metrics {
        let metric_rows = as_rows(&|r| num(r, m.column), both_executable);
        section(&mut md, &mut csv, m, &metric_rows, cmp);
    }
    let safe = safe_name(&cmp.key);
    let suffix = match cmp.plans {
        Plans::Executable => "",
        Plans::Every => "-every-plan",
    };
    let time = (measure.column, measure.name());
    if let Some(f) = &forest {
        md.insert_str(findings_at, &forest_link(measure.column, &f.unit, &format!("compare-{safe}{suffix}")));
    }
    md.insert_str(findings_at, &findings::findings(&csv, &cmp.baseline, &effort(t, &d, &values), time));
    let title = format!("`{}` against `{}`{every}", cmp.key, cmp.baseline);
    let rows_of = |column: &str| as_rows(&|r| num(r, column), both_executable);
    let design = power::text(&title, (&metrics, &rows_of), units.as_ref());
    Ok(Rendered { stem: format!("compare-{safe}{suffix}"), markdown: md, csv, design: Some(design), forest })
}

/// The markdown line that shows the forest plot of the time `column` per `unit`, drawn beside
/// the comparison's files named `stem`.
fn forest_link(column: &str, unit: &str, stem: &str) -> String {
    format!(
        "![Forest plot: `{column}` value ÷ baseline per {unit}, the pooled median with its bootstrap interval, the \
         mean and the margin {}]({stem}-forest.png)\n\n",
        forest::MARGIN_TEXT
    )
}

/// The time the comparison reads ([`TimeMeasure`]) over every run it compares: every plan,
/// executable or not, is compared on mission time (what the planner optimised), as its curve
/// is kept for the executable plans only.
fn time_measure(t: &RunsTable, d: &Design, plans: Plans) -> TimeMeasure {
    let mut rows: Vec<usize> = d.cells.values().flat_map(|runs| runs.values().copied()).collect();
    rows.sort_unstable();
    rows.dedup();
    let measure = TimeMeasure::of(t, &rows);
    match plans {
        Plans::Every if LEVEL_COLUMNS.contains(&measure.column) => {
            TimeMeasure { column: "time_s", basis: crate::report::analysis::level::Basis::Unavailable }
        }
        _ => measure,
    }
}

/// Per value (the baseline's own values first where it stands for several controls), its runs
/// over every stratum and the most evaluations one of them made (nothing where runs.csv has
/// no `evaluations`).
fn effort(t: &RunsTable, d: &Design, values: &[String]) -> Vec<(String, usize, u64)> {
    let Some(c) = t.col("evaluations") else { return Vec::new() };
    values
        .iter()
        .map(|v| {
            let rows: std::collections::BTreeSet<usize> = d
                .cells
                .iter()
                .filter(|((_, value), _)| value == v)
                .flat_map(|(_, runs)| runs.values().copied())
                .collect();
            let most = rows.iter().filter_map(|&r| t.rows[r][c].parse::<u64>().ok()).max().unwrap_or(0);
            (v.clone(), rows.len(), most)
        })
        .collect()
}

/// With several controls as the baseline: which is the strongest in each stratum, as a table.
fn strongest_table(d: &Design) -> String {
    if d.strongest.is_empty() {
        return String::new();
    }
    let mut md = String::from("| stratum | strongest control |\n| --- | --- |\n");
    for (stratum, control) in &d.strongest {
        let _ = writeln!(md, "| {} | {control} |", if stratum.is_empty() { "all" } else { stratum });
    }
    md.push('\n');
    md
}

#[cfg(test)]
mod tests;
