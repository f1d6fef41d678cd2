//! The run-history figure of 003 Fig. 4.8: five panels over the iterations — the best
//! individual's `cov_final` and `t_final`; population `t_final` and `cov_final` (mean, min,
//! max); chromosome length; diversity — with the retrain switch marked.

use super::{Figure, err, text};
use crate::ga::observer::GenerationStats;
use plotters::coord::Shift;
use plotters::prelude::*;

/// A run's history.
pub struct HistoryFigure<'a> {
    /// One entry per iteration.
    pub history: &'a [GenerationStats],
    /// Iterations at which the environment changed.
    pub changes: &'a [u32],
    /// Title line.
    pub title: String,
}

const MEAN: RGBColor = RGBColor(20, 60, 170);
const MIN: RGBColor = RGBColor(200, 60, 40);
const MAX: RGBColor = RGBColor(30, 150, 60);
const SWITCH: RGBColor = RGBColor(120, 120, 120);

type Series<'a> = (&'a str, RGBColor, Box<dyn Fn(&GenerationStats) -> f64 + 'a>);

impl HistoryFigure<'_> {
    fn panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        y_desc: &str,
        series: Vec<Series>,
        last: bool,
    ) -> Result<(), String> {
        let h = self.history;
        let x_max = h.last().map_or(1, |s| s.iteration.max(1));
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for (_, _, f) in &series {
            for s in h {
                let v = f(s);
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
        if !lo.is_finite() {
            (lo, hi) = (0.0, 1.0);
        }
        let pad = ((hi - lo) * 0.08).max(1e-3);
        let mut chart = ChartBuilder::on(area)
            .margin_left(10)
            // The legend sits in this margin, right of the data it would otherwise hide.
            .margin_right(super::SIDE_LEGEND_W)
            .margin_top(8)
            .x_label_area_size(if last { 40 } else { 22 })
            .y_label_area_size(70)
            .build_cartesian_2d(0u32..x_max, (lo - pad)..(hi + pad))
            .map_err(err)?;
        // Counts (lengths, diversity in cells) need no decimals once the range is wide.
        let decimals = if hi - lo >= 20.0 {
            0
        } else if hi - lo >= 2.0 {
            1
        } else {
            2
        };
        chart
            .configure_mesh()
            .y_label_formatter(&|v| format!("{v:.decimals$}"))
            .light_line_style(RGBColor(235, 235, 235))
            .x_desc(if last { "iteration" } else { "" })
            .y_desc(y_desc)
            .label_style(text(14.0))
            .axis_desc_style(text(15.0))
            .draw()
            .map_err(err)?;
        for &c in self.changes {
            chart
                .draw_series([PathElement::new(vec![(c, lo - pad), (c, hi + pad)], SWITCH.stroke_width(2))])
                .map_err(err)?;
        }
        let one_px = (hi - lo + 2.0 * pad) / f64::from(chart.plotting_area().dim_in_pixel().1.max(1));
        let mut legend: Vec<(&str, RGBColor)> = Vec::new();
        for (label, colour, f) in series {
            // Values not measured every iteration (diversity, `output.diversity_every`) are
            // NaN in between: the line joins the measured ones.
            let points: Vec<(u32, f64)> = h.iter().map(|s| (s.iteration, f(s))).filter(|(_, v)| !v.is_nan()).collect();
            super::draw_series_line(&mut chart, &points, colour, one_px)?;
            legend.push((label, colour));
        }
        if !self.changes.is_empty() {
            legend.push(("env. change", SWITCH));
        }
        super::side_legend(area, &legend)?;
        Ok(())
    }
}

impl Figure for HistoryFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 1200)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let root = root.titled(&self.title, text(20.0)).map_err(err)?;
        let panels = root.split_evenly((5, 1));
        let s = |label: &'static str, colour, f: fn(&GenerationStats) -> f64| -> Series<'static> {
            (label, colour, Box::new(f))
        };
        self.panel(
            &panels[0],
            "best individual",
            vec![s("cov_final", MEAN, |g| g.best_cov_final), s("t_final", MIN, |g| g.best_t_final)],
            false,
        )?;
        self.panel(
            &panels[1],
            "population t_final",
            vec![
                s("max", MAX, |g| g.max_t_final),
                s("mean", MEAN, |g| g.mean_t_final),
                s("min", MIN, |g| g.min_t_final),
            ],
            false,
        )?;
        self.panel(
            &panels[2],
            "population cov_final",
            vec![
                s("max", MAX, |g| g.max_cov_final),
                s("mean", MEAN, |g| g.mean_cov_final),
                s("min", MIN, |g| g.min_cov_final),
            ],
            false,
        )?;
        self.panel(
            &panels[3],
            "G_len [actions]",
            vec![
                s("max", MAX, |g| f64::from(g.max_genome_len)),
                s("mean", MEAN, |g| g.mean_genome_len),
                s("min", MIN, |g| f64::from(g.min_genome_len)),
            ],
            false,
        )?;
        self.panel(&panels[4], "diversity Div [cells]", vec![s("Div", MEAN, |g| g.diversity.unwrap_or(f64::NAN))], true)
    }
}
