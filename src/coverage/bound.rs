//! Lower bounds on the time any plan needs to cover a given area, in the scorer's time model
//! (003 eqs. 3.1–3.3: length / speed + turning / rot_speed), written beside every plan's time
//! so that a time reads as "× the bound".
//!
//! - **The area bound**: driving straight is the fastest the footprint sweeps new ground, and
//!   turning in place sweeps none, so covering `A` m² takes at least `A / (width · speed)`.
//! - **The turning bound**: a segment sweeps the cells in its rectangle of width `width`, with no
//!   end caps (003 §3.1.2), so a path that covers `A` m² is at least `L = A / width` long. Cut
//!   the path greedily into pieces whose own turning stays within an angle `θ < π`: every
//!   heading of a piece lies within `θ / 2` of one direction, so the piece advances at least
//!   `cos(θ / 2)` of its length along it, and since it stays inside the free space, a piece is
//!   at most `D / cos(θ / 2)` long, `D` the free space's diameter.
//!   So there are at least `k = ⌈L · cos(θ / 2) / D⌉` pieces, and each of the `k − 1` cuts
//!   spends more than `θ` of turning (the piece's own and the turn at the cut). Any `θ` gives a
//!   valid bound `(k − 1) · θ`; [`min_turning_rad`] takes the best of a fine set of them.
//!
//! Both hold for any path that stays in the free space (an executable plan; a plan that crosses
//! walls may beat the turning bound), in the continuous model (up to the grid's discretisation
//! of the covered area). The turning bound is weak where the map is large and its rooms narrow: it
//! knows only the diameter, not the rooms, so it proves the turns a long sweep cannot avoid,
//! not the many a room of short lanes makes.

use crate::geom::Point;
use crate::map::GridMap;

/// Directions sampled for the diameter, over half a turn.
const DIAMETER_DIRECTIONS: usize = 360;
/// Cut angles tried for the turning bound, in (0, π).
const CUT_ANGLES: usize = 720;

/// The time to sweep `area_m2` at `sweep_rate_m2_s` (Σ width × speed) driving straight: the
/// area bound.
pub fn area_time_s(area_m2: f64, sweep_rate_m2_s: f64) -> f64 {
    area_m2 / sweep_rate_m2_s
}

/// The shortest path that covers `area_m2` with a footprint `width` wide: `A / width`, since a
/// segment sweeps its rectangle and no end caps (003 §3.1.2).
pub fn min_length_m(area_m2: f64, width: f64) -> f64 {
    area_m2 / width
}

/// The least turning, in radians, of any path `length_m` long inside a region of diameter
/// `diameter_m`: the best over cut angles `θ` of `(⌈L · cos(θ/2) / D⌉ − 1) · θ` (the module's
/// argument). Zero where the path fits in one straight piece.
pub fn min_turning_rad(length_m: f64, diameter_m: f64) -> f64 {
    if diameter_m <= 0.0 || length_m <= 0.0 {
        return 0.0;
    }
    (1..CUT_ANGLES)
        .map(|i| {
            let theta = std::f64::consts::PI * i as f64 / CUT_ANGLES as f64;
            let pieces = (length_m * (theta / 2.0).cos() / diameter_m).ceil();
            (pieces - 1.0).max(0.0) * theta
        })
        .fold(0.0, f64::max)
}

/// An upper bound on the diameter of `map`'s free space in metres: the widest extent of its free
/// cells (as squares) over 360 directions in half a turn, divided by the cosine of half
/// the step between directions, which the true diameter's direction lies within.
pub fn free_diameter_m(map: &GridMap) -> f64 {
    let half = map.resolution() / 2.0;
    let centres: Vec<Point> = (0..map.rows())
        .flat_map(|r| (0..map.cols()).map(move |c| (r, c)))
        .filter(|&(r, c)| map.is_free(r, c))
        .map(|(r, c)| map.cell_centre(r, c))
        .collect();
    if centres.is_empty() {
        return 0.0;
    }
    let step = std::f64::consts::PI / DIAMETER_DIRECTIONS as f64;
    let widest = (0..DIAMETER_DIRECTIONS)
        .map(|i| {
            let (s, c) = (i as f64 * step).sin_cos();
            let (lo, hi) = centres.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                let x = p.x * c + p.y * s;
                (lo.min(x), hi.max(x))
            });
            hi - lo + 2.0 * half * (c.abs() + s.abs())
        })
        .fold(0.0, f64::max);
    widest / (step / 2.0).cos()
}

/// The lower bound on the time to cover `area_m2` of a map of free-space diameter
/// `diameter_m` with one robot, in seconds, as its two terms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeBound {
    /// The area bound, `A / (width · speed)`.
    pub area_s: f64,
    /// The turning bound's time, [`min_turning_rad`] of the shortest covering path over
    /// `rot_speed` (zero where turning is free).
    pub turning_s: f64,
}

impl TimeBound {
    /// The bound for one robot of `width` m, `speed` m/s and `rot_speed` rad/s (0: free turning).
    pub fn one_robot(area_m2: f64, (width, speed, rot_speed): (f64, f64, f64), diameter_m: f64) -> Self {
        let turning_s =
            if rot_speed > 0.0 { min_turning_rad(min_length_m(area_m2, width), diameter_m) / rot_speed } else { 0.0 };
        Self { area_s: area_time_s(area_m2, width * speed), turning_s }
    }

    /// The bound in seconds: both terms.
    pub fn total_s(&self) -> f64 {
        self.area_s + self.turning_s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_that_fits_in_one_piece_needs_no_turning() {
        // 9 m inside a 10 m region: one straight piece would do.
        assert_eq!(min_turning_rad(9.0, 10.0), 0.0);
        assert_eq!(min_turning_rad(0.0, 10.0), 0.0);
        assert_eq!(min_turning_rad(5.0, 0.0), 0.0);
    }

    #[test]
    fn a_path_longer_than_the_region_turns_at_least_a_right_angle_or_more() {
        // 25 m in a 10 m region: with θ = π/2 a piece is at most 10/cos(π/4) ≈ 14.1 m, so two
        // pieces and at least π/2 of turning; a boustrophedon of 3 lanes turns 2π.
        let t = min_turning_rad(25.0, 10.0);
        assert!(t >= std::f64::consts::FRAC_PI_2 - 1e-9, "{t}");
        assert!(t <= 2.0 * std::f64::consts::PI, "{t}");
    }

    #[test]
    fn the_turning_bound_grows_about_linearly_with_length() {
        // The best θ·cos(θ/2) is about 1.122, so the bound tends to 1.12 · L / D.
        let (a, b) = (min_turning_rad(1000.0, 10.0), min_turning_rad(2000.0, 10.0));
        assert!((a / 100.0 - 1.122).abs() < 0.03, "{a}");
        assert!(b > 1.9 * a && b < 2.1 * a, "{a} {b}");
    }

    /// The bound holds for real paths: boustrophedons of a square room, their turning
    /// measured as the scorer does (003 eq. 3.2).
    #[test]
    fn boustrophedons_of_a_square_turn_more_than_the_bound() {
        for lanes in [2usize, 5, 12, 40] {
            let (side, width) = (10.0, 10.0 / lanes as f64);
            let mut path = Vec::new();
            for i in 0..lanes {
                let y = width * (i as f64 + 0.5);
                let (a, b) =
                    if i % 2 == 0 { (0.5 * width, side - 0.5 * width) } else { (side - 0.5 * width, 0.5 * width) };
                path.push(Point::new(a, y));
                path.push(Point::new(b, y));
            }
            let (turn, _) = crate::coverage::motion::turning(&path);
            let length = crate::coverage::motion::path_length(&path);
            let bound = min_turning_rad(length, side * std::f64::consts::SQRT_2);
            assert!(bound <= turn + 1e-9, "{lanes} lanes: bound {bound} > turning {turn}");
        }
    }

    #[test]
    fn the_diameter_of_a_free_rectangle_is_its_diagonal() {
        use crate::map::CellState;
        // 8 m × 6 m, all free: diagonal 10 m; with a wall column in the middle, the same.
        let (cols, rows) = (80, 60);
        let free = GridMap::new("r", cols, rows, 0.1, Point::origin(), vec![CellState::Free; cols * rows]).unwrap();
        let d = free_diameter_m(&free);
        assert!((10.0..=10.0 * 1.0001).contains(&d), "{d}");
        let mut cells = vec![CellState::Free; cols * rows];
        (0..rows).for_each(|r| cells[r * cols + 40] = CellState::Occupied);
        assert!(
            (free_diameter_m(&GridMap::new("w", cols, rows, 0.1, Point::origin(), cells).unwrap()) - d).abs() < 1e-9
        );
        // Only the lower-left quarter free: half the diagonal.
        let cells = (0..rows * cols)
            .map(|i| if i / cols < 30 && i % cols < 40 { CellState::Free } else { CellState::Occupied })
            .collect();
        let quarter = free_diameter_m(&GridMap::new("q", cols, rows, 0.1, Point::origin(), cells).unwrap());
        assert!((5.0..=5.0 * 1.0001).contains(&quarter), "{quarter}");
    }

    #[test]
    fn free_turning_adds_nothing() {
        let free = TimeBound::one_robot(100.0, (0.6, 0.3, 0.0), 10.0);
        assert_eq!(free.turning_s, 0.0);
        assert!((free.total_s() - 100.0 / 0.18).abs() < 1e-9);
        let turning = TimeBound::one_robot(100.0, (0.6, 0.3, 0.52), 10.0);
        assert!(turning.turning_s > 0.0 && turning.area_s == free.area_s);
    }
}
