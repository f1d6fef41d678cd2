//! `covga report`: figures, tables and statistics of a study folder — Pareto fronts per group
//! with hypervolume, diversity of the front runs, best paths, the best configuration and run
//! durations per group (003 Tables A.1/A.2, 4.4), means with 95 % confidence intervals over
//! seeds, Kruskal–Wallis tests per swept parameter and the ANOVA of 003 §5.3.
//!
//! The reports layer reads a study's records (`crate::study::records`) and nothing runs here.
//! Its rooms, each reading only from those below it (`tests/it/architecture/report_rooms.rs`
//! holds the order):
//!
//! 1. [`figures`]: every figure, drawn from the numbers it is given, with the legend and colour
//!    helpers they share; no other room draws.
//! 2. [`analysis`]: the study as read and checked, its groups, fronts, best runs and design, and
//!    the run folders' records.
//! 3. [`tables`]: the summary's tables, the parameters' tests and ANOVA, `--measure`,
//!    `--previous`; [`compare`]: `--compare`, a value against a baseline.
//! 4. [`replication`]: what replicates the papers and the committed studies (the planner
//!    comparison, 003's claims and tables, seed to seed, the fleets' report, the plans); no
//!    room below reads from it.
//! 5. The summary's sections (`sections`: `summary.md`, section by section, in the order of
//!    `SECTIONS`) and this module's entry points, which put the rooms together.

pub mod analysis;
pub mod compare;
pub mod figures;
pub mod replication;
mod sections;
pub mod tables;

pub use analysis::ReportError;
use analysis::runs::with_failed_note;
use replication::{fleet_report, plans, seed_to_seed};
use std::path::Path;
use tables::{anova, measures};

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

/// Why `--measure` refuses a fleet study.
const FLEET_NOT_MEASURES: &str = "--measure tabulates figures per group of one robot's runs; this is a fleet study (its \
                                  report groups by fleet and method on its own)";

/// The report folder of `opts`: `<dir>/report`, or `<dir>/report-NAME` for `--name NAME`.
pub fn report_folder(dir: &Path, opts: &ReportOptions) -> Result<std::path::PathBuf, ReportError> {
    analysis::study::report_folder(dir, opts.name.as_deref())
}

/// Writes `<dir>/report/` (grouped by `by`) and returns the path of `summary.md`.
pub fn write_report(dir: &Path, by: &[String]) -> Result<std::path::PathBuf, ReportError> {
    write_report_with(dir, &ReportOptions { by: by.to_vec(), ..Default::default() })
}

/// Writes the report folder of `opts` and returns the path of `summary.md`: the study folder
/// read and checked once (`analysis::study::Loaded`), the groups, fronts and best runs every
/// section shares computed once (`analysis::study::Study`), then each section of `sections::SECTIONS` in turn.
pub fn write_report_with(dir: &Path, opts: &ReportOptions) -> Result<std::path::PathBuf, ReportError> {
    if opts.reference.is_some() && !opts.plans {
        return Err(ReportError::Input("--reference sets the runs against reference plans in plans.md, so it needs --plans (in Python: plans=True)".into()));
    }
    // Rendered before anything is written: what cannot be made leaves no half-written report.
    let plans = match opts.plans {
        true => Some(plans::render(dir, &opts.filter, opts.reference.as_deref(), &report_folder(dir, opts)?)?),
        false => None,
    };
    let loaded = analysis::study::Loaded::read(dir, &opts.by, &opts.filter, opts.name.as_deref())?;
    if fleet_report::applies(&loaded.t) {
        if opts.plans || opts.seed_to_seed {
            return Err(ReportError::Input(plans::FLEET_NOT_PLANS.into()));
        }
        if !opts.measures.is_empty() {
            return Err(ReportError::Input(FLEET_NOT_MEASURES.into()));
        }
        loaded.create_folder()?;
        fleet_report::write(dir, &loaded.t, &loaded.out, loaded.incomplete.as_deref())?;
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
                .map(|r| analysis::rendered::Rendered { markdown: with_failed_note(r.markdown, &loaded.failed), ..r })
        })
        .transpose()?;
    let folders = analysis::folder_record::FolderRecords::open(dir, &loaded.out)?;
    loaded.create_folder()?;
    let study = analysis::study::Study::new(dir, &opts.by, loaded, folders);
    study.write_configurations()?;
    let mut md = String::new();
    for section in sections::SECTIONS {
        if section.applies(&study) {
            section.write(&study, &mut md)?;
        }
    }
    if opts.anova_condensed {
        write_anova_condensed(&study)?;
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

/// Writes `anova-condensed.md` (`--anova-condensed`): the condensed tables of the summary's
/// analysis of variance, or why there is none.
fn write_anova_condensed(study: &analysis::study::Study) -> Result<(), ReportError> {
    let tables = anova::condensed(&study.t, &study.params);
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
        .map_err(|e| ReportError::Io(e.to_string()))
}
