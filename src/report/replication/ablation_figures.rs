//! Figures of a planner comparison: box plots of a metric per planner and map, convergence
//! curves (best footprint coverage against fitness evaluations, median and interquartile band
//! over seeds), and the best path of every planner on every map side by side.

use crate::plot::path::{PathFigure, draw_map_paths};
use crate::plot::{Figure, err, text};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// One box: a planner's values on one map.
pub struct BoxSeries {
    /// Planner label.
    pub label: String,
    /// The values of its executable plans (one per run): the box.
    pub values: Vec<f64>,
    /// The values of its plans that are not executable: drawn as crosses beside the box.
    pub excluded: Vec<f64>,
}

/// Box plots of one metric: one panel per map, one box per planner.
pub struct BoxFigure {
    /// Metric name with unit, for the y axis.
    pub metric: String,
    /// `(map, boxes)` per panel.
    pub panels: Vec<(String, Vec<BoxSeries>)>,
}

/// Tick labels on a value axis (plotters steps no finer than the span over this).
const Y_TICKS: usize = 10;

/// Rows and columns of a panel grid: two columns from three panels on.
fn shape(n: usize) -> (usize, usize) {
    if n <= 2 { (1, n.max(1)) } else { (n.div_ceil(2), 2) }
}

fn colour(k: usize) -> RGBColor {
    crate::plot::series_colour(k)
}

impl BoxFigure {
    /// Each box's axis label: the planner, with its executable share where some plans are not,
    /// and "(1 run)" for a group of one run (drawn as a point: a box needs several).
    fn labels(boxes: &[BoxSeries]) -> Vec<String> {
        boxes
            .iter()
            .map(|b| {
                let runs = b.values.len() + b.excluded.len();
                match (b.excluded.is_empty(), runs) {
                    (true, 1) => format!("{} (1 run)", b.label),
                    (true, _) => b.label.clone(),
                    (false, _) => format!("{} ({}/{runs})", b.label, b.values.len()),
                }
            })
            .collect()
    }

    fn title(&self) -> String {
        format!(
            "{} per planner (box = IQR, line = median, whiskers = min..max of executable plans; a group of one \
             run is a point; grey × = not executable; (k/n) = executable share)",
            self.metric
        )
    }

    /// Height of the band under each panel that holds its labels, written upwards.
    fn label_band(&self) -> u32 {
        let longest = self.panels.iter().flat_map(|(_, b)| Self::labels(b)).map(|l| l.chars().count()).max();
        (longest.unwrap_or(4) as f64 * 0.52 * 12.0) as u32 + 24
    }
}

impl Figure for BoxFigure {
    fn size(&self) -> (u32, u32) {
        let (r, c) = shape(self.panels.len());
        // Labels written upwards under the boxes: a box needs its width, not its label's.
        let boxes = self.panels.iter().map(|(_, b)| b.len()).max().unwrap_or(1) as u32;
        let width = c as u32 * (70 * boxes + 90).max(520);
        (width, r as u32 * (300 + self.label_band()) + crate::plot::title_height(&self.title(), width, 16.0))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let root = crate::plot::titled(root, &self.title(), 16.0)?;
        // One y range for every panel, so that the maps compare at a glance.
        let all: Vec<f64> = self
            .panels
            .iter()
            .flat_map(|(_, boxes)| boxes.iter().flat_map(|b| b.values.iter().chain(&b.excluded).copied()))
            .filter(|v| v.is_finite())
            .collect();
        let (lo, hi) = all.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| (l.min(v), h.max(v)));
        let (lo, hi) = if lo.is_finite() { (lo, hi) } else { (0.0, 1.0) };
        let pad = ((hi - lo) * 0.08).max(1e-3);
        for (area, (map, boxes)) in root.split_evenly(shape(self.panels.len())).iter().zip(&self.panels) {
            let n = boxes.len().max(1);
            let mut chart = ChartBuilder::on(area)
                .caption(map, text(15.0))
                .margin(8)
                .x_label_area_size(self.label_band())
                .y_label_area_size(60)
                .build_cartesian_2d(0.0..n as f64, (lo - pad)..(hi + pad))
                .map_err(err)?;
            let labels = Self::labels(boxes);
            let decimals = crate::plot::step_decimals(hi - lo + 2.0 * pad, Y_TICKS);
            chart
                .configure_mesh()
                .disable_x_mesh()
                .light_line_style(RGBColor(235, 235, 235))
                .x_labels(0)
                .y_labels(Y_TICKS)
                .y_label_formatter(&|v| format!("{v:.decimals$}"))
                .y_desc(&self.metric)
                .label_style(text(12.0))
                .axis_desc_style(text(13.0))
                .draw()
                .map_err(err)?;
            // Labels written upwards under their boxes, ending just below the axis.
            let upwards = text(12.0).transform(FontTransform::Rotate270).pos(Pos::new(HPos::Right, VPos::Center));
            let (below, (ax, ay)) = (lo - pad, area.get_base_pixel());
            for (k, label) in labels.iter().enumerate() {
                let (x, y) = chart.backend_coord(&(k as f64 + 0.5, below));
                area.draw(&Text::new(label.clone(), (x - ax, y - ay + 8), upwards.clone())).map_err(err)?;
            }
            for (k, b) in boxes.iter().enumerate() {
                let grey = RGBColor(120, 120, 120);
                chart
                    .draw_series(b.excluded.iter().map(|&v| Cross::new((k as f64 + 0.85, v), 4, grey.stroke_width(1))))
                    .map_err(err)?;
                if b.values.is_empty() {
                    continue;
                }
                if b.values.len() == 1 {
                    let point = Circle::new((k as f64 + 0.5, b.values[0]), 5, colour(k).filled());
                    chart.draw_series([point]).map_err(err)?;
                    chart
                        .draw_series([Circle::new((k as f64 + 0.5, b.values[0]), 5, BLACK.stroke_width(1))])
                        .map_err(err)?;
                    continue;
                }
                let (q1, med, q3) = crate::stats::quartiles(&b.values);
                let min = b.values.iter().copied().fold(f64::INFINITY, f64::min);
                let max = b.values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                let (x0, x1, xc) = (k as f64 + 0.2, k as f64 + 0.8, k as f64 + 0.5);
                let c = colour(k);
                let series: Vec<PathElement<(f64, f64)>> = vec![
                    PathElement::new(vec![(xc, min), (xc, q1)], BLACK.stroke_width(1)),
                    PathElement::new(vec![(xc, q3), (xc, max)], BLACK.stroke_width(1)),
                    PathElement::new(vec![(x0 + 0.15, min), (x1 - 0.15, min)], BLACK.stroke_width(1)),
                    PathElement::new(vec![(x0 + 0.15, max), (x1 - 0.15, max)], BLACK.stroke_width(1)),
                ];
                chart.draw_series(series).map_err(err)?;
                chart.draw_series([Rectangle::new([(x0, q1), (x1, q3)], c.mix(0.45).filled())]).map_err(err)?;
                chart.draw_series([Rectangle::new([(x0, q1), (x1, q3)], BLACK.stroke_width(1))]).map_err(err)?;
                chart
                    .draw_series([PathElement::new(vec![(x0, med), (x1, med)], BLACK.stroke_width(3))])
                    .map_err(err)?;
            }
        }
        Ok(())
    }
}

/// One convergence curve: `(evaluations, q1, median, q3)` of the best coverage over seeds.
pub struct Curve {
    /// Planner label.
    pub label: String,
    /// Runs behind it.
    pub runs: usize,
    /// The points.
    pub points: Vec<(f64, f64, f64, f64)>,
    /// The median coverage of the same runs' plans as scored: above the curve's end where a
    /// completion pass after the search adds cells (drawn as a diamond at the end).
    pub scored: Option<f64>,
}

/// Height of one line of the legend below the convergence panels, in pixels.
const LEGEND_LINE: u32 = 24;

/// Height of the legend strip of `labels` below panels `width` pixels wide (one line for none).
pub fn legend_strip_height(labels: &[String], width: u32) -> u32 {
    let lines = legend_layout(labels, width).last().map_or(1, |(line, _)| line + 1);
    lines * LEGEND_LINE + 16
}

/// Draws the legend strip below a figure's panels: entry `k`'s key drawn by `key(k, (x, y))`
/// at the start of its place (`y` the middle of its line), its label after it.
pub fn draw_legend_strip<DB: DrawingBackend>(
    strip: &DrawingArea<DB, Shift>,
    labels: &[String],
    key: impl Fn(usize, (i32, i32)) -> Result<(), String>,
) -> Result<(), String> {
    for (k, (label, (line, x))) in labels.iter().zip(legend_layout(labels, strip.dim_in_pixel().0)).enumerate() {
        let y = 20 + (line * LEGEND_LINE) as i32;
        key(k, (x, y))?;
        strip.draw(&Text::new(label.clone(), (x + 28, y - 8), text(14.0))).map_err(err)?;
    }
    Ok(())
}

/// Where legend entries of `labels` go in a strip `width` pixels wide: `(line, x)` per entry,
/// in columns as wide as the widest entry, as many as fit side by side (one at least), filled
/// row by row, so that keys and labels line up down the strip.
pub fn legend_layout(labels: &[String], width: u32) -> Vec<(u32, i32)> {
    let entry = |label: &String| 28 + (label.chars().count() as f64 * 0.6 * 14.0) as i32 + 30;
    let column = labels.iter().map(entry).max().unwrap_or(1).max(1);
    let columns = ((width as i32 - 30) / column).max(1) as usize;
    (0..labels.len()).map(|k| ((k / columns) as u32, 20 + (k % columns) as i32 * column)).collect()
}

/// The y range of a convergence panel: the bands and scored plans with a margin (the curves of
/// a goal-driven planner lie within a few hundredths), within 0..1.
fn fitted_range(curves: &[Curve]) -> (f64, f64) {
    let (lo, hi) = curves
        .iter()
        .flat_map(|c| c.points.iter().flat_map(|p| [p.1, p.3]).chain(c.scored))
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
    let (lo, hi) = if lo.is_finite() { (lo, hi) } else { (0.0, 1.0) };
    let pad = ((hi - lo) * 0.1).max(0.005);
    ((lo - pad).max(0.0), (hi + pad).min(1.0))
}

const CONVERGENCE_TITLE: &str = "Best plan's footprint coverage of the reachable cells vs fitness evaluations: \
                                 median, band = IQR over the seeds with an executable plan; ◆ = the plans as scored \
                                 (after a completion pass, where there is one)";

/// Convergence of the GAs: one panel per map.
pub struct ConvergenceFigure {
    /// `(map, curves)` per panel.
    pub panels: Vec<(String, Vec<Curve>)>,
}

impl ConvergenceFigure {
    /// Every series in the order it first appears, with its legend label; its colour is its
    /// place here in every panel, so that a planner missing from one panel does not shift the
    /// others' colours.
    fn series(&self) -> Vec<(&Curve, String)> {
        let mut series: Vec<&Curve> = Vec::new();
        for c in self.panels.iter().flat_map(|(_, c)| c) {
            if !series.iter().any(|s| s.label == c.label) {
                series.push(c);
            }
        }
        let runs: std::collections::BTreeSet<usize> =
            self.panels.iter().flat_map(|(_, c)| c.iter().map(|c| c.runs)).collect();
        series
            .into_iter()
            .map(|c| {
                let label = match runs.len() {
                    1 => format!("{} ({})", c.label, crate::plot::runs_text(c.runs)),
                    _ => c.label.clone(),
                };
                (c, label)
            })
            .collect()
    }

    /// The legend strip's height for a figure `width` pixels wide.
    fn legend_height(&self, width: u32) -> u32 {
        let labels: Vec<String> = self.series().into_iter().map(|(_, l)| l).collect();
        legend_strip_height(&labels, width)
    }
}

impl Figure for ConvergenceFigure {
    fn size(&self) -> (u32, u32) {
        let (r, c) = shape(self.panels.len());
        let width = c as u32 * 620;
        (width, r as u32 * 400 + crate::plot::title_height(CONVERGENCE_TITLE, width, 16.0) + self.legend_height(width))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let root = crate::plot::titled(root, CONVERGENCE_TITLE, 16.0)?;
        // One legend for all panels, below them, where it hides no curve, wrapped to the width.
        let (width, height) = root.dim_in_pixel();
        let (panels, strip) = root.split_vertically(height - self.legend_height(width));
        let series = self.series();
        let index_of = |label: &str| series.iter().position(|(s, _)| s.label == label).unwrap_or(0);
        let labels: Vec<String> = series.iter().map(|(_, l)| l.clone()).collect();
        draw_legend_strip(&strip, &labels, |k, (x, y)| {
            let dashes: &[(i32, i32)] =
                if crate::plot::series_dashed(k) { &[(0, 5), (9, 14), (18, 23)] } else { &[(0, 22)] };
            for &(a, b) in dashes {
                strip.draw(&PathElement::new(vec![(x + a, y), (x + b, y)], colour(k).stroke_width(3))).map_err(err)?;
            }
            Ok(())
        })?;
        for (area, (map, curves)) in panels.split_evenly(shape(self.panels.len())).iter().zip(&self.panels) {
            let x_max = curves.iter().flat_map(|c| c.points.last().map(|p| p.0)).fold(1.0f64, f64::max);
            let (y0, y1) = fitted_range(curves);
            let decimals = crate::plot::step_decimals(y1 - y0, Y_TICKS);
            let mut chart = ChartBuilder::on(area)
                .caption(crate::plot::panel_label(map), text(15.0))
                .margin(10)
                .margin_right(24)
                .x_label_area_size(45)
                .y_label_area_size(65)
                .build_cartesian_2d(0.0..x_max, y0..y1)
                .map_err(err)?;
            chart
                .configure_mesh()
                .y_labels(Y_TICKS)
                .y_label_formatter(&|v| format!("{v:.decimals$}"))
                .light_line_style(RGBColor(235, 235, 235))
                .x_desc("fitness evaluations")
                .y_desc("cov_final (reachable cells)")
                .x_label_formatter(&|x| {
                    if x_max >= 20_000.0 { format!("{:.0}k", x / 1000.0) } else { format!("{x:.0}") }
                })
                .label_style(text(12.0))
                .axis_desc_style(text(13.0))
                .draw()
                .map_err(err)?;
            for (drawn, c) in curves.iter().enumerate() {
                let k = index_of(&c.label);
                let col = colour(k);
                // Earlier series wider, so that one lying on another still shows around it.
                let stroke = 2 + 2 * (curves.len() - 1 - drawn) as u32;
                let band: Vec<(f64, f64)> =
                    c.points.iter().map(|p| (p.0, p.3)).chain(c.points.iter().rev().map(|p| (p.0, p.1))).collect();
                chart.draw_series([Polygon::new(band, col.mix(0.2).filled())]).map_err(err)?;
                if let (Some(v), Some(last)) = (c.scored, c.points.last()) {
                    let (x, y) = chart.backend_coord(&(last.0, v));
                    let (ax, ay) = area.get_base_pixel();
                    let (x, y) = (x - ax, y - ay);
                    let r = 6 + 2 * (curves.len() - 1 - drawn) as i32;
                    let diamond = vec![(x, y - r - 1), (x - r, y), (x, y + r + 1), (x + r, y)];
                    area.draw(&Polygon::new(diamond.clone(), col.filled())).map_err(err)?;
                    area.draw(&PathElement::new([diamond.clone(), vec![diamond[0]]].concat(), BLACK.stroke_width(1)))
                        .map_err(err)?;
                }
                let median = c.points.iter().map(|p| (p.0, p.2));
                if crate::plot::series_dashed(k) {
                    chart.draw_series(DashedLineSeries::new(median, 7, 5, col.stroke_width(stroke))).map_err(err)?;
                } else {
                    chart.draw_series(LineSeries::new(median, col.stroke_width(stroke))).map_err(err)?;
                }
            }
        }
        Ok(())
    }
}

/// The title of [`PlannerPathsFigure`].
const PLANNER_PATHS_TITLE: &str = "Best executable run of each planner on each map: blue path; cells green once, orange 2+ \
                                   times, red obstacle hit; ▲ start, ✕ end";

/// The best path of each planner (columns) on each map (rows).
pub struct PlannerPathsFigure<'a> {
    /// Rows of panels; a `None` cell is left empty.
    pub rows: Vec<Vec<Option<PathFigure<'a>>>>,
    /// For each empty cell, what it says instead (a planner that ran without an executable
    /// plan); same shape as `rows`.
    pub missing: Vec<Vec<Option<String>>>,
}

impl Figure for PlannerPathsFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let cols = self.rows.iter().map(Vec::len).max().unwrap_or(1).max(1) as u32;
        let title = crate::plot::title_height(PLANNER_PATHS_TITLE, cols * 330, 18.0);
        (cols * 330, self.rows.len().max(1) as u32 * 350 + title)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let root = crate::plot::titled(root, PLANNER_PATHS_TITLE, 18.0)?;
        let cols = self.rows.iter().map(Vec::len).max().unwrap_or(1).max(1);
        let areas = root.split_evenly((self.rows.len().max(1), cols));
        for (r, row) in self.rows.iter().enumerate() {
            for (c, panel) in row.iter().enumerate() {
                let area = &areas[r * cols + c];
                let Some(p) = panel else {
                    if let Some(note) = self.missing.get(r).and_then(|m| m.get(c)).and_then(Option::as_ref) {
                        // The planner on one line, what is missing on the next.
                        let (w, h) = area.dim_in_pixel();
                        let lines: Vec<&str> = note.splitn(2, ": ").collect();
                        for (k, line) in lines.iter().enumerate() {
                            let style =
                                crate::plot::fitting_text(line, w, 14.0).pos(Pos::new(HPos::Center, VPos::Center));
                            let y = h as i32 / 2 + (k as i32 * 2 - lines.len() as i32 + 1) * 10;
                            area.draw_text(line, &style, (w as i32 / 2, y)).map_err(err)?;
                        }
                    }
                    continue;
                };
                // The planner on a line of its own, then the map and scores: a narrow panel
                // keeps both readable.
                match p.title.split_once(", ") {
                    Some((planner, rest)) => {
                        let width = area.dim_in_pixel().0;
                        let below =
                            area.titled(planner, crate::plot::fitting_text(planner, width, 14.0)).map_err(err)?;
                        // The map on a line of its own where map and scores do not fit one.
                        let (below, rest) = match rest.split_once(": ") {
                            Some((map, scores)) if !crate::plot::fits(rest, width, 14.0) => {
                                (below.titled(map, crate::plot::fitting_text(map, width, 13.0)).map_err(err)?, scores)
                            }
                            _ => (below, rest),
                        };
                        draw_map_paths(&below, &PathFigure { title: rest.to_string(), ..p.clone() }, (14.0, 10.0))?;
                    }
                    None => {
                        draw_map_paths(area, p, (14.0, 10.0))?;
                    }
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod layout_tests;

#[cfg(test)]
mod tests {
    use super::*;

    /// Entries run left to right in columns as wide as the widest and wrap before the right
    /// edge; an entry wider than the strip still gets a line of its own.
    #[test]
    fn legend_entries_line_up_in_columns_and_wrap_before_the_edge() {
        let labels = |n: &[usize]| n.iter().map(|&k| "x".repeat(k)).collect::<Vec<_>>();
        // An entry of k characters takes 28 + floor(8.4 k) + 30 pixels.
        for (chars, width, expected) in [
            (vec![10, 10], 1000, vec![(0, 20), (0, 162)]),
            (vec![10, 10, 10], 400, vec![(0, 20), (0, 162), (1, 20)]),
            (vec![200, 5], 300, vec![(0, 20), (1, 20)]),
            // Three columns of the widest entry (310 px): the short ones keep its place.
            (vec![30, 5, 5, 30], 1000, vec![(0, 20), (0, 330), (0, 640), (1, 20)]),
        ] {
            assert_eq!(legend_layout(&labels(&chars), width), expected, "{chars:?} in {width} px");
        }
    }
}
