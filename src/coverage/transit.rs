//! Wall-free transit costs between sweep ends, computed once per map: for every distinct exit
//! point, one Dijkstra over the cell centres where the robot fits (8-connected, no corner
//! cutting, the moves of [`Clearance::steps`]), read at every distinct entry point. Points
//! join the grid at their nearest fitting centre; where the straight segment between an exit
//! and an entry fits, its length is used instead. The grid distance is an upper bound of the
//! route the plan finally drives ([`Clearance::connect`] shortens it by line of sight), so the
//! search never counts on a shortcut that does not exist.

use crate::geom::Point;
use crate::map::clearance::Clearance;
use rayon::prelude::*;
use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};

/// Transit lengths in metres from exits to entries (`f32::INFINITY`: no wall-free route).
#[derive(Clone, Debug)]
pub struct Transit {
    entries: usize,
    metres: Vec<f32>,
}

/// Distinct points in order of first appearance, and each input's index among them.
pub fn distinct(points: &[Point]) -> (Vec<Point>, Vec<u32>) {
    let mut seen: HashMap<(u64, u64), u32> = HashMap::new();
    let mut out = Vec::new();
    let ids = points
        .iter()
        .map(|p| {
            *seen.entry((p.x.to_bits(), p.y.to_bits())).or_insert_with(|| {
                out.push(*p);
                (out.len() - 1) as u32
            })
        })
        .collect();
    (out, ids)
}

impl Transit {
    /// The lengths from every point of `exits` to every point of `entries` (each distinct).
    pub fn new(clear: &Clearance, exits: &[Point], entries: &[Point]) -> Self {
        Self::new_within(clear, exits, entries, None).expect("no deadline")
    }

    /// [`Self::new`], given up (`None`) once `deadline` has passed: a run's wall clock covers
    /// its preparation too.
    pub fn new_within(
        clear: &Clearance,
        exits: &[Point],
        entries: &[Point],
        deadline: Option<std::time::Instant>,
    ) -> Option<Self> {
        let expired = std::sync::atomic::AtomicBool::new(false);
        let past = || {
            deadline.is_some_and(|d| std::time::Instant::now() >= d) && {
                expired.store(true, std::sync::atomic::Ordering::Relaxed);
                true
            }
        };
        let map = clear.map();
        let res = map.resolution();
        let cols = map.cols();
        let centre = |i: usize| map.cell_centre(i / cols, i % cols);
        // A point joins the grid at its nearest fitting centre when that lies within a radius
        // and two cells (a station next to a wall); farther, the nearest centre may lie
        // behind a wall, and the point counts as off the grid.
        let max_snap = clear.radius() + 2.0 * res;
        let snap = |p: Point| clear.snap(p).map(|i| (i, (centre(i) - p).norm())).filter(|(_, d)| *d <= max_snap);
        let entry_snap: Vec<Option<(usize, f64)>> = entries.iter().map(|&p| snap(p)).collect();
        // Straight moves are checked only between points this close: farther pairs rarely see
        // each other on a floor plan, and the grid distance bounds them anyway.
        let near = 8.0 * clear.radius().max(res);
        let metres: Vec<f32> = exits
            .par_iter()
            .map_init(
                || vec![f64::INFINITY; map.rows() * cols],
                |dist, &exit| {
                    let mut row = vec![f32::INFINITY; entries.len()];
                    if expired.load(std::sync::atomic::Ordering::Relaxed) || past() {
                        return row;
                    }
                    if let Some((s, leg)) = snap(exit) {
                        let touched = dijkstra(clear, s, leg, res, dist);
                        for (k, snap) in entry_snap.iter().enumerate() {
                            if let Some((j, leg)) = snap {
                                row[k] = (dist[*j] + leg) as f32;
                            }
                        }
                        for i in touched {
                            dist[i] = f64::INFINITY;
                        }
                    }
                    for (k, &entry) in entries.iter().enumerate() {
                        let straight = (entry - exit).norm();
                        if straight < f64::from(row[k]) && straight <= near && clear.segment_fits(exit, entry) {
                            row[k] = straight as f32;
                        }
                    }
                    row
                },
            )
            .flatten()
            .collect();
        (!expired.into_inner()).then_some(Self { entries: entries.len(), metres })
    }

    /// The transit length from exit `exit` to entry `entry` in metres.
    pub fn metres(&self, exit: usize, entry: usize) -> f64 {
        f64::from(self.metres[exit * self.entries + entry])
    }
}

/// Grid distances in metres from cell `source` (at `offset` metres from the exit) into `dist`
/// (all infinite on entry); returns the cells it set, so the caller can reset them.
fn dijkstra(clear: &Clearance, source: usize, offset: f64, res: f64, dist: &mut [f64]) -> Vec<usize> {
    // Keys in micrometres keep the heap's order total and deterministic.
    let key = |d: f64| (d * 1e6) as u64;
    let mut heap = BinaryHeap::new();
    let mut touched = vec![source];
    dist[source] = offset;
    heap.push(Reverse((key(offset), source)));
    while let Some(Reverse((k, i))) = heap.pop() {
        if k > key(dist[i]) {
            continue;
        }
        for (j, step) in clear.steps(i) {
            let cand = dist[i] + step * res;
            if cand < dist[j] - 1e-12 {
                if dist[j].is_infinite() {
                    touched.push(j);
                }
                dist[j] = cand;
                heap.push(Reverse((key(cand), j)));
            }
        }
    }
    touched
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::CellState;
    use crate::map::GridMap;

    /// Two 2 × 1 m rooms at 0.1 m joined by a door at the top of a wall at x = 2 m.
    fn two_rooms() -> GridMap {
        let (cols, rows) = (41, 10);
        let mut cells = vec![CellState::Free; cols * rows];
        for r in 0..6 {
            cells[r * cols + 20] = CellState::Occupied;
        }
        GridMap::new("rooms", cols, rows, 0.1, Point::origin(), cells).unwrap()
    }

    #[test]
    fn transit_goes_through_the_door_and_straight_where_it_can() {
        let map = two_rooms();
        let clear = Clearance::new(&map, 0.2);
        let exits = [Point::new(1.0, 0.25), Point::new(1.5, 0.55)];
        let entries = [Point::new(3.0, 0.25), Point::new(1.5, 0.25)];
        let t = Transit::new(&clear, &exits, &entries);
        // Around the wall: up to the door (centres at y ≥ 0.7 past x = 2.05) and down again,
        // at least the two straight pieces through that corner, at most the 8-connected
        // grid's excess over them.
        let corner = 2.0 * (1.05f64.powi(2) + 0.45f64.powi(2)).sqrt();
        let around = t.metres(0, 0);
        assert!(around > corner && around < 1.2 * corner, "{around} vs {corner}");
        // Same room: the straight segment.
        assert!((t.metres(1, 1) - 0.3).abs() < 1e-6, "{}", t.metres(1, 1));
        assert!((t.metres(0, 1) - 0.5).abs() < 1e-6);
    }

    #[test]
    fn no_route_is_infinite() {
        let (cols, rows) = (41, 10);
        let mut cells = vec![CellState::Free; cols * rows];
        for r in 0..rows {
            cells[r * cols + 20] = CellState::Occupied;
        }
        let map = GridMap::new("split", cols, rows, 0.1, Point::origin(), cells).unwrap();
        let mut clear = Clearance::new(&map, 0.2);
        clear.restrict(crate::map::reach::reachable_centres(&clear, &[Point::new(0.5, 0.5)]));
        let t = Transit::new(&clear, &[Point::new(0.5, 0.5)], &[Point::new(3.0, 0.5)]);
        assert!(t.metres(0, 0).is_infinite());
    }

    #[test]
    fn distinct_points_keep_their_first_order() {
        let (p, q) = (Point::new(1.0, 2.0), Point::new(0.5, 0.5));
        let (out, ids) = distinct(&[p, q, p]);
        assert_eq!(out, vec![p, q]);
        assert_eq!(ids, vec![0, 1, 0]);
    }
}
