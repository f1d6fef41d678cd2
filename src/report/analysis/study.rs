//! A study folder as `covga report` reads it: the runs table checked once ([`Loaded`]), and the
//! groups, Pareto facets, best runs and configurations every section shares ([`Study`]).

use super::ReportError;
use super::best::{COVERAGE, TIME, best_by_coverage_then_time};
use super::design::projection_scopes;
use super::folder_record::FolderRecords;
use super::runs::{
    ConfigRow, Group, cell_matches, cmp_group_values, coverage_front, failed_note, incomplete_note, param_columns,
    take_failed, where_keys,
};
use super::values::{check_against_grid, check_finite};
use crate::report::figures::pareto::ParetoFacet;
use crate::stats::mean_ci95;
use crate::study::records::RunsTable;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A study folder's runs, checked and filtered, and where its report goes.
pub(crate) struct Loaded {
    /// The runs that finished, after `--where`.
    pub t: RunsTable,
    /// The `--where` filters, in words (`key = value`).
    pub selected: Vec<String>,
    /// The report folder (created).
    pub out: PathBuf,
    /// The notes the report begins with (an incomplete study, failed runs, no `runs/` folder).
    pub incomplete: Option<String>,
    /// The runs that failed while running, as `run <id>: <reason>` (left out of `t`).
    pub failed: Vec<String>,
}

impl Loaded {
    /// Reads `dir`'s `study.json` and `runs.csv`, sets failed runs apart, applies the `--where`
    /// pairs of `filter` and checks the `--by` columns `by`; the report folder is named by
    /// `name` (`--name`). Creates nothing ([`Loaded::create_folder`] does, once every part of
    /// the report has been made).
    pub fn read(
        dir: &Path,
        by: &[String],
        filter: &[(String, String)],
        name: Option<&str>,
    ) -> Result<Self, ReportError> {
        check_study_json(dir)?;
        let runs_file = dir.join("runs.csv");
        let text = std::fs::read_to_string(&runs_file).map_err(|e| missing_runs(dir, &runs_file, e))?;
        let input = |m: String| ReportError::Input(format!("{}: {m}", runs_file.display()));
        let mut t = RunsTable::parse(&text).map_err(input)?;
        check_finite(&t).map_err(input)?;
        check_against_grid(dir, &t).map_err(input)?;
        let recorded = t.rows.len();
        let failed = take_failed(&mut t);
        if t.rows.is_empty() && !failed.is_empty() {
            return Err(ReportError::Input(format!(
                "{}: every recorded run failed while running ({} runs, stop = failed); the first: {}",
                runs_file.display(),
                failed.len(),
                failed[0]
            )));
        }
        let selected = apply_filters(&mut t, filter, &runs_file)?;
        if t.rows.is_empty() {
            return Err(ReportError::Input(format!("{}: no runs recorded yet", runs_file.display())));
        }
        if let Some(b) = by.iter().find(|b| t.col(b).is_none()) {
            return Err(ReportError::Input(format!(
                "--by `{b}` is not a column of {}; columns: {}",
                runs_file.display(),
                t.header.join(", ")
            )));
        }
        let out = report_folder(dir, name)?;
        // Without the runs' own files the report has tables only: say so rather than leave the
        // path and history figures out without a word.
        let no_run_files = (!dir.join("runs").is_dir()).then(|| {
            format!(
                "**No `runs/` folder in {}**: the tables below come from runs.csv alone; the best paths and the \
                 histories (diversity, convergence) that the runs' folders hold are not drawn.",
                dir.display()
            )
        });
        let notes: Vec<String> =
            incomplete_note(dir, recorded).into_iter().chain(failed_note(&failed)).chain(no_run_files).collect();
        let incomplete = (!notes.is_empty()).then(|| notes.join("\n\n"));
        Ok(Self { t, selected, out, incomplete, failed })
    }
}

impl Loaded {
    /// The rows grouped by the `--by` columns `by`, as the report groups them.
    pub fn groups(&self, by: &[String]) -> Vec<Group> {
        groups_of(&self.t, by)
    }

    /// Creates the report folder.
    pub fn create_folder(&self) -> Result<(), ReportError> {
        std::fs::create_dir_all(&self.out).map_err(|e| ReportError::Io(format!("{}: {e}", self.out.display())))
    }
}

/// The rows of `t` grouped by the `--by` columns `by`, groups ordered by their values.
fn groups_of(t: &RunsTable, by: &[String]) -> Vec<Group> {
    let get = |r: usize, c: &str| t.col(c).map(|i| t.rows[r][i].clone()).unwrap_or_default();
    let mut by_values: BTreeMap<Vec<String>, Vec<usize>> = BTreeMap::new();
    for r in 0..t.rows.len() {
        by_values.entry(by.iter().map(|b| get(r, b)).collect()).or_default().push(r);
    }
    let mut by_values: Vec<(Vec<String>, Vec<usize>)> = by_values.into_iter().collect();
    by_values.sort_by(|(a, _), (b, _)| cmp_group_values(a, b));
    by_values
        .into_iter()
        .map(|(values, rows)| {
            // A column left empty (a key a conditional sets only for some runs) does not label
            // the group: `seed_directions=` would read as a value.
            let parts: Vec<String> =
                by.iter().zip(&values).filter(|(_, v)| !v.is_empty()).map(|(b, v)| format!("{b}={v}")).collect();
            let label = if parts.is_empty() { "all runs".to_string() } else { parts.join(", ") };
            Group { label, rows }
        })
        .collect()
}

/// Refuses a folder without a readable `study.json` holding the grid's run count.
fn check_study_json(dir: &Path) -> Result<(), ReportError> {
    if !dir.join("study.json").is_file() {
        return Err(ReportError::Input(format!(
            "{}: not a study folder (no study.json); run `covga grid` into it first",
            dir.display()
        )));
    }
    let runs_count = std::fs::read_to_string(dir.join("study.json"))
        .map_err(|e| e.to_string())
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).map_err(|e| e.to_string()))
        .and_then(|m| m.get("runs").and_then(serde_json::Value::as_u64).ok_or_else(|| "no `runs` count".to_string()));
    match runs_count {
        Ok(_) => Ok(()),
        Err(e) => Err(ReportError::Input(format!(
            "{}: not a covga study description ({e}); it is written by `covga grid`",
            dir.join("study.json").display()
        ))),
    }
}

/// The error for a `runs.csv` that cannot be read: a sharded study names `covga merge`.
fn missing_runs(dir: &Path, runs_file: &Path, e: std::io::Error) -> ReportError {
    let shards = std::fs::read_dir(dir)
        .map(|d| d.flatten().any(|e| e.file_name().to_string_lossy().starts_with("runs-shard-")))
        .unwrap_or(false);
    if shards {
        ReportError::Input(format!(
            "{}: missing; this study has shard files: run `covga merge {}` first",
            runs_file.display(),
            dir.display()
        ))
    } else {
        ReportError::Input(format!("{}: {e}", runs_file.display()))
    }
}

/// Keeps the rows of `t` that every `--where` key accepts (a key given more than once accepts
/// any of its values); the filters in words.
fn apply_filters(t: &mut RunsTable, filter: &[(String, String)], runs_file: &Path) -> Result<Vec<String>, ReportError> {
    let mut selected = Vec::new();
    for (key, wants) in where_keys(filter) {
        let Some(c) = t.col(key) else {
            return Err(ReportError::Input(format!(
                "--where `{key}` is not a column of {}; columns: {}",
                runs_file.display(),
                t.header.join(", ")
            )));
        };
        let before = t.rows.len();
        t.rows.retain(|r| wants.iter().any(|want| cell_matches(&r[c], want)));
        let words = wants.join(" or ");
        if t.rows.is_empty() && before > 0 {
            let which = if wants.len() > 1 { "any of those values" } else { "that value" };
            return Err(ReportError::Input(format!(
                "--where {key}={words}: no recorded run of {} has {which}",
                runs_file.display()
            )));
        }
        selected.push(format!("{key} = {words}"));
    }
    Ok(selected)
}

/// `<dir>/report`, or `<dir>/report-NAME` for `--name NAME`.
pub(crate) fn report_folder(dir: &Path, name: Option<&str>) -> Result<PathBuf, ReportError> {
    match name {
        Some(name) => {
            if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_') {
                return Err(ReportError::Input(format!(
                    "--name `{name}`: expected letters, digits, `-` and `_` only (it names the folder report-NAME)"
                )));
            }
            Ok(dir.join(format!("report-{name}")))
        }
        None => Ok(dir.join("report")),
    }
}

/// What the sections of a report share, computed once.
pub(crate) struct Study<'a> {
    /// The study folder.
    pub dir: &'a Path,
    /// The `--by` columns.
    pub by: &'a [String],
    /// The runs, the filters and notes, and the report folder.
    pub t: RunsTable,
    pub selected: Vec<String>,
    pub out: PathBuf,
    pub incomplete: Option<String>,
    /// The groups of `--by`, in order.
    pub groups: Vec<Group>,
    /// Rows × columns of the panels when two columns group the runs.
    pub shape: Option<(usize, usize)>,
    /// The planners compared, in the registry's order.
    pub kinds: Vec<String>,
    /// Each group's Pareto facet (executable plans on the front).
    pub facets: Vec<ParetoFacet>,
    /// The best run of each group (and projection, where f1 and f2 both occur), labelled.
    pub best: Vec<(String, usize)>,
    /// The swept-parameter columns.
    pub params: Vec<String>,
    /// Configurations over their replicates, best mean f first.
    pub configs: Vec<ConfigRow>,
    /// The runs' folders, or what an earlier report recorded of them.
    pub folders: FolderRecords,
}

impl<'a> Study<'a> {
    /// Groups, facets, best runs and configurations of `loaded`.
    pub fn new(dir: &'a Path, by: &'a [String], loaded: Loaded, folders: FolderRecords) -> Self {
        let Loaded { mut t, selected, out, incomplete, failed: _ } = loaded;
        super::level::add_level_columns(&mut t, &folders);
        let mut study = Self {
            dir,
            by,
            t,
            selected,
            out,
            incomplete,
            groups: Vec::new(),
            shape: None,
            kinds: Vec::new(),
            facets: Vec::new(),
            best: Vec::new(),
            params: Vec::new(),
            configs: Vec::new(),
            folders,
        };
        study.groups = groups_of(&study.t, by);
        study.shape = match by {
            [a, b] => Some((study.distinct(a), study.distinct(b))),
            _ => None,
        };
        study.kinds = planners_of(&study.t);
        study.facets = study.pareto_facets();
        study.best = study.best_runs();
        study.params = param_columns(&study.t);
        study.configs = study.configurations();
        study
    }

    /// Whether the study's figures and tables give the common scorer's measures (mission time
    /// and reachable coverage): every study that runs a planner other than the thesis GA, whose
    /// `t_final` and `f` are 003's own measures ([`super::best`]).
    pub fn common_measures(&self) -> bool {
        self.kinds.iter().any(|k| k != "thesis")
    }

    /// A number of row `r` (NaN where absent).
    pub fn num(&self, r: usize, c: &str) -> f64 {
        self.t.num(&self.t.rows[r], c).unwrap_or(f64::NAN)
    }

    /// A cell of row `r` (empty where absent).
    pub fn get(&self, r: usize, c: &str) -> String {
        self.t.col(c).map(|i| self.t.rows[r][i].clone()).unwrap_or_default()
    }

    /// Whether row `r`'s plan is executable (a table without the column, written before
    /// executability was reported, counts every run).
    pub fn executable(&self, r: usize) -> bool {
        self.t.col("executable").is_none_or(|i| self.t.rows[r][i] == "true")
    }

    /// Distinct values of column `c`.
    fn distinct(&self, c: &str) -> usize {
        (0..self.t.rows.len()).map(|r| self.get(r, c)).collect::<BTreeSet<_>>().len()
    }

    /// `(t_final, cov_final_free)` of row `r`.
    pub fn point(&self, r: usize) -> (f64, f64) {
        (self.num(r, "t_final"), self.num(r, "cov_final_free"))
    }

    /// Each group's front over the plans a robot can drive; the others are drawn apart.
    fn pareto_facets(&self) -> Vec<ParetoFacet> {
        let kind_of = |r: usize| self.kinds.iter().position(|k| *k == self.get(r, "planner")).unwrap_or(0);
        self.groups
            .iter()
            .map(|g| {
                let rows: Vec<usize> = g.rows.iter().copied().filter(|&r| self.executable(r)).collect();
                let points: Vec<(f64, f64)> = rows.iter().map(|&r| self.point(r)).collect();
                let excluded = g.rows.iter().filter(|&&r| !self.executable(r)).map(|&r| self.point(r)).collect();
                let front = coverage_front(&points);
                let kinds = rows.iter().map(|&r| kind_of(r)).collect();
                ParetoFacet { label: g.label.clone(), points, front, rows, excluded, kinds }
            })
            .collect()
    }

    /// Best run per group (per group and projection where the study sweeps it: f1 and f2 are
    /// different functions): the best executable one by `f_free`, or on the common scorer's
    /// measures ([`Study::common_measures`]) by
    /// [`best_by_coverage_then_time`]; a scope without one shows its best
    /// run all the same.
    fn best_runs(&self) -> Vec<(String, usize)> {
        let common = self.common_measures();
        self.groups
            .iter()
            .flat_map(|g| {
                projection_scopes(&self.t, &g.rows).into_iter().map(|(suffix, rows)| {
                    let pool: Vec<usize> = rows.iter().copied().filter(|&r| self.executable(r)).collect();
                    let pool = if pool.is_empty() { rows } else { pool };
                    let by_f = || {
                        *pool
                            .iter()
                            .max_by(|&&a, &&b| self.num(a, "f_free").total_cmp(&self.num(b, "f_free")))
                            .expect("non-empty scope")
                    };
                    let r = match common {
                        true => best_by_coverage_then_time(&pool, |r| (self.num(r, COVERAGE), self.num(r, TIME)))
                            .unwrap_or_else(by_f),
                        false => by_f(),
                    };
                    (format!("{}{suffix}", g.label), r)
                })
            })
            .collect()
    }

    /// Per-configuration means over seeds, best mean f first.
    fn configurations(&self) -> Vec<ConfigRow> {
        let mut configs: BTreeMap<String, Vec<usize>> = BTreeMap::new();
        for r in 0..self.t.rows.len() {
            configs.entry(self.get(r, "config_id")).or_default().push(r);
        }
        let mut rows: Vec<ConfigRow> = configs
            .into_iter()
            .map(|(id, rows)| {
                let cov: Vec<f64> = rows.iter().map(|&r| self.num(r, "cov_final_free")).collect();
                let tf: Vec<f64> = rows.iter().map(|&r| self.num(r, "t_final")).collect();
                let f = rows.iter().map(|&r| self.num(r, "f_free")).sum::<f64>() / rows.len() as f64;
                (id, rows, mean_ci95(&cov), mean_ci95(&tf), f)
            })
            .collect();
        rows.sort_by(|a, b| b.4.total_cmp(&a.4).then(a.0.cmp(&b.0)));
        rows
    }

    /// Writes `configurations.csv`: each configuration's planner, swept values and its means
    /// over seeds, on the measures the summary uses: reachable coverage and mission time where
    /// it compares planners on the common scorer ([`Study::common_measures`]), else 003's
    /// coverage of all free cells, `t_final` and f.
    pub fn write_configurations(&self) -> Result<(), ReportError> {
        let planner = !self.params.iter().any(|p| p == "planner");
        let mut csv = String::from("config_id,");
        if planner {
            csv.push_str("planner,");
        }
        for p in &self.params {
            csv.push_str(&format!("{p},"));
        }
        let common = self.common_measures();
        csv.push_str(match common {
            true => "n,cov_final_reach_mean,cov_final_reach_ci95,time_s_mean,time_s_ci95\n",
            false => "n,cov_final_mean,cov_final_ci95,t_final_mean,t_final_ci95,fitness_mean\n",
        });
        for (id, rows, c, tf, f) in &self.configs {
            let mut vals: Vec<String> = self.params.iter().map(|p| self.get(rows[0], p)).collect();
            if planner {
                vals.insert(0, self.get(rows[0], "planner"));
            }
            let means = match common {
                true => {
                    let of = |c: &str| mean_ci95(&rows.iter().map(|&r| self.num(r, c)).collect::<Vec<_>>());
                    let (cov, time) = (of(COVERAGE), of(TIME));
                    format!("{},{},{},{}", cov.0, cov.1, time.0, time.1)
                }
                false => format!("{},{},{},{},{}", c.0, c.1, tf.0, tf.1, f),
            };
            csv.push_str(&format!("{id},{},{},{means}\n", vals.join(","), rows.len()));
        }
        crate::io::write_atomic(&self.out.join("configurations.csv"), csv.as_bytes())
            .map_err(|e| ReportError::Io(e.to_string()))
    }
}

/// The planners of a study's runs, each with its own colour and label: the registered ones in
/// the registry's order (covga's own, then those registered from outside), then any other
/// planner the runs name, in the order they first appear (a study run by a program that
/// registered a planner, reported by one that did not).
pub fn planners_of(t: &RunsTable) -> Vec<String> {
    let Some(c) = t.col("planner") else { return Vec::new() };
    let ran = |name: &str| t.rows.iter().any(|row| row[c] == name);
    let mut kinds: Vec<String> = crate::experiment::registry::PlannerKind::all()
        .into_iter()
        .map(|k| k.name().to_string())
        .filter(|k| ran(k))
        .collect();
    for row in &t.rows {
        if !row[c].is_empty() && !kinds.contains(&row[c]) {
            kinds.push(row[c].clone());
        }
    }
    kinds
}
