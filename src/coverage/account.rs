//! Where a plan's time goes up to a coverage level (issue 102, item 1: the per-map account of
//! where a plan loses time against the lane control). Each segment's driving is put in one of
//! three terms by what its band sweeps that the plan before it did not: **sweeping** (at least
//! half of its band new, the segment at least a robot width long: lane driving), **short
//! sweeping** (as much new, but shorter than a width: lane ends, specks and completion hops) and
//! **transit** (less than half new: moves between lanes, routes, driving over covered ground);
//! the turning before every segment is a term of its own. Time is the common scorer's
//! (length over speed, turning over the rotation speed, 003 eqs. 3.1–3.3), so the terms add up
//! to the plan's time at the level.

use super::motion::{abs_turn_deg, rotation_time};
use super::raster::for_each_swept_cell;
use super::{CoverageGrid, Footprint};
use crate::geom::{Point, ZERO_LENGTH};
use crate::map::reach::Reach;

/// A plan's time up to a coverage level, in seconds, term by term.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TimeAccount {
    /// Driving segments whose band is at least half new, a width long or longer.
    pub sweeping_s: f64,
    /// Driving segments whose band is at least half new, shorter than a width.
    pub short_sweeping_s: f64,
    /// Driving segments whose band is less than half new.
    pub transit_s: f64,
    /// Turning in place before segments.
    pub turning_s: f64,
    /// The reachable coverage when the account ends.
    pub coverage: f64,
}

impl TimeAccount {
    /// The whole time: every term added.
    pub fn total_s(&self) -> f64 {
        self.sweeping_s + self.short_sweeping_s + self.transit_s + self.turning_s
    }
}

/// The account of `path` driven by `robot`, up to the segment whose sweep brings the share of
/// `reach`'s coverable cells to `level` (the whole path where it never does).
pub fn time_account(grid: &CoverageGrid, reach: &Reach, robot: &Footprint, path: &[Point], level: f64) -> TimeAccount {
    let res = grid.raster().resolution;
    let reachable = reach.coverable_count().max(1);
    let needed = (level * reachable as f64 - 1e-9).ceil().max(0.0) as usize;
    let mut covered = vec![false; grid.len()];
    let (mut count, mut heading) = (0usize, None);
    let mut account = TimeAccount::default();
    for w in path.windows(2) {
        let v = w[1] - w[0];
        let length = v.norm();
        if length < ZERO_LENGTH {
            continue;
        }
        if let Some(h) = heading {
            account.turning_s += rotation_time(abs_turn_deg(h, v).to_radians(), robot.rot_speed);
        }
        heading = Some(v);
        let mut new = 0usize;
        for_each_swept_cell(grid.raster(), w[0], w[1], robot.width, |i| {
            if reach.is_coverable(i) && !covered[i] {
                covered[i] = true;
                new += 1;
            }
        });
        count += new;
        let band = length * robot.width / (res * res);
        let secs = length / robot.speed;
        match (new as f64 >= 0.5 * band, length >= robot.width) {
            (true, true) => account.sweeping_s += secs,
            (true, false) => account.short_sweeping_s += secs,
            (false, _) => account.transit_s += secs,
        }
        if count >= needed {
            break;
        }
    }
    account.coverage = count as f64 / reachable as f64;
    account
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::clearance::Clearance;
    use crate::map::{CellState, GridMap};

    #[test]
    fn a_lane_driven_there_and_back_is_sweeping_then_transit_with_a_half_turn_between() {
        let (w, h) = (100, 40);
        let cells = (0..w * h)
            .map(|i| {
                let (r, c) = (i / w, i % w);
                if r == 0 || c == 0 || r == h - 1 || c == w - 1 { CellState::Occupied } else { CellState::Free }
            })
            .collect();
        let map = GridMap::new("room", w, h, 0.05, Point::origin(), cells).unwrap();
        let robot = Footprint { width: 0.6, speed: 0.3, rot_speed: 0.5 };
        let start = Point::new(0.5, 1.0);
        let reach = Reach::new(&Clearance::new(&map, robot.width), &[start]);
        let grid = CoverageGrid::new(&map);
        let lane =
            [start, Point::new(4.5, 1.0), Point::new(4.5, 1.0 + 0.1), start + crate::geom::Vector::new(0.0, 0.1)];
        let a = time_account(&grid, &reach, &robot, &lane, 1.0);
        assert!((a.sweeping_s - 4.0 / 0.3).abs() < 1e-9, "{a:?}");
        // The step aside is short and sweeps a band mostly covered; the way back covers little.
        assert!((a.transit_s - 4.1 / 0.3).abs() < 1e-9, "{a:?}");
        assert_eq!(a.short_sweeping_s, 0.0);
        assert!((a.turning_s - std::f64::consts::PI / 0.5).abs() < 1e-9, "two quarter turns: {a:?}");
        let whole = crate::coverage::curve::segment_end_times(&lane, &robot);
        assert!((a.total_s() - whole.last().unwrap()).abs() < 1e-9, "the terms add up to the plan's time");
        // Up to a level the lane alone reaches, the account stops after the lane.
        let first = time_account(&grid, &reach, &robot, &lane, 0.2);
        assert_eq!((first.transit_s, first.turning_s), (0.0, 0.0), "{first:?}");
        assert!(first.coverage >= 0.2);
    }
}
