//! `covga report`: figures, tables and statistics of a study folder — Pareto fronts per group
//! with hypervolume, diversity of the front runs, best paths, the best configuration and run
//! durations per group (003 Tables A.1/A.2, 4.4), means with 95 % confidence intervals over
//! seeds, Kruskal–Wallis tests per swept parameter and the ANOVA of 003 §5.3.
//!
//! The reports layer reads a study's records (`crate::study::records`) and nothing runs here.
//! One module per report section: the group tables and figures, the comparisons
//! ([`compare`]), the measures ([`measures`]), the ANOVA tables ([`anova_report`], on
//! [`crate::stats::anova`]); what replicates the papers and the committed studies lives in
//! [`replication`]: the planner comparison ([`ablation`]), the fleet study ([`fleet_report`]),
//! the thesis's tables and claims ([`thesis_report`], [`claims`]), seed to seed and the plans; [`crate::stats`] holds the tests they
//! share, [`figures`] and [`ablation_figures`] the figures drawn with `crate::plot`'s
//! primitives. A study report is its sections in order (`sections::SECTIONS`), each reading
//! what `study::Study` computes once.

pub mod anova_report;
mod bound;
pub mod common_tables;
pub mod compare;
mod curves;
mod design;
mod effects;
pub mod figures;
pub mod folder_record;
pub mod measures;
pub mod planners_pareto;
pub mod replication;
mod report_tables;
pub mod rescore;
pub mod search_objective;
mod sections;
mod study;
mod values;

use crate::ga::pareto::non_dominated;
use crate::stats::median;
use crate::study::records::RunsTable;
pub use replication::{ablation, ablation_figures, claims, fleet_report, plans, seed_to_seed, thesis_report};
use std::path::Path;
pub(super) use values::{check_against_grid, check_finite};

/// Report failures.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// Bad input (no runs, unknown column).
    #[error("{0}")]
    Input(String),
    /// A file could not be read or written.
    #[error("{0}")]
    Io(String),
    /// A figure failed.
    #[error(transparent)]
    Plot(#[from] crate::plot::PlotError),
}

/// One configuration over its replicates: id, rows, cov (mean, CI), t (mean, CI), mean f.
pub(super) type ConfigRow = (String, Vec<usize>, (f64, f64), (f64, f64), f64);

pub(super) struct Group {
    pub(super) label: String,
    pub(super) rows: Vec<usize>,
}

/// The swept-parameter columns of a runs table: between `seed` and the metric columns (a swept
/// `planner` key has the same name as the metric column `planner`, so the metric block is found
/// by its length).
pub fn param_columns(t: &RunsTable) -> Vec<String> {
    let metrics = crate::study::records::metric_columns().len();
    match t.col("seed") {
        Some(a) if t.header.len() >= a + 1 + metrics => t.header[a + 1..t.header.len() - metrics].to_vec(),
        _ => Vec::new(),
    }
}

/// Orders two groups' values parameter by parameter: numbers by magnitude (so the panels of
/// `tournament_size` run 2, 3, 5, 10 and not 10, 2, 3, 5), anything else as text, and a number
/// before a text.
pub(super) fn cmp_group_values(a: &[String], b: &[String]) -> std::cmp::Ordering {
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
fn read_history_diversity(path: &Path) -> Option<Vec<(u32, f64)>> {
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
fn coverage_front(points: &[(f64, f64)]) -> Vec<usize> {
    non_dominated(points).into_iter().filter(|&k| points[k].1 >= FRONT_MIN_COVERAGE).collect()
}

/// What `covga report` reads and where it writes: groups, a filter on the runs and the name of
/// the report folder.
#[derive(Clone, Debug, Default)]
pub struct ReportOptions {
    /// Group (facet) by these columns.
    pub by: Vec<String>,
    /// Keep only the runs whose column equals the value (numbers compared as numbers).
    pub filter: Vec<(String, String)>,
    /// Report folder `<dir>/report-<name>` (default `<dir>/report`).
    pub name: Option<String>,
    /// Also write `anova-condensed.md`: the analysis of variance's condensed tables (main
    /// effects, the three largest interactions, the residual), where the report makes one.
    pub anova_condensed: bool,
    /// Also write `plans.md` and `plans.csv` ([`plans`]): the configurations' plans and final
    /// populations.
    pub plans: bool,
    /// With `plans`: a runs.csv of one reference plan per map to set every run against.
    pub reference: Option<std::path::PathBuf>,
    /// Also write `seed-to-seed.md` ([`seed_to_seed`]): how far one replicate's ranking of the
    /// configurations carries to another.
    pub seed_to_seed: bool,
    /// Also write `measures.md` and `measures.csv` ([`measures`]): these figures per group,
    /// read from runs.csv, each run's `summary.json` or its `history.csv`.
    pub measures: Vec<String>,
}

/// `dir`'s runs.csv as the parts of a report that read it apart from the summary do: the runs
/// that failed while running left out and the `--where` pairs of `filter` applied; with the
/// number of runs recorded (failed and filtered ones included).
pub(super) fn read_filtered_runs(
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
pub(super) fn with_failed_note(md: String, failed: &[String]) -> String {
    let Some(note) = failed_note(failed) else { return md };
    match md.find("\n\n") {
        Some(i) => format!("{}{note}\n\n{}", &md[..i + 2], &md[i + 2..]),
        None => format!("{md}\n\n{note}\n"),
    }
}

/// The `--where` pairs by key, in the order the keys first appear: a key given more than once
/// keeps the runs with any of its values (an OR); different keys must all hold (an AND).
pub(super) fn where_keys(filter: &[(String, String)]) -> Vec<(&str, Vec<&str>)> {
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
pub(super) fn run_folder(dir: &Path, id: &str, reads: &str) -> Result<std::path::PathBuf, ReportError> {
    let folder = dir.join("runs").join(id);
    if folder.is_dir() {
        Ok(folder)
    } else {
        Err(ReportError::Input(format!("{}: no folder for run {id}: {reads}", dir.join("runs").display())))
    }
}

/// Whether a cell of runs.csv equals a `--where` value: as numbers when both parse, else as text.
pub(super) fn cell_matches(cell: &str, want: &str) -> bool {
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

/// Why `--plans` and `--seed-to-seed` refuse a fleet study.
const FLEET_NOT_PLANS: &str = "--plans and --seed-to-seed read studies of one robot's plans; this is a fleet study (its \
                               report compares the fleets' union coverage and makespan)";

/// Why `--measure` refuses a fleet study.
const FLEET_NOT_MEASURES: &str = "--measure tabulates figures per group of one robot's runs; this is a fleet study (its \
                                  report groups by fleet and method on its own)";

/// The report folder of `opts`: `<dir>/report`, or `<dir>/report-NAME` for `--name NAME`.
pub fn report_folder(dir: &Path, opts: &ReportOptions) -> Result<std::path::PathBuf, ReportError> {
    study::report_folder(dir, opts.name.as_deref())
}

/// Writes `<dir>/report/` (grouped by `by`) and returns the path of `summary.md`.
pub fn write_report(dir: &Path, by: &[String]) -> Result<std::path::PathBuf, ReportError> {
    write_report_with(dir, &ReportOptions { by: by.to_vec(), ..Default::default() })
}

/// Writes the report folder of `opts` and returns the path of `summary.md`: the study folder
/// read and checked once (`study::Loaded`), the groups, fronts and best runs every section
/// shares computed once (`study::Study`), then each section of `sections::SECTIONS` in turn.
pub fn write_report_with(dir: &Path, opts: &ReportOptions) -> Result<std::path::PathBuf, ReportError> {
    if opts.reference.is_some() && !opts.plans {
        return Err(ReportError::Input("--reference sets the runs against reference plans in plans.md, so it needs --plans (in Python: plans=True)".into()));
    }
    // Rendered before anything is written: what cannot be made leaves no half-written report.
    let plans = match opts.plans {
        true => Some(plans::render(dir, &opts.filter, opts.reference.as_deref(), &report_folder(dir, opts)?)?),
        false => None,
    };
    let loaded = study::Loaded::read(dir, opts)?;
    if self::fleet_report::applies(&loaded.t) {
        if opts.plans || opts.seed_to_seed {
            return Err(ReportError::Input(FLEET_NOT_PLANS.into()));
        }
        if !opts.measures.is_empty() {
            return Err(ReportError::Input(FLEET_NOT_MEASURES.into()));
        }
        loaded.create_folder()?;
        self::fleet_report::write(dir, &loaded.t, &loaded.out, loaded.incomplete.as_deref())?;
        return Ok(loaded.out.join("summary.md"));
    }
    // Made from the study before anything is written: one that cannot be made leaves no
    // report folder behind.
    let seed_to_seed = opts
        .seed_to_seed
        .then(|| seed_to_seed::render(&loaded.t, &opts.by).map(|md| with_failed_note(md, &loaded.failed)))
        .transpose()?;
    let measures = (!opts.measures.is_empty())
        .then(|| {
            measures::render(dir, &loaded.t, &loaded.groups(&opts.by), &loaded.selected, &opts.measures, &loaded.out)
                .map(|r| compare::Rendered { markdown: with_failed_note(r.markdown, &loaded.failed), ..r })
        })
        .transpose()?;
    let folders = folder_record::FolderRecords::open(dir, &loaded.out)?;
    loaded.create_folder()?;
    let study = study::Study::new(dir, &opts.by, loaded, folders);
    study.write_configurations()?;
    let mut md = String::new();
    for section in sections::SECTIONS {
        if section.applies(&study) {
            section.write(&study, &mut md)?;
        }
    }
    if opts.anova_condensed {
        let tables = anova_report::condensed(&study.t, &study.params);
        let body = if tables.is_empty() {
            "No analysis of variance is made of these runs (`summary.md` says why).\n"
        } else {
            &tables
        };
        let text = format!(
            "# Analysis of variance, condensed\n\nThe main effects, the three largest two-way interactions and the residual \
             of each table of `summary.md`'s analysis of variance, its rows as there.\n\n{}\n",
            body.trim_end()
        );
        crate::io::write_atomic(&study.out.join("anova-condensed.md"), text.as_bytes())
            .map_err(|e| ReportError::Io(e.to_string()))?;
    }
    let path = study.out.join("summary.md");
    crate::io::write_atomic(&path, md.as_bytes()).map_err(|e| ReportError::Io(e.to_string()))?;
    study.folders.save(&study.out)?;
    if let Some(p) = plans {
        p.save(&study.out)?;
    }
    if let Some(m) = measures {
        m.save(&study.out)?;
    }
    if let Some(text) = seed_to_seed {
        crate::io::write_atomic(&study.out.join("seed-to-seed.md"), text.as_bytes())
            .map_err(|e| ReportError::Io(e.to_string()))?;
    }
    Ok(path)
}

#[cfg(test)]
mod tests;
