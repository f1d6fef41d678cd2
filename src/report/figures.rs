//! Study figures: Pareto scatter per group with the front highlighted (003 Figs. 4.2–4.5),
//! diversity over iterations of the front runs (median and range per group), and the best
//! path of each group as a grid of small maps (003 Figs. A.17/A.18).

use crate::plot::path::{PathFigure, draw_map_paths};
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
        super::ablation_figures::legend_strip_height(&labels, width)
    }
}

fn grid_shape(n: usize) -> (usize, usize) {
    let cols = (n as f64).sqrt().ceil().max(1.0) as usize;
    (n.div_ceil(cols).max(1), cols)
}

const PARETO_TITLE: &str = "Best individual per run: 003's coverage against its time efficiency (front in red)";
const PATHS_TITLE: &str =
    "Best path per group: blue path; cells green once, orange 2+, red obstacle hit; ▲ start, ✕ end";

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
        super::ablation_figures::draw_legend_strip(&strip, &labels, |k, (x, y)| {
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

/// Per-iteration diversity summary of one group: `(iteration, median, min, max)`.
pub struct DiversityGroup {
    /// Group label.
    pub label: String,
    /// Runs summarised.
    pub runs: usize,
    /// The curve.
    pub curve: Vec<(u32, f64, f64, f64)>,
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
            let colour = crate::plot::series_colour(k);
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

/// The best path of each group as small maps.
pub struct PathsGridFigure<'a> {
    /// One panel per group (title = group and scores).
    pub panels: Vec<PathFigure<'a>>,
}

impl Figure for PathsGridFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let (r, c) = grid_shape(self.panels.len());
        (c as u32 * 400, r as u32 * 420 + 40)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let root = root
            .titled(PATHS_TITLE, crate::plot::fitting_text(PATHS_TITLE, root.dim_in_pixel().0, 18.0))
            .map_err(err)?;
        let (r, c) = grid_shape(self.panels.len());
        for (area, panel) in root.split_evenly((r, c)).iter().zip(&self.panels) {
            // A caption too wide for one line goes on two: the group, then the scores.
            let width = area.dim_in_pixel().0;
            match panel.title.split_once(": ") {
                Some((group, scores)) if !crate::plot::fits(&panel.title, width, 13.0) => {
                    let below = area.titled(group, crate::plot::fitting_text(group, width, 14.0)).map_err(err)?;
                    draw_map_paths(&below, &PathFigure { title: scores.to_string(), ..panel.clone() }, (13.0, 11.0))?;
                }
                _ => {
                    draw_map_paths(area, panel, (13.0, 11.0))?;
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn group(top: f64) -> DiversityGroup {
        DiversityGroup { label: String::new(), runs: 1, curve: vec![(0, top / 2.0, 0.0, top)] }
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

#[cfg(test)]
mod layout_tests {
    //! The thesis GA's figures on their study shapes (groups of ten runs, one run, many groups):
    //! texts on the canvas, ticks distinct, every group named.
    use super::*;
    use crate::coverage::CoverageGrid;
    use crate::geom::Point;
    use crate::plot::layout::problems;

    fn facet(label: &str, n: usize) -> ParetoFacet {
        let points: Vec<(f64, f64)> = (0..n).map(|k| (0.15 + 0.02 * k as f64, 0.41 - 0.01 * k as f64)).collect();
        ParetoFacet {
            label: label.into(),
            front: (0..n).collect(),
            rows: (0..n).collect(),
            kinds: vec![0; n],
            excluded: vec![(0.3, 0.2)],
            points,
        }
    }

    #[test]
    fn pareto_diversity_and_path_figures_keep_their_texts_on_the_canvas() {
        let mut found = Vec::new();
        for (name, groups) in [
            ("thesis", vec![("selection=elite", 10), ("selection=nsga2", 10)]),
            ("one run", vec![("all", 1)]),
            (
                "many",
                (0..9)
                    .map(|_| ("map.source=experiments/maps/generated/house-1-noisy.yaml, selection=tournament", 5))
                    .collect(),
            ),
        ] {
            let facets = groups.iter().map(|(l, n)| facet(l, *n)).collect();
            let figure = ParetoFigure { facets, shape: None, kinds: Vec::new() };
            for p in
                problems(&figure, &["t_final: 003's time efficiency", "cov_final: share of all free cells"]).unwrap()
            {
                found.push(format!("pareto {name}: {p}"));
            }
            let diversity = DiversityFigure {
                groups: groups
                    .iter()
                    .map(|(l, n)| DiversityGroup {
                        label: l.to_string(),
                        runs: *n,
                        curve: (0..50).map(|i| (i * 10, 40.0, 30.0, 55.0)).collect(),
                    })
                    .collect(),
            };
            for p in problems(&diversity, &[]).unwrap() {
                found.push(format!("diversity {name}: {p}"));
            }
            let texts = crate::plot::layout::drawn_texts(&diversity).unwrap();
            if groups.iter().any(|(_, n)| *n == 1) && !texts.iter().any(|t| t.text.contains("(1 run)")) {
                found.push(format!("diversity {name}: a one-run group says \"1 runs\""));
            }
        }
        let map = crate::map::presets::preset("thesis-1").unwrap();
        let grid = CoverageGrid::new(&map);
        let path = vec![Point::new(1.0, 1.0), Point::new(8.0, 1.0), Point::new(8.0, 8.0)];
        let panel = |title: &str| crate::plot::path::PathFigure {
            map: &map,
            grid: &grid,
            paths: vec![path.clone()],
            width: 0.6,
            robots: Vec::new(),
            title: title.into(),
        };
        for n in [1, 4, 9] {
            let panels = (0..n)
                .map(|k| panel(&format!("selection=elite, c_len=0.{k}: 1234 s, 90.1 % of the reachable cells")))
                .collect();
            for p in problems(&PathsGridFigure { panels }, &["1234 s"]).unwrap() {
                found.push(format!("paths {n}: {p}"));
            }
        }
        assert!(found.is_empty(), "{}", found.join("\n"));
    }
}
