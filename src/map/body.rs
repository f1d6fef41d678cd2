//! The robot's body on the raster: which non-free cells a disc of diameter `width` touches
//! anywhere along a path — the path's Minkowski sum with the disc, vertices, turns and end caps
//! included — and whether it stays on the map. This is the one executability rule of covga:
//! a plan is executable when, for every path and its robot, no body pose touches an occupied,
//! unknown or off-map cell (the book's `docs/src/concepts/scorer.md`, "Executability").
//!
//! Why a disc and not the square of side `width` that 003's footprint sweeps: the robot turns
//! in place at every vertex (003 eqs. 3.1–3.3), and a square turning in place covers its
//! circumscribed disc, of radius `width/√2`, so a square body would make every turn near a wall
//! non-executable while the same plan's straight legs are fine. A disc is the same at every
//! heading, and it is the body that [`super::clearance`] and [`super::reach`] already use for
//! "reachable": a centre is reachable where the disc keeps clear of every non-free cell square,
//! and a plan is executable exactly when every centre along it is such a point. The swept
//! rectangle of 003 (width `width`, no caps) lies inside the capsule, so an executable plan
//! sweeps no obstacle cell either.
//!
//! "Touches" is measured against a cell's whole square, as the clearance is. It allows a
//! slack of [`contact_slack`]: the planners test a disc's clearance at sample points along a
//! line, at most half a cell apart ([`super::clearance::Clearance::fitting_intervals`]), and
//! a line that keeps the radius at two samples can pass a wall's corner between them by up to
//! `r − √(r² − (res/4)²)` (4 mm for a 0.6 m robot on 0.2 m cells, 0.3 mm on 0.05 m cells).
//! That is the slack, so that moves tested at those samples pass; the pattern and cell-order
//! plans are not assumed to: each is read with this rule before it is returned, and repaired
//! or refused where it touches ([`crate::planner::executable`]: a connecting hop from a lane
//! end at the clearance limit is tested at no sample). A vertex or a turn inside a wall, the
//! failure this rule exists to catch, is caught at any resolution. A robot narrower than half a cell keeps at
//! least half its radius. The map's edge is tested without slack (the capsule's extremes are
//! its vertices, which the planners test exactly).
//!
//! The test is exact for that shape: each segment's distance to each non-free cell square near
//! it, in closed form (a segment and a box that do not meet are nearest at a vertex of one of
//! them).

use super::{CellState, GridMap};
use crate::geom::Point;

/// What a body of one width touches along one or more paths.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BodyContact {
    /// Distinct occupied or unknown cells whose square the body comes nearer to than its
    /// radius (less the clearance slack), end caps and turns included.
    pub wall_cells: u64,
    /// Whether some body pose reaches past the map's edge.
    pub off_map: bool,
}

impl BodyContact {
    /// Whether the body touches nothing it must not: no non-free cell and not past the edge.
    pub fn is_clear(&self) -> bool {
        self.wall_cells == 0 && !self.off_map
    }
}

/// How much nearer than its radius `radius` the body may come to a non-free cell of a map of
/// `resolution` metres per cell before it touches it: the planners' sampling error (module
/// doc), `r − √(r² − (res/4)²)`, at most `r/2`, and at least the clearance's own slack.
pub fn contact_slack(resolution: f64, radius: f64) -> f64 {
    let q = 0.25 * resolution;
    let sampling = radius - (radius * radius - q * q).max(0.0).sqrt();
    sampling.min(0.5 * radius).max(super::clearance::CLEARANCE_EPS)
}

/// The non-free cells (row-major indices, sorted, each once) that a disc of diameter `width`
/// touches along `path`, and whether it leaves the map. A path of one point is the disc
/// standing there; an empty path touches nothing.
pub fn touched_cells(map: &GridMap, path: &[Point], width: f64) -> (Vec<usize>, bool) {
    let radius = 0.5 * width;
    let lim = radius - contact_slack(map.resolution(), radius);
    let edge_lim = radius - super::clearance::CLEARANCE_EPS;
    let mut touched = Vec::new();
    let off_map = path.iter().any(|&p| !disc_on_map(map, p, edge_lim));
    match path {
        [] => {}
        [p] => touched_by_segment(map, *p, *p, lim, &mut touched),
        _ => {
            for w in path.windows(2) {
                touched_by_segment(map, w[0], w[1], lim, &mut touched);
            }
        }
    }
    touched.sort_unstable();
    touched.dedup();
    (touched, off_map)
}

/// [`touched_cells`] for a plan whose path `k` is driven by a robot of width `widths[k]`:
/// distinct cells counted once over all paths.
pub fn contact(map: &GridMap, paths: &[Vec<Point>], widths: &[f64]) -> BodyContact {
    assert_eq!(paths.len(), widths.len(), "one width per path");
    let mut all = Vec::new();
    let mut off_map = false;
    for (path, &w) in paths.iter().zip(widths) {
        let (cells, off) = touched_cells(map, path, w);
        all.extend(cells);
        off_map |= off;
    }
    all.sort_unstable();
    all.dedup();
    BodyContact { wall_cells: all.len() as u64, off_map }
}

/// Whether the disc of radius `lim` (the radius less the slack) centred at `p` lies inside the
/// map's rectangle. The capsule of a segment is the hull of its end discs, so checking every
/// vertex checks the whole path.
fn disc_on_map(map: &GridMap, p: Point, lim: f64) -> bool {
    let (lo, w, h) = (map.origin(), map.width_m(), map.height_m());
    p.x.is_finite()
        && p.y.is_finite()
        && p.x - lo.x >= lim
        && p.y - lo.y >= lim
        && lo.x + w - p.x >= lim
        && lo.y + h - p.y >= lim
}

/// Pushes onto `out` the non-free cells whose square lies nearer than `lim` to the segment
/// `a → b`.
fn touched_by_segment(map: &GridMap, a: Point, b: Point, lim: f64, out: &mut Vec<usize>) {
    for_each_touched(map, a, b, lim, |i| {
        out.push(i);
        true
    });
}

/// Whether a disc of diameter `width` along `a → b` keeps clear of every non-free cell, to the
/// contact slack of [`touched_cells`] (the map's edge not tested: a planner tests the ends).
/// What a router asks before it drives a move straight, so that its moves pass this rule.
pub fn segment_clear_of_cells(map: &GridMap, a: Point, b: Point, width: f64) -> bool {
    let radius = 0.5 * width;
    let lim = radius - contact_slack(map.resolution(), radius);
    for_each_touched(map, a, b, lim, |_| false)
}

/// Calls `visit` with each non-free cell whose square lies nearer than `lim` to the segment
/// `a → b`, row by row, until it returns `false`; returns whether every call returned `true`.
/// The capsule's points in a row's band come from the segment's points within `lim` of that
/// band, so only their x range (widened by `lim`) is read.
fn for_each_touched(map: &GridMap, a: Point, b: Point, lim: f64, mut visit: impl FnMut(usize) -> bool) -> bool {
    if lim <= 0.0 || !(a.x.is_finite() && a.y.is_finite() && b.x.is_finite() && b.y.is_finite()) {
        return true;
    }
    let (res, o) = (map.resolution(), map.origin());
    let to_row = |y: f64| ((y - o.y) / res).floor();
    let to_col = |x: f64| ((x - o.x) / res).floor();
    let clamp = |v: f64, n: usize| v.clamp(0.0, n as f64 - 1.0) as usize;
    let (y_lo, y_hi) = (a.y.min(b.y) - lim, a.y.max(b.y) + lim);
    if to_row(y_hi) < 0.0 || to_row(y_lo) >= map.rows() as f64 {
        return true;
    }
    let lim2 = lim * lim;
    for row in clamp(to_row(y_lo), map.rows())..=clamp(to_row(y_hi), map.rows()) {
        let band = (o.y + row as f64 * res, o.y + (row + 1) as f64 * res);
        let Some((x0, x1)) = x_range_near_band(a, b, band.0 - lim, band.1 + lim) else { continue };
        if to_col(x1 + lim) < 0.0 || to_col(x0 - lim) >= map.cols() as f64 {
            continue;
        }
        for col in clamp(to_col(x0 - lim), map.cols())..=clamp(to_col(x1 + lim), map.cols()) {
            let i = map.index(row, col);
            if map.state_at(i) == CellState::Free {
                continue;
            }
            let lo = Point::new(o.x + col as f64 * res, band.0);
            let hi = Point::new(lo.x + res, band.1);
            if segment_box_d2(a, b, lo, hi) < lim2 && !visit(i) {
                return false;
            }
        }
    }
    true
}

/// The x range of the points of segment `a → b` whose y lies in `[y0, y1]`, if any.
fn x_range_near_band(a: Point, b: Point, y0: f64, y1: f64) -> Option<(f64, f64)> {
    let dy = b.y - a.y;
    let (t0, t1) = if dy.abs() < 1e-300 {
        if a.y < y0 || a.y > y1 {
            return None;
        }
        (0.0, 1.0)
    } else {
        let (ta, tb) = ((y0 - a.y) / dy, (y1 - a.y) / dy);
        let (lo, hi) = (ta.min(tb).max(0.0), ta.max(tb).min(1.0));
        if lo > hi {
            return None;
        }
        (lo, hi)
    };
    let (xa, xb) = (a.x + (b.x - a.x) * t0, a.x + (b.x - a.x) * t1);
    Some((xa.min(xb), xa.max(xb)))
}

/// Squared distance from `p` to the box `[lo, hi]` (0 inside).
fn point_box_d2(p: Point, lo: Point, hi: Point) -> f64 {
    let dx = (lo.x - p.x).max(0.0).max(p.x - hi.x);
    let dy = (lo.y - p.y).max(0.0).max(p.y - hi.y);
    dx * dx + dy * dy
}

/// Squared distance from `p` to the segment `a → b`.
fn point_segment_d2(p: Point, a: Point, b: Point) -> f64 {
    let d = b - a;
    let len2 = d.norm_squared();
    let t = if len2 > 0.0 { ((p - a).dot(&d) / len2).clamp(0.0, 1.0) } else { 0.0 };
    (a + d * t - p).norm_squared()
}

/// Whether segment `a → b` meets the box `[lo, hi]` (Liang–Barsky clipping).
fn segment_meets_box(a: Point, b: Point, lo: Point, hi: Point) -> bool {
    let d = b - a;
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (p, q) in [(-d.x, a.x - lo.x), (d.x, hi.x - a.x), (-d.y, a.y - lo.y), (d.y, hi.y - a.y)] {
        if p == 0.0 {
            if q < 0.0 {
                return false;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
            if t0 > t1 {
                return false;
            }
        }
    }
    true
}

/// Squared distance between segment `a → b` and the box `[lo, hi]`: zero where they meet,
/// else the least over the segment's ends to the box and the box's corners to the segment.
pub fn segment_box_d2(a: Point, b: Point, lo: Point, hi: Point) -> f64 {
    if segment_meets_box(a, b, lo, hi) {
        return 0.0;
    }
    let corners = [lo, Point::new(hi.x, lo.y), hi, Point::new(lo.x, hi.y)];
    corners
        .into_iter()
        .map(|c| point_segment_d2(c, a, b))
        .chain([point_box_d2(a, lo, hi), point_box_d2(b, lo, hi)])
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
#[path = "body/tests.rs"]
mod tests;
