//! `covga report DIR --plans [--reference RUNS_CSV]`: every configuration's plans, its runs'
//! final populations and, with a reference (one plan per map, e.g. the boustrophedon plans a
//! thesis GA is seeded with), each run against its map's reference plan. Writes `plans.md`
//! (tables and findings in words, each written from the numbers) and `plans.csv` (one row per
//! run: what its folder says beyond runs.csv).
//!
//! What a run's folder adds: the final population (`population.csv`): the size and the
//! hypervolume of the non-dominated set of its members that sweep no obstacle cell, in 003's
//! two objectives (`cov_final`, `t_final`, eqs. 3.10 and 3.13, both maximised) above (0, 0);
//! whether that set holds a member at least as good as the reference plan on both; the best
//! `cov_final` of the initial population (the first row of `history.csv`); and, for a run with
//! a seed bound (`thesis.seed_bound`, its seed plans' objectives in `summary.json`), whether
//! the plan it reports lies within it. A study whose run folders are gone (a committed results
//! folder) is read back from the `plans.csv` the report wrote when they were there, so that the
//! committed `plans.md` re-makes byte for byte from committed files.

use crate::ga::pareto::{hypervolume_2d, non_dominated};
use crate::report::analysis::ReportError;
use crate::report::analysis::rendered::Rendered;
use crate::report::analysis::runs::{read_filtered_runs, run_folder, with_failed_note};
use crate::report::analysis::values::check_finite;
use crate::study::records::RunsTable;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

mod text;

/// Why `--plans` and `--seed-to-seed` refuse a fleet study.
pub(crate) const FLEET_NOT_PLANS: &str = "--plans and --seed-to-seed read studies of one robot's plans; this is a fleet study (its \
                                          report compares the fleets' union coverage and makespan)";

/// Relative slack when a population member is compared with the reference plan on `cov_final`
/// and `t_final`: the seed genome scores as the plan it encodes up to a few cells (a lane edge
/// the genome's viewpoint lattice moves by a cell; `thesis::seeding`'s tests).
pub const HOLDS_TOLERANCE: f64 = 1e-3;

/// Differences below this count as equal when a plan is set against the reference plan:
/// coverage as a difference, time relative to the reference's (a run that returns its seed
/// genome unchanged drives the seed plan's length up to rounding, about 1e-11).
pub const EQUAL: f64 = 1e-9;

/// The columns of `plans.csv`, in order.
const COLUMNS: [&str; 9] = [
    "run_id",
    "population",
    "front_size",
    "hypervolume",
    "holds_reference",
    "start_max_cov_final",
    "within_bound",
    "seed_cov_final",
    "seed_t_final",
];

/// What a run's folder says beyond its row of runs.csv; `None` where the folder does not say it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RunPlans {
    /// Members of the final population.
    pub population: Option<usize>,
    /// Distinct points of the non-dominated set of the members that sweep no obstacle cell.
    pub front_size: Option<usize>,
    /// Its hypervolume in (`cov_final`, `t_final`) above (0, 0).
    pub hypervolume: Option<f64>,
    /// Whether that set holds a member at least as good as the reference plan on both
    /// objectives (within [`HOLDS_TOLERANCE`]).
    pub holds_reference: Option<bool>,
    /// The best `cov_final` of the initial population.
    pub start_max_cov_final: Option<f64>,
    /// Whether the reported plan lies within the seed bound (at least one seed plan's
    /// `cov_final` and `t_final`).
    pub within_bound: Option<bool>,
    /// The (first) seed plan's `cov_final` and `t_final`, as the bound reads them.
    pub seed: Option<(f64, f64)>,
}

/// The column that names a run's map: the swept `map.source`, else the metric column `map`
/// (the same text; a study on one map does not sweep `map.source`).
pub fn map_column(t: &RunsTable) -> Option<usize> {
    t.col("map.source").or_else(|| t.col("map"))
}

/// The reference plan of each map: its row of the reference runs.csv, by its map.
pub struct Reference {
    /// The file it was read from, as given.
    pub file: PathBuf,
    /// The reference table.
    pub table: RunsTable,
    /// Row of each map.
    pub by_map: BTreeMap<String, usize>,
}

impl Reference {
    /// Reads a runs.csv with one plan per `map.source`.
    pub fn read(file: &Path) -> Result<Self, ReportError> {
        let input = |m: String| ReportError::Input(format!("--reference {}: {m}", file.display()));
        let text = std::fs::read_to_string(file).map_err(|e| input(e.to_string()))?;
        let table = RunsTable::parse(&text).map_err(input)?;
        // The reference rows are the yardstick of every run: checked as a study's own rows are.
        check_finite(&table).map_err(input)?;
        let Some(map) = map_column(&table) else {
            return Err(input(
                "no `map.source` or `map` column: the reference plans are matched to runs by their map".into(),
            ));
        };
        for need in ["cov_final_reach", "time_s", "cov_final_free", "t_final", "f_free", "executable"] {
            if table.col(need).is_none() {
                return Err(input(format!("no `{need}` column: a runs.csv of covga's is expected")));
            }
        }
        let mut by_map = BTreeMap::new();
        for (i, r) in table.rows.iter().enumerate() {
            check_reference_row(&table, r, i).map_err(input)?;
            if by_map.insert(r[map].clone(), i).is_some() {
                return Err(input(format!("two plans for map {}: one reference plan per map", r[map])));
            }
        }
        Ok(Self { file: file.to_path_buf(), table, by_map })
    }

    /// A number of the reference plan of `map`.
    pub fn num(&self, map: &str, column: &str) -> Option<f64> {
        self.by_map.get(map).and_then(|&i| self.table.num(&self.table.rows[i], column))
    }
}

/// Refuses a reference plan (row `i` of `table`) that no run can be set against: one without
/// a number in a column the comparison reads, or with no time (every run's time is read as a
/// share of its reference plan's).
fn check_reference_row(table: &RunsTable, row: &[String], i: usize) -> Result<(), String> {
    let id = table.col("run_id").map_or("?", |c| row[c].as_str());
    for need in ["cov_final_reach", "cov_final_free", "t_final", "time_s"] {
        let cell = table.col(need).map_or("", |c| row[c].as_str());
        let value = cell.parse::<f64>().ok().filter(|v| v.is_finite());
        let Some(value) = value else {
            return Err(format!(
                "run {id} (line {}) has `{need}` = `{cell}`: a reference plan needs a number there (a failed run is no reference)",
                i + 2
            ));
        };
        if need == "time_s" && value <= 0.0 {
            return Err(format!(
                "run {id} (line {}) has `time_s` = {cell}: a reference plan takes time (allowed > 0 s); the runs' times are read against it",
                i + 2
            ));
        }
    }
    Ok(())
}

/// Hypervolume of the non-dominated set of `points` (both maximised) above (0, 0), and its
/// size: the distinct points on it (members that score alike count once).
pub fn population_front(points: &[(f64, f64)]) -> (f64, usize) {
    let mut front: Vec<(f64, f64)> = non_dominated(points).into_iter().map(|i| points[i]).collect();
    front.dedup();
    (hypervolume_2d(points, (0.0, 0.0)), front.len())
}

/// Whether a point of `points` is at least `target` on both coordinates, within `tolerance`
/// relative.
pub fn holds(points: &[(f64, f64)], target: (f64, f64), tolerance: f64) -> bool {
    points.iter().any(|&(c, t)| c >= target.0 * (1.0 - tolerance) && t >= target.1 * (1.0 - tolerance))
}

/// Reads what a run's folder says; `None` where the folder or the file is missing.
fn read_run(folder: &Path, reference: Option<(f64, f64)>) -> Result<RunPlans, ReportError> {
    let mut out = RunPlans::default();
    let bad = |p: &Path, m: String| ReportError::Input(format!("{}: {m}", p.display()));
    let pop_file = folder.join("population.csv");
    if let Ok(text) = std::fs::read_to_string(&pop_file) {
        let t = RunsTable::parse(&text).map_err(|m| bad(&pop_file, m))?;
        let (Some(c), Some(tf), Some(o)) = (t.col("cov_final"), t.col("t_final"), t.col("obstacle_cells")) else {
            return Err(bad(&pop_file, "expected the columns cov_final, t_final and obstacle_cells".into()));
        };
        let mut clear = Vec::new();
        for r in &t.rows {
            let num = |i: usize| r[i].parse::<f64>().map_err(|_| bad(&pop_file, format!("`{}` is not a number", r[i])));
            if num(o)? == 0.0 {
                clear.push((num(c)?, num(tf)?));
            }
        }
        let (hv, size) = population_front(&clear);
        out.population = Some(t.rows.len());
        out.front_size = Some(size);
        out.hypervolume = Some(hv);
        out.holds_reference = reference.map(|r| holds(&clear, r, HOLDS_TOLERANCE));
    }
    let history = folder.join("history.csv");
    if let Ok(text) = std::fs::read_to_string(&history) {
        let t = RunsTable::parse(&text).map_err(|m| bad(&history, m))?;
        out.start_max_cov_final = t.rows.first().and_then(|r| t.num(r, "max_cov_final"));
    }
    let summary = folder.join("summary.json");
    if let Ok(text) = std::fs::read_to_string(&summary) {
        let v: serde_json::Value = serde_json::from_str(&text).map_err(|e| bad(&summary, e.to_string()))?;
        let seeds: Vec<(f64, f64)> = v["seed_bound"]
            .as_array()
            .map(|a| a.iter().filter_map(|p| Some((p[0].as_f64()?, p[1].as_f64()?))).collect())
            .unwrap_or_default();
        if let (Some(first), Some(c), Some(t)) = (seeds.first(), v["cov_final"].as_f64(), v["t_final"].as_f64()) {
            out.seed = Some(*first);
            out.within_bound = Some(seeds.iter().any(|&(sc, st)| c >= sc && t >= st));
        }
    }
    Ok(out)
}

/// One `plans.csv` cell: empty where the folder did not say.
fn cell<T: ToString>(v: Option<T>) -> String {
    v.map_or_else(String::new, |x| x.to_string())
}

/// `plans.csv`: one row per run, by run id.
fn to_csv(ids: &[String], runs: &BTreeMap<String, RunPlans>) -> String {
    let mut s = COLUMNS.join(",");
    s.push('\n');
    for id in ids {
        let p = &runs[id];
        let fields = [
            id.clone(),
            cell(p.population),
            cell(p.front_size),
            cell(p.hypervolume),
            cell(p.holds_reference),
            cell(p.start_max_cov_final),
            cell(p.within_bound),
            cell(p.seed.map(|s| s.0)),
            cell(p.seed.map(|s| s.1)),
        ];
        let _ = writeln!(s, "{}", fields.join(","));
    }
    s
}

/// Reads a `plans.csv` back: what the run folders said when the report was made.
fn from_csv(file: &Path) -> Result<BTreeMap<String, RunPlans>, ReportError> {
    let bad = |m: String| ReportError::Input(format!("{}: {m}", file.display()));
    let text = std::fs::read_to_string(file).map_err(|e| bad(e.to_string()))?;
    let t = RunsTable::parse(&text).map_err(bad)?;
    if t.header != COLUMNS {
        return Err(bad(format!("expected the columns {}", COLUMNS.join(","))));
    }
    fn parse<T: std::str::FromStr>(v: &str, file: &Path) -> Result<Option<T>, ReportError> {
        if v.is_empty() {
            return Ok(None);
        }
        v.parse().map(Some).map_err(|_| ReportError::Input(format!("{}: `{v}` cannot be read", file.display())))
    }
    let mut out = BTreeMap::new();
    for r in &t.rows {
        let seed = match (parse::<f64>(&r[7], file)?, parse::<f64>(&r[8], file)?) {
            (Some(c), Some(t)) => Some((c, t)),
            _ => None,
        };
        out.insert(
            r[0].clone(),
            RunPlans {
                population: parse(&r[1], file)?,
                front_size: parse(&r[2], file)?,
                hypervolume: parse(&r[3], file)?,
                holds_reference: parse(&r[4], file)?,
                start_max_cov_final: parse(&r[5], file)?,
                within_bound: parse(&r[6], file)?,
                seed,
            },
        );
    }
    Ok(out)
}

/// Reads `dir`'s runs (failed runs left out, `filter` applied as the report applies it) and
/// each run's folder, or, where the study holds no run folders, the `plans.csv` of the report
/// folder `previous`; writes nothing.
pub fn render(
    dir: &Path,
    filter: &[(String, String)],
    reference: Option<&Path>,
    previous: &Path,
) -> Result<Rendered, ReportError> {
    let file = dir.join("runs.csv");
    let (t, _, failed) = read_filtered_runs(dir, filter)?;
    if t.rows.is_empty() {
        return Err(ReportError::Input(format!("{}: no runs to report", file.display())));
    }
    if super::fleet_report::applies(&t) {
        return Err(ReportError::Input(FLEET_NOT_PLANS.into()));
    }
    let reference = reference.map(Reference::read).transpose()?;
    let (Some(id), Some(map)) = (t.col("run_id"), map_column(&t)) else {
        return Err(ReportError::Input(format!("{}: expected the columns run_id and map", file.display())));
    };
    if let Some(r) = &reference {
        for row in &t.rows {
            if !r.by_map.contains_key(&row[map]) {
                return Err(ReportError::Input(format!(
                    "--reference {}: no plan for map {} (it has {})",
                    r.file.display(),
                    row[map],
                    r.by_map.keys().cloned().collect::<Vec<_>>().join(", ")
                )));
            }
        }
    }
    let mut ids: Vec<String> = t.rows.iter().map(|r| r[id].clone()).collect();
    let runs = if dir.join("runs").is_dir() {
        let mut runs = BTreeMap::new();
        for row in &t.rows {
            let target = reference
                .as_ref()
                .and_then(|r| Some((r.num(&row[map], "cov_final_free")?, r.num(&row[map], "t_final")?)));
            let folder = run_folder(dir, &row[id], "the report reads each run's population from its folder")?;
            runs.insert(row[id].clone(), read_run(&folder, target)?);
        }
        runs
    } else {
        let recorded = from_csv(&previous.join("plans.csv")).map_err(|e| {
            ReportError::Input(format!("{e} (the study holds no run folders, so the report reads what it recorded)"))
        })?;
        for i in &ids {
            if !recorded.contains_key(i) {
                return Err(ReportError::Input(format!(
                    "{}: run {i} is not recorded, and the study holds no run folders",
                    previous.join("plans.csv").display()
                )));
            }
        }
        recorded
    };
    ids.sort();
    let markdown = text::markdown(&t, &runs, reference.as_ref());
    Ok(Rendered {
        stem: "plans".into(),
        markdown: with_failed_note(markdown, &failed),
        csv: to_csv(&ids, &runs),
        design: None,
        forest: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_population_front_and_its_hypervolume_by_hand() {
        // (0.5, 0.4) is dominated by (0.6, 0.5); the front (0.9, 0.2), (0.6, 0.5) covers
        // 0.9 x 0.2 + 0.6 x 0.3 = 0.36.
        let (hv, size) = population_front(&[(0.9, 0.2), (0.5, 0.4), (0.6, 0.5)]);
        assert!((hv - 0.36).abs() < 1e-12, "{hv}");
        assert_eq!(size, 2);
        assert_eq!(population_front(&[]), (0.0, 0));
        // Members that score alike are one point of the front.
        assert_eq!(population_front(&[(0.9, 0.2), (0.9, 0.2), (0.6, 0.5)]).1, 2);
    }

    #[test]
    fn a_member_holds_the_reference_within_the_tolerance_only() {
        let reference = (0.9, 0.5);
        for (points, want) in [
            (vec![(0.9, 0.5)], true),
            (vec![(0.9 * (1.0 - 0.5e-3), 0.5)], true),
            (vec![(0.9 * (1.0 - 2e-3), 0.6)], false),
            (vec![(0.95, 0.4), (0.5, 0.9)], false),
            (vec![], false),
        ] {
            assert_eq!(holds(&points, reference, HOLDS_TOLERANCE), want, "{points:?}");
        }
    }

    #[test]
    fn plans_csv_reads_back_what_it_wrote() {
        let dir = std::env::temp_dir().join(format!("covga-plans-csv-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut runs = BTreeMap::new();
        runs.insert(
            "a".to_string(),
            RunPlans {
                population: Some(100),
                front_size: Some(7),
                hypervolume: Some(0.123_456_789_012_345_6),
                holds_reference: Some(true),
                start_max_cov_final: Some(0.5),
                within_bound: None,
                seed: Some((0.25, 0.75)),
            },
        );
        runs.insert("b".to_string(), RunPlans::default());
        let ids = vec!["a".to_string(), "b".to_string()];
        std::fs::write(dir.join("plans.csv"), to_csv(&ids, &runs)).unwrap();
        assert_eq!(from_csv(&dir.join("plans.csv")).unwrap(), runs);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
