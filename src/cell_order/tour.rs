//! The tour problem the cell-order planner solves, apart from the map: cells, each with its
//! candidate sweeps (own time, exit and entry), leg times between any two candidates, and a
//! tour's mission time. A tour is a permutation of the cells plus one sweep choice per cell;
//! its time is the leg from the start station, every sweep and every leg between them, and
//! the leg to the end station (the generalised travelling-salesman problem of Bähnemann et al.
//! 2019 with sweeps as cluster members).

use crate::coverage::motion::abs_turn_deg;
use crate::geom::{Point, Vector};

/// One candidate sweep as the tour sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate {
    /// Its own time: length over speed plus its turning over the rotation speed.
    pub time_s: f64,
    /// Entry point and the heading the sweep starts with.
    pub entry: (Point, Vector),
    /// Exit point and the heading the sweep ends with.
    pub exit: (Point, Vector),
    /// The share of the reachable coverable cells it sweeps in its own cell's region.
    pub gain: f64,
    /// The part of `time_s` that charges the completion of what it leaves (not driven by the
    /// sweep itself).
    pub completion_s: f64,
}

/// The turning of a leg in radians: from the heading `from` onto the straight direction to the
/// next entry, then onto the heading `to` (just `from` onto `to` where the points coincide);
/// zero headings (a sweep of one point) add nothing. An estimate: the driven leg may bend.
pub fn leg_turn_rad(from: (Point, Vector), to: (Point, Vector)) -> f64 {
    let turn = |a: Vector, b: Vector| {
        if a.norm() < 1e-12 || b.norm() < 1e-12 { 0.0 } else { abs_turn_deg(a, b).to_radians() }
    };
    let v = to.0 - from.0;
    if v.norm() < crate::geom::ZERO_LENGTH { turn(from.1, to.1) } else { turn(from.1, v) + turn(v, to.1) }
}

/// The tour problem: candidates of every cell and the leg times between them.
#[derive(Clone, Debug)]
pub struct Instance {
    /// Index of each cell's first candidate in the flat candidate list; one more at the end.
    offsets: Vec<usize>,
    /// Every candidate's own time.
    own: Vec<f64>,
    /// Every candidate's share of the reachable coverable cells (its own region's).
    gain: Vec<f64>,
    /// Every candidate's completion charge, part of its own time.
    completion: Vec<f64>,
    /// Seconds of completion charged per unit share of the reachable cells a tour's sweeps
    /// leave (the rate of the candidates' charges; 0 when nothing is charged).
    pub completion_s_per_share: f64,
    /// Leg times between candidates, row = from, column = to (flat).
    legs: Vec<f32>,
    /// Leg time from the start station to each candidate.
    from_start: Vec<f64>,
    /// Leg time from each candidate to the end station.
    to_end: Vec<f64>,
    /// Start to end directly (a map without cells).
    pub start_to_end: f64,
}

impl Instance {
    /// An instance from per-cell candidates and a leg-time function over flat candidate
    /// indices, where `None` stands for a station (the start as a source, the end as a target).
    pub fn new(cells: &[Vec<Candidate>], leg: impl Fn(Option<usize>, Option<usize>) -> f64 + Sync) -> Self {
        let mut offsets = vec![0];
        for c in cells {
            offsets.push(offsets.last().expect("starts with 0") + c.len());
        }
        let n = *offsets.last().expect("starts with 0");
        let own = cells.iter().flatten().map(|c| c.time_s).collect();
        let gain = cells.iter().flatten().map(|c| c.gain).collect();
        let completion = cells.iter().flatten().map(|c| c.completion_s).collect();
        use rayon::prelude::*;
        let legs = (0..n)
            .into_par_iter()
            .flat_map_iter(|a| (0..n).map(move |b| (a, b)))
            .map(|(a, b)| leg(Some(a), Some(b)) as f32)
            .collect();
        Self {
            own,
            gain,
            completion,
            completion_s_per_share: 0.0,
            legs,
            from_start: (0..n).map(|b| leg(None, Some(b))).collect(),
            to_end: (0..n).map(|a| leg(Some(a), None)).collect(),
            start_to_end: leg(None, None),
            offsets,
        }
    }

    /// The number of cells.
    pub fn cells(&self) -> usize {
        self.offsets.len() - 1
    }

    /// The number of candidates of cell `k`.
    pub fn choices(&self, k: usize) -> usize {
        self.offsets[k + 1] - self.offsets[k]
    }

    /// The flat index of cell `k`'s candidate `c`.
    pub fn flat(&self, k: usize, c: usize) -> usize {
        self.offsets[k] + c
    }

    /// The own time of candidate `g` (flat).
    pub fn own(&self, g: usize) -> f64 {
        self.own[g]
    }

    /// The leg time between flat candidates (`None`: the start as `from`, the end as `to`).
    pub fn leg(&self, from: Option<usize>, to: Option<usize>) -> f64 {
        match (from, to) {
            (Some(a), Some(b)) => f64::from(self.legs[a * self.own.len() + b]),
            (None, Some(b)) => self.from_start[b],
            (Some(a), None) => self.to_end[a],
            (None, None) => self.start_to_end,
        }
    }

    /// The mission time of a tour.
    pub fn time(&self, tour: &Tour) -> f64 {
        let mut prev: Option<usize> = None;
        let mut t = 0.0;
        for &k in &tour.order {
            let g = self.flat(k as usize, tour.choice[k as usize] as usize);
            t += self.leg(prev, Some(g)) + self.own[g];
            prev = Some(g);
        }
        t + self.leg(prev, None)
    }

    /// The tour's cost as the search ranks it: its mission time, or with a coverage `goal`
    /// (a share of the reachable coverable cells) [`Instance::time_to_goal`].
    pub fn cost(&self, tour: &Tour, goal: Option<f64>) -> f64 {
        goal.map_or_else(|| self.time(tour), |g| self.time_to_goal(tour, g))
    }

    /// When the tour reaches the coverage `goal`: each candidate adds its gain evenly over the
    /// time it drives (its own time less its completion charge; legs add none), and what the
    /// sweeps leave below the goal is charged at [`Instance::completion_s_per_share`] after
    /// the last sweep. With no charge, a tour that never reaches the goal costs
    /// [`UNREACHED_S`] per unit of shortfall plus [`UNREACHED_S`] plus its whole time: behind
    /// every tour that does.
    pub fn time_to_goal(&self, tour: &Tour, goal: f64) -> f64 {
        let mut prev: Option<usize> = None;
        let (mut t, mut covered) = (0.0, 0.0);
        for &k in &tour.order {
            let g = self.flat(k as usize, tour.choice[k as usize] as usize);
            t += self.leg(prev, Some(g));
            let (gain, driven) = (self.gain[g], self.own[g] - self.completion[g]);
            if gain > 0.0 && covered + gain >= goal {
                return t + driven * ((goal - covered) / gain).clamp(0.0, 1.0);
            }
            covered += gain;
            t += driven;
            prev = Some(g);
        }
        if covered >= goal {
            return t;
        }
        if self.completion_s_per_share > 0.0 {
            return t + (goal - covered) * self.completion_s_per_share;
        }
        UNREACHED_S * (1.0 + goal - covered) + t + self.leg(prev, None)
    }

    /// The flat candidate at position `i` of `tour` (`None` before the first and after the last).
    pub fn at(&self, tour: &Tour, i: isize) -> Option<usize> {
        if i < 0 || i as usize >= tour.order.len() {
            return None;
        }
        let k = tour.order[i as usize] as usize;
        Some(self.flat(k, tour.choice[k] as usize))
    }
}

/// The cost floor of a tour that never reaches its coverage goal, in seconds: above any
/// mission time a map of [`super::MAX_CANDIDATES`] sweeps can take.
pub const UNREACHED_S: f64 = 1e12;

/// A tour: the cells in visiting order and each cell's sweep choice (indexed by cell).
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct Tour {
    /// Cells in the order they are swept.
    pub order: Vec<u32>,
    /// Per cell, the index of its chosen candidate.
    pub choice: Vec<u16>,
}

/// The rotation-aware leg time: transit length over speed plus the estimated turning over the
/// rotation speed (003 eqs. 3.1–3.3 applied to the leg).
pub fn leg_time(metres: f64, turn_rad: f64, speed: f64, rot_speed: f64) -> f64 {
    crate::coverage::motion::drive_time_s(metres, turn_rad, speed, rot_speed)
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// A small instance on a line: cell k at x = 10k with two candidates (left to right or
    /// right to left, 1 m long), legs the straight distance at 1 m/s, no turning.
    pub fn line(n: usize) -> Instance {
        let cells: Vec<Vec<Candidate>> = (0..n)
            .map(|k| {
                let (a, b) = (Point::new(10.0 * k as f64, 0.0), Point::new(10.0 * k as f64 + 1.0, 0.0));
                let z = Vector::zeros();
                vec![
                    Candidate { time_s: 1.0, entry: (a, z), exit: (b, z), gain: 1.0 / n as f64, completion_s: 0.0 },
                    Candidate { time_s: 1.0, entry: (b, z), exit: (a, z), gain: 1.0 / n as f64, completion_s: 0.0 },
                ]
            })
            .collect();
        let flat: Vec<Candidate> = cells.iter().flatten().copied().collect();
        let station = Point::new(-5.0, 0.0);
        Instance::new(&cells, |a, b| {
            let p = a.map_or(station, |a| flat[a].exit.0);
            let q = b.map_or(station, |b| flat[b].entry.0);
            (q - p).norm()
        })
    }

    #[test]
    fn the_time_of_a_tour_is_legs_plus_sweeps() {
        let inst = line(3);
        let tour = Tour { order: vec![0, 1, 2], choice: vec![0, 0, 0] };
        // 5 to the first, 3 × 1 m sweeps, 2 × 9 m legs, 26 m back.
        assert!((inst.time(&tour) - (5.0 + 3.0 + 18.0 + 26.0)).abs() < 1e-9);
        let reversed = Tour { order: vec![2, 1, 0], choice: vec![1, 1, 1] };
        assert!((inst.time(&reversed) - (26.0 + 3.0 + 18.0 + 5.0)).abs() < 1e-9);
        let zigzag = Tour { order: vec![1, 0, 2], choice: vec![0, 0, 0] };
        assert!(inst.time(&zigzag) > inst.time(&tour));
    }

    #[test]
    fn time_to_goal_stops_inside_the_sweep_that_reaches_it() {
        let inst = line(4);
        let tour = Tour { order: vec![0, 1, 2, 3], choice: vec![0; 4] };
        // Each cell a quarter: half the goal is reached at the end of the second sweep (5 + 1 +
        // 9 + 1), 0.6 a tenth of the way (0.4 of its 1 s) into the third.
        assert!((inst.time_to_goal(&tour, 0.5) - 16.0).abs() < 1e-9);
        assert!((inst.time_to_goal(&tour, 0.6) - (16.0 + 9.0 + 0.4)).abs() < 1e-9);
        // The whole map: the whole tour but the way back.
        assert!((inst.time_to_goal(&tour, 1.0) - (inst.time(&tour) - 36.0)).abs() < 1e-9);
        assert_eq!(inst.cost(&tour, None), inst.time(&tour));
        // Beyond what the sweeps cover: behind every tour that reaches its goal, by shortfall.
        let short = inst.time_to_goal(&tour, 1.2);
        assert!(short > UNREACHED_S && short < inst.time_to_goal(&tour, 1.3));
        // With a completion rate, the shortfall is charged at it after the last sweep.
        let charged = Instance { completion_s_per_share: 100.0, ..inst.clone() };
        assert!((charged.time_to_goal(&tour, 1.2) - (inst.time(&tour) - 36.0 + 20.0)).abs() < 1e-9);
    }

    #[test]
    fn leg_turns_follow_eq_3_2() {
        let (x, y) = (Vector::new(1.0, 0.0), Vector::new(0.0, 1.0));
        // Straight on: nothing; a U-turn back along the next lane: 180°.
        assert!(leg_turn_rad((Point::new(0.0, 0.0), x), (Point::new(1.0, 0.0), x)).abs() < 1e-12);
        let u = leg_turn_rad((Point::new(1.0, 0.0), x), (Point::new(1.0, 1.0), -x));
        assert!((u - std::f64::consts::PI).abs() < 1e-12);
        // Same point: the heading change alone.
        let q = leg_turn_rad((Point::new(1.0, 0.0), x), (Point::new(1.0, 0.0), y));
        assert!((q - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert_eq!(leg_turn_rad((Point::new(1.0, 0.0), Vector::zeros()), (Point::new(1.0, 0.0), y)), 0.0);
    }
}
