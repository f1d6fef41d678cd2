//! Inward spiral (the hand-made pattern of 003 Table 3.2, generalised to any map): the free
//! space the robot can reach is split into boustrophedon cells (see [`super::boustrophedon`]),
//! and each cell is covered by contour-parallel rings one robot width apart, from its boundary
//! inwards. A cell is a stack of lane pieces (a staircase polygon); ring `j` runs along its
//! `j`-th lane from the bottom, up its right side inset by `j` widths, back along its `j`-th
//! lane from the top and down its left side inset by `j` widths, then steps one width inwards.
//! Cells are visited nearest entry first; every move is collision-free (or skipped).

use super::boustrophedon::{Piece, decompose, lane_pieces};
use super::{GrowingRoute, PatternError};
use crate::geom::Point;

/// The point of `piece` at lane coordinate `t`, clamped to the piece.
fn at(piece: &Piece, t: f64) -> Point {
    let span = piece.hi - piece.lo;
    if span <= 1e-12 {
        return piece.a;
    }
    let s = ((t - piece.lo) / span).clamp(0.0, 1.0);
    piece.a + (piece.b - piece.a) * s
}

/// The ring points of one cell (lanes ordered from its entry side), outermost ring first.
pub(super) fn rings(cell: &[Piece], width: f64) -> Vec<Point> {
    let k = cell.len();
    let mid = |p: &Piece| 0.5 * (p.lo + p.hi);
    let left = |p: &Piece, inset: f64| (p.lo + inset).min(mid(p));
    let right = |p: &Piece, inset: f64| (p.hi - inset).max(mid(p));
    let mut out = Vec::new();
    for j in 0..k.div_ceil(2) {
        let (bottom, top) = (j, k - 1 - j);
        let inset = j as f64 * width;
        out.push(at(&cell[bottom], left(&cell[bottom], inset)));
        out.push(at(&cell[bottom], right(&cell[bottom], inset)));
        if top == bottom {
            break;
        }
        for lane in &cell[bottom + 1..top] {
            out.push(at(lane, right(lane, inset)));
        }
        out.push(at(&cell[top], right(&cell[top], inset)));
        out.push(at(&cell[top], left(&cell[top], inset)));
        for lane in cell[bottom + 1..top].iter().rev() {
            out.push(at(lane, left(lane, inset)));
        }
    }
    out.dedup_by(|a, b| (*a - *b).norm() < 1e-9);
    out
}

/// A cell seen from its other lane end (coordinates along the lane negated).
fn mirrored(cell: &[Piece]) -> Vec<Piece> {
    cell.iter().map(|p| Piece { a: p.b, b: p.a, lo: -p.hi, hi: -p.lo }).collect()
}

/// Plans the spiral from `start` through every cell (the caller returns it to the end).
pub fn plan(clear: &super::Clearance, width: f64, start: Point) -> Result<GrowingRoute, PatternError> {
    let cells = decompose(&lane_pieces(clear, width, 0.0));
    if cells.is_empty() {
        return Err(PatternError::NoRoom { width });
    }
    // Each cell can be entered at any of its four corners: from its first or last lane, at
    // either end.
    let variants: Vec<[Vec<Point>; 4]> = cells
        .iter()
        .map(|c| {
            let rev: Vec<Piece> = c.iter().rev().copied().collect();
            [rings(c, width), rings(&mirrored(c), width), rings(&rev, width), rings(&mirrored(&rev), width)]
        })
        .collect();
    let mut route = GrowingRoute::new(start);
    let mut visited = vec![false; cells.len()];
    for _ in 0..cells.len() {
        let here = route.last();
        let mut best: Option<(f64, usize, usize)> = None;
        for (k, v) in variants.iter().enumerate().filter(|(k, _)| !visited[*k]) {
            for (m, pts) in v.iter().enumerate() {
                let d = (pts[0] - here).norm();
                if best.is_none_or(|b| d < b.0 - 1e-12) {
                    best = Some((d, k, m));
                }
            }
        }
        let (_, k, m) = best.expect("an unvisited cell remains");
        visited[k] = true;
        for &p in &variants[k][m] {
            route.go(clear, p);
        }
    }
    Ok(route)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn piece(lo: f64, hi: f64, y: f64) -> Piece {
        Piece { a: Point::new(lo, y), b: Point::new(hi, y), lo, hi }
    }

    #[test]
    fn rings_of_a_rectangle_go_inwards() {
        // Four lanes 1 m apart from x = 0 to 5: ring 0 around the outside, ring 1 inset 1 m.
        let cell: Vec<Piece> = (0..4).map(|k| piece(0.0, 5.0, k as f64)).collect();
        let p = |x, y| Point::new(x, y);
        let expected = vec![
            p(0.0, 0.0),
            p(5.0, 0.0),
            p(5.0, 1.0),
            p(5.0, 2.0),
            p(5.0, 3.0),
            p(0.0, 3.0),
            p(0.0, 2.0),
            p(0.0, 1.0),
            p(1.0, 1.0),
            p(4.0, 1.0),
            p(4.0, 2.0),
            p(1.0, 2.0),
        ];
        assert_eq!(rings(&cell, 1.0), expected);
    }

    #[test]
    fn an_odd_stack_ends_on_its_middle_lane_and_short_lanes_collapse() {
        let cell = vec![piece(0.0, 4.0, 0.0), piece(1.0, 2.0, 1.0), piece(0.0, 4.0, 2.0)];
        let r = rings(&cell, 1.0);
        // The middle lane is 1 m long: inset by 1 m it collapses to its midpoint 1.5.
        assert_eq!(r.last().copied(), Some(Point::new(1.5, 1.0)));
        assert_eq!(r[..2], [Point::new(0.0, 0.0), Point::new(4.0, 0.0)]);
    }
}
