//! Approach and return legs: a plan whose planner flies between its own waypoints (000's
//! graph) still starts at the start station and ends at the end station, so that every planner
//! pays the same legs in length, `time_s` and `t_final`. The legs are the wall-free transit of
//! [`crate::map::clearance::Clearance::connect`] (centres ≥ width/2 from every wall, A* over
//! the cells reachable from the start, shortened by line of sight).

use crate::geom::Point;
use crate::map::GridMap;
use crate::map::clearance::Clearance;
use crate::map::reach::reachable_centres;

/// The wall-free routes of one robot width from one start station, built once per run and
/// used for every agent's legs.
pub struct StationLegs<'m> {
    clear: Clearance<'m>,
    start: Point,
}

impl<'m> StationLegs<'m> {
    /// Prepares the clearance of a robot of `width` on `map`, restricted to the part reachable
    /// from `start`.
    pub fn new(map: &'m GridMap, width: f64, start: Point) -> Self {
        let mut clear = Clearance::new(map, width);
        clear.restrict(reachable_centres(&clear, &[start]));
        Self { clear, start }
    }

    /// `path` with a leg from the start to its first point and one from its last point to
    /// `end`, each the shortest wall-free route found; where none exists, the straight leg
    /// (which the common scorer then reports as not executable). An empty path becomes the
    /// route from the start to `end`.
    pub fn around(&self, path: &[Point], end: Point) -> Vec<Point> {
        let leg = |a: Point, b: Point| -> Vec<Point> {
            if (a - b).norm() < crate::geom::ZERO_LENGTH {
                return Vec::new();
            }
            self.clear.connect(a, b).unwrap_or_else(|| vec![b])
        };
        let mut out = vec![self.start];
        let (Some(&first), Some(&last)) = (path.first(), path.last()) else {
            out.extend(leg(self.start, end));
            return out;
        };
        out.extend(leg(self.start, first));
        out.extend_from_slice(&path[1..]);
        out.extend(leg(last, end));
        out
    }
}

/// `path` with the legs of [`StationLegs::around`] for a robot of `width` from `start` to
/// `end` (one path; a run with several builds one [`StationLegs`] for all).
pub fn with_station_legs(map: &GridMap, width: f64, start: Point, end: Point, path: &[Point]) -> Vec<Point> {
    StationLegs::new(map, width, start).around(path, end)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::CellState;

    /// Two rooms of 2 × 1 m at 0.1 m joined by a 0.4 m door at the top of a wall at x = 2 m.
    fn two_rooms() -> GridMap {
        let (cols, rows) = (41, 10);
        let mut cells = vec![CellState::Free; cols * rows];
        for r in 0..rows {
            if !(6..10).contains(&r) {
                cells[r * cols + 20] = CellState::Occupied;
            }
        }
        GridMap::new("rooms", cols, rows, 0.1, Point::origin(), cells).unwrap()
    }

    #[test]
    fn legs_join_the_stations_around_walls() {
        let map = two_rooms();
        let (start, end) = (Point::new(0.5, 0.2), Point::new(3.5, 0.2));
        let path = [Point::new(1.0, 0.5), Point::new(1.5, 0.5)];
        let out = with_station_legs(&map, 0.2, start, end, &path);
        assert_eq!(out[0], start);
        assert_eq!(*out.last().unwrap(), end);
        let i = out.iter().position(|&p| p == path[0]).expect("the plan's first point");
        assert_eq!(out[i + 1], path[1]);
        // The return leg goes through the door: every leg point clear of the wall's cells.
        let clear = Clearance::new(&map, 0.2);
        for w in out[i + 1..].windows(2) {
            assert!(clear.segment_fits(w[0], w[1]), "{w:?}");
        }
        assert!(out.len() > i + 3, "the return leg bends through the door: {out:?}");
    }

    #[test]
    fn an_empty_plan_is_the_route_between_the_stations() {
        let map = two_rooms();
        let out = with_station_legs(&map, 0.2, Point::new(0.5, 0.5), Point::new(0.5, 0.5), &[]);
        assert_eq!(out, vec![Point::new(0.5, 0.5)]);
    }
}
