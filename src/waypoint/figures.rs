//! Figures of the waypoint planner: the waypoint graph (000 Fig. 3), paths per agent with self and inter-agent loop closures
//! (000 Fig. 15), the coverage map (Fig. 5), Pareto-front snapshots (Fig. 11) and average
//! objectives over generations (Fig. 12).

use super::run::WaypointStats;
use crate::coverage::work_map::WorkMap;
use crate::plot::{Figure, err, text};
use plotters::coord::Shift;
use plotters::prelude::*;

const OBSTACLE: RGBColor = RGBColor(70, 70, 70);
const UNKNOWN: RGBColor = RGBColor(175, 175, 175);
const FREE: RGBColor = RGBColor(250, 250, 250);

/// The working pixels whose centre lies on an unknown cell of `map`. The planner treats them as
/// occluded like walls; the figures draw them grey, as `path.png` draws unknown cells, so that a
/// reader tells unmapped space from walls.
pub fn unknown_pixels(work: &WorkMap, map: &crate::map::GridMap) -> Vec<bool> {
    let mut out = vec![false; work.width * work.height];
    for row in 0..work.height {
        for col in 0..work.width {
            let centre = crate::geom::Point::new(
                work.origin.0 + (col as f64 + 0.5) * work.scale,
                work.origin.1 + (row as f64 + 0.5) * work.scale,
            );
            out[row * work.width + col] =
                map.cell_at(centre).is_some_and(|(r, c)| map.state(r, c) == crate::map::CellState::Unknown);
        }
    }
    out
}

/// The colour of an occluded working pixel: unknown space or obstacle.
fn occluded_colour(unknown: &[bool], i: usize) -> RGBColor {
    if unknown[i] { UNKNOWN } else { OBSTACLE }
}

/// The legend entries of the occluded classes present.
fn occluded_entries(unknown: &[bool]) -> Vec<(RGBColor, String)> {
    let mut entries = vec![(OBSTACLE, "obstacle".to_string())];
    if unknown.iter().any(|&u| u) {
        entries.push((UNKNOWN, "unknown (unmapped)".to_string()));
    }
    entries
}

fn agent_colour(k: usize) -> RGBColor {
    [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(23, 190, 207),
    ][k % 6]
}

/// Draws raster classes (`class(index) -> colour`) as row runs on a metre chart.
fn raster_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    map: &WorkMap,
    title: &str,
    class: impl Fn(usize) -> RGBColor,
) -> Result<
    ChartContext<'a, DB, Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>>,
    String,
> {
    let (ox, oy) = map.origin;
    let (w, h) = (map.width as f64 * map.scale, map.height as f64 * map.scale);
    let mut chart = crate::plot::equal_scale_chart(area, title, 18.0, (40, 50), 10, ox..ox + w, oy..oy + h)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_label_formatter(&crate::plot::metre_tick)
        .y_label_formatter(&crate::plot::metre_tick)
        .x_desc("x [m]")
        .y_desc("y [m]")
        .label_style(text(14.0))
        .axis_desc_style(text(15.0))
        .draw()
        .map_err(err)?;
    let rects = crate::plot::cell_runs(map.width, map.height, class).into_iter().map(|(r, c0, c1, colour)| {
        let (x0, y0) = (ox + c0 as f64 * map.scale, oy + r as f64 * map.scale);
        Rectangle::new([(x0, y0), (ox + c1 as f64 * map.scale, y0 + map.scale)], colour.filled())
    });
    chart.draw_series(rects).map_err(err)?;
    Ok(chart)
}

/// Size of a map figure: the map 840 px wide at equal scale beside a legend column.
fn map_figure_size(map: &WorkMap) -> (u32, u32) {
    let aspect = map.height as f64 / map.width as f64;
    (1100, (840.0 * aspect) as u32 + 110)
}

/// Paths over the map, one colour per agent, with loop closures marked.
pub struct PathsFigure<'a> {
    /// The raster.
    pub map: &'a WorkMap,
    /// Paths in metres, one per agent.
    pub paths: Vec<Vec<(f64, f64)>>,
    /// Re-traversed edges of an agent's own path (metres).
    pub self_closures: Vec<((f64, f64), (f64, f64))>,
    /// Edges shared between agents (metres).
    pub shared_closures: Vec<((f64, f64), (f64, f64))>,
    /// Occluded pixels that are unknown space ([`unknown_pixels`]).
    pub unknown: Vec<bool>,
    /// Title.
    pub title: String,
}

impl Figure for PathsFigure<'_> {
    fn size(&self) -> (u32, u32) {
        map_figure_size(self.map)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let (area, side) = root.split_horizontally(860);
        let mut chart = raster_chart(&area, self.map, &self.title, |i| {
            if self.map.occluded[i] { occluded_colour(&self.unknown, i) } else { FREE }
        })?;
        for (k, p) in self.paths.iter().enumerate() {
            // Segment by segment: thick polylines are joined with mitres, which spike where a
            // path turns back on itself.
            let style = agent_colour(k).stroke_width(2);
            chart.draw_series(p.windows(2).map(|w| PathElement::new(vec![w[0], w[1]], style))).map_err(err)?;
            // The bitmap backend leaves gaps in some thick diagonal strokes; a 1-px line on top
            // keeps every segment continuous.
            chart.draw_series(LineSeries::new(p.iter().copied(), agent_colour(k).stroke_width(1))).map_err(err)?;
            if let Some(&s) = p.first() {
                chart.draw_series([TriangleMarker::new(s, 9, agent_colour(k).filled())]).map_err(err)?;
            }
        }
        for &(a, b) in &self.self_closures {
            chart.draw_series([PathElement::new(vec![a, b], RED.stroke_width(6))]).map_err(err)?;
        }
        for &(a, b) in &self.shared_closures {
            chart.draw_series([PathElement::new(vec![a, b], MAGENTA.stroke_width(6))]).map_err(err)?;
        }
        let mut entries: Vec<(RGBColor, String)> =
            (0..self.paths.len()).map(|k| (agent_colour(k), format!("agent {k} path"))).collect();
        entries.push((RED, format!("self loop closure ({})", self.self_closures.len())));
        entries.push((MAGENTA, format!("inter-agent closure ({})", self.shared_closures.len())));
        entries.extend(occluded_entries(&self.unknown));
        crate::plot::legend(&side, &entries, 60)
    }
}

/// The waypoints and traversability graph (000 Fig. 3 and §II-D) with the wall band no
/// traversal can see.
pub struct GraphFigure<'a> {
    /// The raster.
    pub map: &'a WorkMap,
    /// Waypoints in metres.
    pub points: Vec<(f64, f64)>,
    /// Undirected edges (metres).
    pub edges: Vec<((f64, f64), (f64, f64))>,
    /// Start waypoints (metres).
    pub starts: Vec<(f64, f64)>,
    /// Wall band pixels that some traversal sees.
    pub band_seen: Vec<bool>,
    /// Wall band pixels.
    pub band: Vec<bool>,
    /// Occluded pixels that are unknown space ([`unknown_pixels`]).
    pub unknown: Vec<bool>,
    /// Title.
    pub title: String,
}

impl Figure for GraphFigure<'_> {
    fn size(&self) -> (u32, u32) {
        map_figure_size(self.map)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        const BAND: RGBColor = RGBColor(215, 230, 245);
        const LOST: RGBColor = RGBColor(230, 60, 60);
        const EDGE: RGBColor = RGBColor(120, 120, 120);
        let (area, side) = root.split_horizontally(860);
        let mut chart = raster_chart(&area, self.map, &self.title, |i| {
            if self.map.occluded[i] {
                occluded_colour(&self.unknown, i)
            } else if self.band[i] && !self.band_seen[i] {
                LOST
            } else if self.band[i] {
                BAND
            } else {
                FREE
            }
        })?;
        chart
            .draw_series(self.edges.iter().map(|&(a, b)| PathElement::new(vec![a, b], EDGE.stroke_width(1))))
            .map_err(err)?;
        let dot = agent_colour(0);
        chart.draw_series(self.points.iter().map(|&p| Circle::new(p, 3, dot.filled()))).map_err(err)?;
        chart
            .draw_series(self.starts.iter().map(|&s| TriangleMarker::new(s, 9, agent_colour(1).filled())))
            .map_err(err)?;
        let mut entries = vec![
            (dot, format!("waypoint ({})", self.points.len())),
            (EDGE, format!("edge ({})", self.edges.len())),
            (agent_colour(1), "start".to_string()),
            (BAND, "wall band in view".to_string()),
            (LOST, "wall band out of view".to_string()),
        ];
        entries.extend(occluded_entries(&self.unknown));
        crate::plot::legend(&side, &entries, 60)
    }
}

/// The coverage map of 000 Fig. 5.
pub struct CoverageFigure<'a> {
    /// The raster.
    pub map: &'a WorkMap,
    /// Seen pixels.
    pub seen: Vec<bool>,
    /// Wall band pixels.
    pub band: Vec<bool>,
    /// Occluded pixels that are unknown space ([`unknown_pixels`]).
    pub unknown: Vec<bool>,
    /// Title.
    pub title: String,
}

impl Figure for CoverageFigure<'_> {
    fn size(&self) -> (u32, u32) {
        map_figure_size(self.map)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        const SEEN: RGBColor = RGBColor(120, 200, 120);
        const OPEN: RGBColor = RGBColor(255, 255, 255);
        const WALL: RGBColor = RGBColor(230, 60, 60);
        let (area, side) = root.split_horizontally(860);
        raster_chart(&area, self.map, &self.title, |i| {
            if self.map.occluded[i] {
                occluded_colour(&self.unknown, i)
            } else if self.seen[i] {
                SEEN
            } else if self.band[i] {
                WALL
            } else {
                OPEN
            }
        })?;
        let mut entries = occluded_entries(&self.unknown);
        entries.extend([
            (SEEN, "explored".to_string()),
            (OPEN, "unexplored open space".to_string()),
            (WALL, "unexplored wall band".to_string()),
        ]);
        crate::plot::legend(&side, &entries, 60)
    }
}

/// Population objectives at a few generations (000 Fig. 11).
pub struct SnapshotsFigure<'a> {
    /// Seconds per px-equivalent of 000's flight time: the raster scale over the robot's
    /// speed (turning surcharges, lengths in 000, are flown at that speed too).
    pub seconds_per_px: f64,
    /// `(generation, [(coverage, flight time, feasible)])`.
    pub snapshots: &'a [super::run::Snapshot],
}

impl Figure for SnapshotsFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 800)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let root = root
            .titled("Population in objective space (feasible in blue, violating in grey)", text(18.0))
            .map_err(err)?;
        let k = self.seconds_per_px;
        let all = self.snapshots.iter().flat_map(|s| s.1.iter());
        let (mut t0, mut t1, mut c0) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY);
        for &(c, t, _) in all {
            let t = t * k;
            t0 = t0.min(t);
            t1 = t1.max(t);
            c0 = c0.min(c);
        }
        let pad = ((t1 - t0) * 0.05).max(1.0);
        for (area, (g, pts)) in root.split_evenly((2, 2)).iter().zip(self.snapshots) {
            let mut chart = ChartBuilder::on(area)
                .caption(format!("generation {g}"), text(15.0))
                .margin(8)
                .margin_right(24)
                .x_label_area_size(40)
                .y_label_area_size(55)
                .build_cartesian_2d((t0 - pad)..(t1 + pad), (c0 - 0.02).max(0.0)..1.0)
                .map_err(err)?;
            chart
                .configure_mesh()
                .light_line_style(RGBColor(235, 235, 235))
                .x_label_formatter(&|v| format!("{v:.0}"))
                .x_desc("flight time [s]")
                .y_desc("coverage C [-]")
                .label_style(text(12.0))
                .axis_desc_style(text(13.0))
                .draw()
                .map_err(err)?;
            chart
                .draw_series(
                    pts.iter()
                        .filter(|p| !p.2)
                        .map(|p| Circle::new((p.1 * k, p.0), 3, RGBColor(170, 170, 170).filled())),
                )
                .map_err(err)?;
            chart
                .draw_series(
                    pts.iter().filter(|p| p.2).map(|p| Circle::new((p.1 * k, p.0), 3, RGBColor(31, 119, 180).filled())),
                )
                .map_err(err)?;
        }
        Ok(())
    }
}

/// Average objectives over generations (000 Fig. 12).
pub struct ObjectivesFigure<'a> {
    /// Seconds per px-equivalent of flight time (see [`SnapshotsFigure::seconds_per_px`]).
    pub seconds_per_px: f64,
    /// The statistics.
    pub history: &'a [WaypointStats],
}

impl Figure for ObjectivesFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 700)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let root = root.titled("Population averages over generations", text(18.0)).map_err(err)?;
        let panels = root.split_evenly((2, 1));
        let x_max = self.history.last().map_or(1, |s| s.generation.max(1));
        type Pick = fn(&WaypointStats) -> f64;
        // Axis label, factor from the recorded unit to the axis unit, series.
        type Panel<'p> = (&'p str, f64, &'p [(&'p str, RGBColor, Pick)]);
        let series: [Panel; 2] = [
            (
                "coverage [-]",
                1.0,
                &[
                    ("mean C", RGBColor(31, 119, 180), |s| s.mean_coverage),
                    ("mean C_walls", RGBColor(44, 160, 44), |s| s.mean_walls),
                    ("C_req (ramp)", RGBColor(200, 40, 40), |s| s.c_required),
                ],
            ),
            (
                "flight time [s]",
                self.seconds_per_px,
                &[
                    ("mean flight time", RGBColor(255, 127, 14), |s| s.mean_flight_time),
                    ("min flight time", RGBColor(140, 86, 75), |s| s.min_flight_time),
                ],
            ),
        ];
        for (area, (label, scale, lines)) in panels.iter().zip(series) {
            let vals: Vec<f64> = lines.iter().flat_map(|(_, _, f)| self.history.iter().map(|s| f(s) * scale)).collect();
            let (lo, hi) = (
                vals.iter().copied().fold(f64::INFINITY, f64::min),
                vals.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            );
            let pad = ((hi - lo) * 0.05).max(1e-3);
            let mut chart = ChartBuilder::on(area)
                .margin(10)
                .margin_right(crate::plot::SIDE_LEGEND_W)
                .x_label_area_size(40)
                .y_label_area_size(70)
                .build_cartesian_2d(0u32..x_max, (lo - pad)..(hi + pad))
                .map_err(err)?;
            let decimals = crate::plot::tick_decimals(hi - lo);
            chart
                .configure_mesh()
                .y_label_formatter(&|v| format!("{v:.decimals$}"))
                .light_line_style(RGBColor(235, 235, 235))
                .x_desc("generation")
                .y_desc(label)
                .label_style(text(13.0))
                .axis_desc_style(text(14.0))
                .draw()
                .map_err(err)?;
            let one_px = (hi - lo + 2.0 * pad) / f64::from(chart.plotting_area().dim_in_pixel().1.max(1));
            let mut legend = Vec::new();
            for &(name, colour, f) in lines {
                let points: Vec<(u32, f64)> = self.history.iter().map(|s| (s.generation, f(s) * scale)).collect();
                crate::plot::draw_series_line(&mut chart, &points, colour, one_px)?;
                legend.push((name, colour));
            }
            crate::plot::side_legend(area, &legend)?;
        }
        Ok(())
    }
}
