//! A plan ended at its coverage goal: cut after the segment whose sweep brings the share of
//! the reachable coverable cells to the goal, then driven back to the end station. Shared by
//! the planners that plan past their goal and stop there (the cell-order planner, the
//! idealised lane control of `src/layouts`).

use super::GrowingRoute;
use crate::coverage::{CoverageGrid, Footprint};
use crate::geom::Point;
use crate::map::clearance::Clearance;
use crate::map::reach::Reach;

/// `path` cut after the segment whose sweep brings the coverage of `reach`'s cells to `goal`
/// (the whole path when none does), then driven to `end` on a wall-free route.
pub fn end_at_goal(
    clear: &Clearance,
    reach: &Reach,
    grid: &CoverageGrid,
    robot: &Footprint,
    mut path: Vec<Point>,
    goal: f64,
    end: Point,
) -> Vec<Point> {
    let needed = (goal * reach.coverable_count() as f64 - 1e-9).ceil().max(0.0) as usize;
    let mut covered = vec![false; grid.len()];
    let mut count = 0usize;
    let mut cut = None;
    for (j, w) in path.windows(2).enumerate() {
        crate::coverage::raster::for_each_swept_cell(grid.raster(), w[0], w[1], robot.width, |i| {
            if !covered[i] && reach.is_coverable(i) {
                covered[i] = true;
                count += 1;
            }
        });
        if count >= needed {
            cut = Some(j + 2);
            break;
        }
    }
    let Some(keep) = cut else { return path };
    path.truncate(keep);
    let mut route = GrowingRoute::new(*path.last().expect("kept two points"));
    route.finish(clear, end);
    path.extend_from_slice(&route.points()[1..]);
    path
}
