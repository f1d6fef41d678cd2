//! What an evaluation of the thesis GA reads: the map as scored and as bit rows, the robot,
//! the stations and clamping frame, the projection, and how moves are driven.

use super::genome::Frame;
use super::objective::CameraObjective;
use crate::coverage::bits::BitLayers;
use crate::coverage::fitness::Projection;
use crate::coverage::{CoverageGrid, Footprint};
use crate::geom::Point;
use crate::map::GridMap;
use crate::routing::routes::{RouteScratch, Router};
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// Everything an evaluation reads: the map layers, the robot, the stations and the projection.
#[derive(Clone, Debug)]
pub struct ThesisScenario {
    /// The map.
    pub map: GridMap,
    /// Obstacles and pre-marks as scored.
    pub grid: CoverageGrid,
    /// The same layers as bit rows, for the evaluator.
    pub layers: BitLayers,
    /// The robot.
    pub robot: Footprint,
    /// Stations and clamping rectangle.
    pub frame: Frame,
    /// `f1` or `f2`.
    pub projection: Projection,
    /// With routed moves, how the robot drives from one viewpoint to the next (`None`: straight,
    /// as 003).
    pub routes: Option<Arc<Router>>,
    /// With `thesis.objective = "camera"`, what `cov_final` measures instead of the footprint
    /// (`None`: 003's footprint).
    pub camera: Option<Arc<CameraObjective>>,
}

impl ThesisScenario {
    /// The thesis scenario (visit grid, clamping frame) of the common scenario every planner
    /// plans for.
    pub fn from_common(s: &crate::planner::Scenario) -> Self {
        Self::new(s.map.clone(), s.robot, s.start, s.end, s.projection)
    }

    /// A scenario on `map` with stations `start` / `end` (already checked to be free).
    pub fn new(map: GridMap, robot: Footprint, start: Point, end: Point, projection: Projection) -> Self {
        let min = map.origin();
        let max = Point::new(min.x + map.width_m(), min.y + map.height_m());
        let grid = CoverageGrid::new(&map);
        let layers = BitLayers::new(&grid);
        Self {
            grid,
            layers,
            robot,
            frame: Frame::new(start, end, min, max),
            projection,
            map,
            routes: None,
            camera: None,
        }
    }

    /// The same scenario with `cov_final` measured by `camera` (see [`super::objective`]).
    pub fn with_camera(mut self, camera: Option<CameraObjective>) -> Self {
        self.camera = camera.map(Arc::new);
        self
    }

    /// The same scenario with moves driven as `moves` says.
    pub fn with_moves(mut self, moves: Moves) -> Self {
        self.routes = match moves {
            Moves::Straight => None,
            Moves::Routed => {
                let stations = [self.frame.start, self.frame.end];
                Some(Arc::new(Router::new(&self.map, self.robot.width, &stations)))
            }
        };
        self
    }

    /// The path the robot drives through `points` (a genome's viewpoints): the viewpoints
    /// themselves with straight moves, else the routes between them.
    pub fn driven(&self, points: &[Point]) -> Vec<Point> {
        match &self.routes {
            None => points.to_vec(),
            Some(router) => {
                let mut out = Vec::new();
                router.expand(points, &mut RouteScratch::default(), &mut out);
                out
            }
        }
    }

    /// Replaces the pre-marks by the flagged free cells (see
    /// [`CoverageGrid::set_premarks`]). Individuals must be re-evaluated in full afterwards.
    pub fn set_premarks(&mut self, cells: &[bool]) {
        self.grid.set_premarks(cells);
        self.layers = BitLayers::new(&self.grid);
    }

    /// Marks the free cells whose centre lies in `[x0, x1) × [y0, y1)` as already covered
    /// (the retrain region, R25). Individuals must be re-evaluated in full afterwards.
    pub fn premark_rect(&mut self, x0: f64, y0: f64, x1: f64, y1: f64) {
        self.grid.premark_rect(x0, y0, x1, y1);
        self.layers = BitLayers::new(&self.grid);
    }
}

/// How the robot drives from one viewpoint to the next (`thesis.moves`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Moves {
    /// Straight segments, as 003: a move into a wall sweeps it and is penalised (eq. 3.16).
    #[default]
    Straight,
    /// Around obstacles (003 §5.3's future work): see [`crate::routing::routes`].
    Routed,
}

impl Moves {
    /// Why every plan of these moves is executable, where that holds by construction: a routed
    /// move follows a route the robot's body fits along ([`crate::routing::routes`]).
    pub fn executable_by_construction(&self) -> Option<&'static str> {
        match self {
            Moves::Straight => None,
            Moves::Routed => Some("every routed move follows a route the robot's body fits along"),
        }
    }

    /// Whether these are 003's straight moves.
    pub fn is_straight(&self) -> bool {
        matches!(self, Moves::Straight)
    }
}
