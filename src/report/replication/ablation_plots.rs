//! The figures of the planner comparison ([`super::ablation`], read from [`super::comparing`]): box plots of coverage and
//! time per map, the GAs' convergence curves (median and quartiles over seeds) and the best
//! executable path of each planner on each map.

use super::comparing::{Comparing, short_map};
use crate::coverage::CoverageGrid;
use crate::plot::path::PathFigure;
use crate::report::analysis::ReportError;
use crate::report::analysis::best::{COVERAGE, TIME, best_by_coverage_then_time};
use crate::report::figures::boxes::{BoxFigure, BoxSeries};
use crate::report::figures::convergence::{ConvergenceFigure, Curve};
use crate::report::figures::paths::PlannerPathsFigure;
use crate::stats::quartiles;
use crate::study::records::RunsTable;
use std::collections::BTreeMap;
use std::path::Path;

/// A best run loaded for its panel: map, visit grid, plan, robot width, title.
type LoadedPanel = (crate::map::GridMap, CoverageGrid, Vec<Vec<crate::geom::Point>>, f64, String);

/// Each variant's colour: its first run's in the report (`colours`, by run id), else its
/// place among the variants. Variants finer than the report's groups (the thesis GA's settings,
/// where the report groups by planner) share their group's colour only in the first of them;
/// the others take colours past the report's, so that no two boxes of one panel share one.
fn variant_colours(c: &Comparing, colours: &BTreeMap<String, usize>) -> Vec<usize> {
    let mut next = colours.values().max().map_or(c.variants.len(), |&k| (k + 1).max(c.variants.len()));
    let mut taken: Vec<usize> = Vec::new();
    for (i, v) in c.variants.iter().enumerate() {
        let ids = c.maps.iter().flat_map(|map| c.all_rows_of(map, v)).map(|r| &c.t.rows[r][0]);
        let mut k = ids.into_iter().find_map(|id| colours.get(id).copied()).unwrap_or(i);
        if taken.contains(&k) {
            k = next;
            next += 1;
        }
        taken.push(k);
    }
    taken
}

/// Draws the comparison's figures into `out`; `dir` holds the runs' folders; `colours` gives
/// each run's colour in the report, by run id.
pub(super) fn draw(
    c: &Comparing,
    dir: &Path,
    out: &Path,
    colours: &BTreeMap<String, usize>,
) -> Result<(), ReportError> {
    let colours = variant_colours(c, colours);
    crate::plot::save(
        &BoxFigure {
            metric: "cov_final over reachable cells".into(),
            panels: boxes(c, &colours, |_| ("cov_final_reach", String::new())),
        },
        &out.join("boxplots_cov"),
    )?;
    crate::plot::save(
        &BoxFigure {
            metric: "time [s] to the panel's level".into(),
            panels: boxes(c, &colours, |map| {
                let m = c.time_measure(map);
                (m.column, format!(": {}", m.name()))
            }),
        },
        &out.join("boxplots_time"),
    )?;
    crate::plot::save(&convergence(c, dir, &colours), &out.join("convergence"))?;
    let loaded = best_paths(c, dir);
    let missing = c
        .maps
        .iter()
        .map(|map| {
            c.variants
                .iter()
                .map(|v| {
                    let ran = c.all_rows_of(map, v).len();
                    (ran > 0 && c.rows_of(map, v).is_empty()).then(|| format!("{v}: no executable plan (0/{ran})"))
                })
                .collect()
        })
        .collect();
    let rows: Vec<Vec<Option<PathFigure>>> = loaded
        .iter()
        .map(|row| {
            row.iter()
                .map(|p| {
                    p.as_ref().map(|(m, g, paths, w, title)| PathFigure {
                        map: m,
                        grid: g,
                        paths: paths.clone(),
                        width: *w,
                        robots: Vec::new(),
                        title: title.clone(),
                    })
                })
                .collect()
        })
        .collect();
    crate::plot::save(&PlannerPathsFigure { rows, missing }, &out.join("planner_paths"))?;
    Ok(())
}

/// The box plot panels of the metric `metric` gives per map (its column, and what the panel's
/// title adds): per map, each variant's executable values and the others'.
fn boxes<'a>(
    c: &Comparing,
    colours: &[usize],
    metric: impl Fn(&str) -> (&'a str, String),
) -> Vec<(String, Vec<BoxSeries>)> {
    c.maps
        .iter()
        .map(|map| {
            let (metric, title) = metric(map);
            let series = c
                .variants
                .iter()
                .zip(colours)
                .map(|(v, &colour)| BoxSeries {
                    label: v.clone(),
                    colour,
                    values: c.rows_of(map, v).iter().map(|&r| c.num(r, metric)).collect(),
                    excluded: c
                        .all_rows_of(map, v)
                        .into_iter()
                        .filter(|&r| !c.flag(r, "executable"))
                        .map(|r| c.num(r, metric))
                        .collect(),
                })
                .filter(|b| !b.values.is_empty() || !b.excluded.is_empty())
                .collect();
            (format!("{}{title}", short_map(map)), series)
        })
        .collect()
}

/// The convergence curves of the planners with a history: reachable coverage against
/// evaluations, median and quartiles over the executable runs, per map.
fn convergence(c: &Comparing, dir: &Path, colours: &[usize]) -> ConvergenceFigure {
    let mut panels = Vec::new();
    for map in &c.maps {
        let mut curves = Vec::new();
        for (v, &colour) in c.variants.iter().zip(colours) {
            let with_history: Vec<(usize, Vec<(f64, f64)>)> = c
                .rows_of(map, v)
                .iter()
                .filter_map(|&r| Some((r, history(&dir.join("runs").join(&c.t.rows[r][0]).join("history.csv"))?)))
                .collect();
            if with_history.is_empty() {
                continue;
            }
            // The plans as scored (after a completion pass, where the planner has one).
            let scored: Vec<f64> = with_history.iter().map(|(r, _)| c.num(*r, "cov_final_reach")).collect();
            let hs: Vec<Vec<(f64, f64)>> = with_history.into_iter().map(|(_, h)| h).collect();
            let x_max = hs.iter().flat_map(|h| h.last().map(|p| p.0)).fold(0.0, f64::max);
            let points = (0..=60)
                .map(|k| {
                    let e = x_max * k as f64 / 60.0;
                    let vals: Vec<f64> = hs.iter().filter_map(|h| at(h, e)).collect();
                    let (q1, m, q3) = quartiles(&vals);
                    (e, q1, m, q3)
                })
                .filter(|p| p.2.is_finite())
                .collect();
            let scored = Some(quartiles(&scored).1).filter(|m| m.is_finite());
            curves.push(Curve { label: v.clone(), runs: hs.len(), points, scored, colour });
        }
        panels.push((short_map(map), curves));
    }
    ConvergenceFigure { panels }
}

/// The best run of each variant on each map on the common scorer's measures
/// ([`best_by_coverage_then_time`]), loaded for its panel.
fn best_paths(c: &Comparing, dir: &Path) -> Vec<Vec<Option<LoadedPanel>>> {
    let mut loaded = Vec::new();
    for map in &c.maps {
        let mut row = Vec::new();
        for v in &c.variants {
            let rows = c.rows_of(map, v);
            let Some(best) = best_by_coverage_then_time(&rows, |r| (c.num(r, COVERAGE), c.num(r, TIME))) else {
                row.push(None);
                continue;
            };
            let run_dir = dir.join("runs").join(&c.t.rows[best][0]);
            let cfg = crate::experiment::file::ExperimentFile::read(&run_dir.join("config.toml")).ok();
            let paths = crate::io::read_path_csv(&run_dir.join("best_path.csv")).ok();
            let panel = cfg.zip(paths).and_then(|(cfg, paths)| {
                let m = crate::map::ros::load_map(&cfg.map.source, &cfg.map.bare_image()).ok()?;
                let g = CoverageGrid::new(&m);
                let title = format!(
                    "{v}, {}: {:.0} s, {:.1} % of the reachable cells",
                    short_map(map),
                    c.num(best, "time_s"),
                    100.0 * c.num(best, "cov_final_reach")
                );
                Some((m, g, paths, cfg.robot.width, title))
            });
            row.push(panel);
        }
        loaded.push(row);
    }
    loaded
}

/// The best coverage at evaluation `e` of a history (a step function of the evaluations).
fn at(curve: &[(f64, f64)], e: f64) -> Option<f64> {
    curve.iter().take_while(|(x, _)| *x <= e).last().map(|(_, y)| *y)
}

/// A run's `(evaluations, best_coverage_reach)` curve: the reachable coverage the tables
/// headline (histories written before that column existed have none).
fn history(path: &Path) -> Option<Vec<(f64, f64)>> {
    let t = RunsTable::parse(&std::fs::read_to_string(path).ok()?).ok()?;
    let (e, c) = (t.col("evaluations")?, t.col("best_coverage_reach")?);
    let v: Option<Vec<(f64, f64)>> = t.rows.iter().map(|r| Some((r[e].parse().ok()?, r[c].parse().ok()?))).collect();
    v.filter(|v| v.len() > 1)
}
