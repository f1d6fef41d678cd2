//! Lower bounds on the time any plan needs to cover a given area, in the scorer's time model
//! (003 eqs. 3.1–3.3: length / speed + turning / rot_speed), written beside every plan's time
//! so that a time reads as "× the bound". They hold for **every path the scorer can score**, at
//! any cell size and width, wall-crossing paths included, because they count what the scorer
//! counts: cells whose centres a segment's rectangle holds. The book's page
//! `docs/src/concepts/lower-bound.md` gives the proofs below in full, what each term counts,
//! why the length term keeps `w + √2·r` per metre (a strip holds `w + r`, but that is not
//! proved for every path) and the test over every committed run.
//!
//! Notation: `w` the robot's width, `r` the cell size, `A` the area of the cells to cover (their
//! count × `r²`), `K` the disc of radius `w/2` grown by a cell square of side `r` (area
//! `π w²/4 + 2 r w + r²`, width at most `w + √2·r` across any direction).
//!
//! - **The length bound**: a segment sweeps the cell centres of its rectangle of width `w`
//!   (003 §3.1.2, no end caps), all within `w/2` of the segment; so the cell squares a path
//!   covers lie inside the path grown by `K`. A polyline of length `L` grown by a convex `K`
//!   has area at most `L · (w + √2·r) + area(K)` (each segment adds its length times `K`'s
//!   width across it, and the start adds `K`). Cell squares do not overlap, so
//!   `A ≤ L · (w + √2·r) + area(K)` and `L ≥ (A − area(K)) / (w + √2·r)`. Turning in place
//!   sweeps nothing, so the time is at least `L / speed`. On cells much finer than the robot
//!   this is `A / (w · speed)`; on coarse cells it is what a strip of centres allows (lanes
//!   `w + r` apart can each sweep `w + r` of centres per metre on a grid).
//! - **The turning bound**: cut the path greedily into pieces whose own turning stays below
//!   `θ < π`; a piece's headings lie within `θ / 2` of one direction `u`, so it advances at least
//!   `cos(θ / 2)` of its length along `u`. Only its part within `w/2` (along `u`) of the cells'
//!   extent `D` covers anything, which is at most `(D + w) / cos(θ / 2)` long; so a piece covers
//!   at most `a(θ) = (w + √2·r) · (D + w) / cos(θ / 2) + area(K)`. There are at least
//!   `k = ⌈A / a(θ)⌉` pieces and each of the `k − 1` cuts spends at least `θ` (a piece's own
//!   turning and the turn at the cut). Any `θ` gives a valid bound `(k − 1) · θ`;
//!   [`min_turning_rad`] takes the best of a fine set of them. `D` is an upper bound on the
//!   diameter of the map's free cells ([`free_diameter_m`]), so no path, inside the free space
//!   or not, escapes it.
//!
//! The turning bound is weak where the map is large and its rooms narrow: it knows only the
//! diameter, not the rooms, so it proves the turns a long sweep cannot avoid, not the many a
//! room of short lanes makes. A fleet's makespan bound is the length bound over the robots'
//! summed rates (each robot covers at most its own `(w_i + √2·r) · speed_i · T + area(K_i)`).

use crate::geom::Point;
use crate::map::GridMap;
use std::f64::consts::{PI, SQRT_2};

/// Directions sampled for the diameter, over half a turn.
const DIAMETER_DIRECTIONS: usize = 360;
/// Cut angles tried for the turning bound, in (0, π).
const CUT_ANGLES: usize = 720;

/// The most area of cell squares a path can add per metre driven: `K`'s widest extent,
/// `w + √2·r` (the module's length bound).
pub fn sweep_width_m(width: f64, resolution: f64) -> f64 {
    width + SQRT_2 * resolution
}

/// The area of cell squares a path's start adds before it drives: `area(K) = π w²/4 + 2 r w + r²`
/// (the disc of radius `w/2` grown by a cell square).
pub fn start_area_m2(width: f64, resolution: f64) -> f64 {
    PI * width * width / 4.0 + 2.0 * resolution * width + resolution * resolution
}

/// The shortest path whose sweep can cover `area_m2` of cells `resolution` m wide with a
/// footprint `width` wide: `(A − area(K)) / (w + √2·r)`, never below zero.
pub fn min_length_m(area_m2: f64, width: f64, resolution: f64) -> f64 {
    ((area_m2 - start_area_m2(width, resolution)) / sweep_width_m(width, resolution)).max(0.0)
}

/// The least time robots `(width, speed)` need, all driving at once, before their sweeps can
/// cover `area_m2` of cells `resolution` m wide: the length bound over their summed rates,
/// `(A − Σ area(K_i)) / Σ (w_i + √2·r) · speed_i` (the makespan of a fleet; one robot's
/// `min_length_m / speed`).
pub fn area_time_s(area_m2: f64, robots: &[(f64, f64)], resolution: f64) -> f64 {
    let rate: f64 = robots.iter().map(|&(w, v)| sweep_width_m(w, resolution) * v).sum();
    let start: f64 = robots.iter().map(|&(w, _)| start_area_m2(w, resolution)).sum();
    if rate > 0.0 { ((area_m2 - start) / rate).max(0.0) } else { 0.0 }
}

/// The least turning, in radians, of any path whose sweep covers `area_m2` of cells
/// `resolution` m wide with a footprint `width` wide, on a map whose free cells span at most
/// `diameter_m`: the best over cut angles `θ` of `(⌈A / a(θ)⌉ − 1) · θ` (the module's
/// argument). Zero where one piece could cover it all.
pub fn min_turning_rad(area_m2: f64, width: f64, resolution: f64, diameter_m: f64) -> f64 {
    if diameter_m <= 0.0 || area_m2 <= 0.0 {
        return 0.0;
    }
    let (per_metre, start) = (sweep_width_m(width, resolution), start_area_m2(width, resolution));
    (1..CUT_ANGLES)
        .map(|i| {
            let theta = PI * i as f64 / CUT_ANGLES as f64;
            let per_piece = per_metre * (diameter_m + width) / (theta / 2.0).cos() + start;
            let pieces = (area_m2 / per_piece).ceil();
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

/// The lower bound on the time one robot needs to cover `area_m2` of cells `resolution` m wide
/// on a map of free-space diameter `diameter_m`, in seconds, as its two terms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeBound {
    /// The length bound's time, [`min_length_m`] over `speed`.
    pub area_s: f64,
    /// The turning bound's time, [`min_turning_rad`] over `rot_speed` (zero where turning is
    /// free).
    pub turning_s: f64,
}

impl TimeBound {
    /// The bound for one robot of `width` m, `speed` m/s and `rot_speed` rad/s (0: free turning)
    /// on cells `resolution` m wide.
    pub fn one_robot(
        area_m2: f64,
        (width, speed, rot_speed): (f64, f64, f64),
        resolution: f64,
        diameter_m: f64,
    ) -> Self {
        let turning_s =
            if rot_speed > 0.0 { min_turning_rad(area_m2, width, resolution, diameter_m) / rot_speed } else { 0.0 };
        Self { area_s: area_time_s(area_m2, &[(width, speed)], resolution), turning_s }
    }

    /// The bound in seconds: both terms.
    pub fn total_s(&self) -> f64 {
        self.area_s + self.turning_s
    }
}

#[cfg(test)]
#[path = "bound/tests.rs"]
mod tests;
