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
use super::wall_rows::{WallRows, axis_gap};
use crate::geom::Point;

/// Lattice points per cell edge (`h = resolution / LATTICE_PER_CELL`).
pub const LATTICE_PER_CELL: usize = 8;

/// Distance from `p` to the nearest non-free cell or the map's edge, or `cap` when both are
/// farther than `cap`. Only the non-free cells of each row nearest to `p` are measured
/// ([`WallRows`]): the minimum is the one over the whole window.
fn clearance(map: &GridMap, walls: &WallRows, p: Point, cap: f64) -> f64 {
    let (ox, oy) = (map.origin().x, map.origin().y);
    let edge = (p.x - ox).min(p.y - oy).min(ox + map.width_m() - p.x).min(oy + map.height_m() - p.y);
    let window = (cap / map.resolution()).ceil() as isize + 1;
    // `√(dy·dy)` as rounded, not `dy`: the least distance a cell of the row can round to.
    walls.least_near(map, p, window, edge.min(cap), |dx, dy| (dx * dx + dy * dy).sqrt(), |dy| (dy * dy).sqrt())
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

/// Which lattice points a centre may take (clearance ≥ r − δ), found lazily cell by cell.
struct KeptPoints<'m> {
    lat: &'m Lattice<'m>,
    walls: WallRows,
    need: f64,
    /// Per cell: 0 unknown, [`ROOMY`], [`HOPELESS`] or [`MIXED`].
    cells: Vec<u8>,
    /// Per lattice point of a mixed cell: 0 unknown, 1 kept, 2 not kept.
    points: Vec<u8>,
}

/// Every lattice point of the cell is kept: its centre's clearance exceeds `need` by half the
/// cell's diagonal (clearance is 1-Lipschitz).
const ROOMY: u8 = 1;
/// No lattice point of the cell is kept: its centre's clearance falls short of `need` by more
/// than half the diagonal (with a margin far above rounding).
const HOPELESS: u8 = 2;
/// Each point is tested on its own.
const MIXED: u8 = 3;

impl KeptPoints<'_> {
    fn cell_class(&mut self, cell: usize) -> u8 {
        if self.cells[cell] == 0 {
            let map = self.lat.map;
            let half_diagonal = map.resolution() * std::f64::consts::FRAC_1_SQRT_2;
            let wanted = self.need + half_diagonal;
            let c = map.cell_centre(cell / map.cols(), cell % map.cols());
            let v = clearance(map, &self.walls, c, wanted + 1e-9);
            self.cells[cell] = if v >= wanted {
                ROOMY
            } else if v + half_diagonal < self.need - 1e-9 {
                HOPELESS
            } else {
                MIXED
            };
        }
        self.cells[cell]
    }

    fn kept(&mut self, k: usize) -> bool {
        let lat = self.lat;
        let (i, j) = (k % lat.cols, k / lat.cols);
        let s = LATTICE_PER_CELL;
        match self.cell_class(lat.map.index(j / s, i / s)) {
            ROOMY => true,
            HOPELESS => false,
            _ => {
                if self.points[k] == 0 {
                    self.test_points(lat.map.index(j / s, i / s));
                }
                self.points[k] == 1
            }
        }
    }

    /// Tests every lattice point of a mixed cell. Its points share the window and the row
    /// candidates of [`clearance`], so the walls are gathered once, and those whose square
    /// lies farther than the cap from the cell's square (a margin far above rounding) are
    /// left out: they cannot lower a clearance capped there. Each point's clearance is that
    /// of [`clearance`] to the bit.
    fn test_points(&mut self, cell: usize) {
        let (lat, s) = (self.lat, LATTICE_PER_CELL);
        let map = lat.map;
        let (ox, oy, res) = (map.origin().x, map.origin().y, map.resolution());
        let (row, col) = (cell / map.cols(), cell % map.cols());
        let cap = self.need + 1e-9;
        let window = (cap / res).ceil() as isize + 1;
        let (lo, hi) =
            ((col as isize - window).max(0) as usize, (col as isize + window).min(map.cols() as isize - 1) as usize);
        let (cx, cy) = (ox + col as f64 * res, oy + row as f64 * res);
        let gap = |a: f64, b: f64| (a - b - res).max(0.0).max(b - a - res);
        let mut boxes: Vec<(f64, f64)> = Vec::new();
        for r in (row as isize - window).max(0)..=(row as isize + window).min(map.rows() as isize - 1) {
            let y0 = oy + r as f64 * res;
            self.walls.candidates(r as usize, col as isize, lo, hi, |c| {
                let x0 = ox + c as f64 * res;
                if gap(x0, cx).hypot(gap(y0, cy)) <= cap + 1e-9 {
                    boxes.push((x0, y0));
                }
            });
        }
        for j in row * s..(row + 1) * s {
            for i in col * s..(col + 1) * s {
                let p = lat.point(i, j);
                let edge = (p.x - ox).min(p.y - oy).min(ox + map.width_m() - p.x).min(oy + map.height_m() - p.y);
                let mut best = edge.min(cap);
                for &(x0, y0) in &boxes {
                    let (dx, dy) = (axis_gap(x0, p.x, res), axis_gap(y0, p.y, res));
                    best = best.min((dx * dx + dy * dy).sqrt());
                }
                let ok = map.is_free_point(p) && best >= self.need;
                self.points[j * lat.cols + i] = if ok { 1 } else { 2 };
            }
        }
    }
}

/// The kept lattice points 8-connected to the seeds' nearest kept points, and per cell whether
/// it holds one. Entering a roomy cell reaches all its points at once; from it, a roomy
/// neighbour cell is entered whole (some of their points are neighbours, all are kept), and
/// only the points of a mixed neighbour next to its rim are tried one by one.
fn flood(kept: &mut KeptPoints, seeds: &[Point]) -> (Vec<bool>, Vec<bool>) {
    let mut f = Flood {
        reached: vec![false; kept.lat.cols * kept.lat.rows],
        cell_reached: vec![false; kept.lat.map.rows() * kept.lat.map.cols()],
        points: Vec::new(),
        cells: Vec::new(),
    };
    for &p in seeds {
        f.enter(kept, kept.lat.nearest(p));
    }
    let lat = kept.lat;
    let (s, cols, rows) = (LATTICE_PER_CELL as isize, lat.map.cols() as isize, lat.map.rows() as isize);
    let neighbours = [(-1, 0), (1, 0), (0, -1), (0, 1), (-1, -1), (-1, 1), (1, -1), (1, 1)];
    loop {
        if let Some(k) = f.points.pop() {
            let (i, j) = ((k % lat.cols) as isize, (k / lat.cols) as isize);
            for (di, dj) in neighbours {
                let (ni, nj) = (i + di, j + dj);
                if ni >= 0 && nj >= 0 && ni < lat.cols as isize && nj < lat.rows as isize {
                    f.enter(kept, nj as usize * lat.cols + ni as usize);
                }
            }
        } else if let Some(cell) = f.cells.pop() {
            let (r, c) = ((cell / lat.map.cols()) as isize, (cell % lat.map.cols()) as isize);
            for (dc, dr) in neighbours {
                let (nr, nc) = (r + dr, c + dc);
                if nr < 0 || nc < 0 || nr >= rows || nc >= cols {
                    continue;
                }
                let next = (nr * cols + nc) as usize;
                match kept.cell_class(next) {
                    ROOMY => f.enter(kept, (nr * s) as usize * lat.cols + (nc * s) as usize),
                    HOPELESS => {}
                    _ => {
                        // The rim points of `cell` facing `next`, and their neighbours in `next`.
                        let span = |d: isize, o: isize| {
                            if d < 0 {
                                o..o + 1
                            } else if d > 0 {
                                o + s - 1..o + s
                            } else {
                                o..o + s
                            }
                        };
                        for qj in span(dr, r * s) {
                            for qi in span(dc, c * s) {
                                for (di, dj) in neighbours {
                                    let (ni, nj) = (qi + di, qj + dj);
                                    if ni.div_euclid(s) == nc && nj.div_euclid(s) == nr {
                                        f.enter(kept, nj as usize * lat.cols + ni as usize);
                                    }
                                }
                            }
                        }
                    }
                }
            }
        } else {
            break;
        }
    }
    (f.reached, f.cell_reached)
}

/// The state of [`flood`]: points and cells reached, and those still to explore from.
struct Flood {
    reached: Vec<bool>,
    cell_reached: Vec<bool>,
    points: Vec<usize>,
    cells: Vec<usize>,
}

impl Flood {
    /// Reaches lattice point `n` if it is kept and new: with its whole cell when that is roomy.
    fn enter(&mut self, kept: &mut KeptPoints, n: usize) {
        if self.reached[n] || !kept.kept(n) {
            return;
        }
        let (lat, s) = (kept.lat, LATTICE_PER_CELL);
        let (i, j) = (n % lat.cols, n / lat.cols);
        let cell = lat.map.index(j / s, i / s);
        self.cell_reached[cell] = true;
        if kept.cell_class(cell) != ROOMY {
            self.reached[n] = true;
            self.points.push(n);
            return;
        }
        let (i0, j0) = (i / s * s, j / s * s);
        for jj in j0..j0 + s {
            self.reached[jj * lat.cols + i0..jj * lat.cols + i0 + s].fill(true);
        }
        self.cells.push(cell);
    }
}

/// Coverable flags, one per cell (row-major), for a robot of radius `radius` whose centre
/// starts at any of `seeds`: see the module documentation.
pub fn coverable_cells(map: &GridMap, radius: f64, seeds: &[Point]) -> Vec<bool> {
    let s = LATTICE_PER_CELL;
    let lat = Lattice { map, cols: map.cols() * s, rows: map.rows() * s, h: map.resolution() / s as f64 };
    let delta = lat.h * std::f64::consts::FRAC_1_SQRT_2;
    let need = (radius - delta).max(0.0);
    let mut kept = KeptPoints {
        lat: &lat,
        walls: WallRows::new(map),
        need,
        cells: vec![0; map.rows() * map.cols()],
        points: vec![0; lat.cols * lat.rows],
    };
    let (reached, cell_reached) = flood(&mut kept, seeds);
    // A free cell is coverable when a reached lattice point lies within r + δ of its centre.
    // Lattice points are looked at only in cells that hold a reached one and whose square
    // comes that close (a margin far above rounding keeps every candidate point).
    let reach_r = radius + delta;
    let span = (reach_r / lat.h).ceil() as isize + 1;
    let res = map.resolution();
    let cell_span = (reach_r / res).ceil() as isize + 1;
    let coverable = |row: usize, col: usize| {
        if !map.is_free(row, col) {
            return false;
        }
        let c = map.cell_centre(row, col);
        let k = lat.nearest(c);
        if reached[k] {
            return true;
        }
        let (ci, cj) = ((k % lat.cols) as isize, (k / lat.cols) as isize);
        let within = |ni: isize, nj: isize| {
            (ni - ci).abs() <= span
                && (nj - cj).abs() <= span
                && reached[nj as usize * lat.cols + ni as usize]
                && (lat.point(ni as usize, nj as usize) - c).norm() <= reach_r
        };
        cells_around(map, row, col, cell_span).any(|(r2, c2)| {
            if !cell_reached[map.index(r2, c2)] || box_distance(map, r2, c2, c) > reach_r * (1.0 + 1e-9) + 1e-12 {
                return false;
            }
            let (i0, j0) = ((c2 * s) as isize, (r2 * s) as isize);
            (j0..j0 + s as isize).any(|nj| (i0..i0 + s as isize).any(|ni| within(ni, nj)))
        })
    };
    // Each cell's flag reads the flood's result alone.
    map.par_cells(coverable)
}

/// The cells of the square of `span` cells around `(row, col)`, on the map.
fn cells_around(map: &GridMap, row: usize, col: usize, span: isize) -> impl Iterator<Item = (usize, usize)> {
    let (row, col) = (row as isize, col as isize);
    let (r0, r1) = ((row - span).max(0), (row + span).min(map.rows() as isize - 1));
    let (c0, c1) = ((col - span).max(0), (col + span).min(map.cols() as isize - 1));
    (r0..=r1).flat_map(move |r| (c0..=c1).map(move |c| (r as usize, c as usize)))
}

/// Distance from `p` to the square of cell `(row, col)`.
fn box_distance(map: &GridMap, row: usize, col: usize, p: Point) -> f64 {
    let res = map.resolution();
    let (x0, y0) = (map.origin().x + col as f64 * res, map.origin().y + row as f64 * res);
    axis_gap(x0, p.x, res).hypot(axis_gap(y0, p.y, res))
}

#[cfg(test)]
mod tests;
