//! The searched completion (`completion = "quota_search"`): the quota completion's pieces
//! ([`super::quota::pieces`]), but which of them to cover, in which order and which way round is
//! decided by a local search of their time with the legs between them — transit over speed plus
//! the turning at both ends of every leg (003 eqs. 3.1–3.3), which the quota heuristic's
//! cheapest-per-cell rule does not see. The goal is a quota: a plan stops once it covers the
//! share it must, so a piece far from the others may be left for one nearer that covers as much.
//!
//! The search starts from the quota heuristic's choice in its turn-aware order and takes a move
//! only where it shortens that time while the chosen pieces still cover what the goal needs, so
//! it never ends worse than its start on its own cost. Moves: a piece moved to its best place
//! and direction (Or-opt with flips), a stretch of the order reversed (2-opt), a piece dropped,
//! and a piece brought in with the pieces it makes unnecessary dropped. It draws no random
//! number: every plan of a configuration gets the same completion. The legs are straight-line
//! estimates; the path drives them round the walls.

use super::quota::Piece;
use super::tour::{leg_time, leg_turn_rad};
use crate::geom::{Point, Vector};

/// Rounds of all moves at most; each round that improves nothing ends the search.
pub const ROUNDS: usize = 50;

/// Where a piece driven one way starts and ends, with the headings it starts and ends with.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Drive {
    entry: (Point, Vector),
    exit: (Point, Vector),
}

/// A piece of the plan: its index and the way round it is driven (0 as found, 1 reversed).
type Step = (usize, u8);

/// The search's problem: the pieces, both ways round, where the sweeps end, and the robot's
/// speeds.
struct Problem<'a> {
    pieces: &'a [Piece],
    drives: Vec<[Drive; 2]>,
    start: (Point, Vector),
    speed: f64,
    rot_speed: f64,
}

impl Problem<'_> {
    /// The leg time from `from` (a step, or the start where `None`) to step `to`.
    fn leg(&self, from: Option<Step>, to: Step) -> f64 {
        let a = from.map_or(self.start, |(k, d)| self.drives[k][d as usize].exit);
        let b = self.drives[to.0][to.1 as usize].entry;
        leg_time((b.0 - a.0).norm(), leg_turn_rad(a, b), self.speed, self.rot_speed)
    }

    /// The time of a plan: its legs and its pieces' own times.
    fn time(&self, plan: &[Step]) -> f64 {
        let mut prev = None;
        let mut t = 0.0;
        for &s in plan {
            t += self.leg(prev, s) + self.pieces[s.0].time_s;
            prev = Some(s);
        }
        t
    }

    /// The best place and direction for piece `k` in `plan`: the position it goes before
    /// (`plan.len()`: at the end), its direction and the time it adds.
    fn best_insertion(&self, plan: &[Step], k: usize) -> (usize, u8, f64) {
        let mut best = (plan.len(), 0, f64::INFINITY);
        for pos in 0..=plan.len() {
            let prev = pos.checked_sub(1).map(|i| plan[i]);
            let next = plan.get(pos).copied();
            let old = next.map_or(0.0, |n| self.leg(prev, n));
            for d in 0..2u8 {
                let new = self.leg(prev, (k, d)) + next.map_or(0.0, |n| self.leg(Some((k, d)), n));
                let added = new - old + self.pieces[k].time_s;
                if added < best.2 - 1e-9 {
                    best = (pos, d, added);
                }
            }
        }
        best
    }

    /// The time saved by taking the step at `i` out of `plan`.
    fn removal_saving(&self, plan: &[Step], i: usize) -> f64 {
        let prev = i.checked_sub(1).map(|j| plan[j]);
        let s = plan[i];
        let next = plan.get(i + 1).copied();
        let old = self.leg(prev, s) + next.map_or(0.0, |n| self.leg(Some(s), n));
        let new = next.map_or(0.0, |n| self.leg(prev, n));
        old + self.pieces[s.0].time_s - new
    }
}

/// How many chosen pieces cover each target cell, and how many targets are covered.
struct Cover {
    count: Vec<u16>,
    covered: usize,
}

impl Cover {
    fn add(&mut self, piece: &Piece) {
        for &i in &piece.cells {
            self.covered += usize::from(self.count[i as usize] == 0);
            self.count[i as usize] += 1;
        }
    }

    fn remove(&mut self, piece: &Piece) {
        for &i in &piece.cells {
            self.count[i as usize] -= 1;
            self.covered -= usize::from(self.count[i as usize] == 0);
        }
    }

    /// The targets only `piece` covers among the chosen ones.
    fn only(&self, piece: &Piece) -> usize {
        piece.cells.iter().filter(|&&i| self.count[i as usize] == 1).count()
    }
}

/// The pieces to cover and how: starting from `chosen` (the quota heuristic's pieces, in the
/// order given or each put in its cheapest place, whichever is faster), a plan from `start` (a
/// point and the heading the sweeps end with) that covers at least `needed` of the target cells
/// (`cells` map cells; all that `chosen` covers, where that is fewer) in no longer an estimated
/// time, as (piece, reversed) pairs.
pub fn search(
    pieces: &[Piece],
    chosen: &[usize],
    needed: usize,
    cells: usize,
    start: (Point, Vector),
    robot: &crate::coverage::Footprint,
) -> Vec<(usize, bool)> {
    let drives = pieces.iter().map(|p| drives_of(&p.points)).collect();
    let problem = Problem { pieces, drives, start, speed: robot.speed, rot_speed: robot.rot_speed };
    let mut cover = Cover { count: vec![0; cells], covered: 0 };
    let mut built: Vec<Step> = Vec::with_capacity(chosen.len());
    for &k in chosen {
        cover.add(&pieces[k]);
        let (pos, d, _) = problem.best_insertion(&built, k);
        built.insert(pos, (k, d));
    }
    let given: Vec<Step> = chosen.iter().map(|&k| (k, 0)).collect();
    let mut plan = if problem.time(&built) < problem.time(&given) { built } else { given };
    let needed = needed.min(cover.covered);
    for _ in 0..ROUNDS {
        let before = problem.time(&plan);
        or_opt(&problem, &mut plan);
        two_opt(&problem, &mut plan);
        drop_unneeded(&problem, &mut plan, &mut cover, needed);
        bring_in(&problem, &mut plan, &mut cover, needed);
        if problem.time(&plan) >= before - 1e-9 {
            break;
        }
    }
    plan.into_iter().map(|(k, d)| (k, d == 1)).collect()
}

/// Both ways round a piece's points: entry and exit with the headings of its first and last
/// segments (zero for a piece of one point).
fn drives_of(points: &[Point]) -> [Drive; 2] {
    let heading = |a: Point, b: Point| {
        let v = b - a;
        if v.norm() < crate::geom::ZERO_LENGTH { Vector::zeros() } else { v.normalize() }
    };
    let n = points.len();
    let (first, last) = (points[0], points[n - 1]);
    let (h0, h1) = if n < 2 {
        (Vector::zeros(), Vector::zeros())
    } else {
        (heading(points[0], points[1]), heading(points[n - 2], points[n - 1]))
    };
    [Drive { entry: (first, h0), exit: (last, h1) }, Drive { entry: (last, -h1), exit: (first, -h0) }]
}

/// Each step moved to its best place and direction while that saves time.
fn or_opt(problem: &Problem, plan: &mut Vec<Step>) {
    let mut i = 0;
    while i < plan.len() {
        let saving = problem.removal_saving(plan, i);
        let step = plan.remove(i);
        let (pos, d, added) = problem.best_insertion(plan, step.0);
        if added < saving - 1e-9 {
            plan.insert(pos, (step.0, d));
        } else {
            plan.insert(i, step);
        }
        i += 1;
    }
}

/// Stretches of the plan reversed (every piece in them turned round) while that saves time.
fn two_opt(problem: &Problem, plan: &mut [Step]) {
    let flip = |(k, d): Step| (k, 1 - d);
    let n = plan.len();
    for i in 0..n {
        for j in i + 1..n {
            let prev = i.checked_sub(1).map(|p| plan[p]);
            let next = plan.get(j + 1).copied();
            // A leg driven backwards between the turned pieces has the same length and turns
            // (`leg_turn_rad` counts turns by their size), so only the two outer legs change.
            let old = problem.leg(prev, plan[i]) + next.map_or(0.0, |s| problem.leg(Some(plan[j]), s));
            let new = problem.leg(prev, flip(plan[j])) + next.map_or(0.0, |s| problem.leg(Some(flip(plan[i])), s));
            if new < old - 1e-9 {
                plan[i..=j].reverse();
                for s in &mut plan[i..=j] {
                    *s = flip(*s);
                }
            }
        }
    }
}

/// The pieces the goal does not need dropped, the largest saving first.
fn drop_unneeded(problem: &Problem, plan: &mut Vec<Step>, cover: &mut Cover, needed: usize) -> f64 {
    let mut saved = 0.0;
    loop {
        let best = (0..plan.len())
            .filter(|&i| cover.covered - cover.only(&problem.pieces[plan[i].0]) >= needed)
            .map(|i| (i, problem.removal_saving(plan, i)))
            .filter(|&(_, s)| s > 1e-9)
            .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)));
        let Some((i, s)) = best else { return saved };
        cover.remove(&problem.pieces[plan[i].0]);
        plan.remove(i);
        saved += s;
    }
}

/// Each piece not in the plan tried at its best place, with the pieces it makes unnecessary
/// dropped; kept where that saves time.
fn bring_in(problem: &Problem, plan: &mut Vec<Step>, cover: &mut Cover, needed: usize) {
    let mut inside = vec![false; problem.pieces.len()];
    for &(k, _) in plan.iter() {
        inside[k] = true;
    }
    for k in 0..problem.pieces.len() {
        if inside[k] || problem.pieces[k].cells.is_empty() {
            continue;
        }
        let (pos, d, added) = problem.best_insertion(plan, k);
        let mut trial = plan.clone();
        trial.insert(pos, (k, d));
        cover.add(&problem.pieces[k]);
        let saved = drop_unneeded(problem, &mut trial, cover, needed);
        if saved > added + 1e-9 {
            for &(j, _) in plan.iter() {
                inside[j] = false;
            }
            *plan = trial;
            for &(j, _) in plan.iter() {
                inside[j] = true;
            }
        } else {
            // Undo: the dropped pieces back, the new one out (unless it was dropped itself).
            let kept: Vec<usize> = trial.iter().map(|s| s.0).collect();
            for &(j, _) in plan.iter() {
                if !kept.contains(&j) {
                    cover.add(&problem.pieces[j]);
                }
            }
            if kept.contains(&k) {
                cover.remove(&problem.pieces[k]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn piece(points: &[(f64, f64)], cells: &[u32]) -> Piece {
        let points: Vec<Point> = points.iter().map(|&(x, y)| Point::new(x, y)).collect();
        let time_s = crate::coverage::motion::path_length(&points);
        Piece { points, cells: cells.to_vec(), time_s }
    }

    fn robot(rot_speed: f64) -> crate::coverage::Footprint {
        crate::coverage::Footprint { width: 0.5, speed: 1.0, rot_speed }
    }

    fn time(pieces: &[Piece], plan: &[(usize, bool)], start: (Point, Vector), rot_speed: f64) -> f64 {
        let problem = Problem {
            pieces,
            drives: pieces.iter().map(|p| drives_of(&p.points)).collect(),
            start,
            speed: 1.0,
            rot_speed,
        };
        problem.time(&plan.iter().map(|&(k, r)| (k, u8::from(r))).collect::<Vec<_>>())
    }

    #[test]
    fn a_far_piece_is_left_for_a_near_one_that_covers_as_much() {
        // The quota heuristic takes the far piece (cheaper per cell on its own); the near one
        // covers as many cells and is next to where the sweeps end.
        let pieces = [piece(&[(100.0, 0.0), (101.0, 0.0)], &[0, 1, 2]), piece(&[(1.0, 0.0), (2.5, 0.0)], &[3, 4, 5])];
        let start = (Point::origin(), Vector::new(1.0, 0.0));
        let plan = search(&pieces, &[0], 3, 6, start, &robot(1.0));
        assert_eq!(plan, vec![(1, false)]);
        assert!(time(&pieces, &plan, start, 1.0) < time(&pieces, &[(0, false)], start, 1.0));
    }

    #[test]
    fn pieces_are_turned_and_ordered_so_that_the_robot_drives_on() {
        // Three pieces on a line, found right to left and out of order: driven left to right.
        let pieces = [
            piece(&[(6.0, 0.0), (4.0, 0.0)], &[0]),
            piece(&[(3.0, 0.0), (1.0, 0.0)], &[1]),
            piece(&[(9.0, 0.0), (7.0, 0.0)], &[2]),
        ];
        let start = (Point::origin(), Vector::new(1.0, 0.0));
        let plan = search(&pieces, &[0, 1, 2], 3, 3, start, &robot(0.5));
        assert_eq!(plan, vec![(1, true), (0, true), (2, true)]);
        assert!((time(&pieces, &plan, start, 0.5) - 9.0).abs() < 1e-9, "straight on, no turning");
    }

    #[test]
    fn the_goal_is_kept_and_the_start_never_beaten_by_a_worse_plan() {
        // Pieces scattered on a ring round the start: whatever the search keeps covers the goal
        // and takes no longer than the quota's choice in its best order.
        let pieces: Vec<Piece> = (0..12)
            .map(|k| {
                let a = k as f64 * 0.5;
                let (x, y) = (10.0 * a.cos(), 10.0 * a.sin());
                piece(&[(x, y), (x + 1.0, y + 0.5)], &[k, k + 1])
            })
            .collect();
        let start = (Point::origin(), Vector::zeros());
        for needed in [1, 5, 8, 13] {
            let chosen: Vec<usize> = (0..12).rev().collect();
            let plan = search(&pieces, &chosen, needed, 13, start, &robot(0.52));
            let mut covered = [false; 13];
            for &(k, _) in &plan {
                for &i in &pieces[k].cells {
                    covered[i as usize] = true;
                }
            }
            assert!(covered.iter().filter(|&&c| c).count() >= needed, "{needed}: {plan:?}");
            if needed == 1 {
                assert_eq!(plan.len(), 1, "one piece covers the goal: {plan:?}");
            }
            let seed: Vec<(usize, bool)> = chosen.iter().map(|&k| (k, false)).collect();
            assert!(time(&pieces, &plan, start, 0.52) <= time(&pieces, &seed, start, 0.52) + 1e-9, "{needed}");
        }
    }
}
