//! Classical coverage patterns used as baselines: boustrophedon (its lanes are the lanes layer's,
//! [`crate::lanes::boustrophedon`]) and an inward spiral ([`spiral`]), both built on
//! collision-free connections ([`crate::map::clearance`]).

pub mod entry;
pub mod hand_made;
pub mod planner;

pub mod spiral;

use crate::geom::Point;
use crate::lanes::band::band_route;
use crate::lanes::{GrowingRoute, PatternError, boustrophedon, check_lane_count};
use crate::map::GridMap;
use crate::map::clearance::Clearance;
use crate::map::passages::planning_map_from;
use crate::map::reach::Reach;
use std::borrow::Cow;

/// A coverage pattern.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Pattern {
    /// Parallel lanes at `angle_deg` (0 = along +x).
    Boustrophedon {
        /// Lane direction in degrees.
        angle_deg: f64,
    },
    /// Inward contour-parallel spiral in each boustrophedon cell.
    Spiral,
}

/// A planned pattern: the path and what it had to leave out.
#[derive(Clone, Debug, PartialEq)]
pub struct PatternPlan {
    /// The path from the start station to the end station.
    pub points: Vec<Point>,
    /// Free pockets the robot cannot reach or sweep from the start.
    pub pockets: usize,
    /// Their area in m².
    pub pocket_area_m2: f64,
    /// Lane ends the route could not reach without a collision and skipped.
    pub skipped_targets: usize,
}

/// Plans `pattern` over the free cells of `region` (a map equal to `map` with the cells outside
/// the region closed), then visits the cells of `targets` the lanes left unswept travelling on
/// the whole `map`: the lanes stay in the region, the connecting moves may cross the rest
/// (needed where the region is one piece of cells but not one piece for the robot's disc).
pub fn plan_region(
    map: &GridMap,
    region: &GridMap,
    targets: &[bool],
    pattern: Pattern,
    width: f64,
    start: Point,
    end: Point,
) -> Result<PatternPlan, PatternError> {
    check_lane_count(map, width)?;
    // Planned on the refined raster where the map is coarse (`map::refine`).
    let k = crate::map::passages::planning_refinement(map, width, start);
    let (map, region, targets) = if k > 1 {
        use crate::map::refine::{refined, refined_flags};
        (Cow::Owned(refined(map, k)), Cow::Owned(refined(region, k)), Cow::Owned(refined_flags(map, targets, k)))
    } else {
        (Cow::Borrowed(map), Cow::Borrowed(region), Cow::Borrowed(targets))
    };
    let (map, region, targets) = (&*map, &*region, &*targets);
    let mut lanes = Clearance::new(region, width);
    let region_reach = Reach::new(&lanes, &[start]);
    let mut whole = Clearance::new(map, width);
    let mut reach = Reach::new(&whole, &[start]);
    if reach.centres().iter().all(|c| !c) {
        return band_plan(&whole, &reach, width, start, end);
    }
    whole.restrict(reach.centres().to_vec());
    let mut route = if region_reach.centres().iter().any(|c| *c) {
        // Where the region closes the start's surroundings (a robot whose region is cut to its
        // start cell), the lanes' nearest centre can lie metres away behind walls: drive there
        // over the whole map first, and let the lanes start from it.
        let entry = lanes.snap(start).filter(|&i| whole.snap(start) != Some(i)).map(|i| {
            let cols = region.cols();
            region.cell_centre(i / cols, i % cols)
        });
        let mut route = GrowingRoute::new(start);
        let from = entry.unwrap_or(start);
        route.go(&whole, from);
        lanes.restrict(region_reach.centres().to_vec());
        // A region that holds no lane is the caller's to name (a fleet's share too small).
        let lanes_route = lanes_of(pattern, &lanes, width, from)?;
        // The lanes' route starts at `from`, which the route has reached.
        route.append(lanes_route);
        route
    } else {
        GrowingRoute::new(start)
    };
    reach.keep_only(targets);
    crate::lanes::complete::complete(&whole, &reach, width, &mut route);
    route.finish(&whole, end);
    Ok(PatternPlan {
        skipped_targets: route.skipped(),
        points: checked(&whole, width, route.into_points())?,
        pockets: reach.pocket_count(),
        pocket_area_m2: reach.pocket_area_m2(),
    })
}

/// The route of `pattern`'s lanes over the centres of `clear` from `start`.
fn lanes_of(pattern: Pattern, clear: &Clearance, width: f64, start: Point) -> Result<GrowingRoute, PatternError> {
    match pattern {
        Pattern::Boustrophedon { angle_deg } => boustrophedon::plan(clear, width, angle_deg, start),
        Pattern::Spiral => spiral::plan(clear, width, start),
    }
}

/// The plan of a robot that fits at `start` only in a band holding no cell centre of the
/// planning raster, or too few for a lane ([`crate::lanes::band`]): the band's route, checked
/// by the body rule, or [`PatternError::NoRoom`] where the robot cannot move there.
fn band_plan(
    clear: &Clearance,
    reach: &Reach,
    width: f64,
    start: Point,
    end: Point,
) -> Result<PatternPlan, PatternError> {
    let points = band_route(clear.map(), width, start, end).ok_or(PatternError::NoRoom { width })?;
    Ok(PatternPlan {
        points: checked(clear, width, points)?,
        pockets: reach.pocket_count(),
        pocket_area_m2: reach.pocket_area_m2(),
        skipped_targets: 0,
    })
}

/// `points` made executable on the planning raster of `clear` ([`crate::planner::executable`]),
/// or why it cannot be.
fn checked(clear: &Clearance, width: f64, points: Vec<Point>) -> Result<Vec<Point>, PatternError> {
    crate::planner::executable::executable(clear, width, points).map_err(|e| PatternError::NotExecutable(e.to_string()))
}

/// Checks the inputs of [`plan`] as a user gives them, naming the input that is wrong with
/// `names` (`[start, end, width]`, e.g. `["--start", "--end", "--width"]`): both stations on
/// free cells of the map where the robot's body fits, a lane count within [`crate::lanes::MAX_LANES`], and
/// an end the robot can reach from the start.
pub fn check_plan_inputs(map: &GridMap, width: f64, start: Point, end: Point, names: [&str; 3]) -> Result<(), String> {
    use crate::map::reach::{station_misfit, unreachable_end};
    let [start_name, end_name, width_name] = names;
    map.check_station(start, start_name)?;
    map.check_station(end, end_name)?;
    check_lane_count(map, width).map_err(|e| format!("{width_name}: {e}"))?;
    let planning = planning_map_from(map, width, start);
    let clear = Clearance::new(&planning, width);
    for (p, name) in [(start, start_name), (end, end_name)] {
        if let Some(why) = station_misfit(&clear, p, name) {
            return Err(why);
        }
    }
    if end != start
        && let Some(why) = unreachable_end(&clear, start, end)
    {
        return Err(format!("{end_name}: {why}"));
    }
    Ok(())
}

/// Plans `pattern` on `map` for a robot `width` metres wide, from `start` back to `end`, over
/// the part of the map the robot can reach from `start` ([`crate::map::reach::Reach`]); with
/// `complete`, the strips the pattern left are visited afterwards (coverage completion).
pub fn plan(
    map: &GridMap,
    pattern: Pattern,
    width: f64,
    start: Point,
    end: Point,
    complete: bool,
) -> Result<PatternPlan, PatternError> {
    check_lane_count(map, width)?;
    // Planned on the refined raster where the map is coarse (`map::refine`).
    let map = &*planning_map_from(map, width, start);
    let mut clear = Clearance::new(map, width);
    let reach = Reach::new(&clear, &[start]);
    if reach.centres().iter().all(|c| !c) {
        return band_plan(&clear, &reach, width, start, end);
    }
    clear.restrict(reach.centres().to_vec());
    let mut route = match lanes_of(pattern, &clear, width, start) {
        Err(PatternError::NoRoom { .. }) => return band_plan(&clear, &reach, width, start, end),
        other => other?,
    };
    if complete {
        crate::lanes::complete::complete(&clear, &reach, width, &mut route);
    }
    route.finish(&clear, end);
    Ok(PatternPlan {
        skipped_targets: route.skipped(),
        points: checked(&clear, width, route.into_points())?,
        pockets: reach.pocket_count(),
        pocket_area_m2: reach.pocket_area_m2(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::fitness::{Projection, score};
    use crate::coverage::{CoverageGrid, Footprint, SweepScratch};
    use crate::map::presets::preset;

    fn scored(map: &str, pattern: Pattern) -> (f64, f64, u64) {
        let m = preset(map).unwrap();
        let s = Point::new(1.3, 1.3);
        let path = plan(&m, pattern, 0.6, s, s, false).unwrap().points;
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

    #[test]
    fn a_pocket_behind_a_narrow_door_is_skipped_and_reported() {
        use crate::map::CellState;
        // A 2 x 1.5 m room and, behind a 0.3 m door, a 1 x 1.5 m pocket; a 0.6 m robot.
        let (cols, rows) = (34, 17);
        let mut cells = vec![CellState::Occupied; cols * rows];
        for r in 1..16 {
            for c in 1..21 {
                cells[r * cols + c] = CellState::Free;
            }
            for c in 22..32 {
                cells[r * cols + c] = CellState::Free;
            }
        }
        for r in 7..10 {
            cells[r * cols + 21] = CellState::Free;
        }
        let m = GridMap::new("pocket", cols, rows, 0.1, Point::origin(), cells).unwrap();
        let s = Point::new(0.5, 0.5);
        for pattern in [Pattern::Boustrophedon { angle_deg: 0.0 }, Pattern::Spiral] {
            let p = plan(&m, pattern, 0.6, s, s, true).unwrap();
            // The pocket (150 cells) and the door (3 cells) at least; the room's corners,
            // which no disc pose reaches, are pockets too.
            assert!(p.pockets >= 1, "{pattern:?}");
            assert!(p.pocket_area_m2 >= 1.53 - 1e-9 && p.pocket_area_m2 < 3.0, "{pattern:?}: {}", p.pocket_area_m2);
            assert!(p.points.iter().all(|q| q.x < 2.1), "{pattern:?} never enters the pocket");
            assert_eq!((p.points[0], *p.points.last().unwrap()), (s, s));
        }
    }
    #[test]
    fn a_region_cut_to_its_start_cell_is_entered_over_the_map_not_through_the_wall() {
        use crate::map::CellState;
        // Two 2 x 2 m rooms split by a wall at x = 2 m with a door at the top; the region is
        // the right room and the start cell in the left one (a robot whose area division left
        // it its start cell only): the way in goes through the door.
        let (cols, rows) = (42, 22);
        let mut cells = vec![CellState::Occupied; cols * rows];
        for r in 1..21 {
            for c in 1..41 {
                if c != 20 || r >= 14 {
                    cells[r * cols + c] = CellState::Free;
                }
            }
        }
        let m = GridMap::new("rooms", cols, rows, 0.1, Point::origin(), cells.clone()).unwrap();
        let s = Point::new(0.55, 0.55);
        let (sr, sc) = m.cell_at(s).unwrap();
        let mut open = vec![false; cols * rows];
        for r in 0..rows {
            for c in 21..cols {
                open[r * cols + c] = true;
            }
        }
        open[sr * cols + sc] = true;
        let closed: Vec<CellState> = cells
            .iter()
            .zip(&open)
            .map(|(&c, &o)| if c == CellState::Free && !o { CellState::Occupied } else { c })
            .collect();
        let region = GridMap::new("rooms", cols, rows, 0.1, Point::origin(), closed).unwrap();
        let p = plan_region(&m, &region, &open, Pattern::Boustrophedon { angle_deg: 0.0 }, 0.4, s, s).unwrap();
        let g = CoverageGrid::new(&m);
        let fp = Footprint { width: 0.4, ..Footprint::default() };
        let metrics = fp.measure(&g, &mut SweepScratch::new(&g), &p.points);
        assert_eq!(metrics.obstacle_cells, 0, "{:?}", &p.points[..4]);
        assert!(p.points.iter().any(|q| q.x > 3.0), "the right room is swept");
        assert_eq!((p.points[0], *p.points.last().unwrap()), (s, s));
    }
}
