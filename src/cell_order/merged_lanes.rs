//! Lanes that continue across small obstacles. A boustrophedon decomposition ends a lane
//! wherever the robot's body does not fit, so every speck and pillar of a SLAM map splits the
//! cell around it into more cells of shorter lanes. Here the pieces of one lane are joined
//! across a gap of at most `merge_gap_m` metres where every obstacle the robot's body meets in
//! the gap is small — a connected obstacle that fits in a square of the gap's side (a speck, a
//! pillar; not a wall, which joins the map's other walls) — and the robot can drive around it
//! on a detour at most [`DETOUR_SLACK_WIDTHS`] robot widths longer than the gap. Cells merge
//! across the obstacle, and the sweep of a joined piece drives its lane around it
//! ([`crate::lanes::boustrophedon::sweep_cells_with`]), so that the plan stays executable.
//! This is the merged-cells question Bähnemann et al. (2019) leave open.

use crate::lanes::boustrophedon::Piece;
use crate::map::clearance::Clearance;

/// How a map's lanes are laid out for the cell-order planner: joined across gaps of up to
/// `merge_gap_m` metres, and whether every cell is also offered its sweeps with lanes split at
/// every obstacle, so that a search chooses per cell between joined and split lanes (the
/// per-region layout choice; the controls try each layout for the whole map).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaneLayout {
    /// The longest gap a lane continues across, in metres; 0 splits lanes at every obstacle.
    pub merge_gap_m: f64,
    /// Offer every cell its split sweeps beside its joined ones (only where lanes are joined).
    pub split_too: bool,
}

impl LaneLayout {
    /// Lanes split at every obstacle, as a plain boustrophedon decomposition has them.
    pub const SPLIT: Self = Self { merge_gap_m: 0.0, split_too: false };

    /// Lanes joined across gaps of up to `merge_gap_m`, with no split alternative.
    pub fn joined(merge_gap_m: f64) -> Self {
        Self { merge_gap_m, split_too: false }
    }

    /// The layouts the controls try, one plan each per lane direction: `false` for the
    /// (possibly joined) lanes, then `true` for the split ones where they are offered.
    pub fn control_layouts(&self) -> &'static [bool] {
        if self.offers_split() { &[false, true] } else { &[false] }
    }

    /// Whether split sweeps are offered beside joined ones.
    pub fn offers_split(&self) -> bool {
        self.split_too && self.merge_gap_m > 0.0
    }
}

/// How much longer than the gap the detour around the obstacle in it may be, in robot widths.
pub const DETOUR_SLACK_WIDTHS: f64 = 2.0;

/// How lanes are joined on one map: the gap, the robot's width and, where the gap is not 0,
/// the map's small obstacles (found once for every lane direction).
pub struct LaneJoin<'c, 'm> {
    clear: &'c Clearance<'m>,
    merge_gap_m: f64,
    width: f64,
    small: Option<SmallObstacles<'c>>,
}

impl<'c, 'm> LaneJoin<'c, 'm> {
    /// Joins across gaps of at most `merge_gap_m` metres for a robot `width` wide on `clear`'s
    /// map; 0 joins nothing.
    pub fn new(clear: &'c Clearance<'m>, merge_gap_m: f64, width: f64) -> Self {
        let small = (merge_gap_m > 0.0).then(|| SmallObstacles::of(clear.map(), merge_gap_m));
        Self { clear, merge_gap_m, width, small }
    }

    /// `lanes` with the consecutive pieces of each lane joined across every gap of at most the
    /// merge gap whose obstacles within the robot's radius are all small (each fits in a square
    /// of the gap's side) and whose detour (the wall-free route from one piece's end to the
    /// next one's start) is at most [`DETOUR_SLACK_WIDTHS`] widths longer than the gap; `lanes`
    /// as they are when the gap is 0.
    pub fn joined(&self, lanes: Vec<Vec<Piece>>) -> Vec<Vec<Piece>> {
        let Some(small) = &self.small else { return lanes };
        let (clear, width) = (self.clear, self.width);
        lanes
            .into_iter()
            .map(|lane| {
                let mut out: Vec<Piece> = Vec::with_capacity(lane.len());
                for q in lane {
                    if let Some(p) = out.last_mut()
                        && q.lo - p.hi <= self.merge_gap_m
                        && small.only_small_near(p.b, q.a, 0.5 * width)
                        && detour_m(clear, p.b, q.a).is_some_and(|d| d <= q.lo - p.hi + DETOUR_SLACK_WIDTHS * width)
                    {
                        (p.b, p.hi) = (q.b, q.hi);
                        continue;
                    }
                    out.push(q);
                }
                out
            })
            .collect()
    }
}

/// The map's obstacles (8-connected components of cells that are not free), each marked small
/// where it fits in a square of the merge gap's side: a speck or a pillar, not a wall.
struct SmallObstacles<'m> {
    map: &'m crate::map::GridMap,
    /// Per map cell: whether it is a cell of a small obstacle (false for free cells).
    small: Vec<bool>,
}

impl<'m> SmallObstacles<'m> {
    fn of(map: &'m crate::map::GridMap, side_m: f64) -> Self {
        let (rows, cols) = (map.rows(), map.cols());
        let mut component = vec![u32::MAX; rows * cols];
        let mut small = vec![false; rows * cols];
        let mut stack = Vec::new();
        let mut members = Vec::new();
        let limit = (side_m / map.resolution()).ceil() as usize;
        for start in 0..rows * cols {
            if component[start] != u32::MAX || map.is_free(start / cols, start % cols) {
                continue;
            }
            let id = start as u32;
            component[start] = id;
            stack.push(start);
            members.clear();
            let (mut r0, mut r1, mut c0, mut c1) = (usize::MAX, 0, usize::MAX, 0);
            while let Some(i) = stack.pop() {
                members.push(i);
                let (r, c) = (i / cols, i % cols);
                (r0, r1, c0, c1) = (r0.min(r), r1.max(r), c0.min(c), c1.max(c));
                for dr in -1isize..=1 {
                    for dc in -1isize..=1 {
                        let (nr, nc) = (r as isize + dr, c as isize + dc);
                        if nr < 0 || nc < 0 || nr >= rows as isize || nc >= cols as isize {
                            continue;
                        }
                        let j = nr as usize * cols + nc as usize;
                        if component[j] == u32::MAX && !map.is_free(nr as usize, nc as usize) {
                            component[j] = id;
                            stack.push(j);
                        }
                    }
                }
            }
            let fits = r1 - r0 < limit && c1 - c0 < limit;
            for &i in &members {
                small[i] = fits;
            }
        }
        Self { map, small }
    }

    /// Whether every obstacle cell within `radius` of the segment from `a` to `b` belongs to a
    /// small obstacle.
    fn only_small_near(&self, a: crate::geom::Point, b: crate::geom::Point, radius: f64) -> bool {
        let map = self.map;
        let res = map.resolution();
        let reach = radius + res;
        let (x0, x1) = (a.x.min(b.x) - reach, a.x.max(b.x) + reach);
        let (y0, y1) = (a.y.min(b.y) - reach, a.y.max(b.y) + reach);
        let col = |x: f64| (((x - map.origin().x) / res).floor().max(0.0) as usize).min(map.cols() - 1);
        let row = |y: f64| (((y - map.origin().y) / res).floor().max(0.0) as usize).min(map.rows() - 1);
        for r in row(y0)..=row(y1) {
            for c in col(x0)..=col(x1) {
                if map.is_free(r, c) || self.small[map.index(r, c)] {
                    continue;
                }
                let p = map.cell_centre(r, c);
                let ab = b - a;
                let t =
                    if ab.norm_squared() > 0.0 { ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0) } else { 0.0 };
                if (p - (a + ab * t)).norm() <= radius + 0.5 * res {
                    return false;
                }
            }
        }
        true
    }
}

/// The length of the wall-free route from `a` to `b`, if there is one.
fn detour_m(clear: &Clearance, a: crate::geom::Point, b: crate::geom::Point) -> Option<f64> {
    let route: Vec<crate::geom::Point> = std::iter::once(a).chain(clear.connect(a, b)?).collect();
    Some(crate::coverage::motion::path_length(&route))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point;
    use crate::lanes::boustrophedon::{decompose, lane_pieces, sweep_cells_with};
    use crate::map::{CellState, GridMap};

    /// A 10 × 6 m room at 0.1 m with a 0.4 m pillar in the middle and, where `wall`, a wall
    /// 0.2 m thick across the room at x = 7 m, its door (y from 4.8 to 5.9 m) at the top.
    fn room(wall: bool) -> GridMap {
        let (cols, rows) = (100, 60);
        let mut cells = vec![CellState::Free; cols * rows];
        for r in 0..rows {
            for c in 0..cols {
                let border = r == 0 || c == 0 || r == rows - 1 || c == cols - 1;
                let pillar = (48..52).contains(&c) && (28..32).contains(&r);
                let divider = wall && (70..72).contains(&c) && r < 48;
                if border || pillar || divider {
                    cells[r * cols + c] = CellState::Occupied;
                }
            }
        }
        GridMap::new("room", cols, rows, 0.1, Point::origin(), cells).unwrap()
    }

    #[test]
    fn lanes_join_around_a_pillar_and_not_through_a_wall() {
        let map = room(true);
        let clear = Clearance::new(&map, 0.6);
        let split = lane_pieces(&clear, 0.6, 0.0);
        let merged = LaneJoin::new(&clear, 2.0, 0.6).joined(split.clone());
        let pieces = |lanes: &[Vec<Piece>]| lanes.iter().map(Vec::len).sum::<usize>();
        // The lanes the pillar cuts are whole again; those the wall cuts stay cut.
        assert!(pieces(&merged) < pieces(&split), "{} vs {}", pieces(&merged), pieces(&split));
        for lane in &merged {
            for p in lane {
                // A wall is no small obstacle, even where a short detour rounds its end.
                let crosses_wall = p.a.x < 7.0 && p.b.x > 7.2;
                assert!(!crosses_wall || p.a.y > 4.9, "a lane through the wall: {p:?}");
            }
        }
        assert!(decompose(&merged).len() < decompose(&split).len());
        assert_eq!(pieces(&LaneJoin::new(&clear, 0.0, 0.6).joined(split.clone())), pieces(&split));
    }

    #[test]
    fn a_pillar_is_a_small_obstacle_and_a_wall_is_not() {
        let map = room(true);
        let small = SmallObstacles::of(&map, 2.0);
        let at = |x: f64, y: f64| small.small[map.index((y / 0.1) as usize, (x / 0.1) as usize)];
        assert!(at(4.95, 2.95), "the pillar");
        assert!(!at(7.05, 2.0) && !at(0.05, 3.0), "the divider and the border");
        // A lane through the pillar meets only it; one into the divider meets the wall.
        assert!(small.only_small_near(Point::new(4.4, 3.0), Point::new(5.6, 3.0), 0.3));
        assert!(!small.only_small_near(Point::new(6.6, 2.0), Point::new(7.6, 2.0), 0.3));
        // With a smaller square the pillar (0.4 m) is no longer small.
        assert!(!SmallObstacles::of(&map, 0.3).only_small_near(Point::new(4.4, 3.0), Point::new(5.6, 3.0), 0.3));
    }

    #[test]
    fn a_joined_lane_is_driven_around_the_pillar_without_touching_it() {
        let map = room(false);
        let clear = Clearance::new(&map, 0.6);
        let cells = decompose(&LaneJoin::new(&clear, 2.0, 0.6).joined(lane_pieces(&clear, 0.6, 0.0)));
        assert_eq!(cells.len(), 1, "the pillar no longer splits the room");
        let route = sweep_cells_with(&clear, &cells, Point::new(0.5, 0.5), true);
        let points = route.points();
        for w in points.windows(2).skip(1) {
            assert!(clear.segment_fits(w[0], w[1]), "{:?} → {:?}", w[0], w[1]);
        }
        // The lanes the pillar blocks (y = 2.8 and 3.4 m) are driven on both sides of it.
        for y in [2.8, 3.4] {
            let on = |left: bool| points.iter().any(|p| (p.y - y).abs() < 1e-6 && (p.x < 4.5) == left);
            assert!(on(true) && on(false), "the lane at y = {y} m");
        }
    }
}
