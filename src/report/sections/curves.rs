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
            let figure =
                CurvesFigure { panels: panels.iter().map(|(m, series)| (m.clone(), summarise(series))).collect() };
            crate::plot::save(&figure, &s.out.join("coverage_curves"))?;
        }
        let _ = writeln!(md, "## Time to coverage\n");
        let _ = writeln!(
            md,
            "Reachable coverage against mission time along each executable plan (median over the runs, band \
             between the quartiles; a segment's cells count once it is driven). Times to a level are medians over \
             the runs that reach it; in brackets, the median over them of the time over the lower bound (the \
             level's share of the reachable cells' area over the robots' combined width × speed, plus for one \
             robot that turns at a finite rate the turning any path covering that area inside the map needs: no \
             plan covers it sooner).\n\n![Time-to-coverage curves](coverage_curves.png)\n"
        );
        if let Some(why) = &bounds.missing {
            let _ = writeln!(md, "The lower bound is not given: {why}.\n");
        }
        let _ = writeln!(
            md,
            "| map | series | runs | reach 80 % | time to 80 % [s] (× bound) | reach 90 % | time to 90 % [s] (× bound) | \
             reach 95 % | time to 95 % [s] (× bound) |"
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

/// Samples every series of a panel at [`SAMPLES`] times up to the longest plan's end.
fn summarise(series: &[Series]) -> Vec<Drawn> {
    let end =
        series.iter().flat_map(|s| s.curves.iter().filter_map(|c| c.points().last().map(|p| p.0))).fold(0.0, f64::max);
    let end = if end > 0.0 { end } else { 1.0 };
    series
        .iter()
        .map(|s| Drawn {
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
mod tests {
    use super::*;

    /// Every `--by` group is a series; the planner joins it where the study has several.
    #[test]
    fn each_group_is_a_series_with_its_planner() {
        for (group, planner, one, series) in [
            (
                "planner=cell_order, cell_order.solver=ga",
                "cell_order",
                false,
                "planner=cell_order, cell_order.solver=ga",
            ),
            ("cell_order.solver=ga", "cell_order", false, "planner=cell_order, cell_order.solver=ga"),
            ("map.source=office", "spiral", false, "spiral"),
            ("thesis.selection=elite", "thesis", true, "thesis.selection=elite"),
        ] {
            assert_eq!(series_label(group, planner, one), series, "{group}");
        }
    }

    #[test]
    fn legend_labels_keep_what_tells_the_series_apart() {
        let labels: Vec<String> = [
            "planner=cell_order, cell_order.solver=ga, cell_order.seed_directions=true",
            "planner=cell_order, cell_order.solver=nearest, cell_order.seed_directions=",
        ]
        .map(String::from)
        .to_vec();
        assert_eq!(distinct_parts(&labels), ["solver=ga, seed_directions=true", "solver=nearest"]);
        assert_eq!(distinct_parts(&["planner=thesis".to_string()]), ["planner=thesis"]);
        // The panel names the map: a series told apart by its map alone is the panel's runs.
        let by_map = ["map.source=office".to_string(), "map.source=thesis-2".to_string()];
        assert_eq!(distinct_parts(&by_map), ["executable runs", "executable runs"]);
        let both = ["map.source=office, thesis.moves=routed".to_string()];
        assert_eq!(distinct_parts(&both), ["moves=routed"]);
    }

    #[test]
    fn a_level_shows_the_median_time_and_its_median_ratio_to_the_bound() {
        let times = vec![[Some(80.0), Some(100.0), None], [Some(40.0), None, None], [None, None, None]];
        let b = |full: f64| Some(LEVELS.map(|l| l * full));
        let se = Series { label: "a".into(), times, bounds: vec![b(100.0), b(50.0), None], curves: Vec::new() };
        // 80 s over 0.8 × 100 s and 40 s over 0.8 × 50 s; the third run reaches no level.
        assert_eq!(bound_ratios(&se, 0), vec![1.0, 1.0]);
        assert_eq!(level_cell(&[80.0, 40.0], &bound_ratios(&se, 0)), "60 (1.00×)");
        assert_eq!(level_cell(&[100.0], &bound_ratios(&se, 1)), "100 (1.11×)");
        assert_eq!(level_cell(&[], &bound_ratios(&se, 2)), "–");
        // A run that reaches the level without a bound: no ratio for anyone.
        let se = Series { bounds: vec![b(100.0), None, None], ..se };
        assert!(bound_ratios(&se, 0).is_empty());
        assert_eq!(level_cell(&[80.0, 40.0], &[]), "60");
    }

    #[test]
    fn curves_are_read_and_sampled_as_steps() {
        let read_curve = |f: &std::path::Path| CoverageCurve::parse_csv(&std::fs::read_to_string(f).ok()?);
        let dir = std::env::temp_dir().join(format!("covga-curves-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("coverage_curve.csv");
        std::fs::write(&file, "time_s,coverage_reach\n0,0\n10,0.5\n20,0.9\n30,0.95\n").unwrap();
        let c = read_curve(&file).unwrap();
        assert_eq!(c.points().len(), 4);
        let at = |t| c.coverage_at(t);
        assert_eq!((at(9.9), at(10.0), at(25.0), at(99.0)), (0.0, 0.5, 0.9, 0.95));
        assert_eq!((c.time_to(0.8), c.time_to(0.95), c.time_to(0.96)), (Some(20.0), Some(30.0), None));
        for bad in ["x,y\n0,0\n", "time_s,coverage_reach\n0,0\n10,x\n", "time_s,coverage_reach\n0,0.5\n10,0.4\n"] {
            std::fs::write(&file, bad).unwrap();
            assert!(read_curve(&file).is_none(), "{bad:?} is not a curve");
        }
        let slower = CoverageCurve::parse_csv("time_s,coverage_reach\n0,0\n20,0.5\n40,0.9\n60,0.95\n").unwrap();
        let series = [Series { label: "a".into(), times: Vec::new(), bounds: Vec::new(), curves: vec![c, slower] }];
        let drawn = summarise(&series);
        assert_eq!(drawn[0].curve.len(), SAMPLES + 1);
        // At the end of the longer plan both runs have reached 0.95.
        let last = drawn[0].curve.last().unwrap();
        assert_eq!((last.0, last.1), (60.0, 0.95));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
