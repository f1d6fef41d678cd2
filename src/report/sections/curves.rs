//! Time-to-coverage curves of a study (issue of comparing plans at equal coverage): per map,
//! one curve per planner (or per group, where the study has one planner) — the median over its
//! runs of the reachable coverage reached by each time, with the band between the quartiles —
//! and a table of the times to 80, 90 and 95 % of the reachable cells. Read from each run's
//! `coverage_curve.csv` ([`crate::coverage::curve`]); executable plans only.

use super::Section;
use crate::coverage::curve::{CoverageCurve, LEVELS};
use crate::report::analysis::ReportError;
use crate::report::analysis::bound::AreaBounds;
use crate::report::analysis::design::followed_by;
use crate::report::analysis::study::Study;
use crate::report::figures::curves::{CurvesFigure, Drawn};
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// Sample times per panel.
const SAMPLES: usize = 240;

/// One series of a panel: its label, each run's times to the levels and, where the run
/// folders are there, the runs' curves.
struct Series {
    label: String,
    times: Vec<[Option<f64>; 3]>,
    /// Each run's lower bound on the time to each level ([`AreaBounds`]).
    bounds: Vec<Option<[f64; 3]>>,
    curves: Vec<CoverageCurve>,
    /// Its colour in the report's figures ([`super::colours::RunColours`]).
    colour: usize,
    /// Its first run's id: the bound and the robot the figure draws for it.
    first: String,
}

/// A run's curve, or what a report recorded of it.
struct Run {
    id: String,
    times: [Option<f64>; 3],
    curve: Option<CoverageCurve>,
}

/// The panels, or, where some executable plans have a curve and others not (a study re-run in
/// part, its other run folders gone), how many lack one: a table over whichever runs happen to
/// have folders would not be the study's.
enum Panels {
    Made(Vec<(String, Vec<Series>)>),
    Partial { missing: usize, of: usize },
}

/// Median, first and third quartile of `v`.
fn quartiles(v: &[f64]) -> (f64, f64, f64) {
    let (q1, m, q3) = crate::stats::quartiles(v);
    (m, q1, q3)
}

/// The swept columns that split a map's panel: the robot's (`robot.*`: its speeds set the
/// time axis, so a second robot's runs must not share a median with the first's) where set on
/// every run with two values or more, neither a `--by` column nor one that follows the map. The
/// planners' own settings stay within a panel, pooled or told apart by `--by`.
fn panel_columns(s: &Study) -> Vec<usize> {
    let map = s.t.col("map.source");
    s.params
        .iter()
        .filter(|p| p.starts_with("robot.") && !s.by.contains(p))
        .filter_map(|p| s.t.col(p))
        .filter(|&c| {
            let values: std::collections::BTreeSet<&str> = s.t.rows.iter().map(|r| r[c].as_str()).collect();
            values.len() > 1 && !values.contains("") && map.is_none_or(|m| followed_by(&s.t, c, &[m]).is_none())
        })
        .collect()
}

/// `labels` for a legend: without the `key=value` parts every one of them shares
/// (`planner=cell_order` where the report keeps one planner), that set nothing (`key=`) or
/// name the map (each panel is one map, and its title names it), and each key by its last
/// name (`solver=ga`), so that the legend names what tells the series apart; a label with no
/// part left is "executable runs".
pub(crate) fn distinct_parts(labels: &[String]) -> Vec<String> {
    let parts: Vec<Vec<&str>> = labels.iter().map(|l| l.split(", ").collect()).collect();
    let shared = |p: &str| labels.len() > 1 && parts.iter().all(|ps| ps.contains(&p));
    let short = |p: &str| match p.split_once('=') {
        Some((key, value)) => format!("{}={value}", key.rsplit('.').next().unwrap_or(key)),
        None => p.to_string(),
    };
    parts
        .iter()
        .zip(labels)
        .map(|(ps, whole)| {
            let kept: Vec<String> = ps
                .iter()
                .copied()
                .filter(|p| !shared(p) && !p.ends_with('=') && !p.starts_with("map.source="))
                .map(short)
                .collect();
            match (kept.is_empty(), ps.iter().any(|p| p.starts_with("map.source="))) {
                (false, _) => kept.join(", "),
                (true, true) => "executable runs".into(),
                (true, false) => whole.clone(),
            }
        })
        .collect()
}

/// The series a run of group `group` and planner `planner` belongs to: its `--by` group, with
/// its planner where the study has several and the group does not name it; a group that names
/// only the map (each panel is one map) is its planner's.
pub(crate) fn series_label(group: &str, planner: &str, one_planner: bool) -> String {
    let only_map = group.split(", ").all(|part| part.starts_with("map.") || part.is_empty());
    match (one_planner, group.contains("planner=")) {
        (true, _) | (false, true) => group.to_string(),
        (false, false) if only_map => planner.to_string(),
        (false, false) => format!("planner={planner}, {group}"),
    }
}

/// The panels: per map (and value of each [`panel_columns`] column), its series in the order
/// the study lists them.
fn panels(s: &Study, bounds: &AreaBounds) -> Panels {
    let colours = super::colours::RunColours::of(s);
    let one_planner = s.kinds.len() <= 1;
    let splits = panel_columns(s);
    let mut by_panel: BTreeMap<String, BTreeMap<String, Vec<Run>>> = BTreeMap::new();
    let mut order: Vec<String> = Vec::new();
    let (mut missing, mut of) = (0, 0);
    for g in &s.groups {
        for &r in &g.rows {
            if !s.executable(r) {
                continue;
            }
            of += 1;
            let id = s.get(r, "run_id");
            let run = match s.folders.from_folders() {
                true => s.folders.curve(&id).map(|c| Run { times: LEVELS.map(|l| c.time_to(l)), curve: Some(c), id }),
                false => s.folders.times(&id).map(|times| Run { times, curve: None, id }),
            };
            let Some(run) = run else {
                missing += 1;
                continue;
            };
            let series = series_label(&g.label, &s.get(r, "planner"), one_planner);
            if !order.contains(&series) {
                order.push(series.clone());
            }
            let mut panel = s.get(r, "map");
            for &c in &splits {
                panel.push_str(&format!(", {}={}", s.t.header[c], s.t.rows[r][c]));
            }
            by_panel.entry(panel).or_default().entry(series).or_default().push(run);
        }
    }
    if missing > 0 && missing < of {
        return Panels::Partial { missing, of };
    }
    for run in by_panel.values().flat_map(|series| series.values().flatten()) {
        s.folders.record_times(&run.id, run.times);
    }
    let names: BTreeMap<String, String> = order.iter().cloned().zip(distinct_parts(&order)).collect();
    let made = by_panel
        .into_iter()
        .map(|(panel, mut series)| {
            let list = order
                .iter()
                .filter_map(|label| {
                    series.remove(label).map(|runs| Series {
                        colour: colours.of_runs(runs.iter().map(|r| r.id.as_str()), 0),
                        first: runs[0].id.clone(),
                        label: names[label].clone(),
                        times: runs.iter().map(|r| r.times).collect(),
                        bounds: runs.iter().map(|r| level_bounds(bounds, &r.id)).collect(),
                        curves: runs.into_iter().filter_map(|r| r.curve).collect(),
                    })
                })
                .collect();
            (panel, list)
        })
        .collect();
    Panels::Made(made)
}

/// The section: the figure and the table, where runs have curves.
pub(crate) struct CoverageCurves;

impl Section for CoverageCurves {
    fn write(&self, s: &Study, md: &mut String) -> Result<(), ReportError> {
        let bounds = AreaBounds::of(s.dir, &s.t);
        let panels = match panels(s, &bounds) {
            Panels::Made(panels) => panels,
            Panels::Partial { missing, of } => {
                let _ = writeln!(
                    md,
                    "## Time to coverage\n\nNot made: {missing} of the {of} executable plans have no coverage curve \
                     (`coverage_curve.csv`) in their run folder, and a table of the others would not be the study's.\n"
                );
                return Ok(());
            }
        };
        if panels.is_empty() {
            return Ok(());
        }
        // Without the run folders the curves are not there to draw: the figure made with them
        // stays, and the table comes from what that report recorded.
        if s.folders.from_folders() {
            let figure = CurvesFigure {
                panels: panels
                    .iter()
                    .map(|(m, series)| (panel_title(m, series, &bounds), summarise(series, &bounds)))
                    .collect(),
            };
            crate::plot::save(&figure, &s.out.join("coverage_curves"))?;
        }
        let _ = writeln!(md, "## Time to coverage\n");
        let _ = writeln!(
            md,
            "Reachable coverage against mission time along each executable plan (median over the runs, band \
             between the quartiles; a segment's cells count once it is driven). Times to a level are medians over \
             the runs that reach it; in brackets, the median over them of the time over the lower bound, drawn \
             dashed in the figure: its length term (the level's share of the reachable cells' area, less the \
             footprint's start area, over the robots' summed (width + √2 × cell size) × speed) plus, for one robot \
             that turns at a finite rate, its turning term (the turning any path sweeping that area within the \
             map's diameter needs); no plan covers the level sooner (the book's \"The lower bound on a plan's \
             time\").\n\n![Time-to-coverage curves](coverage_curves.png)\n"
        );
        if let Some(why) = &bounds.missing {
            let _ = writeln!(md, "The lower bound is not given: {why}.\n");
        }
        let _ = writeln!(
            md,
            "| map | series | runs | reach 80 % | time to 80 % [s] (× length + turning bound) | reach 90 % | time to \
             90 % [s] (× length + turning bound) | reach 95 % | time to 95 % [s] (× length + turning bound) |"
        );
        let _ = writeln!(md, "| --- | --- | --- | --- | --- | --- | --- | --- | --- |");
        for (map, series) in &panels {
            for se in series {
                let mut cells = Vec::new();
                for k in 0..LEVELS.len() {
                    let times: Vec<f64> = se.times.iter().filter_map(|t| t[k]).collect();
                    cells.push(format!("{} of {}", times.len(), se.times.len()));
                    cells.push(level_cell(&times, &bound_ratios(se, k)));
                }
                let _ = writeln!(md, "| {map} | {} | {} | {} |", se.label, se.times.len(), cells.join(" | "));
            }
        }
        let _ = writeln!(md);
        Ok(())
    }
}

/// Run `id`'s bound on the time to each level, where it has one.
fn level_bounds(bounds: &AreaBounds, id: &str) -> Option<[f64; 3]> {
    let b = LEVELS.map(|l| bounds.to_level_s(id, l));
    Some([b[0]?, b[1]?, b[2]?])
}

/// Each run's time to level `k` over its bound, for the runs that reach the level; empty
/// where any of them has no bound.
fn bound_ratios(se: &Series, k: usize) -> Vec<f64> {
    let pairs: Vec<(f64, Option<f64>)> =
        se.times.iter().zip(&se.bounds).filter_map(|(t, b)| t[k].map(|t| (t, b.map(|b| b[k])))).collect();
    match pairs.iter().all(|(_, b)| b.is_some_and(|b| b > 0.0)) {
        true => pairs.into_iter().filter_map(|(t, b)| b.map(|b| t / b)).collect(),
        false => Vec::new(),
    }
}

/// A table cell: the median time to a level and, where there are bounds, the median of the
/// times over them.
fn level_cell(times: &[f64], ratios: &[f64]) -> String {
    match (times.is_empty(), ratios.is_empty()) {
        (true, _) => "–".into(),
        (false, true) => format!("{:.0}", quartiles(times).0),
        (false, false) => format!("{:.0} ({:.2}×)", quartiles(times).0, quartiles(ratios).0),
    }
}

/// A panel's title: its map and the robots of its series ([`AreaBounds::robot_text`]).
fn panel_title(panel: &str, series: &[Series], bounds: &AreaBounds) -> String {
    let mut robots: Vec<String> = Vec::new();
    for text in series.iter().filter_map(|se| bounds.robot_text(&se.first)) {
        if !robots.contains(&text) {
            robots.push(text);
        }
    }
    match robots.is_empty() {
        true => crate::plot::panel_label(panel),
        false => format!("{}: {}", crate::plot::panel_label(panel), robots.join("; ")),
    }
}

/// The bound on the time to each coverage of run `id`, as `(time, coverage)` at every
/// hundredth; empty where it has none.
fn bound_curve(bounds: &AreaBounds, id: &str) -> Vec<(f64, f64)> {
    (0..=100).filter_map(|k| bounds.to_level_s(id, k as f64 / 100.0).map(|t| (t, k as f64 / 100.0))).collect()
}

/// Samples every series of a panel at [`SAMPLES`] times up to the longest plan's end.
fn summarise(series: &[Series], bounds: &AreaBounds) -> Vec<Drawn> {
    let end =
        series.iter().flat_map(|s| s.curves.iter().filter_map(|c| c.points().last().map(|p| p.0))).fold(0.0, f64::max);
    let end = if end > 0.0 { end } else { 1.0 };
    series
        .iter()
        .map(|s| Drawn {
            colour: s.colour,
            bound: bound_curve(bounds, &s.first),
            label: s.label.clone(),
            runs: s.curves.len(),
            curve: (0..=SAMPLES)
                .map(|k| {
                    let t = end * k as f64 / SAMPLES as f64;
                    let v: Vec<f64> = s.curves.iter().map(|c| c.coverage_at(t)).collect();
                    let (m, q1, q3) = quartiles(&v);
                    (t, m, q1, q3)
                })
                .collect(),
        })
        .collect()
}

#[cfg(test)]
#[path = "curves/tests.rs"]
mod tests;
