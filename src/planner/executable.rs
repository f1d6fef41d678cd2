//! Executability checked, never assumed: every plan a routing planner (the patterns, the
//! cell-order planner) returns is read with the body rule of [`crate::map::body`] — the rule
//! `covga eval` reports as "executable" — before the planner returns it. A segment whose body
//! touches a wall, an unknown cell or the map's edge is replaced by a detour whose every
//! segment passes the rule; a plan that still touches is refused, naming the segment, instead
//! of being returned as if it were executable.
//!
//! Why a check and not a proof: the planners' moves are tested at sample points and their
//! connecting routes run over cell centres, and a lane end at the clearance limit between two
//! cell centres (a lane through a gap exactly one robot wide) has no centre it can drive to
//! straight. [`Clearance::connect`] cannot leave such a point to a centre without cutting a
//! wall's corner (15 mm on 0.3 m cells for a 0.6 m robot, where the rule allows 9.5 mm); the
//! detour backs off along the segment the robot came in on (the reverse of a move it already
//! made) until a straight hop to the route's centres fits.
//!
//! The check reads the planning raster ([`crate::planner::Scenario::for_planning`]): its cells
//! lie inside the cells of the map as given, and the body rule's slack shrinks with the cell,
//! so a plan clear on the planning raster is clear on the map it is scored on.

use crate::geom::Point;
use crate::map::GridMap;
use crate::map::body::touched_cells;
use crate::map::clearance::Clearance;

/// Points tried along the segment before (after) a touching segment, as the detour's new
/// start (end): enough to walk back along a lane in steps of half a cell up to this many.
const BACK_OFF_STEPS: usize = 24;

/// Whether a robot `width` metres wide driving `a → b` on `map` passes the body rule.
pub fn segment_executable(map: &GridMap, a: Point, b: Point, width: f64) -> bool {
    let (cells, off_map) = touched_cells(map, &[a, b], width);
    cells.is_empty() && !off_map
}

/// A plan that could not be made executable: the first segment that still touches.
#[derive(Clone, Debug, PartialEq)]
pub struct NotExecutable {
    /// Index of the segment's first point in the plan.
    pub segment: usize,
    /// Its ends.
    pub from: Point,
    /// Its ends.
    pub to: Point,
    /// Non-free cells its body touches (row-major indices of the planning raster).
    pub cells: usize,
    /// Whether the body reaches past the map's edge.
    pub off_map: bool,
}

impl std::fmt::Display for NotExecutable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the plan is not executable and no wall-free detour was found: segment {} from ({:.3}, {:.3}) to \
             ({:.3}, {:.3}) m brings the robot's body onto {} occupied or unknown cells{}",
            self.segment,
            self.from.x,
            self.from.y,
            self.to.x,
            self.to.y,
            self.cells,
            if self.off_map { " and past the map's edge" } else { "" }
        )
    }
}

/// `path` with every segment that touches replaced by a detour that does not (best effort:
/// a segment no detour replaces is kept as it is, for [`executable`] to refuse). Segments
/// that pass the rule are kept bit for bit, so an executable plan is returned unchanged.
pub fn repaired(clear: &Clearance, width: f64, path: Vec<Point>) -> Vec<Point> {
    let map = clear.map();
    if path.windows(2).all(|w| segment_executable(map, w[0], w[1], width)) {
        return path;
    }
    let mut out: Vec<Point> = Vec::with_capacity(path.len() + 8);
    out.push(path[0]);
    for k in 1..path.len() {
        let (a, b) = (*out.last().expect("a start"), path[k]);
        if segment_executable(map, a, b, width) {
            out.push(b);
            continue;
        }
        let before = (out.len() >= 2).then(|| out[out.len() - 2]);
        match detour(clear, width, (before, a), (b, path.get(k + 1).copied())) {
            Some(points) => out.extend(points),
            None => out.push(b),
        }
    }
    out
}

/// [`repaired`], then checked: the plan, or the first segment that still touches.
pub fn executable(clear: &Clearance, width: f64, path: Vec<Point>) -> Result<Vec<Point>, NotExecutable> {
    let path = repaired(clear, width, path);
    let map = clear.map();
    for (segment, w) in path.windows(2).enumerate() {
        let (cells, off_map) = touched_cells(map, w, width);
        if !cells.is_empty() || off_map {
            return Err(NotExecutable { segment, from: w[0], to: w[1], cells: cells.len(), off_map });
        }
    }
    Ok(path)
}

/// The points after `a` of a route from `a` to `b` whose every segment passes the body rule,
/// where one is found: a wall-free route ([`Clearance::connect`]) from a point `a'` on the
/// segment the robot came in on (`before → a`, driven back) to a point `b'` on the segment it
/// leaves `b` by (`b → after`, driven back to `b`).
fn detour(
    clear: &Clearance,
    width: f64,
    (before, a): (Option<Point>, Point),
    (b, after): (Point, Option<Point>),
) -> Option<Vec<Point>> {
    let map = clear.map();
    let ok = |p: Point, q: Point| (p - q).norm() < 1e-12 || segment_executable(map, p, q, width);
    let steps = |from: Point, towards: Option<Point>| -> Vec<Point> {
        let Some(to) = towards else { return vec![from] };
        let n = (((to - from).norm() / (0.5 * map.resolution())).ceil() as usize).clamp(1, BACK_OFF_STEPS);
        (0..=n).map(|i| from + (to - from) * (i as f64 / n as f64)).collect()
    };
    let (starts, ends) = (steps(a, before), steps(b, after));
    // Backing off at one end first, then at both: the fewest extra metres first.
    let pairs = (0..starts.len())
        .map(|i| (i, 0))
        .chain((1..ends.len()).map(|j| (0, j)))
        .chain((1..starts.len().min(ends.len())).map(|i| (i, i)));
    for (i, j) in pairs {
        let (a2, b2) = (starts[i], ends[j]);
        if !ok(a, a2) || !ok(b2, b) {
            continue;
        }
        let Some(hops) = clear.connect(a2, b2) else { continue };
        let mut route = Vec::with_capacity(hops.len() + 2);
        if i > 0 {
            route.push(a2);
        }
        route.extend(hops);
        if j > 0 {
            route.push(b);
        }
        let mut prev = a;
        let clear_all = route.iter().all(|&p| {
            let fine = ok(prev, p);
            prev = p;
            fine
        });
        if clear_all {
            return Some(route);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::CellState;

    /// Cells of 0.3 m: a block (rows 1–2, columns 1–5) and a wall (column 8) leave a gap
    /// exactly one 0.6 m robot wide (x 1.8–2.4 m), whose middle is a cell border where no cell
    /// centre lies. A lane down the gap ends level with the block's top (y = 0.9 m); the
    /// straight hop from there to the nearest centre up-left cuts the block's corner (0.2846 m
    /// from it, the 15 mm of the office map at 0.3 m).
    fn gap_map() -> GridMap {
        let (cols, rows) = (12, 12);
        let mut cells = vec![CellState::Free; cols * rows];
        for r in 0..rows {
            for c in 0..cols {
                let border = r == 0 || c == 0 || r == rows - 1 || c == cols - 1;
                if border || c == 8 || ((1..=2).contains(&r) && c <= 5) {
                    cells[r * cols + c] = CellState::Occupied;
                }
            }
        }
        GridMap::new("gap", cols, rows, 0.3, Point::origin(), cells).unwrap()
    }

    #[test]
    fn a_corner_cutting_hop_is_detoured_and_a_clear_plan_kept_bit_for_bit() {
        let map = gap_map();
        let clear = Clearance::new(&map, 0.6);
        let path = vec![Point::new(2.1, 3.0), Point::new(2.1, 0.9), Point::new(1.95, 1.35)];
        assert!(segment_executable(&map, path[0], path[1], 0.6), "the lane itself is clear");
        assert!(!segment_executable(&map, path[1], path[2], 0.6), "the case must touch");
        let fixed = executable(&clear, 0.6, path.clone()).expect("a detour exists");
        assert_eq!((fixed[0], fixed[1], *fixed.last().unwrap()), (path[0], path[1], path[2]));
        assert!(fixed.windows(2).all(|w| segment_executable(&map, w[0], w[1], 0.6)), "{fixed:?}");
        let clean = vec![Point::new(2.1, 3.0), Point::new(2.1, 0.9), Point::new(2.1, 1.5)];
        assert_eq!(repaired(&clear, 0.6, clean.clone()), clean);
    }

    #[test]
    fn a_plan_through_a_wall_is_refused_naming_the_segment() {
        let map = gap_map();
        let clear = Clearance::new(&map, 0.6);
        // Into the block, where the body cannot stand at all.
        let path = vec![Point::new(1.2, 2.85), Point::new(1.2, 0.6)];
        let err = executable(&clear, 0.6, path).unwrap_err();
        assert_eq!(err.segment, 0);
        assert!(err.cells > 0 && err.to_string().contains("segment 0"), "{err}");
    }
}
