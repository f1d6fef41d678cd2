//! The diversity of each group's front runs over the iterations: median and range per group.

use crate::plot::{Figure, err, text};
use plotters::coord::Shift;
use plotters::prelude::*;

/// Per-iteration diversity summary of one group: `(iteration, median, min, max)`.
pub struct DiversityGroup {
    /// Group label.
    pub label: String,
    /// Runs summarised.
    pub runs: usize,
    /// The curve.
    pub curve: Vec<(u32, f64, f64, f64)>,
    /// Its colour's number ([`crate::plot::series_colour`]), the same in every figure of the
    /// report.
    pub colour: usize,
}

/// Diversity over iterations of the runs on each group's front.
pub struct DiversityFigure {
    /// The groups.
    pub groups: Vec<DiversityGroup>,
}

impl DiversityGroup {
    /// The top of this group's y axis: 5 % above its highest band value (at least 1).
    fn y_top(&self) -> f64 {
        self.curve.iter().map(|c| c.3).fold(1.0f64, f64::max) * 1.05
    }
}

/// Panels share one y scale when their tops lie within this factor of each other; beyond it
/// (groups on maps of very different sizes) one linear axis would flatten the small ones, so
/// each panel gets its own.
const SHARED_Y_MAX_RATIO: f64 = 10.0;

impl DiversityFigure {
    /// The one y-axis top of every panel, where the groups' ranges are comparable.
    fn shared_y_max(&self) -> Option<f64> {
        let tops: Vec<f64> = self.groups.iter().map(DiversityGroup::y_top).collect();
        let (lo, hi) = tops.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &t| (lo.min(t), hi.max(t)));
        (!tops.is_empty() && hi <= SHARED_Y_MAX_RATIO * lo).then_some(hi)
    }
}

impl Figure for DiversityFigure {
    fn size(&self) -> (u32, u32) {
        (1000, 70 + 230 * self.groups.len().max(1) as u32)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let shared = self.shared_y_max();
        let title = if shared.is_some() {
            "Diversity of each group's front runs (median, band = min..max; one y scale; patterns record none)"
        } else {
            "Diversity of each group's front runs (median, band = min..max; y scale per panel; patterns record none)"
        };
        let root = root.titled(title, crate::plot::fitting_text(title, root.dim_in_pixel().0, 18.0)).map_err(err)?;
        let x_max = self.groups.iter().flat_map(|g| g.curve.last().map(|c| c.0)).max().unwrap_or(1).max(1);
        let panels = root.split_evenly((self.groups.len().max(1), 1));
        for (k, (area, g)) in panels.iter().zip(&self.groups).enumerate() {
            let last = k + 1 == self.groups.len();
            let y_max = shared.unwrap_or_else(|| g.y_top());
            let label = crate::plot::panel_label(&g.label);
            let mut chart = ChartBuilder::on(area)
                .caption(
                    format!("{label} ({})", crate::plot::runs_text(g.runs)),
                    crate::plot::fitting_text(&label, 800, 14.0),
                )
                .margin(8)
                .margin_right(24)
                .x_label_area_size(if last { 45 } else { 25 })
                .y_label_area_size(80)
                .build_cartesian_2d(0u32..x_max, 0.0..y_max)
                .map_err(err)?;
            let decimals = crate::plot::tick_decimals(y_max);
            chart
                .configure_mesh()
                .y_label_formatter(&|v| format!("{v:.decimals$}"))
                .light_line_style(RGBColor(235, 235, 235))
                .x_desc(if last { "iteration" } else { "" })
                .y_desc("Div [cells]")
                .label_style(text(14.0))
                .axis_desc_style(text(14.0))
                .draw()
                .map_err(err)?;
            let colour = crate::plot::series_colour(g.colour);
            let band: Vec<(u32, f64)> =
                g.curve.iter().map(|c| (c.0, c.3)).chain(g.curve.iter().rev().map(|c| (c.0, c.2))).collect();
            chart.draw_series([Polygon::new(band, colour.mix(0.18).filled())]).map_err(err)?;
            let one_px = y_max / f64::from(chart.plotting_area().dim_in_pixel().1.max(1));
            let median: Vec<(u32, f64)> = g.curve.iter().map(|c| (c.0, c.1)).collect();
            crate::plot::draw_series_line(&mut chart, &median, colour, one_px)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn group(top: f64) -> DiversityGroup {
        DiversityGroup { label: String::new(), runs: 1, curve: vec![(0, top / 2.0, 0.0, top)], colour: 0 }
    }

    /// Panels within a factor of ten share the highest top; wider spreads keep their own.
    #[test]
    fn diversity_panels_share_a_y_scale_only_when_comparable() {
        for (tops, shared) in [
            (vec![100.0, 500.0], Some(525.0)),
            (vec![100.0, 1000.0], Some(1050.0)),
            (vec![100.0, 1001.0], None),
            (vec![40.0], Some(42.0)),
        ] {
            let figure = DiversityFigure { groups: tops.iter().map(|&t| group(t)).collect() };
            match (figure.shared_y_max(), shared) {
                (Some(a), Some(b)) => assert!((a - b).abs() < 1e-9, "{tops:?}: {a} vs {b}"),
                (a, b) => assert_eq!(a, b, "{tops:?}"),
            }
        }
    }
}
