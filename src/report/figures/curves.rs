//! The time-to-coverage figure: per map, the reachable coverage over mission time of each
//! series (median line, band between the quartiles), one legend below the panels.

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
}

/// One panel per map, one median line and quartile band per series; one legend below the
/// panels, each series in one colour in every panel.
pub struct CurvesFigure {
    /// `(map, series)` per panel.
    pub panels: Vec<(String, Vec<Drawn>)>,
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
