//! Time-to-coverage curves of a study (issue of comparing plans at equal coverage): per map,
//! one curve per planner (or per group, where the study has one planner) — the median over its
//! runs of the reachable coverage reached by each time, with the band between the quartiles —
//! and a table of the times to 80, 90 and 95 % of the reachable cells. Read from each run's
//! `coverage_curve.csv` ([`crate::coverage::curve`]); executable plans only.

use super::ReportError;
use super::bound::AreaBounds;
use super::study::Study;
use crate::coverage::curve::{CoverageCurve, LEVELS};
use crate::plot::{Figure, err, text};
use crate::report::replication::ablation_figures::{draw_legend_strip, legend_strip_height};
use plotters::coord::Shift;
use plotters::prelude::*;
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
            values.len() > 1
                && !values.contains("")
                && map.is_none_or(|m| super::design::followed_by(&s.t, c, &[m]).is_none())
        })
        .collect()
}

/// `labels` for a legend: without the `key=value` parts every one of them shares
/// (`planner=cell_order` where the report keeps one planner), that set nothing (`key=`) or
/// name the map (each panel is one map, and its title names it), and each key by its last
/// name (`solver=ga`), so that the legend names what tells the series apart; a label with no
/// part left is "executable runs".
pub(super) fn distinct_parts(labels: &[String]) -> Vec<String> {
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
pub(super) fn series_label(group: &str, planner: &str, one_planner: bool) -> String {
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
pub(super) struct CoverageCurves;

impl super::sections::Section for CoverageCurves {
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

/// A series drawn: label, runs, and `(time, median, q1, q3)` at the panel's sample times.
struct Drawn {
    label: String,
    runs: usize,
    curve: Vec<(f64, f64, f64, f64)>,
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

/// One panel per map, one median line and quartile band per series; one legend below the
/// panels, each series in one colour in every panel.
struct CurvesFigure {
    panels: Vec<(String, Vec<Drawn>)>,
}

const CURVES_TITLE: &str =
    "Time to coverage: reachable coverage over mission time (median, band = quartiles over runs)";

impl CurvesFigure {
    /// Rows and columns of panels: one column up to three panels, two beyond.
    fn grid(&self) -> (usize, usize) {
        let n = self.panels.len().max(1);
        if n <= 3 { (n, 1) } else { (n.div_ceil(2), 2) }
    }

    /// Every series in the order it first appears, with its legend label.
    fn series(&self) -> Vec<String> {
        let mut labels: Vec<String> = Vec::new();
        for d in self.panels.iter().flat_map(|(_, s)| s) {
            if !labels.contains(&d.label) {
                labels.push(d.label.clone());
            }
        }
        labels
    }

    /// The legend's entries: each series with its runs (summed over the panels).
    fn entries(&self) -> Vec<String> {
        self.series()
            .into_iter()
            .map(|label| {
                let runs: usize =
                    self.panels.iter().flat_map(|(_, s)| s).filter(|d| d.label == label).map(|d| d.runs).sum();
                format!("{label} ({})", crate::plot::runs_text(runs))
            })
            .collect()
    }

    fn legend_height(&self, width: u32) -> u32 {
        legend_strip_height(&self.entries(), width)
    }
}

impl Figure for CurvesFigure {
    fn size(&self) -> (u32, u32) {
        let (rows, columns) = self.grid();
        let width = 800 * columns as u32;
        (width, crate::plot::title_height(CURVES_TITLE, width, 18.0) + 320 * rows as u32 + self.legend_height(width))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let root = crate::plot::titled(root, CURVES_TITLE, 18.0)?;
        let (width, height) = root.dim_in_pixel();
        let (panels, strip) = root.split_vertically(height - self.legend_height(width));
        let series = self.series();
        let entries = self.entries();
        draw_legend_strip(&strip, &entries, |k, (x, y)| {
            let colour = crate::plot::series_colour(k);
            strip.draw(&PathElement::new(vec![(x, y), (x + 22, y)], colour.stroke_width(3))).map_err(err)
        })?;
        for (area, (map, drawn)) in panels.split_evenly(self.grid()).iter().zip(&self.panels) {
            let x_max = drawn.iter().flat_map(|s| s.curve.last().map(|c| c.0)).fold(1.0, f64::max);
            let mut chart = ChartBuilder::on(area)
                .caption(crate::plot::panel_label(map), text(15.0))
                .margin(8)
                .margin_right(24)
                .x_label_area_size(45)
                .y_label_area_size(70)
                .build_cartesian_2d(0.0..x_max, 0.0..1.0)
                .map_err(err)?;
            chart
                .configure_mesh()
                .y_label_formatter(&|v| format!("{v:.1}"))
                .x_label_formatter(&|v| format!("{v:.0}"))
                // No minor grid: at one line every few pixels it blurred the curves and made
                // the PNG of a many-map study tens of megabytes.
                .max_light_lines(0)
                .x_desc("mission time [s]")
                .y_desc("coverage of reachable cells")
                .label_style(text(14.0))
                .axis_desc_style(text(14.0))
                .draw()
                .map_err(err)?;
            let one_px = 1.0 / f64::from(chart.plotting_area().dim_in_pixel().1.max(1));
            for s in drawn {
                let colour = crate::plot::series_colour(series.iter().position(|l| *l == s.label).unwrap_or(0));
                let band: Vec<(f64, f64)> =
                    s.curve.iter().map(|c| (c.0, c.3)).chain(s.curve.iter().rev().map(|c| (c.0, c.2))).collect();
                chart.draw_series([Polygon::new(band, colour.mix(0.15).filled())]).map_err(err)?;
                let median: Vec<(f64, f64)> = s.curve.iter().map(|c| (c.0, c.1)).collect();
                crate::plot::draw_series_line(&mut chart, &median, colour, one_px)?;
            }
        }
        Ok(())
    }
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

    /// The four study shapes: every text on the canvas, no repeated tick, every series and map
    /// named, "1 run" for one.
    #[test]
    fn the_curves_figure_keeps_its_texts_on_the_canvas() {
        let drawn = |label: &str, runs: usize| Drawn {
            label: label.into(),
            runs,
            curve: (0..=10).map(|k| (k as f64 * 400.0, (k as f64 / 10.0).min(0.95), 0.0, 1.0)).collect(),
        };
        type Panels = Vec<(String, Vec<Drawn>)>;
        let shapes: [(&str, Panels); 4] = [
            ("thesis", vec![("thesis-1".into(), vec![drawn("selection=elite", 10), drawn("selection=nsga2", 10)])]),
            (
                "mixed",
                vec![(
                    "experiments/maps/generated/office-1.yaml".into(),
                    vec![drawn("boustrophedon", 1), drawn("spiral", 1), drawn("solver=ga", 3), drawn("solver=ils", 3)],
                )],
            ),
            ("one run", vec![("basement".into(), vec![drawn("nearest", 1)])]),
            ("many maps", (0..5).map(|m| (format!("maps/house-{m}.yaml"), vec![drawn("ils", 5)])).collect()),
        ];
        let mut found = Vec::new();
        for (name, panels) in shapes {
            let mut expected: Vec<String> =
                panels.iter().flat_map(|(_, d)| d.iter().map(|d| d.label.clone())).collect();
            expected.extend(panels.iter().map(|(m, _)| crate::plot::panel_label(m)));
            let figure = CurvesFigure { panels };
            let expected: Vec<&str> = expected.iter().map(String::as_str).collect();
            for p in crate::plot::layout::problems(&figure, &expected).unwrap() {
                found.push(format!("{name}: {p}"));
            }
            let texts = crate::plot::layout::drawn_texts(&figure).unwrap();
            if texts.iter().any(|t| t.text.contains("(1 runs)") || t.text.starts_with("map ")) {
                found.push(format!("{name}: \"1 runs\" or a map's path as a title"));
            }
        }
        assert!(found.is_empty(), "{}", found.join("\n"));
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
