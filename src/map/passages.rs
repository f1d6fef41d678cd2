//! Passages the common scorer counts open and a planning raster closes, and the split that
//! opens them.
//!
//! The scorer reads the robot's centre continuously ([`super::coverable`]): a door 0.5 m wide
//! lets a 0.49 m robot through along a band 1 cm wide. The routing planners place the centre
//! at cell centres ([`super::clearance`]): on 5 cm cells whose borders run through the door's
//! middle no centre lies in that band, so the room behind is out of their reach while the scorer
//! counts it reachable, and the plan covers half of what it is scored against. Splitting the
//! cells ([`super::refine::refined`]) puts centres nearer every line; the least split that
//! brings what the planners reach up to what the scorer counts is the one planned on.
//!
//! Maps where the planners' centres already reach what the scorer counts (every committed
//! study's map) are planned as they were.

use super::GridMap;
use super::clearance::Clearance;
use super::reach::{Reach, reachable_centres};
use super::refine::{refined, refinement};
use crate::geom::Point;
use std::borrow::Cow;
use std::f64::consts::FRAC_1_SQRT_2;

/// The share of the scorer's coverable cells a planning raster's reachable centres must come
/// within sweeping distance of; below it the raster is split further.
pub const MIN_SWEPT_SHARE: f64 = 0.99;

/// The most cells a raster split to open passages may have (about 256 MB of planning state at
/// [`super::refine::PLANNING_BYTES_PER_CELL`]); a larger map keeps the split of
/// [`refinement`], and its closed passages are reported as pockets are.
pub const MAX_PASSAGE_CELLS: u64 = 1 << 21;

/// The splits tried beyond [`refinement`]'s, as multiples of it.
pub const PASSAGE_SPLITS: [usize; 5] = [2, 3, 4, 6, 8];

/// The share of the cells the scorer counts coverable from `start` ([`Reach`] on `map`) that
/// lie within sweeping distance of a centre a planner reaches from `start` on `map` split
/// `k × k`: within the robot's radius of it, plus half a diagonal of a cell of each raster (the
/// scorer's cells are swept from continuous positions between the planners' centres).
///
/// Only the centres on the border of the reached set are measured: a point outside the set is
/// nearer to some border centre than to any inner one (every inner centre has a neighbour
/// nearer to it); cells holding a reached centre count as swept.
pub fn swept_share(map: &GridMap, reach: &Reach, width: f64, start: Point, k: usize) -> f64 {
    if reach.coverable_count() == 0 {
        return 1.0;
    }
    let planning: Cow<'_, GridMap> = if k == 1 { Cow::Borrowed(map) } else { Cow::Owned(refined(map, k)) };
    let clear = Clearance::new(&planning, width);
    let centres = reachable_centres(&clear, &[start]);
    let (pcols, prows) = (planning.cols(), planning.rows());
    let res = map.resolution();
    let tol = 0.5 * width + (planning.resolution() + res) * FRAC_1_SQRT_2;
    let mut swept = vec![false; map.rows() * map.cols()];
    let reached = |r: isize, c: isize| {
        r >= 0 && c >= 0 && (r as usize) < prows && (c as usize) < pcols && centres[r as usize * pcols + c as usize]
    };
    for i in (0..centres.len()).filter(|&i| centres[i]) {
        let (r, c) = (i / pcols, i % pcols);
        swept[map.index(r / k, c / k)] = true;
        let inner = (-1..=1).all(|dr| (-1..=1).all(|dc| reached(r as isize + dr, c as isize + dc)));
        if !inner {
            stamp(map, planning.cell_centre(r, c), tol, &mut swept);
        }
    }
    let kept = (0..swept.len()).filter(|&j| swept[j] && reach.is_coverable(j)).count();
    kept as f64 / reach.coverable_count() as f64
}

/// Marks the cells of `map` whose centre lies within `radius` of `p`.
fn stamp(map: &GridMap, p: Point, radius: f64, flags: &mut [bool]) {
    let res = map.resolution();
    let (ox, oy) = (map.origin().x, map.origin().y);
    let span = |lo: f64, n: usize| {
        let a = ((lo - radius) / res - 0.5).floor().max(0.0) as usize;
        let b = (((lo + radius) / res - 0.5).ceil().max(0.0) as usize).min(n.saturating_sub(1));
        (a, b)
    };
    let (c0, c1) = span(p.x - ox, map.cols());
    let (r0, r1) = span(p.y - oy, map.rows());
    for r in r0..=r1 {
        for c in c0..=c1 {
            let q = map.cell_centre(r, c);
            if (q.x - p.x).powi(2) + (q.y - p.y).powi(2) <= radius * radius {
                flags[map.index(r, c)] = true;
            }
        }
    }
}

/// How many times each cell of `map` is split for a routing planner planning for a robot
/// `width` metres wide from `start`: [`refinement`]'s split, or where the centres the planner
/// reaches on it come within sweeping distance of less than [`MIN_SWEPT_SHARE`] of what the
/// scorer counts coverable ([`swept_share`]), the least of [`PASSAGE_SPLITS`] (within
/// [`MAX_PASSAGE_CELLS`]) that reaches it, else the one that comes nearest (kept only where it
/// gains a hundredth of the coverable cells).
pub fn planning_refinement(map: &GridMap, width: f64, start: Point) -> usize {
    let k0 = refinement(map.resolution(), width);
    if width.is_nan() || width <= 0.0 || !map.cell_at(start).is_some_and(|(r, c)| map.is_free(r, c)) {
        return k0;
    }
    let reach = Reach::for_width(map, width, &[start]);
    let first = swept_share(map, &reach, width, start, k0);
    if first >= MIN_SWEPT_SHARE {
        return k0;
    }
    let cells = (map.cols() * map.rows()) as u64;
    let mut best = (first, k0);
    for k in PASSAGE_SPLITS.iter().map(|m| m * k0) {
        if cells * (k * k) as u64 > MAX_PASSAGE_CELLS {
            break;
        }
        let share = swept_share(map, &reach, width, start, k);
        if share >= MIN_SWEPT_SHARE {
            return k;
        }
        if share > best.0 + 0.01 {
            best = (share, k);
        }
    }
    best.1
}

/// The raster a routing planner plans on for a robot `width` metres wide starting at `start`:
/// `map` itself, or `map` split by [`planning_refinement`].
pub fn planning_map_from(map: &GridMap, width: f64, start: Point) -> Cow<'_, GridMap> {
    match planning_refinement(map, width, start) {
        1 => Cow::Borrowed(map),
        k => Cow::Owned(refined(map, k)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::CellState;

    /// Two rooms of 2.5 × 2 m on 5 cm cells, joined by a door 0.5 m wide in a wall 0.1 m thick
    /// (the door's middle on a cell border).
    fn two_rooms() -> GridMap {
        let (cols, rows) = (102, 40);
        let cells = (0..rows * cols)
            .map(|i| {
                let (r, c) = (i / cols, i % cols);
                let wall = (50..52).contains(&c) && !(15..25).contains(&r);
                if wall { CellState::Occupied } else { CellState::Free }
            })
            .collect();
        GridMap::new("two rooms", cols, rows, 0.05, Point::new(0.0, 0.0), cells).unwrap()
    }

    #[test]
    fn a_door_barely_wider_than_the_robot_is_opened_by_a_split() {
        let map = two_rooms();
        let start = Point::new(1.0, 1.0);
        let reach = Reach::for_width(&map, 0.49, &[start]);
        let on_map = swept_share(&map, &reach, 0.49, start, 1);
        assert!(on_map < 0.6, "the door closes the second room on the map's centres: {on_map}");
        let k = planning_refinement(&map, 0.49, start);
        assert!(k > 1, "a split opens it");
        assert!(swept_share(&map, &reach, 0.49, start, k) >= MIN_SWEPT_SHARE);
    }

    #[test]
    fn maps_whose_centres_reach_what_the_scorer_counts_keep_their_cells() {
        let map = two_rooms();
        let start = Point::new(1.0, 1.0);
        // A 0.4 m robot passes the door through cell centres: nothing to split.
        assert_eq!(planning_refinement(&map, 0.4, start), 1);
        assert!(matches!(planning_map_from(&map, 0.4, start), Cow::Borrowed(_)));
        // A 0.6 m robot fits through no door: the scorer counts one room, as the planners do.
        assert_eq!(planning_refinement(&map, 0.6, start), 1);
    }
}
