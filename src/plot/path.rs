//! Path pictures: the map, free cells covered once / several times / never, pre-marked cells,
//! obstacle cells the path swept, the occupied or unknown cells the robot's body touches (what
//! makes a plan not executable), the path on top, a legend and a metre scale.

use super::{Figure, err, legend, text};
use crate::coverage::CoverageGrid;
use crate::coverage::raster::for_each_swept_cell;
use crate::geom::Point;
use crate::map::{CellState, GridMap};
use plotters::coord::Shift;
use plotters::prelude::*;

const OBSTACLE: RGBColor = RGBColor(70, 70, 70);
const UNKNOWN: RGBColor = RGBColor(160, 160, 160);
const NEVER: RGBColor = RGBColor(255, 255, 255);
const ONCE: RGBColor = RGBColor(150, 215, 150);
const SEVERAL: RGBColor = RGBColor(240, 170, 80);
const PREMARKED: RGBColor = RGBColor(170, 200, 240);
const HIT: RGBColor = RGBColor(220, 30, 30);
const TOUCHED: RGBColor = RGBColor(170, 0, 220);
const PATH: RGBColor = RGBColor(20, 40, 160);
/// Colours of a fleet's robots, in order (repeated past eight robots).
const ROBOTS: [RGBColor; 8] = [
    RGBColor(20, 40, 160),
    RGBColor(190, 30, 140),
    RGBColor(0, 130, 130),
    RGBColor(120, 60, 10),
    RGBColor(110, 30, 200),
    RGBColor(60, 120, 20),
    RGBColor(200, 80, 0),
    RGBColor(0, 0, 0),
];

/// A path over its map with the coverage it produces.
#[derive(Clone)]
pub struct PathFigure<'a> {
    /// The map.
    pub map: &'a GridMap,
    /// Obstacles and pre-marks as scored.
    pub grid: &'a CoverageGrid,
    /// The paths (one per agent).
    pub paths: Vec<Vec<Point>>,
    /// Robot width in metres.
    pub width: f64,
    /// A fleet's robots, one `(name, width)` per path: each path is swept with its robot's
    /// width and drawn in its own colour, named in the legend. Empty: one robot of `width`.
    pub robots: Vec<(String, f64)>,
    /// Title line.
    pub title: String,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Class {
    Obstacle,
    Unknown,
    Never,
    Once,
    Several,
    Premarked,
    Hit,
    /// Occupied or unknown, not swept, but touched by the robot's body (a disc of its width
    /// along the path, turns and ends included: the executability rule of `map::body`).
    Touched,
    /// Swept by this one robot of a fleet (any number of times).
    Robot(usize),
}

impl Class {
    fn colour(self) -> RGBColor {
        match self {
            Class::Obstacle => OBSTACLE,
            Class::Unknown => UNKNOWN,
            Class::Never => NEVER,
            Class::Once => ONCE,
            Class::Several => SEVERAL,
            Class::Premarked => PREMARKED,
            Class::Hit => HIT,
            Class::Touched => TOUCHED,
            Class::Robot(k) => robot_tint(k),
        }
    }
}

/// The light tint of robot `k`'s colour its cells are filled with.
fn robot_tint(k: usize) -> RGBColor {
    let RGBColor(r, g, b) = ROBOTS[k % ROBOTS.len()];
    let tint = |c: u8| c + ((255 - c) as f64 * 0.65) as u8;
    RGBColor(tint(r), tint(g), tint(b))
}

impl PathFigure<'_> {
    /// What the figure shows, `(x0, y0, x1, y1)` in metres: the free cells and the paths with
    /// a margin of half a metre (at least 3 % of the larger side), within the map — not the
    /// unknown border a SLAM map carries around the building.
    pub fn extent(&self) -> (f64, f64, f64, f64) {
        let map = self.map;
        let (ox, oy, res) = (map.origin().x, map.origin().y, map.resolution());
        let (mut x0, mut y0, mut x1, mut y1) = (f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
        for r in 0..map.rows() {
            for c in 0..map.cols() {
                if map.state_at(map.index(r, c)) == CellState::Free {
                    let (x, y) = (ox + c as f64 * res, oy + r as f64 * res);
                    (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x + res), y1.max(y + res));
                }
            }
        }
        for p in self.paths.iter().flatten() {
            (x0, y0, x1, y1) = (x0.min(p.x), y0.min(p.y), x1.max(p.x), y1.max(p.y));
        }
        let (mx0, my0, mx1, my1) = (ox, oy, ox + map.width_m(), oy + map.height_m());
        if !x0.is_finite() {
            return (mx0, my0, mx1, my1);
        }
        let margin = (0.03 * (x1 - x0).max(y1 - y0)).max(0.5);
        ((x0 - margin).max(mx0), (y0 - margin).max(my0), (x1 + margin).min(mx1), (y1 + margin).min(my1))
    }

    fn classes(&self) -> Vec<Class> {
        let n = self.grid.len();
        let mut visits = vec![0u32; n];
        let mut hits = vec![false; n];
        // For a fleet: the one robot that swept a cell, or `MANY` for two robots or more.
        const NONE: usize = usize::MAX;
        const MANY: usize = usize::MAX - 1;
        let mut owner = vec![NONE; if self.robots.is_empty() { 0 } else { n }];
        for (k, path) in self.paths.iter().enumerate() {
            let width = self.robots.get(k).map_or(self.width, |r| r.1);
            for w in path.windows(2) {
                for_each_swept_cell(self.grid.raster(), w[0], w[1], width, |i| {
                    if self.grid.is_blocked(i) {
                        hits[i] = true
                    } else {
                        visits[i] += 1;
                        if let Some(o) = owner.get_mut(i) {
                            *o = if *o == NONE || *o == k { k } else { MANY };
                        }
                    }
                });
            }
        }
        let mut touched = vec![false; n];
        for (k, path) in self.paths.iter().enumerate() {
            let width = self.robots.get(k).map_or(self.width, |r| r.1);
            for i in crate::map::body::touched_cells(self.map, path, width).0 {
                touched[i] = true;
            }
        }
        (0..n)
            .map(|i| match self.map.state_at(i) {
                _ if hits[i] => Class::Hit,
                _ if touched[i] => Class::Touched,
                CellState::Occupied => Class::Obstacle,
                CellState::Unknown => Class::Unknown,
                CellState::Free if self.grid.is_premarked(i) => Class::Premarked,
                CellState::Free if !owner.is_empty() => match owner[i] {
                    NONE => Class::Never,
                    MANY => Class::Several,
                    k => Class::Robot(k),
                },
                CellState::Free => match visits[i] {
                    0 => Class::Never,
                    1 => Class::Once,
                    _ => Class::Several,
                },
            })
            .collect()
    }
}

/// The points of `path` that a drawing can tell apart: each kept point lies at least `min_step_m`
/// from the previous kept one, and the first and last are always kept. A dense path (a robot's
/// log of a million points) then draws as fast, and its SVG as small, as the line it looks like.
pub fn thinned(path: &[Point], min_step_m: f64) -> Vec<Point> {
    let mut kept: Vec<Point> = Vec::with_capacity(path.len().min(1 << 16));
    for (i, &p) in path.iter().enumerate() {
        let last = i + 1 == path.len();
        match kept.last() {
            Some(&q) if !last && (p - q).norm() < min_step_m => {}
            _ => kept.push(p),
        }
    }
    kept
}

/// Draws the map, coverage classes and paths of `fig` into `area` at one scale on both axes
/// (metres); `(title, labels)` are font sizes. Returns the pixels per metre, for a scale bar
/// beside the map.
pub fn draw_map_paths<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    fig: &PathFigure,
    fonts: (f64, f64),
) -> Result<f64, String> {
    let map = fig.map;
    let (ox, oy) = (map.origin().x, map.origin().y);
    let (x0, y0, x1, y1) = fig.extent();
    let small = fonts.1 < 14.0;
    // Label areas wide enough for the tick labels and the axis title beside them; a margin
    // that keeps the last tick label inside the panel.
    let labels = if small { (34, 50) } else { (45, 62) };
    let mut chart =
        super::equal_scale_chart(area, &fig.title, fonts.0, labels, if small { 14 } else { 16 }, x0..x1, y0..y1)?;
    let tick = super::metre_tick;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_label_formatter(&tick)
        .y_label_formatter(&tick)
        .x_desc("x [m]")
        .y_desc("y [m]")
        .x_labels(if small { 4 } else { 10 })
        .y_labels(if small { 4 } else { 10 })
        .label_style(text(fonts.1))
        .axis_desc_style(text(fonts.1 + 2.0))
        .draw()
        .map_err(err)?;
    // Cells, merged into runs of one class per row to keep the SVG small.
    let classes = fig.classes();
    let res = map.resolution();
    // Only the rows and columns inside the extent (the chart clips the rest anyway).
    let inside = |(r, c0, c1, _): &(usize, usize, usize, Class)| {
        let (ya, xa, xb) = (oy + *r as f64 * res, ox + *c0 as f64 * res, ox + *c1 as f64 * res);
        ya + res >= y0 && ya <= y1 && xb >= x0 && xa <= x1
    };
    let rects = super::cell_runs(map.cols(), map.rows(), |i| classes[i]).into_iter().filter(inside).map(
        |(r, c0, c1, class)| {
            let (xa, ya) = (ox + c0 as f64 * res, oy + r as f64 * res);
            Rectangle::new(
                [(xa.max(x0), ya.max(y0)), ((ox + c1 as f64 * res).min(x1), (ya + res).min(y1))],
                class.colour().filled(),
            )
        },
    );
    chart.draw_series(rects).map_err(err)?;
    draw_paths(&mut chart, fig, small, (ox, oy))?;
    let (a, b) = (chart.backend_coord(&(ox, oy)), chart.backend_coord(&(ox + 1.0, oy)));
    let px_per_m = f64::from(b.0 - a.0);
    // Walls and swept obstacle cells once more on top of the paths, each at least a pixel
    // wide, so that thin walls and doors stay visible in small panels and a reader can judge
    // whether a path crosses a wall.
    let pad = if px_per_m > 0.0 { (0.5 / px_per_m - 0.5 * res).max(0.0) } else { 0.0 };
    let on_top = super::cell_runs(map.cols(), map.rows(), |i| match classes[i] {
        Class::Obstacle | Class::Hit | Class::Touched => classes[i],
        _ => Class::Never,
    });
    let walls = on_top.into_iter().filter(|run| run.3 != Class::Never).filter(inside).map(|(r, c0, c1, class)| {
        let (xa, ya) = (ox + c0 as f64 * res, oy + r as f64 * res);
        Rectangle::new([(xa - pad, ya - pad), (ox + c1 as f64 * res + pad, ya + res + pad)], class.colour().filled())
    });
    chart.draw_series(walls).map_err(err)?;
    Ok(px_per_m)
}

/// The paths of `fig` on its chart: segment by segment, each viewpoint a dot, ▲ start and ✕ end.
fn draw_paths<DB: DrawingBackend>(
    chart: &mut ChartContext<
        '_,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    fig: &PathFigure,
    small: bool,
    (ox, oy): (f64, f64),
) -> Result<(), String> {
    let dot = if small { 1 } else { 2 };
    let (a, b) = (chart.backend_coord(&(ox, oy)), chart.backend_coord(&(ox + 1.0, oy)));
    let half_px_m = if b.0 > a.0 { 0.5 / f64::from(b.0 - a.0) } else { 0.0 };
    for (k, path) in fig.paths.iter().enumerate() {
        let path = &thinned(path, half_px_m);
        let colour = if fig.robots.is_empty() { PATH } else { ROBOTS[k % ROBOTS.len()] };
        // Segment by segment: a thick polyline is joined with mitres, and a path that turns
        // back on itself would grow a spike far past its viewpoints.
        let style = colour.stroke_width(if small { 1 } else { 2 });
        chart
            .draw_series(path.windows(2).map(|w| PathElement::new(vec![(w[0].x, w[0].y), (w[1].x, w[1].y)], style)))
            .map_err(err)?;
        if !small {
            // The bitmap backend leaves gaps in some thick diagonal strokes; a 1-px line on
            // top keeps every segment continuous.
            chart.draw_series(LineSeries::new(path.iter().map(|p| (p.x, p.y)), colour.stroke_width(1))).map_err(err)?;
        }
        chart.draw_series(path.iter().map(|p| Circle::new((p.x, p.y), dot, colour.filled()))).map_err(err)?;
        if let (Some(s), Some(e)) = (path.first(), path.last()) {
            // The end first, the start on top: both stay visible where they coincide.
            chart.draw_series([Cross::new((e.x, e.y), 9, RED.stroke_width(3))]).map_err(err)?;
            chart.draw_series([TriangleMarker::new((s.x, s.y), 6, GREEN.filled())]).map_err(err)?;
        }
    }
    Ok(())
}

/// A round scale-bar length (1, 2 or 5 × 10^k m) near a fifth of `extent`.
pub fn scale_length(extent: f64) -> f64 {
    let target = extent / 5.0;
    let base = 10f64.powf(target.log10().floor());
    [5.0, 2.0, 1.0].into_iter().map(|m| m * base).find(|&l| l <= target).unwrap_or(base)
}

impl Figure for PathFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let (x0, y0, x1, y1) = self.extent();
        let aspect = (y1 - y0) / (x1 - x0);
        let w = 820u32;
        (w + 260, ((w as f64 - 80.0) * aspect) as u32 + 120)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let (w, _) = self.size();
        let (plot_area, side) = root.split_horizontally(w - 260);
        let px_per_m = draw_map_paths(&plot_area, self, (20.0, 15.0))?;
        // Legend on the side.
        let fleet = !self.robots.is_empty();
        let entries = [
            (NEVER, "free, not covered"),
            (ONCE, "covered once"),
            (SEVERAL, if fleet { "swept by 2+ robots" } else { "covered 2+ times" }),
            (PREMARKED, "pre-marked as covered"),
            (HIT, "obstacle swept"),
            (TOUCHED, "touched by the body"),
            (OBSTACLE, "obstacle"),
            (UNKNOWN, "unknown"),
        ];
        // Only the classes the figure shows (a fleet's cells are tinted by robot, so "covered
        // once" never applies to it).
        let classes = self.classes();
        let shown = |colour: RGBColor| classes.iter().any(|c| c.colour() == colour);
        let mut entries: Vec<(RGBColor, String)> = entries
            .iter()
            .filter(|(c, _)| (!fleet || *c != ONCE) && shown(*c))
            .map(|(c, s)| (*c, s.to_string()))
            .collect();
        if fleet {
            for (k, (name, width)) in self.robots.iter().enumerate() {
                entries.push((robot_tint(k), format!("{name} ({width} m), alone")));
            }
        } else {
            entries.push((PATH, "path".into()));
        }
        legend(&side, &entries, 60)?;
        if fleet {
            // Each robot's path colour across its swatch.
            let first = entries.len() - self.robots.len();
            for k in 0..self.robots.len() {
                let y = 60 + 26 * (first + k) as i32 + 9;
                side.draw(&PathElement::new(vec![(8, y), (26, y)], ROBOTS[k % ROBOTS.len()].stroke_width(3)))
                    .map_err(err)?;
            }
        }
        let below = 60 + 26 * entries.len() as i32;
        side.draw(&TriangleMarker::new((17, below + 9), 9, GREEN.filled())).map_err(err)?;
        side.draw(&Text::new("start", (34, below), text(17.0))).map_err(err)?;
        side.draw(&Cross::new((17, below + 26 + 9), 8, RED.stroke_width(3))).map_err(err)?;
        side.draw(&Text::new("end", (34, below + 26), text(17.0))).map_err(err)?;
        // The scale bar beside the map, not over it.
        let (x0, y0, x1, y1) = self.extent();
        let len = scale_length((x1 - x0).max(y1 - y0));
        let bar = (len * px_per_m).round() as i32;
        let y = below + 26 * 3;
        side.draw(&PathElement::new(vec![(8, y), (8 + bar, y)], BLACK.stroke_width(4))).map_err(err)?;
        side.draw(&Text::new(format!("{len} m"), (8, y + 8), text(16.0))).map_err(err)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points closer than the step to the last kept one are dropped; the ends always stay.
    #[test]
    fn thinning_keeps_the_ends_and_every_visible_step() {
        let p = |xs: &[f64]| xs.iter().map(|&x| Point::new(x, 0.0)).collect::<Vec<_>>();
        for (input, step, kept) in [
            (vec![], 0.1, vec![]),
            (vec![0.0], 0.1, vec![0.0]),
            (vec![0.0, 0.01, 0.02, 0.15, 0.16, 0.3], 0.1, vec![0.0, 0.15, 0.3]),
            (vec![0.0, 0.01, 0.02], 0.1, vec![0.0, 0.02]),
            (vec![0.0, 0.01, 0.02], 0.0, vec![0.0, 0.01, 0.02]),
            (vec![0.0, 5.0, 0.0], 0.1, vec![0.0, 5.0, 0.0]),
        ] {
            assert_eq!(thinned(&p(&input), step), p(&kept), "{input:?} at {step}");
        }
    }

    /// One metre is the same number of pixels on both axes of a map figure.
    #[test]
    fn map_figures_have_equal_scale() {
        for (area, extent) in [((1080, 700), (11.0, 11.0)), ((400, 420), (30.0, 20.0)), ((820, 300), (30.0, 30.0))] {
            let (labels, margin) = ((45, 55), 10);
            let (t, b, l, r) = crate::plot::equal_scale_margins(area, labels, margin, extent);
            let pw = (area.0 - labels.1 - l - r) as f64;
            let ph = (area.1 - labels.0 - t - b) as f64;
            let (sx, sy) = (pw / extent.0, ph / extent.1);
            assert!((sx - sy).abs() / sx < 0.01, "{area:?} {extent:?}: {sx} vs {sy} px per metre");
        }
    }

    #[test]
    fn scale_bar_lengths_are_round() {
        assert_eq!(scale_length(11.0), 2.0);
        assert_eq!(scale_length(30.0), 5.0);
        assert_eq!(scale_length(3.0), 0.5);
    }

    #[test]
    fn fleet_cells_are_classed_by_the_robot_that_swept_them() {
        // thesis-1 (0.2 m cells): robot 0 (0.4 m) along y = 3 from x = 2 to 6, robot 1 (0.8 m)
        // from x = 4 to 8; x in [4, 6) is swept by both.
        let map = crate::map::presets::preset("thesis-1").unwrap();
        let grid = CoverageGrid::new(&map);
        let p = |x: f64, y: f64| Point::new(x, y);
        let fig = PathFigure {
            map: &map,
            grid: &grid,
            paths: vec![vec![p(2.0, 3.0), p(6.0, 3.0)], vec![p(4.0, 3.0), p(8.0, 3.0)]],
            width: 0.6,
            robots: vec![("a".into(), 0.4), ("b".into(), 0.8)],
            title: String::new(),
        };
        let classes = fig.classes();
        let at = |x: f64, y: f64| {
            let (r, c) = map.cell_at(p(x, y)).unwrap();
            classes[r * map.cols() + c]
        };
        assert!(at(3.0, 3.1) == Class::Robot(0));
        assert!(at(7.0, 3.3) == Class::Robot(1));
        assert!(at(5.0, 3.1) == Class::Several);
        assert!(at(5.0, 3.3) == Class::Robot(1), "outside robot 0's 0.4 m");
        assert!(at(5.0, 5.0) == Class::Never);
        let count = |k: Class| classes.iter().filter(|c| **c == k).count();
        assert_eq!((count(Class::Robot(0)), count(Class::Robot(1)), count(Class::Several)), (20, 60, 20));
    }

    /// A wall the swept rectangle misses but the body (a disc of the robot's width) touches is
    /// drawn as touched, so that a figure shows where a plan is not executable.
    #[test]
    fn walls_the_body_touches_are_classed_as_touched() {
        // 10 × 10 cells of 0.1 m, column 5 (x in [0.5, 0.6)) a wall; a 0.5 m robot along
        // x = 0.26 sweeps cell centres up to x = 0.51 (not the wall's, at 0.55), while its body
        // comes within 0.24 m of the wall.
        let (cols, rows) = (10, 10);
        let mut cells = vec![CellState::Free; cols * rows];
        for r in 0..rows {
            cells[r * cols + 5] = CellState::Occupied;
        }
        let map = GridMap::new("wall", cols, rows, 0.1, Point::origin(), cells).unwrap();
        let grid = CoverageGrid::new(&map);
        let figure = |x: f64| PathFigure {
            map: &map,
            grid: &grid,
            paths: vec![vec![Point::new(x, 0.3), Point::new(x, 0.7)]],
            width: 0.5,
            robots: Vec::new(),
            title: String::new(),
        };
        let classes = figure(0.26).classes();
        let touched: Vec<usize> = (0..classes.len()).filter(|&i| classes[i] == Class::Touched).collect();
        assert!(!touched.is_empty() && touched.iter().all(|i| i % cols == 5), "{touched:?}");
        assert!(!classes.contains(&Class::Hit));
        assert!(!figure(0.2).classes().contains(&Class::Touched), "a body clear of the wall touches nothing");
    }
}
