//! The idealised control's lane order (issue 102, item 1): from where the robot stands, next
//! the lane piece with an end nearest by the wall-free grid distance (a Dijkstra over the
//! fitting cell centres, the moves of [`Clearance::steps`], stopped at the first centre that
//! holds an end of a piece not yet driven), entered at that end. The buffers of the search
//! are allocated once per order and reused for every step.

use super::lanes::LanePiece;
use crate::geom::Point;
use crate::map::clearance::Clearance;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// One leg of the order: which piece, whether it is driven from `b` to `a`, and the grid
/// distance from where the robot stood to its entry (metres; infinite where no route
/// reaches it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Leg {
    /// Index of the piece.
    pub piece: usize,
    /// Driven from `b` to `a`.
    pub reversed: bool,
    /// The grid distance to its entry in metres.
    pub transit_m: f64,
}

/// A centre of the search queue, nearest first (ties: the lower cell index).
#[derive(Clone, Copy, PartialEq)]
struct Queued(f64, usize);

impl Eq for Queued {}

impl Ord for Queued {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

impl PartialOrd for Queued {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// The greedy nearest order of `pieces` from `start`: every piece once, the pieces no route
/// reaches left out.
pub fn greedy(clear: &Clearance, pieces: &[LanePiece], start: Point) -> Vec<Leg> {
    let cells = clear.map().rows() * clear.map().cols();
    // Per centre, the first end held there; per end, the next end at the same centre.
    let mut first_end = vec![u32::MAX; cells];
    let mut next_end = vec![u32::MAX; 2 * pieces.len()];
    for (e, p) in pieces.iter().flat_map(|p| [p.a, p.b]).enumerate() {
        if let Some(c) = clear.snap(p) {
            next_end[e] = first_end[c];
            first_end[c] = e as u32;
        }
    }
    let mut done = vec![false; pieces.len()];
    let mut dist = vec![f64::INFINITY; cells];
    let mut touched: Vec<usize> = Vec::new();
    let mut heap = BinaryHeap::new();
    let mut here = clear.snap(start);
    let mut legs = Vec::with_capacity(pieces.len());
    while let Some(from) = here {
        for &i in &touched {
            dist[i] = f64::INFINITY;
        }
        touched.clear();
        heap.clear();
        dist[from] = 0.0;
        touched.push(from);
        heap.push(Queued(0.0, from));
        let mut found = None;
        while let Some(Queued(d, i)) = heap.pop() {
            if d > dist[i] {
                continue;
            }
            let mut e = first_end[i];
            while e != u32::MAX {
                if !done[e as usize / 2] && found.is_none_or(|f| e < f) {
                    found = Some(e);
                }
                e = next_end[e as usize];
            }
            if let Some(e) = found {
                let piece = e as usize / 2;
                done[piece] = true;
                legs.push(Leg { piece, reversed: e % 2 == 1, transit_m: d });
                // The robot leaves the piece at its other end.
                let exit = if e % 2 == 1 { pieces[piece].a } else { pieces[piece].b };
                here = clear.snap(exit);
                break;
            }
            for (j, step) in clear.steps(i) {
                let nd = d + step;
                if nd < dist[j] {
                    if dist[j].is_infinite() {
                        touched.push(j);
                    }
                    dist[j] = nd;
                    heap.push(Queued(nd, j));
                }
            }
        }
        if found.is_none() {
            break;
        }
    }
    legs
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layouts::room;

    #[test]
    fn every_reachable_piece_is_driven_once_nearest_first() {
        let map = room(80, 80);
        let clear = Clearance::new(&map, 0.6);
        let pieces: Vec<LanePiece> = (0..6)
            .map(|k| {
                let y = 0.5 + 0.55 * k as f64;
                LanePiece { a: Point::new(0.5, y), b: Point::new(3.0, y) }
            })
            .collect();
        let legs = greedy(&clear, &pieces, Point::new(0.5, 0.5));
        let mut seen: Vec<usize> = legs.iter().map(|l| l.piece).collect();
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen.len(), legs.len(), "a piece driven twice: {legs:?}");
        assert_eq!(legs[0].piece, 0, "the piece at the start first");
        assert!(legs[0].transit_m < 0.1);
        // Back and forth: each next lane entered at the end the last one left.
        for w in legs.windows(2) {
            assert_ne!(w[0].reversed, w[1].reversed, "{legs:?}");
        }
    }
}
