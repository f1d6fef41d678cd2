//! The lanes every sweeping planner drives, below the planners so that they share them as
//! peers: the boustrophedon decomposition into lanes and cells ([`boustrophedon`], which the
//! boustrophedon pattern mows and the cell-order planner orders), the route that grows along
//! them ([`GrowingRoute`]), coverage completion of the strips they leave ([`complete`]), a
//! plan ended at its coverage goal ([`goal`]), the route of a robot that fits only in a band
//! thinner than the raster ([`band`]), and the cap on lanes across a map ([`check_lane_count`]).

pub mod band;
pub mod boustrophedon;
pub mod complete;
pub mod goal;

use crate::geom::Point;
use crate::map::GridMap;
use crate::map::clearance::Clearance;

/// Why a pattern could not be planned.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum PatternError {
    /// No place reachable from the start fits the robot: no cell centre, and no straight move
    /// through the start ([`band`]).
    #[error("no free area reachable from the start fits a robot {width} m wide")]
    NoRoom {
        /// The robot width.
        width: f64,
    },
    /// The plan touches a wall, an unknown cell or the map's edge and no detour repairs it
    /// (the body rule of [`crate::map::body`], checked before a plan is returned).
    #[error("{0}")]
    NotExecutable(String),
    /// The robot is so narrow that the lanes across the map would not fit in memory or time.
    #[error(
        "a robot {} m wide needs about {lanes:.3e} lanes across map `{map}` ({across:.1} m); at most {MAX_LANES} \
         are planned (a width of at least {min_width:.3e} m)",
        crate::io::short_number(*width)
    )]
    TooManyLanes {
        /// The robot width.
        width: f64,
        /// The map's name.
        map: String,
        /// Its diagonal in metres.
        across: f64,
        /// Lanes one width apart across the diagonal.
        lanes: f64,
        /// The narrowest width within the limit.
        min_width: f64,
    },
}

/// The most lanes a pattern lays across a map (at any direction): far above any real floor plan
/// at a real robot's width (basement, 30 m across at 0.6 m: 71), and a bound that keeps a
/// mistyped width from allocating lanes without end.
pub const MAX_LANES: f64 = 100_000.0;

/// Refuses a width that would lay more than [`MAX_LANES`] lanes across `map`'s diagonal.
pub fn check_lane_count(map: &GridMap, width: f64) -> Result<(), PatternError> {
    let across = map.width_m().hypot(map.height_m());
    let lanes = across / width;
    if lanes.is_finite() && lanes <= MAX_LANES {
        return Ok(());
    }
    Err(PatternError::TooManyLanes { width, map: map.name().to_string(), across, lanes, min_width: across / MAX_LANES })
}

/// A growing polyline that starts at a station; targets it cannot reach are skipped.
#[derive(Clone, Debug)]
pub struct GrowingRoute {
    points: Vec<Point>,
    skipped: usize,
}

impl GrowingRoute {
    /// A route standing at `start`.
    pub fn new(start: Point) -> Self {
        Self { points: vec![start], skipped: 0 }
    }
    /// The points so far, the start first.
    pub fn points(&self) -> &[Point] {
        &self.points
    }
    /// Targets skipped because no collision-free connection reached them.
    pub fn skipped(&self) -> usize {
        self.skipped
    }
    /// The points, giving the route up.
    pub fn into_points(self) -> Vec<Point> {
        self.points
    }
    /// Drives along `points` as they are (a sweep planned collision-free beforehand), after a
    /// connecting move to the first; `false` when that move found no connection.
    pub fn drive(&mut self, clear: &Clearance, points: &[Point]) -> bool {
        let Some((&first, rest)) = points.split_first() else { return true };
        if !self.go(clear, first) {
            return false;
        }
        self.points.extend_from_slice(rest);
        true
    }
    /// Where the route stands.
    pub fn last(&self) -> Point {
        *self.points.last().expect("a route has a start")
    }
    /// Moves to `p` along a collision-free connection (repeated points are dropped); `false`
    /// when `p` cannot be reached, and the route stays where it is.
    fn connect(&mut self, clear: &Clearance, p: Point) -> bool {
        let here = self.last();
        if (p - here).norm() < 1e-9 {
            return true;
        }
        match clear.connect(here, p) {
            Some(hops) => {
                self.points.extend(hops);
                true
            }
            None => false,
        }
    }
    /// `GrowingRoute::connect`, counting a target that cannot be reached as skipped.
    pub fn go(&mut self, clear: &Clearance, p: Point) -> bool {
        let reached = self.connect(clear, p);
        self.skipped += usize::from(!reached);
        reached
    }
    /// Continues with `other`, a route that starts where this one stands.
    pub fn append(&mut self, other: GrowingRoute) {
        self.points.extend_from_slice(&other.points[1..]);
        self.skipped += other.skipped;
    }
    /// Returns to the end station: through the fitting cell nearest to it when the station
    /// itself is too close to a wall for the disc (stations are free cells, checked at load).
    pub fn finish(&mut self, clear: &Clearance, end: Point) {
        if self.connect(clear, end) {
            return;
        }
        if let Some(i) = clear.snap(end) {
            let cols = clear.map().cols();
            self.go(clear, clear.map().cell_centre(i / cols, i % cols));
        }
        self.points.push(end);
    }
}
