//! Convergence curves of the GAs: the best footprint coverage against fitness evaluations,
//! median and interquartile band over seeds, one panel per map, one legend below them.

use super::panels::{Y_TICKS, colour, draw_legend_strip, legend_strip_height, two_columns};
use crate::plot::{Figure, err, text};
use plotters::coord::Shift;
use plotters::prelude::*;

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
    /// Its colour's number ([`crate::plot::series_colour`]), the same in every figure of the
    /// report.
    pub colour: usize,
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
        let (r, c) = two_columns(self.panels.len());
        let width = c as u32 * 620;
        (width, r as u32 * 400 + crate::plot::title_height(CONVERGENCE_TITLE, width, 16.0) + self.legend_height(width))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let root = crate::plot::titled(root, CONVERGENCE_TITLE, 16.0)?;
        // One legend for all panels, below them, where it hides no curve, wrapped to the width.
        let (width, height) = root.dim_in_pixel();
        let (panels, strip) = root.split_vertically(height - self.legend_height(width));
        let series = self.series();
        let labels: Vec<String> = series.iter().map(|(_, l)| l.clone()).collect();
        draw_legend_strip(&strip, &labels, |entry, (x, y)| {
            let k = series[entry].0.colour;
            let dashes: &[(i32, i32)] =
                if crate::plot::series_dashed(k) { &[(0, 5), (9, 14), (18, 23)] } else { &[(0, 22)] };
            for &(a, b) in dashes {
                strip.draw(&PathElement::new(vec![(x + a, y), (x + b, y)], colour(k).stroke_width(3))).map_err(err)?;
            }
            Ok(())
        })?;
        for (area, (map, curves)) in panels.split_evenly(two_columns(self.panels.len())).iter().zip(&self.panels) {
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
                let k = c.colour;
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
