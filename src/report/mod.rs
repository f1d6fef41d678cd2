//! `covga report`: figures, tables and statistics of a study folder — Pareto fronts per group
//! with hypervolume, diversity of the front runs, best paths, the best configuration and run
//! durations per group (003 Tables A.1/A.2, 4.4), means with 95 % confidence intervals over
//! seeds, Kruskal–Wallis tests per swept parameter and the ANOVA of 003 §5.3.
//!
//! The reports layer reads a study's records (`crate::study::records`) and nothing runs here.
//! One module per report section: the planner comparison ([`ablation`]), the fleet study
//! ([`fleet_report`]), the thesis's tables and claims ([`thesis_report`], [`claims`]), the
//! ANOVA ([`anova`], [`anova_report`]) and the group tables; [`crate::stats`] holds the tests they
//! share, [`figures`] and [`ablation_figures`] the figures drawn with `crate::plot`'s
//! primitives.

pub mod ablation;
pub mod ablation_figures;
pub mod anova;
pub mod anova_report;
pub mod claims;
pub mod compare;
pub mod figures;
pub mod fleet_report;
mod report_tables;
pub mod rescore;
pub mod search_objective;
pub mod thesis_report;

use crate::coverage::CoverageGrid;
use crate::ga::pareto::non_dominated;
use crate::plot::path::PathFigure;
use crate::stats::mean_ci95;
use crate::study::records::RunsTable;
use figures::{DiversityFigure, DiversityGroup, ParetoFacet, ParetoFigure, PathsGridFigure};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

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

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 { v[n / 2] } else { 0.5 * (v[n / 2 - 1] + v[n / 2]) }
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
}

/// Whether a cell of runs.csv equals a `--where` value: as numbers when both parse, else as text.
pub(super) fn cell_matches(cell: &str, want: &str) -> bool {
    match (cell.parse::<f64>(), want.parse::<f64>()) {
        (Ok(a), Ok(b)) => a == b,
        _ => cell == want,
    }
}

/// A metric of runs.csv that is not a finite number (a hand-edited or damaged file): the
/// report would print `NaN ± NaN` or an infinite hypervolume as if they were results.
fn check_finite(t: &RunsTable) -> Result<(), String> {
    let id = t.col("run_id");
    if let Some(i) = id {
        let mut seen = std::collections::BTreeSet::new();
        for row in &t.rows {
            if !seen.insert(row[i].as_str()) {
                return Err(format!(
                    "run {} is recorded twice: every run id appears once (was the file edited by hand?)",
                    row[i]
                ));
            }
        }
    }
    // Shares lie in [0, 1]; lengths, times and counts are not negative.
    let shares =
        ["cov_final_free", "cov_final_reach", "cam_walls_free", "cam_open_free", "cam_walls_reach", "cam_open_reach"];
    for name in crate::coverage::score::Score::column_names() {
        let Some(c) = t.col(name) else { continue };
        let (lo, hi) = if shares.contains(&name) { (0.0, 1.0) } else { (0.0, f64::INFINITY) };
        for row in &t.rows {
            if row[c].parse::<f64>().is_ok_and(|v| v.is_finite() && !(lo..=hi).contains(&v)) {
                return Err(format!(
                    "run {} has `{name}` = {}: allowed [{lo}, {hi}] (was the file edited by hand?)",
                    id.map_or("?", |i| row[i].as_str()),
                    row[c]
                ));
            }
        }
    }
    for name in crate::coverage::score::Score::column_names() {
        let Some(c) = t.col(name) else { continue };
        for row in &t.rows {
            if row[c].parse::<f64>().is_ok_and(|v| !v.is_finite()) {
                return Err(format!(
                    "run {} has `{name}` = {}: every metric must be a finite number (was the file edited by hand?)",
                    id.map_or("?", |i| row[i].as_str()),
                    row[c]
                ));
            }
        }
    }
    Ok(())
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

/// Writes `<dir>/report/` (grouped by `by`) and returns the path of `summary.md`.
pub fn write_report(dir: &Path, by: &[String]) -> Result<std::path::PathBuf, ReportError> {
    write_report_with(dir, &ReportOptions { by: by.to_vec(), ..Default::default() })
}

/// Writes the report folder of `opts` and returns the path of `summary.md`.
pub fn write_report_with(dir: &Path, opts: &ReportOptions) -> Result<std::path::PathBuf, ReportError> {
    let by = &opts.by[..];
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
    if let Err(e) = runs_count {
        return Err(ReportError::Input(format!(
            "{}: not a covga study description ({e}); it is written by `covga grid`",
            dir.join("study.json").display()
        )));
    }
    let runs_file = dir.join("runs.csv");
    let text = std::fs::read_to_string(&runs_file).map_err(|e| {
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
    })?;
    let mut t = RunsTable::parse(&text).map_err(|m| ReportError::Input(format!("{}: {m}", runs_file.display())))?;
    check_finite(&t).map_err(|m| ReportError::Input(format!("{}: {m}", runs_file.display())))?;
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
    let mut selected = Vec::new();
    for (key, want) in &opts.filter {
        let Some(c) = t.col(key) else {
            return Err(ReportError::Input(format!(
                "--where `{key}` is not a column of {}; columns: {}",
                runs_file.display(),
                t.header.join(", ")
            )));
        };
        let before = t.rows.len();
        t.rows.retain(|r| cell_matches(&r[c], want));
        if t.rows.is_empty() && before > 0 {
            return Err(ReportError::Input(format!(
                "--where {key}={want}: no recorded run of {} has that value",
                runs_file.display()
            )));
        }
        selected.push(format!("{key} = {want}"));
    }
    if t.rows.is_empty() {
        return Err(ReportError::Input(format!("{}: no runs recorded yet", runs_file.display())));
    }
    for b in by {
        if t.col(b).is_none() {
            return Err(ReportError::Input(format!(
                "--by `{b}` is not a column of {}; columns: {}",
                runs_file.display(),
                t.header.join(", ")
            )));
        }
    }
    let out = match &opts.name {
        Some(name) => {
            if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_') {
                return Err(ReportError::Input(format!(
                    "--name `{name}`: expected letters, digits, `-` and `_` only (it names the folder report-NAME)"
                )));
            }
            dir.join(format!("report-{name}"))
        }
        None => dir.join("report"),
    };
    std::fs::create_dir_all(&out).map_err(|e| ReportError::Io(format!("{}: {e}", out.display())))?;
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
    if self::fleet_report::applies(&t) {
        self::fleet_report::write(dir, &t, &out, incomplete.as_deref())?;
        return Ok(out.join("summary.md"));
    }
    let num = |r: usize, c: &str| t.num(&t.rows[r], c).unwrap_or(f64::NAN);
    let get = |r: usize, c: &str| t.col(c).map(|i| t.rows[r][i].clone()).unwrap_or_default();
    // Groups by the --by columns.
    let mut by_values: BTreeMap<Vec<String>, Vec<usize>> = BTreeMap::new();
    for r in 0..t.rows.len() {
        by_values.entry(by.iter().map(|b| get(r, b)).collect()).or_default().push(r);
    }
    let mut by_values: Vec<(Vec<String>, Vec<usize>)> = by_values.into_iter().collect();
    by_values.sort_by(|(a, _), (b, _)| cmp_group_values(a, b));
    let groups: Vec<Group> = by_values
        .into_iter()
        .map(|(values, rows)| {
            let label = if by.is_empty() {
                "all runs".to_string()
            } else {
                by.iter().zip(&values).map(|(b, v)| format!("{b}={v}")).collect::<Vec<_>>().join(", ")
            };
            Group { label, rows }
        })
        .collect();
    let point = |r: usize| (num(r, "t_final"), num(r, "cov_final_free"));
    // Two grouping columns lay the panels out as rows × columns when every combination ran.
    let shape = match by {
        [a, b] => {
            let distinct =
                |c: &str| (0..t.rows.len()).map(|r| get(r, c)).collect::<std::collections::BTreeSet<_>>().len();
            Some((distinct(a), distinct(b)))
        }
        _ => None,
    };
    // Pareto facets.
    // Fronts over the plans a robot can drive; the others are drawn apart. A table without
    // the column (written before executability was reported) counts every run.
    let executable = |r: usize| t.col("executable").is_none_or(|i| t.rows[r][i] == "true");
    // The planners of a comparison, in the registry's order, each with its own colour.
    let kinds: Vec<String> = crate::experiment::registry::PlannerKind::ALL
        .iter()
        .map(|k| k.name().to_string())
        .filter(|k| t.col("planner").is_some_and(|c| t.rows.iter().any(|row| &row[c] == k)))
        .collect();
    let kind_of = |r: usize| kinds.iter().position(|k| *k == get(r, "planner")).unwrap_or(0);
    let facets: Vec<ParetoFacet> = groups
        .iter()
        .map(|g| {
            let rows: Vec<usize> = g.rows.iter().copied().filter(|&r| executable(r)).collect();
            let points: Vec<(f64, f64)> = rows.iter().map(|&r| point(r)).collect();
            let excluded = g.rows.iter().filter(|&&r| !executable(r)).map(|&r| point(r)).collect();
            let front = coverage_front(&points);
            let kinds = rows.iter().map(|&r| kind_of(r)).collect();
            ParetoFacet { label: g.label.clone(), points, front, rows, excluded, kinds }
        })
        .collect();
    crate::plot::save(
        &ParetoFigure {
            facets: facets
                .iter()
                .map(|f| ParetoFacet {
                    label: f.label.clone(),
                    points: f.points.clone(),
                    front: f.front.clone(),
                    rows: f.rows.clone(),
                    excluded: f.excluded.clone(),
                    kinds: f.kinds.clone(),
                })
                .collect(),
            shape,
            kinds: if kinds.len() > 1 { kinds.clone() } else { Vec::new() },
        },
        &out.join("pareto"),
    )?;
    // Diversity of the front runs.
    let mut div_groups = Vec::new();
    for (g, f) in groups.iter().zip(&facets) {
        let curves: Vec<Vec<(u32, f64)>> = f
            .front
            .iter()
            .filter_map(|&k| {
                read_history_diversity(&dir.join("runs").join(get(f.rows[k], "run_id")).join("history.csv"))
            })
            .collect();
        if curves.is_empty() {
            continue;
        }
        let len = curves.iter().map(Vec::len).min().unwrap_or(0);
        let curve = (0..len)
            .map(|i| {
                let mut v: Vec<f64> = curves.iter().map(|c| c[i].1).collect();
                let (lo, hi) = (
                    v.iter().copied().fold(f64::INFINITY, f64::min),
                    v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                );
                (curves[0][i].0, median(&mut v), lo, hi)
            })
            .collect();
        div_groups.push(DiversityGroup { label: g.label.clone(), runs: curves.len(), curve });
    }
    let wrote_diversity = !div_groups.is_empty();
    if wrote_diversity {
        crate::plot::save(&DiversityFigure { groups: div_groups }, &out.join("diversity"))?;
    }
    // Best run per group (per group and projection where the study sweeps it: f1 and f2 are
    // different functions), its path.
    let best: Vec<(String, usize)> = groups
        .iter()
        .flat_map(|g| {
            self::report_tables::projection_scopes(&t, &g.rows).into_iter().map(|(suffix, rows)| {
                // The best executable run; a scope without one shows its best run all the same.
                let pool: Vec<usize> = rows.iter().copied().filter(|&r| executable(r)).collect();
                let pool = if pool.is_empty() { rows } else { pool };
                let r = *pool
                    .iter()
                    .max_by(|&&a, &&b| num(a, "f_free").total_cmp(&num(b, "f_free")))
                    .expect("non-empty scope");
                (format!("{}{suffix}", g.label), r)
            })
        })
        .collect();
    let by_planner_varies =
        t.header.iter().rposition(|h| h == "planner").is_some_and(|c| {
            t.rows.iter().map(|row| row[c].as_str()).collect::<std::collections::BTreeSet<_>>().len() > 1
        });
    let mut loaded = Vec::new();
    for (group_label, r) in &best {
        let r = *r;
        let run_dir = dir.join("runs").join(get(r, "run_id"));
        let Ok(cfg) = crate::experiment::file::ExperimentFile::read(&run_dir.join("config.toml")) else { continue };
        let Ok(paths) = crate::io::read_path_csv(&run_dir.join("best_path.csv")) else { continue };
        let Ok(map) = crate::map::ros::load_map(&cfg.map.source, &cfg.map.bare_image()) else { continue };
        let mut grid = CoverageGrid::new(&map);
        if let Some(rt) = cfg.retrain {
            let [x0, y0, x1, y1] = rt.region;
            grid.premark_rect(x0, y0, x1, y1);
        }
        // The planner too, where a study compares several.
        let planner = t.header.iter().rposition(|h| h == "planner").map(|c| t.rows[r][c].as_str());
        let label = match planner {
            Some(p) if !group_label.contains(p) && by_planner_varies => format!("{group_label}, {p}"),
            _ => group_label.clone(),
        };
        let title = format!(
            "{}: cov {:.3}, t {:.3}",
            crate::plot::panel_label(&label),
            num(r, "cov_final_free"),
            num(r, "t_final")
        );
        loaded.push((map, grid, paths, cfg.robot.width, title));
    }
    let wrote_paths = !loaded.is_empty();
    if wrote_paths {
        let panels = loaded
            .iter()
            .map(|(map, grid, paths, width, title)| PathFigure {
                map,
                grid,
                paths: paths.clone(),
                width: *width,
                robots: Vec::new(),
                title: title.clone(),
            })
            .collect();
        crate::plot::save(&PathsGridFigure { panels }, &out.join("best_paths"))?;
    }
    // Per-configuration means over seeds.
    let params = param_columns(&t);
    let mut configs: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for r in 0..t.rows.len() {
        configs.entry(get(r, "config_id")).or_default().push(r);
    }
    let mut conf_rows: Vec<ConfigRow> = configs
        .into_iter()
        .map(|(id, rows)| {
            let cov: Vec<f64> = rows.iter().map(|&r| num(r, "cov_final_free")).collect();
            let tf: Vec<f64> = rows.iter().map(|&r| num(r, "t_final")).collect();
            let f = rows.iter().map(|&r| num(r, "f_free")).sum::<f64>() / rows.len() as f64;
            (id, rows, mean_ci95(&cov), mean_ci95(&tf), f)
        })
        .collect();
    conf_rows.sort_by(|a, b| b.4.total_cmp(&a.4).then(a.0.cmp(&b.0)));
    let mut csv = String::from("config_id,");
    for p in &params {
        csv.push_str(&format!("{p},"));
    }
    csv.push_str("n,cov_final_mean,cov_final_ci95,t_final_mean,t_final_ci95,fitness_mean\n");
    for (id, rows, c, tf, f) in &conf_rows {
        let vals: Vec<String> = params.iter().map(|p| get(rows[0], p)).collect();
        csv.push_str(&format!("{id},{},{},{},{},{},{},{}\n", vals.join(","), rows.len(), c.0, c.1, tf.0, tf.1, f));
    }
    crate::io::write_atomic(&out.join("configurations.csv"), csv.as_bytes())
        .map_err(|e| ReportError::Io(e.to_string()))?;
    // summary.md
    let mut md = String::new();
    let replicates = t
        .rows
        .iter()
        .map(|r| r[t.col("replicate").unwrap_or(0)].clone())
        .collect::<std::collections::BTreeSet<_>>()
        .len();
    let _ = writeln!(md, "# Study report: {}\n", dir.display());
    if let Some(note) = &incomplete {
        let _ = writeln!(md, "{note}\n");
    }
    if !selected.is_empty() {
        let _ = writeln!(md, "Runs with {} only.\n", selected.join(", "));
    }
    let _ = writeln!(
        md,
        "{} runs, {} configurations, {} replicate(s); grouped by {}.\n",
        t.rows.len(),
        conf_rows.len(),
        replicates,
        if by.is_empty() { "nothing (one group)".to_string() } else { by.join(", ") }
    );
    let _ = writeln!(md, "![Pareto fronts](pareto.png)\n");
    if wrote_diversity {
        let _ = writeln!(md, "![Diversity of the front runs](diversity.png)\n");
    }
    if wrote_paths {
        let _ = writeln!(md, "![Best path per group](best_paths.png)\n");
    }
    if self::ablation::applies(&t) {
        md.push_str(&self::ablation::compare(dir, &t, &out)?.markdown);
    }
    self::report_tables::GroupTables {
        t: &t,
        groups: &groups,
        best: &best,
        facets: &facets,
        configs: &conf_rows,
        params: &params,
    }
    .write(&mut md);
    if self::thesis_report::applies(&t) {
        md.push_str(&self::thesis_report::sections(dir, &t));
    }
    md.push_str(&self::anova_report::section(&t, &params));
    let path = out.join("summary.md");
    crate::io::write_atomic(&path, md.as_bytes()).map_err(|e| ReportError::Io(e.to_string()))?;
    Ok(path)
}

#[cfg(test)]
mod tests;
