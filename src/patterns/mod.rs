//! Classical coverage patterns used as baselines: boustrophedon ([`boustrophedon`]) and an
//! inward spiral ([`spiral`]), both built on collision-free connections ([`clearance`]).

pub mod boustrophedon;
pub mod clearance;
pub mod spiral;

use crate::geom::Point;
use crate::map::GridMap;
use clearance::Clearance;

/// Why a pattern could not be planned.
#[derive(Debug, thiserror::Error)]
pub enum PatternError {
    /// No place on the map fits the robot.
    #[error("no free area on the map fits a robot {width} m wide")]
    NoRoom {
        /// The robot width.
        width: f64,
    },
    /// A point cannot be reached from the route.
    #[error("cannot reach ({x:.2}, {y:.2}) m from the route without hitting an obstacle")]
    Unreachable {
        /// Target x.
        x: f64,
        /// Target y.
        y: f64,
    },
}

/// A coverage pattern.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Pattern {
    /// Parallel lanes at `angle_deg` (0 = along +x).
    Boustrophedon {
        /// Lane direction in degrees.
        angle_deg: f64,
    },
    /// Inward rectangular spiral.
    Spiral,
}

/// A growing polyline that starts at a station.
#[derive(Clone, Debug)]
pub struct Route {
    points: Vec<Point>,
}

impl Route {
    fn new(start: Point) -> Self {
        Self { points: vec![start] }
    }
    fn last(&self) -> Point {
        *self.points.last().expect("a route has a start")
    }
    /// Moves to `p` along a collision-free connection; repeated points are dropped.
    fn go(&mut self, clear: &Clearance, p: Point) -> Result<(), PatternError> {
        let here = self.last();
        if (p - here).norm() < 1e-9 {
            return Ok(());
        }
        let hops = clear.connect(here, p).ok_or(PatternError::Unreachable { x: p.x, y: p.y })?;
        self.points.extend(hops);
        Ok(())
    }
    /// The points.
    pub fn into_points(self) -> Vec<Point> {
        self.points
    }
}

/// Plans `pattern` on `map` for a robot `width` metres wide, from `start` back to `end`.
pub fn plan(map: &GridMap, pattern: Pattern, width: f64, start: Point, end: Point) -> Result<Vec<Point>, PatternError> {
    let clear = Clearance::new(map, width);
    let route = match pattern {
        Pattern::Boustrophedon { angle_deg } => boustrophedon::plan(&clear, width, angle_deg, start, end)?,
        Pattern::Spiral => spiral::plan(&clear, width, start, end)?,
    };
    Ok(route.into_points())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::{CoverageGrid, Footprint, SweepScratch};
    use crate::map::presets::preset;
    use crate::thesis::fitness::{Projection, score};

    fn scored(map: &str, pattern: Pattern) -> (f64, f64, u64) {
        let m = preset(map).unwrap();
        let s = Point::new(1.3, 1.3);
        let path = plan(&m, pattern, 0.6, s, s).unwrap();
        assert_eq!(path[0], s);
        assert_eq!(*path.last().unwrap(), s);
        let g = CoverageGrid::new(&m);
        let fp = Footprint::default();
        let metrics = fp.measure(&g, &mut SweepScratch::new(&g), &path);
        let sc = score(&metrics, &fp, m.resolution(), Projection::F1);
        (sc.cov_final, sc.t_final, metrics.obstacle_cells)
    }

    #[test]
    fn patterns_cover_thesis_map_1_like_table_3_1() {
        for pattern in [Pattern::Boustrophedon { angle_deg: 0.0 }, Pattern::Spiral] {
            let (cov, t, obj) = scored("thesis-1", pattern);
            assert!(cov >= 0.93 && t >= 0.85 && obj == 0, "{pattern:?}: cov {cov}, t {t}, obj {obj}");
        }
    }

    #[test]
    fn boustrophedon_splits_around_the_disc() {
        for angle_deg in [0.0, 30.0, 90.0] {
            let (cov, _, obj) = scored("thesis-2", Pattern::Boustrophedon { angle_deg });
            assert!(cov >= 0.85 && obj == 0, "angle {angle_deg}: cov {cov}, obj {obj}");
        }
    }
}
