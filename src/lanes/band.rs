//! A route for a robot that fits at its start only in a band narrower than the raster: in a
//! corridor or niche barely wider than the robot, the positions where its body clears every
//! wall can form a strip thinner than a cell, holding no cell centre even on the finest raster
//! the planners split to ([`crate::map::passages::planning_refinement`]). The scorer reads the
//! robot's centre continuously and counts the cells swept from that strip as reachable, so a
//! planner that plans over cell centres would refuse a map the scorer says it can cover.
//!
//! The band's route drives from the start to both ends of the longest straight move through the
//! start that the body rule ([`crate::map::body`]) accepts, and on to the end station: the band
//! is a strip about one robot long, so one straight axis through it is what can be driven.

use crate::geom::{Point, Vector};
use crate::map::GridMap;
use crate::map::body::touched_cells;

/// Whether a robot `width` metres wide driving `a → b` on `map` passes the body rule.
fn segment_executable(map: &GridMap, a: Point, b: Point, width: f64) -> bool {
    let (cells, off_map) = touched_cells(map, &[a, b], width);
    cells.is_empty() && !off_map
}

/// Directions tried for the band's axis, evenly over half a turn (every 2°).
const AXIS_DIRECTIONS: usize = 90;

/// Steps per cell when a move is extended along a direction.
const STEPS_PER_CELL: f64 = 8.0;

/// The farthest distance from `start` along the unit vector `u` that a robot `width` metres
/// wide drives straight under the body rule, in steps of an eighth of a cell, at most `limit`.
fn reach_along(map: &GridMap, start: Point, u: Vector, width: f64, limit: f64) -> f64 {
    let step = map.resolution() / STEPS_PER_CELL;
    let mut d = 0.0;
    // Each step checks its own piece: the body swept along a straight move is the union of the
    // bodies swept along its pieces.
    while d + step <= limit && segment_executable(map, start + u * d, start + u * (d + step), width) {
        d += step;
    }
    d
}

/// The route `start → a → b → end` through the band around `start`: `a` and `b` the ends of the
/// longest straight move through `start` the body rule accepts, then `end` straight from `b`,
/// or back through `start` where that does not pass. `None` where the robot cannot move at
/// all, or the end cannot be driven to straight from the band.
pub fn band_route(map: &GridMap, width: f64, start: Point, end: Point) -> Option<Vec<Point>> {
    if !segment_executable(map, start, start, width) {
        return None;
    }
    let limit = map.width_m().hypot(map.height_m());
    let (mut best, mut axis) = (0.0, None);
    for k in 0..AXIS_DIRECTIONS {
        let angle = std::f64::consts::PI * k as f64 / AXIS_DIRECTIONS as f64;
        let u = Vector::new(angle.cos(), angle.sin());
        let (forward, back) = (reach_along(map, start, u, width, limit), reach_along(map, start, -u, width, limit));
        if forward + back > best {
            (best, axis) = (forward + back, Some((start + u * forward, start - u * back)));
        }
    }
    let (a, b) = axis?;
    let mut route = vec![start, a, b];
    if !segment_executable(map, b, end, width) {
        if !segment_executable(map, start, end, width) {
            return None;
        }
        route.push(start);
    }
    route.push(end);
    route.dedup();
    Some(route)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::CellState;

    /// A corridor `gap` metres wide across a 4 m square map of 0.1 m cells, walls above and below.
    fn corridor(gap: f64) -> GridMap {
        let res = 0.1;
        let n = 40;
        let mut cells = vec![CellState::Occupied; n * n];
        let (lo, hi) = (2.0 - gap / 2.0, 2.0 + gap / 2.0);
        for r in 0..n {
            let (y0, y1) = (r as f64 * res, (r + 1) as f64 * res);
            if y0 >= lo - 1e-9 && y1 <= hi + 1e-9 {
                for c in 0..n {
                    cells[r * n + c] = CellState::Free;
                }
            }
        }
        GridMap::new("corridor", n, n, res, Point::new(0.0, 0.0), cells).unwrap()
    }

    #[test]
    fn a_robot_in_a_corridor_its_own_width_drives_its_length() {
        let map = corridor(1.0);
        let width = 0.999;
        let start = Point::new(2.0, 2.0);
        let route = band_route(&map, width, start, start).expect("the robot fits at its start");
        let xs: Vec<f64> = route.iter().map(|p| p.x).collect();
        let (lo, hi) = xs.iter().fold((f64::MAX, f64::MIN), |(l, h), &x| (l.min(x), h.max(x)));
        // The disc (radius ~0.5) stops half a width from the map's edges at x = 0 and 4.
        assert!(lo < 0.6 && hi > 3.4, "the route spans x {lo}..{hi}");
        assert!(route.iter().all(|p| (p.y - 2.0).abs() < 1e-9), "the route stays on the corridor's axis: {route:?}");
        assert!(route.windows(2).all(|w| segment_executable(&map, w[0], w[1], width)));
        assert_eq!(route.first(), Some(&start));
        assert_eq!(route.last(), Some(&start));
    }

    #[test]
    fn a_robot_that_does_not_fit_gets_no_route() {
        let map = corridor(1.0);
        assert_eq!(band_route(&map, 1.2, Point::new(2.0, 2.0), Point::new(2.0, 2.0)), None);
    }
}
