//! Boustrophedon (lawn-mower) coverage with a simple boustrophedon cell decomposition:
//! parallel lanes one robot width apart at any angle, split where the robot does not fit,
//! grouped into cells of one-to-one overlapping lane pieces, each cell mowed back and forth,
//! cells visited greedily by distance and joined by collision-free connecting moves
//! (the hand-made pattern of 003 Table 3.1, generalised). Pieces only exist where the robot
//! fits and can get to from the start (the clearance is restricted to the reachable part).

use super::{GrowingRoute, PatternError};
use crate::geom::{Point, Vector};
use crate::map::clearance::Clearance;

/// One fitting piece of a lane: its two ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Piece {
    /// The end at the low lane coordinate.
    pub a: Point,
    /// The end at the high lane coordinate.
    pub b: Point,
    /// Extent along the lane direction (for overlap tests).
    pub lo: f64,
    /// Upper end of the extent.
    pub hi: f64,
}

/// The lane pieces of the map at `angle_deg`, one robot width apart.
pub fn lane_pieces(clear: &Clearance, width: f64, angle_deg: f64) -> Vec<Vec<Piece>> {
    let map = clear.map();
    let u = Vector::new(angle_deg.to_radians().cos(), angle_deg.to_radians().sin());
    let n = Vector::new(-u.y, u.x);
    let half = 0.5 * map.resolution();
    // Extent of the free cells along u and n (cell corners included).
    let (mut u_lo, mut u_hi, mut n_lo, mut n_hi) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for r in 0..map.rows() {
        for c in 0..map.cols() {
            if !map.is_free(r, c) {
                continue;
            }
            let p = map.cell_centre(r, c).coords;
            let (pu, pn) = (p.dot(&u), p.dot(&n));
            let spread = half * (u.x.abs() + u.y.abs());
            u_lo = u_lo.min(pu - spread);
            u_hi = u_hi.max(pu + spread);
            n_lo = n_lo.min(pn - spread);
            n_hi = n_hi.max(pn + spread);
        }
    }
    let offsets = centre_offsets(map, width, n, (n_lo, n_hi)).unwrap_or_else(|| spaced_offsets(width, n_lo, n_hi));
    offsets
        .iter()
        .map(|&o| {
            let start = Point::from(u * u_lo + n * o);
            let end = Point::from(u * u_hi + n * o);
            let len = u_hi - u_lo;
            clear
                .fitting_intervals(start, end, map.resolution())
                .into_iter()
                .map(|(t0, t1)| Piece {
                    a: start + (end - start) * t0,
                    b: start + (end - start) * t1,
                    lo: u_lo + t0 * len,
                    hi: u_lo + t1 * len,
                })
                .collect()
        })
        .collect()
}

/// Lane offsets (along `n`) through the centres of the cells the plan is scored on, where the
/// robot is narrower than those cells and the lanes run along the raster's axes; `None`
/// elsewhere.
///
/// Why: the scorer sweeps the cells whose centres lie within half a width of a lane
/// ([`crate::coverage::raster`], 003 §3.1, a half-open band). Lanes one width apart from the
/// free space's edge put every centre of cells wider than the robot on a band's edge, which
/// alternate lanes leave out from both sides (thesis map 1, a 0.1 m robot on 0.2 m cells:
/// 1.4 % covered). A lane through each row of centres sweeps that row.
fn centre_offsets(map: &crate::map::GridMap, width: f64, n: Vector, (n_lo, n_hi): (f64, f64)) -> Option<Vec<f64>> {
    let cell = map.scored_resolution();
    if width >= cell {
        return None;
    }
    // `n` is ±x or ±y: the centres' coordinates along it are those of one axis.
    let (o, extent, sign) = if n.x.abs() < 1e-12 {
        (map.origin().y, map.height_m(), n.y.signum())
    } else if n.y.abs() < 1e-12 {
        (map.origin().x, map.width_m(), n.x.signum())
    } else {
        return None;
    };
    let count = (extent / cell).round() as usize;
    let mut offsets: Vec<f64> =
        (0..count).map(|j| sign * (o + (j as f64 + 0.5) * cell)).filter(|&v| v >= n_lo && v <= n_hi).collect();
    offsets.sort_by(f64::total_cmp);
    Some(offsets)
}

/// Lane offsets one `width` apart from `n_lo` (the free space's edge along the lanes' normal),
/// with a last lane flush with the far side `n_hi` where the spacing leaves a strip.
fn spaced_offsets(width: f64, n_lo: f64, n_hi: f64) -> Vec<f64> {
    let mut offsets = Vec::new();
    let mut o = n_lo + 0.5 * width;
    while o <= n_hi - 0.5 * width + 1e-9 {
        offsets.push(o);
        o += width;
    }
    // A last lane flush with the far side when the regular spacing leaves a strip uncovered.
    let far = n_hi - 0.5 * width;
    if offsets.last().is_none_or(|&l| far - l > 1e-6) && far >= n_lo {
        offsets.push(far.max(n_lo + 0.5 * width).min(far));
    }
    offsets
}

/// Groups lane pieces into boustrophedon cells: a cell grows while its last piece overlaps
/// exactly one piece of the next lane and that piece overlaps only it.
pub fn decompose(lanes: &[Vec<Piece>]) -> Vec<Vec<Piece>> {
    let overlaps = |p: &Piece, q: &Piece| p.lo < q.hi && q.lo < p.hi;
    let mut done: Vec<Vec<Piece>> = Vec::new();
    let mut open: Vec<Vec<Piece>> = Vec::new();
    for lane in lanes {
        let last = |c: &Vec<Piece>| *c.last().expect("cells are never empty");
        // How many open cells each piece of this lane touches.
        let touching: Vec<usize> = lane.iter().map(|q| open.iter().filter(|c| overlaps(&last(c), q)).count()).collect();
        let mut used = vec![false; lane.len()];
        let mut next_open = Vec::new();
        for mut cell in open.drain(..) {
            let hits: Vec<usize> = (0..lane.len()).filter(|&j| overlaps(&last(&cell), &lane[j])).collect();
            if let [j] = hits[..]
                && touching[j] == 1
            {
                used[j] = true;
                cell.push(lane[j]);
                next_open.push(cell);
            } else {
                done.push(cell);
            }
        }
        next_open.extend(lane.iter().zip(&used).filter(|(_, u)| !**u).map(|(p, _)| vec![*p]));
        open = next_open;
    }
    done.extend(open);
    done
}

/// Plans a boustrophedon route from `start` over all cells (the caller returns it to the end).
pub fn plan(clear: &Clearance, width: f64, angle_deg: f64, start: Point) -> Result<GrowingRoute, PatternError> {
    let cells = decompose(&lane_pieces(clear, width, angle_deg));
    if cells.is_empty() {
        return Err(PatternError::NoRoom { width });
    }
    Ok(sweep_cells(clear, &cells, start))
}

/// Mows `cells` back and forth from `start`: next the unvisited cell with the entry corner
/// nearest to where the robot is (nearest neighbour), each cell lane by lane from that corner,
/// joined by collision-free connecting moves.
pub fn sweep_cells(clear: &Clearance, cells: &[Vec<Piece>], start: Point) -> GrowingRoute {
    sweep_cells_with(clear, cells, start, false)
}

/// [`sweep_cells`]; with `along`, a piece whose straight line is blocked (one joined across an
/// obstacle, the cell-order planner's merged lanes) is driven along its lane, around each
/// obstacle from one fitting stretch to the next, instead of by the shortest route between its
/// ends.
pub fn sweep_cells_with(clear: &Clearance, cells: &[Vec<Piece>], start: Point, along: bool) -> GrowingRoute {
    let mut route = GrowingRoute::new(start);
    let mut visited = vec![false; cells.len()];
    for _ in 0..cells.len() {
        // Nearest entry corner among the unvisited cells: (distance, cell, from_first_lane, flip).
        let here = route.last();
        let mut best: Option<(f64, usize, bool, bool)> = None;
        for (k, cell) in cells.iter().enumerate().filter(|(k, _)| !visited[*k]) {
            let (first, last) = (cell[0], cell[cell.len() - 1]);
            for (p, from_first, flip) in
                [(first.a, true, false), (first.b, true, true), (last.a, false, false), (last.b, false, true)]
            {
                let d = (p - here).norm();
                if best.is_none_or(|b| d < b.0 - 1e-12) {
                    best = Some((d, k, from_first, flip));
                }
            }
        }
        let (_, k, from_first, mut flip) = best.expect("an unvisited cell remains");
        visited[k] = true;
        let order: Vec<&Piece> = if from_first { cells[k].iter().collect() } else { cells[k].iter().rev().collect() };
        for piece in order {
            let (a, b) = if flip { (piece.b, piece.a) } else { (piece.a, piece.b) };
            route.go(clear, a);
            if along && !clear.segment_fits(a, b) {
                for (t0, t1) in clear.fitting_intervals(a, b, clear.map().resolution()) {
                    route.go(clear, a + (b - a) * t0);
                    route.go(clear, a + (b - a) * t1);
                }
            }
            route.go(clear, b);
            flip = !flip;
        }
    }
    route
}
