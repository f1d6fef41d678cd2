//! The idealised control's lanes (issue 102, item 1): straight lanes through the cell centres
//! where the robot fits and that the start reaches, `spacing` apart at one direction, the
//! first of them at one of a few offsets within a spacing; each lane piece trimmed to where it
//! sweeps cells that the lanes before it did not, and dropped where what is left is shorter
//! than the lane's minimum length (a speck the completion takes more cheaply than a lane).

use crate::coverage::CoverageGrid;
use crate::coverage::raster::for_each_swept_cell;
use crate::geom::{Point, Vector};
use crate::map::clearance::Clearance;
use crate::map::reach::Reach;

/// One candidate lane layout: a direction, a spacing and an offset of the first lane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layout {
    /// Lane direction in degrees from +x.
    pub direction_deg: f64,
    /// Distance between neighbouring lanes in metres.
    pub spacing_m: f64,
    /// Which of `offsets` shifts of the first lane, each `spacing / offsets` further.
    pub offset: usize,
    /// How many shifts the spacing is divided into.
    pub offsets: usize,
}

/// A lane piece to drive, either way round.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LanePiece {
    /// One end.
    pub a: Point,
    /// The other end.
    pub b: Point,
}

impl LanePiece {
    /// Its length in metres.
    pub fn length(&self) -> f64 {
        (self.b - self.a).norm()
    }
}

/// Lanes laid on the raster: the pieces and the coverable cells they sweep.
#[derive(Clone, Debug)]
pub struct Laid {
    /// The lane pieces, in order across the map.
    pub pieces: Vec<LanePiece>,
    /// Per map cell: swept by a piece and coverable.
    pub covered: Vec<bool>,
    /// How many cells `covered` marks.
    pub count: usize,
}

impl Laid {
    /// The share of `reach`'s coverable cells the pieces sweep.
    pub fn share(&self, reach: &Reach) -> f64 {
        self.count as f64 / reach.coverable_count().max(1) as f64
    }

    /// Adds `piece`, marking the coverable cells it sweeps.
    pub fn push(&mut self, grid: &CoverageGrid, reach: &Reach, width: f64, piece: LanePiece) {
        let (covered, count) = (&mut self.covered, &mut self.count);
        for_each_swept_cell(grid.raster(), piece.a, piece.b, width, |i| {
            if reach.is_coverable(i) && !covered[i] {
                covered[i] = true;
                *count += 1;
            }
        });
        self.pieces.push(piece);
    }
}

/// The extent of the fitting centres of `clear` along `u` and along `n`: `(u_lo, u_hi, n_lo,
/// n_hi)`, empty (lo > hi) where none fits.
pub fn extent(clear: &Clearance, u: Vector, n: Vector) -> (f64, f64, f64, f64) {
    let map = clear.map();
    let (mut u_lo, mut u_hi, mut n_lo, mut n_hi) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for i in 0..map.rows() * map.cols() {
        if clear.centre_fits(i) {
            let p = map.cell_centre(i / map.cols(), i % map.cols()).coords;
            let (pu, pn) = (p.dot(&u), p.dot(&n));
            u_lo = u_lo.min(pu);
            u_hi = u_hi.max(pu);
            n_lo = n_lo.min(pn);
            n_hi = n_hi.max(pn);
        }
    }
    (u_lo, u_hi, n_lo, n_hi)
}

/// The unit vectors along and across lanes at `direction_deg`.
pub fn axes(direction_deg: f64) -> (Vector, Vector) {
    let angle = direction_deg.to_radians();
    let u = Vector::new(angle.cos(), angle.sin());
    (u, Vector::new(-u.y, u.x))
}

/// The lane pieces of `layout` over the reachable part of `clear` (restricted to it), trimmed
/// against what the lanes before each sweep (lanes in order across the map) and with pieces
/// shorter than `min_lane_m` dropped.
pub fn lay(clear: &Clearance, reach: &Reach, grid: &CoverageGrid, width: f64, layout: Layout, min_lane_m: f64) -> Laid {
    let res = clear.map().resolution();
    let (u, n) = axes(layout.direction_deg);
    let (u_lo, u_hi, n_lo, n_hi) = extent(clear, u, n);
    let mut laid = Laid { pieces: Vec::new(), covered: vec![false; grid.len()], count: 0 };
    if u_lo > u_hi {
        return laid;
    }
    // Lines a cell beyond the fitting centres at both ends, so that the bisection finds the ends.
    let (u_lo, u_hi) = (u_lo - res, u_hi + res);
    let shift = layout.spacing_m * layout.offset as f64 / layout.offsets.max(1) as f64;
    let mut o = n_lo - 0.5 * res + shift;
    while o <= n_hi + 0.5 * res {
        let (start, end) = (Point::from(u * u_lo + n * o), Point::from(u * u_hi + n * o));
        for (t0, t1) in clear.fitting_intervals(start, end, res) {
            let piece = LanePiece { a: start + (end - start) * t0, b: start + (end - start) * t1 };
            if let Some(kept) = trimmed(grid, reach, &laid.covered, width, piece, res)
                && kept.length() >= min_lane_m
            {
                laid.push(grid, reach, width, kept);
            }
        }
        o += layout.spacing_m;
    }
    laid
}

/// `piece` cut to the stretch between the first and the last of its steps (`step` metres
/// long) that sweep a coverable cell not yet `covered`; `None` where no step does.
pub fn trimmed(
    grid: &CoverageGrid,
    reach: &Reach,
    covered: &[bool],
    width: f64,
    piece: LanePiece,
    step: f64,
) -> Option<LanePiece> {
    let steps = (piece.length() / step).ceil().max(1.0) as usize;
    let at = |k: usize| piece.a + (piece.b - piece.a) * (k as f64 / steps as f64);
    let adds = |k: usize| {
        let mut new = false;
        for_each_swept_cell(grid.raster(), at(k), at(k + 1), width, |i| new |= reach.is_coverable(i) && !covered[i]);
        new
    };
    let first = (0..steps).find(|&k| adds(k))?;
    let last = (first..steps).rev().find(|&k| adds(k)).unwrap_or(first);
    Some(LanePiece { a: at(first), b: at(last + 1) })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layouts::room;
    use crate::map::GridMap;

    fn laid(map: &GridMap, layout: Layout, min_lane_m: f64) -> (Vec<LanePiece>, f64) {
        let mut clear = Clearance::new(map, 0.6);
        let start = Point::new(1.0, 1.0);
        let reach = Reach::new(&clear, &[start]);
        clear.restrict(reach.centres().to_vec());
        let grid = CoverageGrid::new(map);
        let laid = lay(&clear, &reach, &grid, 0.6, layout, min_lane_m);
        let share = laid.share(&reach);
        (laid.pieces, share)
    }

    #[test]
    fn lanes_are_parallel_spaced_and_inside_the_room() {
        let map = room(100, 80);
        let layout = Layout { direction_deg: 0.0, spacing_m: 0.55, offset: 0, offsets: 12 };
        let (pieces, share) = laid(&map, layout, 0.6);
        assert!(pieces.len() >= 5, "{pieces:?}");
        for w in pieces.windows(2) {
            let gap = w[1].a.y - w[0].a.y;
            assert!((gap - 0.55).abs() < 1e-9, "lanes {gap} m apart");
        }
        for p in &pieces {
            assert!((p.a.y - p.b.y).abs() < 1e-12, "a lane at 0° is horizontal");
            assert!(p.a.x >= 0.3 && p.b.x <= 5.0 - 0.3 + 1e-9, "{p:?}");
        }
        assert!(share > 0.8 && share <= 1.0, "{share}");
    }

    #[test]
    fn a_piece_shorter_than_the_minimum_lane_is_dropped() {
        // 5 m × 4 m inside the walls: lanes at 90° are 3.4 m long, at 0° 4.4 m.
        let map = room(100, 80);
        let at = |direction_deg: f64, min: f64| {
            laid(&map, Layout { direction_deg, spacing_m: 0.6, offset: 3, offsets: 12 }, min).0
        };
        assert!(!at(90.0, 0.0).is_empty());
        assert!(at(90.0, 3.5).is_empty(), "every lane is shorter than 3.5 m");
        let across = at(0.0, 3.5);
        assert!(!across.is_empty() && across.iter().all(|p| p.length() >= 3.5), "{across:?}");
    }

    #[test]
    fn closer_lanes_sweep_no_less() {
        let map = room(120, 90);
        let share = |s: f64| laid(&map, Layout { direction_deg: 0.0, spacing_m: s, offset: 0, offsets: 1 }, 0.0).1;
        assert!(share(0.45) >= share(0.6) - 1e-12);
    }
}
