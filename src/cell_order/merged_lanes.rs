//! Lanes that continue across small obstacles. A boustrophedon decomposition ends a lane
//! wherever the robot's body does not fit, so every speck and pillar of a SLAM map splits the
//! cell around it into more cells of shorter lanes. Here the pieces of one lane are joined
//! across a gap of at most `merge_gap_m` metres wherever the robot can drive around the
//! obstacle in it on a detour at most [`DETOUR_SLACK_WIDTHS`] robot widths longer than the gap
//! (a wall between two rooms has no such detour, a pillar does): cells merge across the
//! obstacle, and the sweep of a joined piece drives its lane around it
//! ([`crate::patterns::boustrophedon::sweep_cells_with`]), so that the plan stays executable.
//! This is the merged-cells question Bähnemann et al. (2019) leave open.

use crate::map::clearance::Clearance;
use crate::patterns::boustrophedon::Piece;

/// How much longer than the gap the detour around the obstacle in it may be, in robot widths.
pub const DETOUR_SLACK_WIDTHS: f64 = 2.0;

/// `lanes` with the consecutive pieces of each lane joined across every gap of at most
/// `merge_gap_m` metres whose detour (the wall-free route from one piece's end to the next
/// one's start) is at most [`DETOUR_SLACK_WIDTHS`] · `width` longer than the gap; `lanes` as
/// they are when `merge_gap_m` is 0.
pub fn joined(clear: &Clearance, lanes: Vec<Vec<Piece>>, merge_gap_m: f64, width: f64) -> Vec<Vec<Piece>> {
    if merge_gap_m <= 0.0 {
        return lanes;
    }
    lanes
        .into_iter()
        .map(|lane| {
            let mut out: Vec<Piece> = Vec::with_capacity(lane.len());
            for q in lane {
                if let Some(p) = out.last_mut()
                    && q.lo - p.hi <= merge_gap_m
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

/// The length of the wall-free route from `a` to `b`, if there is one.
fn detour_m(clear: &Clearance, a: crate::geom::Point, b: crate::geom::Point) -> Option<f64> {
    let hops = clear.connect(a, b)?;
    let mut length = 0.0;
    let mut prev = a;
    for p in hops {
        length += (p - prev).norm();
        prev = p;
    }
    Some(length)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point;
    use crate::map::{CellState, GridMap};
    use crate::patterns::boustrophedon::{decompose, lane_pieces, sweep_cells_with};

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
        let merged = joined(&clear, split.clone(), 2.0, 0.6);
        let pieces = |lanes: &[Vec<Piece>]| lanes.iter().map(Vec::len).sum::<usize>();
        // The lanes the pillar cuts are whole again; those the wall cuts stay cut.
        assert!(pieces(&merged) < pieces(&split), "{} vs {}", pieces(&merged), pieces(&split));
        for lane in &merged {
            for p in lane {
                // Beside the door a lane may round the wall's end (a short detour); lower down
                // the only way round is through the door, far longer than the gap.
                let crosses_wall = p.a.x < 7.0 && p.b.x > 7.2;
                assert!(!crosses_wall || p.a.y > 4.0, "a lane through the wall: {p:?}");
            }
        }
        assert!(decompose(&merged).len() < decompose(&split).len());
        assert_eq!(pieces(&joined(&clear, split.clone(), 0.0, 0.6)), pieces(&split));
    }

    #[test]
    fn a_joined_lane_is_driven_around_the_pillar_without_touching_it() {
        let map = room(false);
        let clear = Clearance::new(&map, 0.6);
        let cells = decompose(&joined(&clear, lane_pieces(&clear, 0.6, 0.0), 2.0, 0.6));
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
