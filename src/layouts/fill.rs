//! Extra lanes where the regular ones leave strips (issue 102, item 1: lane spacing against
//! the raster). Lanes `spacing` apart end where the robot fits and leave, along every wall
//! and obstacle parallel to them, a strip up to a spacing wide that the scorer's band does not
//! reach, and the completion then chases it cell by cell. Here lanes at the same direction, a
//! map cell apart, are offered as candidates, each cut into the stretches that sweep cells the
//! lanes so far leave (stretches joined across gaps shorter than the minimum lane); the
//! stretch that sweeps most new cells per second of its own driving and turning is added,
//! greedily, until the lanes sweep the goal's share of the reachable cells. Gains only fall as
//! lanes are added, so a stretch is re-read only when it reaches the top of the queue.

use super::lanes::{Laid, LanePiece, axes, extent};
use crate::coverage::raster::for_each_swept_cell;
use crate::coverage::{CoverageGrid, Footprint};
use crate::map::clearance::Clearance;
use crate::map::reach::Reach;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// What the greedy fill reads: the map, the robot and the shortest lane it adds.
pub struct Fill<'a> {
    /// The reachable clearance.
    pub clear: &'a Clearance<'a>,
    /// The reachable coverable cells.
    pub reach: &'a Reach,
    /// The scorer's raster.
    pub grid: &'a CoverageGrid,
    /// The robot.
    pub robot: Footprint,
    /// The shortest stretch added, in metres.
    pub min_lane_m: f64,
}

/// A queued candidate: its best stretch's cells per second when last read, and its index.
#[derive(Clone, Copy, PartialEq)]
struct Queued(f64, usize);

impl Eq for Queued {}

impl Ord for Queued {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.total_cmp(&other.0).then(other.1.cmp(&self.1))
    }
}

impl PartialOrd for Queued {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Fill<'_> {
    /// Adds stretches of lanes at `direction_deg` to `laid` until it sweeps `goal` of the
    /// reachable coverable cells, or no stretch of at least `min_lane_m` sweeps a robot
    /// square's worth of new cells.
    pub fn fill(&self, direction_deg: f64, laid: &mut Laid, goal: f64) {
        let target = (goal * self.reach.coverable_count() as f64).ceil() as usize;
        if laid.count >= target {
            return;
        }
        let mut candidates = self.candidates(direction_deg);
        candidates.extend(self.candidates(direction_deg + 90.0));
        let res = self.clear.map().resolution();
        let min_gain = ((self.robot.width / res).powi(2) / 4.0).ceil() as usize;
        let mut steps: Vec<usize> = Vec::new();
        let mut heap: BinaryHeap<Queued> = BinaryHeap::with_capacity(candidates.len());
        for (k, &c) in candidates.iter().enumerate() {
            if let Some((rate, _)) = self.best_stretch(c, laid, &mut steps, min_gain) {
                heap.push(Queued(rate, k));
            }
        }
        while laid.count < target
            && let Some(Queued(_, k)) = heap.pop()
        {
            let Some((rate, stretch)) = self.best_stretch(candidates[k], laid, &mut steps, min_gain) else {
                continue;
            };
            if heap.peek().is_some_and(|top| top.0 > rate) {
                heap.push(Queued(rate, k));
                continue;
            }
            laid.push(self.grid, self.reach, self.robot.width, stretch);
            heap.push(Queued(rate, k));
        }
    }

    /// The fitting pieces of the lines at `direction_deg` one map cell apart.
    fn candidates(&self, direction_deg: f64) -> Vec<LanePiece> {
        let res = self.clear.map().resolution();
        let (u, n) = axes(direction_deg);
        let (u_lo, u_hi, n_lo, n_hi) = extent(self.clear, u, n);
        let mut out = Vec::new();
        if u_lo > u_hi {
            return out;
        }
        let lines = ((n_hi - n_lo) / res).floor() as usize;
        for k in 0..=lines {
            let o = n_lo + k as f64 * res;
            let (start, end) = (
                crate::geom::Point::from(u * (u_lo - res) + n * o),
                crate::geom::Point::from(u * (u_hi + res) + n * o),
            );
            for (t0, t1) in self.clear.fitting_intervals(start, end, self.min_lane_m.max(res)) {
                out.push(LanePiece { a: start + (end - start) * t0, b: start + (end - start) * t1 });
            }
        }
        out
    }

    /// The stretch of `piece` that sweeps most cells `laid` leaves per second, with that rate:
    /// runs of steps (a map cell long) that sweep new cells, joined across gaps shorter than
    /// the minimum lane; `None` where no run is long enough or sweeps `min_gain` cells.
    fn best_stretch(
        &self,
        piece: LanePiece,
        laid: &Laid,
        steps: &mut Vec<usize>,
        min_gain: usize,
    ) -> Option<(f64, LanePiece)> {
        let res = self.clear.map().resolution();
        let n = (piece.length() / res).ceil().max(1.0) as usize;
        let at = |k: usize| piece.a + (piece.b - piece.a) * (k as f64 / n as f64);
        steps.clear();
        for k in 0..n {
            let mut new = 0usize;
            for_each_swept_cell(self.grid.raster(), at(k), at(k + 1), self.robot.width, |i| {
                new += usize::from(self.reach.is_coverable(i) && !laid.covered[i]);
            });
            steps.push(new);
        }
        let gap = (self.min_lane_m / res).ceil() as usize;
        let r = &self.robot;
        let turn_s = if r.rot_speed > 0.0 { std::f64::consts::PI / r.rot_speed } else { 0.0 };
        let mut best: Option<(f64, LanePiece)> = None;
        let mut k = 0;
        while k < n {
            if steps[k] == 0 {
                k += 1;
                continue;
            }
            let (first, mut last, mut gain) = (k, k, 0usize);
            while k < n && k - last <= gap {
                if steps[k] > 0 {
                    last = k;
                    gain += steps[k];
                }
                k += 1;
            }
            let stretch = LanePiece { a: at(first), b: at(last + 1) };
            let secs = (stretch.length() + r.width) / r.speed + turn_s;
            let rate = gain as f64 / secs;
            if stretch.length() >= self.min_lane_m && gain >= min_gain && best.is_none_or(|b| rate > b.0) {
                best = Some((rate, stretch));
            }
        }
        best
    }
}
