//! The Pareto scatter of a study of the thesis GA: one panel per group, the front highlighted
//! (003 Figs. 4.2–4.5), the planners in their colours where there are several.

use super::panels::{draw_legend_strip, grid_shape, legend_strip_height};
use crate::plot::{Figure, err, text};
use plotters::coord::Shift;
use plotters::prelude::*;

/// One facet of the Pareto figure.
pub struct ParetoFacet {
    /// Group label.
    pub label: String,
    /// `(t_final, cov_final)` of each run's best individual.
    pub points: Vec<(f64, f64)>,
    /// Indices of the non-dominated points.
    pub front: Vec<usize>,
    /// The runs table's row of each point.
    pub rows: Vec<usize>,
    /// `(t_final, cov_final)` of the runs whose plan is not executable (no part of the front).
    pub excluded: Vec<(f64, f64)>,
    /// Each point's planner, an index into [`ParetoFigure::kinds`] (all 0 with one planner).
    pub kinds: Vec<usize>,
}

/// Pareto scatter, one panel per group.
pub struct ParetoFigure {
    /// The facets, row by row.
    pub facets: Vec<ParetoFacet>,
    /// Rows × columns of panels (e.g. the values of two grouping columns, as 003 lays out its
    /// Figs. 4.2–4.5); `None` for a near-square grid.
    pub shape: Option<(usize, usize)>,
    /// The planners of the points, when there are several: each drawn in its own colour,
    /// named in a legend below the panels (empty or one: one colour, named in each panel).
    pub kinds: Vec<String>,
}

impl ParetoFigure {
    fn shape(&self) -> (usize, usize) {
        self.shape.filter(|&(r, c)| r * c == self.facets.len()).unwrap_or_else(|| grid_shape(self.facets.len()))
    }

    /// The planner legend's entries, with their point counts (none for one planner).
    fn kind_labels(&self) -> Vec<String> {
        if self.kinds.len() < 2 {
            return Vec::new();
        }
        (0..self.kinds.len())
            .map(|k| {
                let n: usize = self.facets.iter().map(|f| f.kinds.iter().filter(|&&j| j == k).count()).sum();
                format!("{} ({n} executable)", self.kinds[k])
            })
            .collect()
    }

    /// Height of the planner legend below the panels (0 for one planner).
    fn legend_height(&self, width: u32) -> u32 {
        let labels = self.kind_labels();
        if labels.is_empty() {
            return 0;
        }
        legend_strip_height(&labels, width)
    }
}

const PARETO_TITLE: &str = "Best individual per run: 003's coverage against its time efficiency (front in red)";

const RUN: RGBColor = RGBColor(120, 150, 200);
const FRONT: RGBColor = RGBColor(210, 40, 30);

impl Figure for ParetoFigure {
    fn size(&self) -> (u32, u32) {
        let (r, c) = self.shape();
        let width = c as u32 * 480;
        (width, r as u32 * 440 + crate::plot::title_height(PARETO_TITLE, width, 18.0) + self.legend_height(width))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let root = crate::plot::titled(root, PARETO_TITLE, 18.0)?;
        let (width, height) = root.dim_in_pixel();
        let (root, strip) = root.split_vertically(height - self.legend_height(width));
        let labels = self.kind_labels();
        draw_legend_strip(&strip, &labels, |k, (x, y)| {
            strip.draw(&Circle::new((x + 11, y), 5, crate::plot::series_colour(k).filled())).map_err(err)
        })?;
        let ranges = self.ranges();
        for (area, facet) in root.split_evenly(self.shape()).iter().zip(&self.facets) {
            draw_pareto_facet(area, facet, labels.is_empty(), ranges)?;
        }
        Ok(())
    }
}

impl ParetoFigure {
    /// The axes' ranges shared by every panel, `((x0, x1), (y0, y1))`: 0.05 beyond the points on
    /// each side, within 0..1.
    fn ranges(&self) -> ((f64, f64), (f64, f64)) {
        let (mut lo_x, mut lo_y, mut hi_x, mut hi_y) = (1.0f64, 1.0f64, 0.0f64, 0.0f64);
        for f in &self.facets {
            for p in f.points.iter().chain(&f.excluded) {
                (lo_x, lo_y, hi_x, hi_y) = (lo_x.min(p.0), lo_y.min(p.1), hi_x.max(p.0), hi_y.max(p.1));
            }
        }
        if hi_x < lo_x {
            return ((0.0, 1.0), (0.0, 1.0));
        }
        let fit = |lo: f64, hi: f64| ((lo - 0.05).max(0.0), (hi + 0.05).min(1.0));
        (fit(lo_x, hi_x), fit(lo_y, hi_y))
    }
}

/// One panel of the Pareto figure: the executable runs (in their planner's colour when
/// `one_kind` is false), the not executable ones as crosses, the front in red.
fn draw_pareto_facet<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    facet: &ParetoFacet,
    one_kind: bool,
    ((x0, x1), (y0, y1)): ((f64, f64), (f64, f64)),
) -> Result<(), String> {
    let caption = crate::plot::panel_label(&facet.label);
    let mut chart = ChartBuilder::on(area)
        .caption(&caption, crate::plot::fitting_text(&caption, area.dim_in_pixel().0, 16.0))
        .margin(8)
        // Room for the last tick label, centred on the right end of the axis.
        .margin_right(24)
        .x_label_area_size(40)
        .y_label_area_size(55)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .light_line_style(RGBColor(235, 235, 235))
        .x_desc("t_final: 003's time efficiency (higher is faster)")
        .y_desc("cov_final: share of all free cells")
        .label_style(text(13.0))
        .axis_desc_style(text(14.0))
        .draw()
        .map_err(err)?;
    if one_kind {
        chart
            .draw_series(facet.points.iter().map(|&p| Circle::new(p, 3, RUN.filled())))
            .map_err(err)?
            .label(format!("executable runs ({})", facet.points.len()))
            .legend(|(x, y)| Circle::new((x + 8, y), 4, RUN.filled()));
    } else {
        let coloured = facet.points.iter().zip(&facet.kinds);
        chart
            .draw_series(coloured.map(|(&p, &k)| Circle::new(p, 3, crate::plot::series_colour(k).filled())))
            .map_err(err)?;
    }
    if !facet.excluded.is_empty() {
        let grey = RGBColor(120, 120, 120);
        chart
            .draw_series(facet.excluded.iter().map(|&p| Cross::new(p, 4, grey.stroke_width(1))))
            .map_err(err)?
            .label(format!("not executable ({})", facet.excluded.len()))
            .legend(move |(x, y)| Cross::new((x + 8, y), 4, grey.stroke_width(1)));
    }
    let mut front: Vec<(f64, f64)> = facet.front.iter().map(|&i| facet.points[i]).collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    chart.draw_series(LineSeries::new(front.iter().copied(), FRONT.stroke_width(1))).map_err(err)?;
    if one_kind {
        chart
            .draw_series(front.iter().map(|&p| Circle::new(p, 5, FRONT.filled())))
            .map_err(err)?
            .label(format!("non-dominated ({})", front.len()))
            .legend(|(x, y)| Circle::new((x + 8, y), 5, FRONT.filled()));
    } else {
        // A red ring around each front point, its planner's colour inside.
        chart
            .draw_series(front.iter().map(|&p| Circle::new(p, 6, FRONT.stroke_width(2))))
            .map_err(err)?
            .label(format!("non-dominated ({})", front.len()))
            .legend(|(x, y)| Circle::new((x + 8, y), 6, FRONT.stroke_width(2)));
        let on_front = facet.front.iter().map(|&i| (facet.points[i], facet.kinds[i]));
        chart
            .draw_series(on_front.map(|(p, k)| Circle::new(p, 3, crate::plot::series_colour(k).filled())))
            .map_err(err)?;
    }
    crate::plot::series_legend(&mut chart, SeriesLabelPosition::LowerLeft)
}
