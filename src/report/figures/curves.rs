//! The time-to-coverage figure: per map, the reachable coverage over mission time of each
//! series (median line, band between the quartiles), the lower bound on the time to each
//! coverage (`docs/src/concepts/lower-bound.md`: no plan's curve lies left of it) and the
//! robot in the panel's title, one legend below the panels. Series that coincide stay
//! visible: each earlier one is drawn wider under the later ones.

use super::panels::{draw_legend_strip, legend_strip_height};
use crate::plot::{Figure, err, text};
use plotters::coord::Shift;
use plotters::prelude::*;

/// A series drawn: label, runs, and `(time, median, q1, q3)` at the panel's sample times.
pub struct Drawn {
    /// The series' legend label.
    pub label: String,
    /// Runs behind it.
    pub runs: usize,
    /// `(time, median, q1, q3)` at the sample times.
    pub curve: Vec<(f64, f64, f64, f64)>,
    /// Its colour's number ([`crate::plot::series_colour`]), the same in every figure of the
    /// report.
    pub colour: usize,
    /// The lower bound on its runs' time to each coverage, as `(time, coverage)` (empty where
    /// there is none); drawn once per panel where its series share it.
    pub bound: Vec<(f64, f64)>,
}

/// One panel per map, one median line and quartile band per series; one legend below the
/// panels, each series in one colour in every panel.
pub struct CurvesFigure {
    /// `(title, series)` per panel: the map and its robot.
    pub panels: Vec<(String, Vec<Drawn>)>,
}

/// The legend's entry for the bound: what it counts.
pub const BOUND_ENTRY: &str = "lower bound (length + turning terms): no plan lies left of it";

const CURVES_TITLE: &str = "Time to coverage: reachable coverage over mission time (median, band = quartiles over \
                            runs; where series coincide, the earlier one is drawn wider beneath)";

impl CurvesFigure {
    /// Rows and columns of panels: one column up to three panels, two beyond.
    fn grid(&self) -> (usize, usize) {
        let n = self.panels.len().max(1);
        if n <= 3 { (n, 1) } else { (n.div_ceil(2), 2) }
    }

    /// Every series in the order it first appears, with its legend label and colour.
    fn series(&self) -> Vec<(String, usize)> {
        let mut labels: Vec<(String, usize)> = Vec::new();
        for d in self.panels.iter().flat_map(|(_, s)| s) {
            if !labels.iter().any(|(l, _)| *l == d.label) {
                labels.push((d.label.clone(), d.colour));
            }
        }
        labels
    }

    /// Whether any panel draws a bound.
    fn has_bound(&self) -> bool {
        self.panels.iter().flat_map(|(_, s)| s).any(|d| !d.bound.is_empty())
    }

    /// The legend's entries: each series with its runs (summed over the panels), and the bound.
    fn entries(&self) -> Vec<String> {
        let mut entries: Vec<String> = self
            .series()
            .into_iter()
            .map(|(label, _)| {
                let runs: usize =
                    self.panels.iter().flat_map(|(_, s)| s).filter(|d| d.label == label).map(|d| d.runs).sum();
                format!("{label} ({})", crate::plot::runs_text(runs))
            })
            .collect();
        if self.has_bound() {
            entries.push(BOUND_ENTRY.into());
        }
        entries
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
        draw_legend_strip(&strip, &entries, |k, (x, y)| match series.get(k) {
            Some(&(_, c)) => {
                let colour = crate::plot::series_colour(c);
                strip.draw(&PathElement::new(vec![(x, y), (x + 22, y)], colour.stroke_width(3))).map_err(err)
            }
            None => dashed(&strip, (x, y)),
        })?;
        for (area, (title, drawn)) in panels.split_evenly(self.grid()).iter().zip(&self.panels) {
            draw_panel(area, title, drawn)?;
        }
        Ok(())
    }
}

/// The bound's legend key: a black dashed stroke.
fn dashed<DB: DrawingBackend>(strip: &DrawingArea<DB, Shift>, (x, y): (i32, i32)) -> Result<(), String> {
    for a in [0, 9, 18] {
        strip.draw(&PathElement::new(vec![(x + a, y), (x + a + 5, y)], BLACK.stroke_width(2))).map_err(err)?;
    }
    Ok(())
}

/// One panel: its series' bands and medians, earlier series wider beneath, and the bounds.
fn draw_panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, title: &str, drawn: &[Drawn]) -> Result<(), String> {
    let x_max = drawn.iter().flat_map(|s| s.curve.last().map(|c| c.0)).fold(1.0, f64::max);
    let mut chart = ChartBuilder::on(area)
        .caption(title, text(15.0))
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
    for s in drawn {
        let colour = crate::plot::series_colour(s.colour);
        let band: Vec<(f64, f64)> =
            s.curve.iter().map(|c| (c.0, c.3)).chain(s.curve.iter().rev().map(|c| (c.0, c.2))).collect();
        chart.draw_series([Polygon::new(band, colour.mix(0.15).filled())]).map_err(err)?;
    }
    for (k, s) in drawn.iter().enumerate() {
        // Earlier series wider (3 px a step, at most 4 steps), so that one lying on a later one
        // still shows around it.
        let stroke = 2 + 3 * (drawn.len() - 1 - k).min(4) as u32;
        let median = s.curve.iter().map(|c| (c.0, c.1));
        chart
            .draw_series(LineSeries::new(median, crate::plot::series_colour(s.colour).stroke_width(stroke)))
            .map_err(err)?;
    }
    let mut bounds: Vec<&Vec<(f64, f64)>> = Vec::new();
    for s in drawn.iter().filter(|s| !s.bound.is_empty()) {
        if !bounds.contains(&&s.bound) {
            bounds.push(&s.bound);
        }
    }
    for b in bounds {
        let inside = b.iter().copied().filter(|p| p.0 <= x_max);
        chart.draw_series(DashedLineSeries::new(inside, 6, 5, BLACK.stroke_width(2))).map_err(err)?;
    }
    Ok(())
}
