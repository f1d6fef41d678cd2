//! The cells a robot's footprint can sweep without touching a wall, from the continuous
//! positions its centre can take: every point with clearance ≥ width/2 to all non-free cells
//! and to the map's edge, in the component connected to the stations. A cell is coverable
//! when its centre lies within width/2 of such a point (003 §3.1: the swept rectangle of a
//! short move with its heading across that direction contains the centre).
//!
//! The continuous set is read on a lattice of [`LATTICE_PER_CELL`]² points per cell, spacing
//! `h`, with the slack `δ = h/√2` (the farthest any point lies from its nearest lattice point)
//! on both tests: lattice points with clearance ≥ r − δ, 8-connected, and cells within r + δ of
//! one. Clearance is 1-Lipschitz, so every wall-free position maps to a kept lattice point and
//! every continuous path to an 8-connected chain of them: the set contains every cell a
//! wall-free plan can sweep, and at most the cells within 2δ of that set besides.

use super::GridMap;
use crate::geom::Point;

/// Lattice points per cell edge (`h = resolution / LATTICE_PER_CELL`).
pub const LATTICE_PER_CELL: usize = 8;

/// Distance from `p` to the nearest non-free cell or the map's edge, or `cap` when both are
/// farther than `cap`.
fn clearance(map: &GridMap, p: Point, cap: f64) -> f64 {
    let (ox, oy, res) = (map.origin().x, map.origin().y, map.resolution());
    let edge = (p.x - ox).min(p.y - oy).min(ox + map.width_m() - p.x).min(oy + map.height_m() - p.y);
    let mut best = edge.min(cap);
    let window = (cap / res).ceil() as isize + 1;
    let (cc, cr) = (((p.x - ox) / res).floor() as isize, ((p.y - oy) / res).floor() as isize);
    for r in (cr - window).max(0)..=(cr + window).min(map.rows() as isize - 1) {
        for c in (cc - window).max(0)..=(cc + window).min(map.cols() as isize - 1) {
            if map.is_free(r as usize, c as usize) {
                continue;
            }
            let (x0, y0) = (ox + c as f64 * res, oy + r as f64 * res);
            let dx = (x0 - p.x).max(0.0).max(p.x - x0 - res);
            let dy = (y0 - p.y).max(0.0).max(p.y - y0 - res);
            best = best.min((dx * dx + dy * dy).sqrt());
        }
    }
    best
}

/// The lattice over a map: `cols·s × rows·s` points, point `(i, j)` at
/// `origin + ((i + ½)·h, (j + ½)·h)`.
struct Lattice<'m> {
    map: &'m GridMap,
    cols: usize,
    rows: usize,
    h: f64,
}

impl Lattice<'_> {
    fn point(&self, i: usize, j: usize) -> Point {
        let o = self.map.origin();
        Point::new(o.x + (i as f64 + 0.5) * self.h, o.y + (j as f64 + 0.5) * self.h)
    }
    /// The lattice point nearest to `p` (clamped onto the lattice).
    fn nearest(&self, p: Point) -> usize {
        let o = self.map.origin();
        let at = |v: f64, n: usize| ((v / self.h - 0.5).round().max(0.0) as usize).min(n - 1);
        at(p.y - o.y, self.rows) * self.cols + at(p.x - o.x, self.cols)
    }
}

/// Coverable flags, one per cell (row-major), for a robot of radius `radius` whose centre
/// starts at any of `seeds`: see the module documentation.
pub fn coverable_cells(map: &GridMap, radius: f64, seeds: &[Point]) -> Vec<bool> {
    let s = LATTICE_PER_CELL;
    let lat = Lattice { map, cols: map.cols() * s, rows: map.rows() * s, h: map.resolution() / s as f64 };
    let delta = lat.h * std::f64::consts::FRAC_1_SQRT_2;
    let need = (radius - delta).max(0.0);
    // A cell whose centre has clearance ≥ need + half its diagonal keeps all its lattice
    // points (clearance is 1-Lipschitz): one scan per cell instead of one per point.
    let half_diagonal = map.resolution() * std::f64::consts::FRAC_1_SQRT_2;
    let mut roomy = vec![0u8; map.rows() * map.cols()];
    // Kept lattice points, found lazily: 0 unknown, 1 kept, 2 not kept.
    let mut state = vec![0u8; lat.cols * lat.rows];
    let mut kept = |k: usize, state: &mut Vec<u8>| {
        if state[k] == 0 {
            let (i, j) = (k % lat.cols, k / lat.cols);
            let cell = map.index(j / s, i / s);
            if roomy[cell] == 0 {
                let c = map.cell_centre(j / s, i / s);
                let wanted = need + half_diagonal;
                roomy[cell] = if clearance(map, c, wanted + 1e-9) >= wanted { 1 } else { 2 };
            }
            let p = lat.point(i, j);
            let ok = roomy[cell] == 1 || (map.is_free_point(p) && clearance(map, p, need + 1e-9) >= need);
            state[k] = if ok { 1 } else { 2 };
        }
        state[k] == 1
    };
    let mut reached = vec![false; lat.cols * lat.rows];
    let mut stack: Vec<usize> = Vec::new();
    for &p in seeds {
        let k = lat.nearest(p);
        if !reached[k] && kept(k, &mut state) {
            reached[k] = true;
            stack.push(k);
        }
    }
    while let Some(k) = stack.pop() {
        let (i, j) = ((k % lat.cols) as isize, (k / lat.cols) as isize);
        for (di, dj) in [(-1, 0), (1, 0), (0, -1), (0, 1), (-1, -1), (-1, 1), (1, -1), (1, 1)] {
            let (ni, nj) = (i + di, j + dj);
            if ni < 0 || nj < 0 || ni >= lat.cols as isize || nj >= lat.rows as isize {
                continue;
            }
            let n = nj as usize * lat.cols + ni as usize;
            if !reached[n] && kept(n, &mut state) {
                reached[n] = true;
                stack.push(n);
            }
        }
    }
    // A free cell is coverable when a reached lattice point lies within r + δ of its centre.
    let reach_r = radius + delta;
    let span = (reach_r / lat.h).ceil() as isize + 1;
    let mut out = vec![false; map.rows() * map.cols()];
    for row in 0..map.rows() {
        for col in 0..map.cols() {
            if !map.is_free(row, col) {
                continue;
            }
            let c = map.cell_centre(row, col);
            let k = lat.nearest(c);
            if reached[k] {
                out[map.index(row, col)] = true;
                continue;
            }
            let (ci, cj) = ((k % lat.cols) as isize, (k / lat.cols) as isize);
            'search: for dj in -span..=span {
                for di in -span..=span {
                    let (ni, nj) = (ci + di, cj + dj);
                    if ni < 0 || nj < 0 || ni >= lat.cols as isize || nj >= lat.rows as isize {
                        continue;
                    }
                    let n = nj as usize * lat.cols + ni as usize;
                    if reached[n] && (lat.point(ni as usize, nj as usize) - c).norm() <= reach_r {
                        out[map.index(row, col)] = true;
                        break 'search;
                    }
                }
            }
        }
    }
    out
}
