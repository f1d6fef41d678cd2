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
mod pooled;
mod strongest;

use super::design::{followed_by, split_followers};
use super::{ReportError, cmp_group_values, param_columns};
use crate::stats::{Contrast, Family, bootstrap_ci, vargha_delaney_a12, wilcoxon_signed_rank};
use crate::study::records::RunsTable;
use std::collections::BTreeMap;
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

const METRICS: [Metric; 2] = [
    Metric { column: "cov_final_reach", higher_is_better: true, contrast: Contrast::MedianDifference, decimals: 4 },
    Metric { column: "time_s", higher_is_better: false, contrast: Contrast::MedianRatio, decimals: 1 },
];

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

    /// The CSV fields every section starts a row with, `metric` among them.
    fn lead_csv(&self, metric: &str) -> String {
        format!(
            "{},{},{metric},{},{},{},{},{}",
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

/// The rows of runs.csv by stratum (the other parameters that vary on their own) and value.
struct Design {
    strata: Vec<String>,
    /// Their columns.
    kept: Vec<usize>,
    /// Parameters that follow the strata's own (confounded with them), with the ones they follow.
    followers: Vec<(String, String)>,
    /// Parameters set under some compared values only (never on the baseline's runs): written
    /// into those values' labels.
    nested: Vec<String>,
    /// With several controls as the baseline: the strongest in each stratum.
    strongest: BTreeMap<String, String>,
    /// Whether a configuration recorded once pairs with every seed of the other side (a
    /// finished study); else runs pair by seed only.
    once_run_pairs: bool,
    /// `(stratum, value) → seed → row`.
    cells: BTreeMap<(String, String), BTreeMap<String, usize>>,
}

impl Design {
    /// Whether some compared configuration ran once while others ran over several seeds.
    fn once_run(&self) -> bool {
        let sizes: std::collections::BTreeSet<usize> = self.cells.values().map(BTreeMap::len).collect();
        sizes.contains(&1) && sizes.iter().any(|&n| n > 1)
    }

    /// Whether the comparisons are also pooled over the strata: when there is more than one.
    fn pooled(&self) -> bool {
        let mut strata = self.cells.keys().map(|(s, _)| s);
        strata.next().is_some_and(|first| strata.any(|s| s != first))
    }
}

fn design(t: &RunsTable, cmp: &Comparison, key: usize) -> Design {
    let others: Vec<usize> =
        param_columns(t).into_iter().filter(|p| *p != cmp.key).filter_map(|name| t.col(&name)).collect();
    // A parameter set only under some of the compared values (the GA's memetic step under
    // `solver = "ga"`) is empty on every baseline row: it is part of those values, not a stratum.
    let controls = strongest::controls(&cmp.baseline);
    let is_baseline = |r: &Vec<String>| controls.contains(&r[key].as_str());
    let (nested, candidates): (Vec<usize>, Vec<usize>) = others.into_iter().partition(|&c| {
        t.rows.iter().filter(|r| is_baseline(r)).all(|r| r[c].is_empty()) && t.rows.iter().any(|r| !r[c].is_empty())
    });
    let (kept, followers) = split_followers(t, &candidates);
    let strata: Vec<String> = kept.iter().map(|&c| t.header[c].clone()).collect();
    let followers: Vec<(String, String)> = followers.into_iter().map(|(c, of)| (t.header[c].clone(), of)).collect();
    let seed = t.col("seed").unwrap_or(0);
    let mut cells: BTreeMap<(String, String), BTreeMap<String, usize>> = BTreeMap::new();
    for (i, r) in t.rows.iter().enumerate() {
        let label = kept.iter().map(|&c| format!("{}={}", t.header[c], r[c])).collect::<Vec<_>>().join(", ");
        let mut value = r[key].clone();
        for &c in nested.iter().filter(|&&c| !r[c].is_empty()) {
            let _ = write!(value, " ({}={})", t.header[c], r[c]);
        }
        cells.entry((label, value)).or_default().insert(r[seed].clone(), i);
    }
    let nested = nested.iter().map(|&c| t.header[c].clone()).collect();
    // Several controls: each stratum's strongest stands for the baseline there, the controls
    // themselves are not compared.
    let mut strongest = BTreeMap::new();
    if controls.len() > 1 {
        strongest = strongest::per_stratum(t, &cells, &controls);
        for (stratum, control) in &strongest {
            let runs = cells[&(stratum.clone(), control.clone())].clone();
            cells.insert((stratum.clone(), cmp.baseline.clone()), runs);
        }
        cells.retain(|(_, v), _| !controls.contains(&v.as_str()));
    }
    Design { strata, kept, followers, nested, strongest, once_run_pairs: true, cells }
}

/// The pairs of a baseline's runs and a value's, by seed; where one side ran once and the other
/// over several seeds (a grid runs a configuration whose planner reads no seed once), its one
/// run pairs with every run of the other.
fn seed_pairs(base: &BTreeMap<String, usize>, other: &BTreeMap<String, usize>, once_run: bool) -> Vec<(usize, usize)> {
    match (base.len(), other.len()) {
        _ if !once_run => base.iter().filter_map(|(seed, &b)| other.get(seed).map(|&o| (b, o))).collect(),
        (1, n) if n > 1 => {
            let b = *base.values().next().expect("one run");
            other.values().map(|&o| (b, o)).collect()
        }
        (n, 1) if n > 1 => {
            let o = *other.values().next().expect("one run");
            base.values().map(|&b| (b, o)).collect()
        }
        _ => base.iter().filter_map(|(seed, &b)| other.get(seed).map(|&o| (b, o))).collect(),
    }
}

/// A comparison made, not yet written: its files' names and texts.
#[derive(Clone, Debug)]
pub struct Rendered {
    /// `compare-KEY` (the key's characters other than letters, digits, `.` and `-` as `_`).
    pub stem: String,
    /// The markdown report.
    pub markdown: String,
    /// One row per stratum, value and metric.
    pub csv: String,
}

impl Rendered {
    /// Writes `STEM.md` and `STEM.csv` into `out`; returns the markdown's path.
    pub fn save(&self, out: &Path) -> Result<PathBuf, ReportError> {
        let md = out.join(format!("{}.md", self.stem));
        let csv = out.join(format!("{}.csv", self.stem));
        for (path, text) in [(&md, &self.markdown), (&csv, &self.csv)] {
            crate::io::write_atomic(path, text.as_bytes())
                .map_err(|e| ReportError::Io(format!("{}: {e}", path.display())))?;
        }
        Ok(md)
    }
}

/// Reads `dir`'s runs.csv (failed runs left out, the `--where` pairs of `filter` applied as
/// the report applies them) and makes each comparison, writing nothing: a comparison that
/// cannot be made is refused before the report folder is touched.
pub fn render_all(
    dir: &Path,
    filter: &[(String, String)],
    comparisons: &[Comparison],
) -> Result<Vec<Rendered>, ReportError> {
    if comparisons.is_empty() {
        return Ok(Vec::new());
    }
    let (t, recorded) = super::read_filtered_runs(dir, filter)?;
    // A configuration recorded once pairs with every seed only in a finished study: in one
    // stopped part-way it may be a seeded configuration whose other seeds have not run.
    let expected = std::fs::read_to_string(dir.join("study.json"))
        .ok()
        .and_then(|j| serde_json::from_str::<serde_json::Value>(&j).ok())
        .and_then(|v| v["runs"].as_u64());
    let complete = expected.is_none_or(|n| recorded as u64 >= n);
    let mut rendered: Vec<Rendered> =
        comparisons.iter().map(|c| render_with(&t, c, complete)).collect::<Result<_, _>>()?;
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

/// The column of `cmp`'s key and its values (sorted), refused when the key is not swept, the
/// baseline is none of its values, or runs.csv lacks a compared metric.
fn compared_values(t: &RunsTable, cmp: &Comparison) -> Result<(usize, Vec<String>), ReportError> {
    let input = |m: String| ReportError::Input(m);
    let params = param_columns(t);
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
        return Err(input(format!(
            "--compare {}={}: no run has {which}; values: {}",
            cmp.key,
            cmp.baseline,
            values.join(", ")
        )));
    }
    for m in &METRICS {
        if t.col(m.column).is_none() {
            return Err(input(format!("--compare: runs.csv has no `{}` column (written by an older covga)", m.column)));
        }
    }
    Ok((key, values))
}

/// Makes the comparison `cmp` of the runs `t` of a finished study.
pub fn render(t: &RunsTable, cmp: &Comparison) -> Result<Rendered, ReportError> {
    render_with(t, cmp, true)
}

/// [`render`]; `complete` says whether the study is finished (else a configuration recorded
/// once is paired by seed like any other).
fn render_with(t: &RunsTable, cmp: &Comparison, complete: bool) -> Result<Rendered, ReportError> {
    let input = |m: String| ReportError::Input(m);
    let (key, _) = compared_values(t, cmp)?;
    let mut d = design(t, cmp, key);
    d.once_run_pairs = complete;
    // The compared values as labelled (with the parameters nested in them), in order.
    let mut values: Vec<String> = d.cells.keys().map(|(_, v)| v.clone()).collect();
    values.sort_by(|a, b| cmp_group_values(std::slice::from_ref(a), std::slice::from_ref(b)));
    values.dedup();
    let executable = |r: usize| t.col("executable").is_none_or(|c| t.rows[r][c] == "true");
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
    if rows.is_empty() {
        let why = match followed_by(t, key, &d.kept) {
            Some(of) => format!("`{}` follows {of} (confounded with it)", cmp.key),
            None => "the grid never crosses it with the other parameters".to_string(),
        };
        return Err(input(format!(
            "--compare {}={}: no stratum of the other parameters holds both the baseline and another value: {why}",
            cmp.key, cmp.baseline
        )));
    }
    let num = |r: usize, c: &str| t.col(c).and_then(|i| t.rows[r][i].parse::<f64>().ok()).unwrap_or(f64::NAN);
    let mut md = String::new();
    let mut csv = String::from(
        "stratum,value,metric,runs_baseline,runs_value,executable_baseline,executable_value,pairs,median_baseline,\
         median_value,contrast,estimate,ci_low,ci_high,value_better,value_worse,a12_value_greater,test,p,\
         p_holm,note\n",
    );
    let every = match cmp.plans {
        Plans::Executable => "",
        Plans::Every => ", every plan",
    };
    let _ = writeln!(md, "# `{}`: each value against `{}`{every}\n", cmp.key, cmp.baseline);
    let _ = writeln!(md, "{}\n", intro(&d, cmp));
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
    if d.pooled() {
        pooled::executability(&mut md, &mut csv, &pooled::pool(&executable_rows), cmp);
        for m in &METRICS {
            pooled::section(&mut md, &mut csv, m, &pooled::pool(&as_rows(&|r| num(r, m.column), both_executable)), cmp);
        }
    }
    executability(&mut md, &mut csv, &executable_rows, cmp);
    for m in &METRICS {
        let metric_rows = as_rows(&|r| num(r, m.column), both_executable);
        section(&mut md, &mut csv, m, &metric_rows, cmp);
    }
    let safe = safe_name(&cmp.key);
    let suffix = match cmp.plans {
        Plans::Executable => "",
        Plans::Every => "-every-plan",
    };
    md.insert_str(findings_at, &findings::findings(&csv, &cmp.baseline, &effort(t, &d, &values)));
    Ok(Rendered { stem: format!("compare-{safe}{suffix}"), markdown: md, csv })
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

/// The paragraph saying how the comparison is made.
fn intro(d: &Design, cmp: &Comparison) -> String {
    let strata = if d.strata.is_empty() {
        "one stratum (no other parameter varies)".to_string()
    } else {
        format!("within each combination of {}", d.strata.join(", "))
    };
    let which = match cmp.plans {
        Plans::Executable => "a pair counts where both plans are executable",
        Plans::Every => {
            "every pair counts, executable or not (what the planner optimised, whether a robot can drive \
             its plan or not)"
        }
    };
    let mut s = format!(
        "Each value of `{}` against `{}`, {strata}. Runs are paired by seed (replicate `i` of every \
         configuration has the same seed); {which}. Coverage is \
         `cov_final_reach` (higher is better), compared as the median of the value's runs minus the \
         baseline's; time is `time_s` (lower is better), compared as the ratio of medians. Intervals: \
         {:.0} % percentile bootstrap over pairs ({RESAMPLES} resamples, seed {BOOTSTRAP_SEED}). Tests: \
         two-sided Wilcoxon signed-rank over the pairs (exact up to 50 pairs), Holm–Bonferroni over \
         the family of the metric's comparisons below; \"shown\" means a Holm-adjusted p below {:.2}.",
        cmp.key,
        cmp.baseline,
        LEVEL * 100.0,
        1.0 - LEVEL
    );
    for (name, of) in &d.followers {
        let _ = write!(s, " `{name}` follows {of} (confounded with it: not a stratum of its own).");
    }
    for name in &d.nested {
        let _ = write!(
            s,
            " `{name}` is set under some values of `{}` only: the values are told apart by it, not stratified.",
            cmp.key
        );
    }
    if !d.strongest.is_empty() {
        let _ = write!(
            s,
            " `{}` stands for the strongest of these controls in each stratum: the one whose executable \
             plans have the lowest median `time_s` there (named stratum by stratum below).",
            cmp.baseline,
        );
    }
    if d.once_run() && !d.once_run_pairs {
        s.push_str(
            " The study is not finished: a configuration recorded once is paired by seed only, as if its \
             other seeds had not run yet.",
        );
    } else if d.once_run() {
        s.push_str(
            " Where one side of a comparison ran once (a configuration whose planner reads no seed \
             runs once in a grid) its one run pairs with every seed of the other.",
        );
    }
    if d.pooled() {
        s.push_str(
            " The comparisons are made twice: first pooled over the strata (every stratum's pairs \
             together; the pair effect is the difference, or for time the ratio, within each pair; \
             its median with a paired bootstrap interval; the signed-rank test of the differences, \
             of the log-ratios for time; Holm over the values of each metric), then stratum by stratum.",
        );
    }
    s
}

/// The executable plans of each value against the baseline's, pair by pair: the exact
/// McNemar test, i.e. the sign test over the pairs where one plan is executable and the other
/// not, Holm-corrected over the file's comparisons. `pairs` hold 1 (executable) or 0.
fn executability(md: &mut String, csv: &mut String, rows: &[Row], cmp: &Comparison) {
    let mut family =
        Family::new(format!("executability ({} comparisons of `{}` against `{}`)", rows.len(), cmp.key, cmp.baseline));
    let split = |r: &Row| {
        let gained = r.pairs.iter().filter(|(b, v)| v > b).count();
        let lost = r.pairs.iter().filter(|(b, v)| v < b).count();
        (gained, lost)
    };
    let tests: Vec<Option<f64>> = rows
        .iter()
        .map(|r| {
            let (gained, lost) = split(r);
            let signs: Vec<f64> = std::iter::repeat_n(1.0, gained).chain(std::iter::repeat_n(-1.0, lost)).collect();
            crate::stats::sign_test(&signs, 0.0)
        })
        .collect();
    for (r, p) in rows.iter().zip(&tests) {
        if let Some(p) = p {
            family.push(format!("{} {}", r.stratum, r.value), *p);
        }
    }
    let mut adjusted = family.adjusted().into_iter();
    let _ = writeln!(
        md,
        "## Executable plans
"
    );
    let _ = writeln!(
        md,
        "| stratum | value | executable (baseline, value) | pairs | only the value's executable | only the baseline's executable | p (exact McNemar) | p (Holm) | finding |"
    );
    let _ = writeln!(md, "| --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    let mut shown = (0, 0);
    for (r, p) in rows.iter().zip(&tests) {
        let (gained, lost) = split(r);
        let holm = p.map(|_| adjusted.next().expect("one adjusted p per test"));
        let finding = match holm {
            _ if r.pairs.is_empty() => "no pair: not compared".to_string(),
            None => "the same in every pair: not tested".to_string(),
            Some(h) if h < 1.0 - LEVEL => {
                let more = gained > lost;
                if more {
                    shown.0 += 1
                } else {
                    shown.1 += 1
                }
                format!("{} often executable than {} (shown)", if more { "more" } else { "less" }, cmp.baseline)
            }
            Some(_) => "not shown".to_string(),
        };
        let _ = writeln!(
            md,
            "{} {gained} | {lost} | {} | {} | {finding} |",
            r.lead_md(),
            p.map_or("–".into(), p_text),
            holm.map_or("–".into(), p_text),
        );
        let field = |x: Option<f64>| x.map_or(String::new(), |x| format!("{x}"));
        let _ = writeln!(
            csv,
            "{},,,,,,,{gained},{lost},,{},{},{},{}",
            r.lead_csv("executable"),
            if p.is_some() { "mcnemar exact" } else { "" },
            field(*p),
            field(holm),
            quoted(&finding),
        );
    }
    let _ = writeln!(
        md,
        "\n{} Of {} comparisons, {} show the value's plans more often executable than `{}`'s and {} less often.\n",
        family.statement(),
        rows.len(),
        shown.0,
        cmp.baseline,
        shown.1
    );
}

fn p_text(p: f64) -> String {
    if p < 1e-4 { format!("{p:.1e}") } else { format!("{p:.4}") }
}

/// One compared row's numbers: both sides' medians, pairs better and worse, the bootstrap
/// interval of the contrast, A₁₂, the signed-rank test and its Holm-adjusted p, the finding.
struct RowStats {
    medians: (Option<f64>, Option<f64>),
    better: usize,
    worse: usize,
    ci: Option<crate::stats::Interval>,
    a12: f64,
    test: Option<crate::stats::SignedRank>,
    holm: Option<f64>,
    finding: String,
}

/// The numbers of row `r` of metric `m` against `cmp`'s baseline, with its test's Holm-adjusted
/// p; `shown` counts the rows shown better and worse.
fn row_stats(
    m: &Metric,
    r: &Row,
    cmp: &Comparison,
    (test, holm): (Option<crate::stats::SignedRank>, Option<f64>),
    shown: &mut (usize, usize),
) -> RowStats {
    let (b, v): (Vec<f64>, Vec<f64>) = r.pairs.iter().copied().unzip();
    let better = r.pairs.iter().filter(|(b, v)| if m.higher_is_better { v > b } else { v < b }).count();
    let worse = r.pairs.iter().filter(|(b, v)| if m.higher_is_better { v < b } else { v > b }).count();
    let median = |x: &[f64]| (!x.is_empty()).then(|| crate::stats::quartiles(x).1);
    let ci = bootstrap_ci(&v, &b, m.contrast, true, LEVEL, RESAMPLES, BOOTSTRAP_SEED);
    let a12 = if r.pairs.is_empty() { f64::NAN } else { vargha_delaney_a12(&v, &b) };
    let min_p = 2.0 * 0.5f64.powi(r.pairs.len() as i32);
    let finding = match (test, holm) {
        _ if r.pairs.is_empty() => "no pair of executable plans: not compared".to_string(),
        (None, _) => "equal in every pair: not tested".to_string(),
        (Some(_), Some(h)) if h < 1.0 - LEVEL => {
            let word = if better > worse { "better" } else { "worse" };
            if better > worse {
                shown.0 += 1
            } else {
                shown.1 += 1
            }
            format!("{word} than {} (shown)", cmp.baseline)
        }
        (Some(_), _) if min_p >= 1.0 - LEVEL => {
            format!("not shown: {} pairs cannot reach p < {:.2}", r.pairs.len(), 1.0 - LEVEL)
        }
        (Some(_), _) => "not shown".to_string(),
    };
    RowStats { medians: (median(&b), median(&v)), better, worse, ci, a12, test, holm, finding }
}

/// Row `r`'s line of the metric's table in `summary.md`.
fn md_row(m: &Metric, r: &Row, st: &RowStats) -> String {
    let d = m.decimals;
    let ci_text = match st.ci {
        Some(c) if m.contrast == Contrast::MedianRatio => format!("{:.3}× [{:.3}, {:.3}]", c.estimate, c.low, c.high),
        Some(c) => format!("{:+.4} [{:+.4}, {:+.4}]", c.estimate, c.low, c.high),
        None => "–".into(),
    };
    let median = |x: Option<f64>| x.map_or("–".into(), |x| format!("{x:.d$}"));
    format!(
        "{} {} | {} | {} | {} of {} | {} | {} | {} | {} |",
        r.lead_md(),
        median(st.medians.0),
        median(st.medians.1),
        ci_text,
        st.better,
        r.pairs.len(),
        if st.a12.is_nan() { "–".into() } else { format!("{:.2}", st.a12) },
        st.test.map_or("–".into(), |t| format!("{} ({})", p_text(t.p_value), t.method.name())),
        st.holm.map_or("–".into(), p_text),
        st.finding
    )
}

/// Row `r`'s line of the comparisons CSV.
fn csv_row(m: &Metric, r: &Row, st: &RowStats) -> String {
    let field = |x: Option<f64>| x.map_or(String::new(), |x| format!("{x}"));
    format!(
        "{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
        r.lead_csv(m.column),
        field(st.medians.0),
        field(st.medians.1),
        match m.contrast {
            Contrast::MedianDifference => "difference",
            Contrast::MedianRatio => "ratio",
        },
        field(st.ci.map(|c| c.estimate)),
        field(st.ci.map(|c| c.low)),
        field(st.ci.map(|c| c.high)),
        st.better,
        st.worse,
        field((!st.a12.is_nan()).then_some(st.a12)),
        st.test.map_or(String::new(), |t| format!("wilcoxon {}", t.method.name())),
        field(st.test.map(|t| t.p_value)),
        field(st.holm),
        quoted(&st.finding)
    )
}

/// The table and findings of one metric.
fn section(md: &mut String, csv: &mut String, m: &Metric, rows: &[Row], cmp: &Comparison) {
    let mut family =
        Family::new(format!("`{}` ({} comparisons of `{}` against `{}`)", m.column, rows.len(), cmp.key, cmp.baseline));
    let tests: Vec<Option<crate::stats::SignedRank>> = rows
        .iter()
        .map(|r| {
            let (b, v): (Vec<f64>, Vec<f64>) = r.pairs.iter().copied().unzip();
            wilcoxon_signed_rank(&v, &b)
        })
        .collect();
    for (r, t) in rows.iter().zip(&tests) {
        if let Some(t) = t {
            family.push(format!("{} {}", r.stratum, r.value), t.p_value);
        }
    }
    let mut adjusted = family.adjusted().into_iter();
    let effect = match m.contrast {
        Contrast::MedianDifference => "difference of medians",
        Contrast::MedianRatio => "ratio of medians",
    };
    let _ = writeln!(md, "## `{}`\n", m.column);
    let _ = writeln!(
        md,
        "| stratum | value | executable (baseline, value) | pairs | median baseline | median value | {effect} [{:.0} % CI] | value better in | A₁₂ (value > baseline) | p | p (Holm) | finding |",
        LEVEL * 100.0
    );
    let _ = writeln!(md, "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    let mut shown = (0, 0);
    for (r, t) in rows.iter().zip(&tests) {
        let holm = t.map(|_| adjusted.next().expect("one adjusted p per test"));
        let st = row_stats(m, r, cmp, (*t, holm), &mut shown);
        let _ = writeln!(md, "{}", md_row(m, r, &st));
        let _ = writeln!(csv, "{}", csv_row(m, r, &st));
    }
    let _ = writeln!(
        md,
        "\n{} Of {} comparisons, {} show the value better than `{}` and {} worse; the rest show no \
         difference at this level (which is not evidence of equality).\n",
        family.statement(),
        rows.len(),
        shown.0,
        cmp.baseline,
        shown.1
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::records::metric_columns;

    /// A runs table of `a` (a, b) × `map` (m1, m2, with `budget` following it) × 6 seeds; `b`
    /// covers `shift` more and takes 20 s longer; one `b` plan on m2 is not executable.
    fn table(shift: f64) -> RunsTable {
        let metrics = metric_columns();
        let mut text = format!("run_id,config_id,replicate,seed,a,map,budget,{}\n", metrics.join(","));
        for (ai, a) in ["a", "b"].iter().enumerate() {
            for (mi, map) in ["m1", "m2"].iter().enumerate() {
                for s in 0..6 {
                    let cov = 0.5 + 0.01 * s as f64 + if ai == 1 { shift } else { 0.0 };
                    let time = 100.0 + s as f64 * 3.0 + if ai == 1 { 20.0 } else { 0.0 };
                    let exec = !(ai == 1 && mi == 1 && s == 0);
                    let fields: Vec<String> = metrics
                        .iter()
                        .map(|m| match m.as_str() {
                            "planner" => "thesis".into(),
                            "executable" => exec.to_string(),
                            "cov_final_reach" => cov.to_string(),
                            "time_s" => time.to_string(),
                            _ => "0".into(),
                        })
                        .collect();
                    let budget = 1000 * (mi + 1);
                    let _ = writeln!(
                        text,
                        "r{ai}{mi}{s},c{ai}{mi},{s},{},{a},{map},{budget},{}",
                        100 + s,
                        fields.join(",")
                    );
                }
            }
        }
        RunsTable::parse(&text).unwrap()
    }

    /// A control run once (it reads no seed) against a GA over 6 seeds, with and without a
    /// step (`memetic`) that is set under `solver = "ga"` only.
    fn control_table() -> RunsTable {
        let metrics = metric_columns();
        let mut text = format!("run_id,config_id,replicate,seed,solver,memetic,{}\n", metrics.join(","));
        let mut line = |id: String, rep: usize, solver: &str, memetic: &str, time: f64| {
            let fields: Vec<String> = metrics
                .iter()
                .map(|m| match m.as_str() {
                    "planner" => "cell_order".into(),
                    "executable" => "true".into(),
                    "cov_final_reach" => "0.9".into(),
                    "time_s" => time.to_string(),
                    _ => "0".into(),
                })
                .collect();
            let _ =
                writeln!(text, "{id},c{solver}{memetic},{rep},{},{solver},{memetic},{}", 100 + rep, fields.join(","));
        };
        line("n".into(), 0, "nearest", "", 100.0);
        for s in 0..6 {
            line(format!("t{s}"), s, "ga", "true", 90.0 - s as f64);
            line(format!("f{s}"), s, "ga", "false", 110.0 + s as f64);
        }
        RunsTable::parse(&text).unwrap()
    }

    #[test]
    fn a_control_run_once_pairs_with_every_seed_and_nested_settings_label_the_values() {
        let dir = tempfile::tempdir().unwrap();
        let md = write(&control_table(), &Comparison::parse("solver=nearest").unwrap(), dir.path()).unwrap();
        let text = std::fs::read_to_string(&md).unwrap();
        assert!(text.contains("`memetic` is set under some values of `solver` only"), "{text}");
        assert!(text.contains("its one run pairs with every seed of the other"), "{text}");
        let csv = RunsTable::parse(&std::fs::read_to_string(dir.path().join("compare-solver.csv")).unwrap()).unwrap();
        let get = |r: &Vec<String>, c: &str| r[csv.col(c).unwrap()].clone();
        let time = |value: &str| {
            csv.rows.iter().find(|r| get(r, "metric") == "time_s" && get(r, "value") == value).cloned().unwrap()
        };
        let (with, without) = (time("ga (memetic=true)"), time("ga (memetic=false)"));
        assert_eq!((get(&with, "pairs"), get(&without, "pairs")), ("6".into(), "6".into()));
        assert_eq!((get(&with, "runs_baseline"), get(&with, "runs_value")), ("1".into(), "6".into()));
        // Faster in all six pairs, slower in all six: exact p = 2/2⁶ each.
        assert_eq!((get(&with, "value_better"), get(&without, "value_worse")), ("6".into(), "6".into()));
        assert_eq!(get(&with, "p").parse::<f64>().unwrap(), 2.0 / 64.0);
        assert_eq!(get(&with, "estimate").parse::<f64>().unwrap(), 87.5 / 100.0);
        // A study not yet finished pairs by seed only: the control's one run meets replicate 0.
        let part = render_with(&control_table(), &Comparison::parse("solver=nearest").unwrap(), false).unwrap();
        assert!(part.markdown.contains("The study is not finished"), "{}", part.markdown);
        let csv = RunsTable::parse(&part.csv).unwrap();
        let time = csv.rows.iter().find(|r| get(r, "metric") == "time_s" && get(r, "stratum") != "pooled").unwrap();
        assert_eq!(get(time, "pairs"), "1");
    }

    #[test]
    fn pairs_by_seed_within_strata_corrects_the_family_and_names_the_confounded_column() {
        let dir = tempfile::tempdir().unwrap();
        let t = table(0.1);
        let md = write(&t, &Comparison::parse("a=a").unwrap(), dir.path()).unwrap();
        let text = std::fs::read_to_string(&md).unwrap();
        assert!(text.contains("within each combination of map"), "{text}");
        assert!(text.contains("`budget` follows map"), "{text}");
        let csv = RunsTable::parse(&std::fs::read_to_string(dir.path().join("compare-a.csv")).unwrap()).unwrap();
        let get = |r: &Vec<String>, c: &str| r[csv.col(c).unwrap()].clone();
        assert_eq!(csv.rows.len(), 9, "pooled and two strata × executability and two metrics");
        let exec_m2 =
            csv.rows.iter().find(|r| get(r, "metric") == "executable" && get(r, "stratum") == "map=m2").unwrap();
        // Seed 0 of b on m2 is the only discordant pair: McNemar's exact p = 1.
        assert_eq!((get(exec_m2, "value_better"), get(exec_m2, "value_worse")), ("0".into(), "1".into()));
        assert_eq!((get(exec_m2, "test"), get(exec_m2, "p")), ("mcnemar exact".into(), "1".into()));
        let time_m1 = csv.rows.iter().find(|r| get(r, "metric") == "time_s" && get(r, "stratum") == "map=m1").unwrap();
        // Six pairs, b slower in each: exact p = 2/2⁶; m2 has five pairs (2/2⁵). Holm over the
        // two: 2 · 1/32 and 1/16, both 0.0625 — nothing shown.
        assert_eq!(get(time_m1, "pairs"), "6");
        assert_eq!(get(time_m1, "value_worse"), "6");
        assert_eq!(get(time_m1, "p").parse::<f64>().unwrap(), 2.0 / 64.0);
        assert_eq!(get(time_m1, "p_holm").parse::<f64>().unwrap(), 0.0625);
        assert_eq!(get(time_m1, "estimate").parse::<f64>().unwrap(), 127.5 / 107.5);
        let time_m2 = csv.rows.iter().find(|r| get(r, "metric") == "time_s" && get(r, "stratum") == "map=m2").unwrap();
        assert_eq!((get(time_m2, "pairs"), get(time_m2, "executable_value")), ("5".into(), "5".into()));
        assert!(get(time_m2, "note").contains("5 pairs cannot reach p < 0.05"), "{:?}", get(time_m2, "note"));
        // No difference in coverage: every pair ties, not tested.
        let same = table(0.0);
        write(&same, &Comparison::parse("a=a").unwrap(), dir.path()).unwrap();
        let csv = RunsTable::parse(&std::fs::read_to_string(dir.path().join("compare-a.csv")).unwrap()).unwrap();
        let cov = csv.rows.iter().find(|r| get(r, "metric") == "cov_final_reach").unwrap();
        assert_eq!((get(cov, "p"), get(cov, "note")), (String::new(), "equal in every pair: not tested".into()));
    }

    #[test]
    fn pooled_over_the_strata_pairs_every_strata_pair_in_one_test() {
        let dir = tempfile::tempdir().unwrap();
        let md = write(&table(0.1), &Comparison::parse("a=a").unwrap(), dir.path()).unwrap();
        let text = std::fs::read_to_string(&md).unwrap();
        assert!(text.contains("## `time_s`, pooled over the strata"), "{text}");
        assert!(text.contains("One test of `time_s` pooled over the strata (1 value against `a`)"), "{text}");
        let csv = RunsTable::parse(&std::fs::read_to_string(dir.path().join("compare-a.csv")).unwrap()).unwrap();
        let get = |r: &Vec<String>, c: &str| r[csv.col(c).unwrap()].clone();
        let pooled = |metric: &str| {
            csv.rows.iter().find(|r| get(r, "metric") == metric && get(r, "stratum") == "pooled").unwrap().clone()
        };
        // Six pairs on m1 and five on m2 (one plan of b there is not executable), b covers 0.1
        // more in each: exact p = 2/2¹¹, one test, nothing to correct.
        let cov = pooled("cov_final_reach");
        assert_eq!((get(&cov, "pairs"), get(&cov, "value_better")), ("11".into(), "11".into()));
        assert_eq!(get(&cov, "contrast"), "pair difference");
        assert!((get(&cov, "estimate").parse::<f64>().unwrap() - 0.1).abs() < 1e-12);
        assert_eq!(get(&cov, "p").parse::<f64>().unwrap(), 2.0 / 2048.0);
        assert_eq!(get(&cov, "p_holm"), get(&cov, "p"));
        // Time: the ratio within each pair, (120 + 3s)/(100 + 3s); the median of the eleven is
        // seed 3's.
        let time = pooled("time_s");
        assert_eq!((get(&time, "contrast"), get(&time, "value_worse")), ("pair ratio".into(), "11".into()));
        assert_eq!(get(&time, "estimate").parse::<f64>().unwrap(), 129.0 / 109.0);
        let exec = pooled("executable");
        assert_eq!(
            (get(&exec, "pairs"), get(&exec, "value_worse"), get(&exec, "p")),
            ("12".into(), "1".into(), "1".into())
        );
        // Every plan: the pair with b's plan not executable counts too, in a file of its own.
        let every = Comparison::parse_every_plan("a=a").unwrap();
        write(&table(0.1), &every, dir.path()).unwrap();
        let text = std::fs::read_to_string(dir.path().join("compare-a-every-plan.md")).unwrap();
        assert!(text.contains("every pair counts, executable or not"), "{text}");
        let csv =
            RunsTable::parse(&std::fs::read_to_string(dir.path().join("compare-a-every-plan.csv")).unwrap()).unwrap();
        let time = csv.rows.iter().find(|r| get(r, "metric") == "time_s" && get(r, "stratum") == "pooled").unwrap();
        assert_eq!(get(time, "pairs"), "12");
        // One stratum: nothing to pool.
        let one: Vec<Vec<String>> = table(0.1).rows.into_iter().filter(|r| r[5] == "m1").collect();
        let mut t = table(0.1);
        t.rows = one;
        write(&t, &Comparison::parse("a=a").unwrap(), dir.path()).unwrap();
        let text = std::fs::read_to_string(dir.path().join("compare-a.md")).unwrap();
        assert!(!text.contains("pooled"), "{text}");
    }

    #[test]
    fn comparisons_that_cannot_be_made_are_refused_with_the_reason() {
        let dir = tempfile::tempdir().unwrap();
        let t = table(0.1);
        let err = |text: &str| match write(&t, &Comparison::parse(text).unwrap(), dir.path()) {
            Err(ReportError::Input(m)) => m,
            other => panic!("{text}: {other:?}"),
        };
        assert!(err("budget=1000").contains("`budget` follows map (confounded with it)"), "{}", err("budget=1000"));
        assert!(err("a=c").contains("no run has that value; values: a, b"), "{}", err("a=c"));
        assert!(err("a=a|c").contains("no run has the value c; values: a, b"), "{}", err("a=a|c"));
        assert!(err("time_s=1").contains("not a swept parameter; swept: a, map, budget"), "{}", err("time_s=1"));
        assert!(Comparison::parse("a").is_err() && Comparison::parse("=x").is_err());
        assert!(Comparison::parse_every_plan("a").unwrap_err().starts_with("--compare-every-plan a:"));
    }
}
