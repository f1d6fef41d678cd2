//! Wall-free transit costs between sweep ends, computed once per map: for every distinct exit
//! point, one Dijkstra over the cell centres where the robot fits (8-connected, no corner
//! cutting, the moves of [`Clearance::steps`]), read at every distinct entry point. Points
//! join the grid at their nearest fitting centre; where the straight segment between an exit
//! and an entry fits, its length is used instead. The grid distance is an upper bound of the
//! route the plan finally drives ([`Clearance::connect`] shortens it by line of sight), so the
//! search never counts on a shortcut that does not exist.

use super::bucket_queue::BucketQueue;
use crate::geom::Point;
use crate::map::clearance::Clearance;
use rayon::prelude::*;
use std::collections::HashMap;

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
        Self::new_within(clear, exits, entries, &|| false).expect("never given up")
    }

    /// [`Self::new`], given up (`None`) once `give_up` says so (asked before each exit's
    /// routes): a run's wall clock and its interrupt cover its preparation too.
    pub fn new_within(
        clear: &Clearance,
        exits: &[Point],
        entries: &[Point],
        give_up: &(dyn Fn() -> bool + Sync),
    ) -> Option<Self> {
        let expired = std::sync::atomic::AtomicBool::new(false);
        let past = || {
            give_up() && {
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
        let grid = StepGrid::of(clear);
        // Each exit's row is written in place: no row is held twice (the matrix is most of the
        // set-up's memory on a large map).
        let mut metres = vec![f32::INFINITY; exits.len() * entries.len()];
        metres.par_chunks_mut(entries.len().max(1)).zip(exits.par_iter()).for_each_init(
            || Search::new(map.rows() * cols, res),
            |search, (row, &exit)| {
                if expired.load(std::sync::atomic::Ordering::Relaxed) || past() {
                    return;
                }
                if let Some((s, leg)) = snap(exit) {
                    search.dijkstra(&grid, s, leg, res);
                    for (k, snap) in entry_snap.iter().enumerate() {
                        if let Some((j, leg)) = snap {
                            row[k] = (search.dist[*j] + leg) as f32;
                        }
                    }
                    search.reset();
                }
                for (k, &entry) in entries.iter().enumerate() {
                    let straight = (entry - exit).norm();
                    if straight < f64::from(row[k]) && straight <= near && clear.segment_fits(exit, entry) {
                        row[k] = straight as f32;
                    }
                }
            },
        );
        (!expired.into_inner()).then_some(Self { entries: entries.len(), metres })
    }

    /// The transit length from exit `exit` to entry `entry` in metres.
    pub fn metres(&self, exit: usize, entry: usize) -> f64 {
        f64::from(self.metres[exit * self.entries + entry])
    }
}

/// The steps of [`Clearance::steps`] of every cell, as one byte of flags per cell (bit `d` for
/// the `d`-th of its eight directions, in the order `steps` lists them), read once per map
/// instead of once per search.
struct StepGrid {
    allowed: Vec<u8>,
    /// Index offsets of the eight directions.
    offsets: [isize; 8],
}

/// The eight directions of [`Clearance::steps`], in its order: (row, column) offsets.
const DIRECTIONS: [(isize, isize); 8] = [(-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1)];

impl StepGrid {
    fn of(clear: &Clearance) -> Self {
        let cols = clear.map().cols() as isize;
        let offsets = DIRECTIONS.map(|(dr, dc)| dr * cols + dc);
        let allowed = (0..clear.map().rows() * clear.map().cols())
            .into_par_iter()
            .map(|i| {
                clear.steps(i).fold(0u8, |mask, (j, _)| {
                    let d = offsets.iter().position(|&o| i as isize + o == j as isize).expect("a neighbour");
                    mask | (1 << d)
                })
            })
            .collect();
        Self { allowed, offsets }
    }
}

/// One worker's Dijkstra: the distances, the cells it set and its queue, reused search after
/// search.
struct Search {
    dist: Vec<f64>,
    touched: Vec<usize>,
    heap: BucketQueue,
}

impl Search {
    /// For a grid of `cells` cells of `res` metres: keys are micrometres, a step adds at most
    /// √2 cells (plus one for the truncation), buckets are a 32nd of a cell wide.
    fn new(cells: usize, res: f64) -> Self {
        let (step, width) = ((res * 1e6 * std::f64::consts::SQRT_2).ceil() as u64 + 2, (res * 1e6 / 32.0) as u64);
        Self { dist: vec![f64::INFINITY; cells], touched: Vec::new(), heap: BucketQueue::new(width, step) }
    }

    /// Grid distances in metres from cell `source` (at `offset` metres from the exit) into
    /// `dist` (all infinite before). Cells are settled by their distance in whole micrometres,
    /// then by index — a total, deterministic order, the one the binary heap this replaced
    /// gave (`tests::the_bucket_queue_search_equals_the_binary_heap_search`) — and a cell takes a
    /// new distance only when it is shorter by more than 1e-12 m.
    fn dijkstra(&mut self, grid: &StepGrid, source: usize, offset: f64, res: f64) {
        let key = |d: f64| (d * 1e6) as u64;
        let (dist, touched, heap) = (&mut self.dist, &mut self.touched, &mut self.heap);
        touched.push(source);
        dist[source] = offset;
        heap.push_source(key(offset), source as u32);
        while let Some((k, i)) = heap.pop() {
            let i = i as usize;
            if k > key(dist[i]) {
                continue;
            }
            let mask = grid.allowed[i];
            for (d, &o) in grid.offsets.iter().enumerate() {
                if mask & (1 << d) == 0 {
                    continue;
                }
                let j = (i as isize + o) as usize;
                let step = if d == 0 || d == 2 || d == 5 || d == 7 { std::f64::consts::SQRT_2 } else { 1.0 };
                let cand = dist[i] + step * res;
                if cand < dist[j] - 1e-12 {
                    if dist[j].is_infinite() {
                        touched.push(j);
                    }
                    dist[j] = cand;
                    heap.push(key(cand), j as u32);
                }
            }
        }
    }

    /// Back to all infinite, for the next search.
    fn reset(&mut self) {
        for &i in &self.touched {
            self.dist[i] = f64::INFINITY;
        }
        self.touched.clear();
        self.heap.clear();
    }
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

    /// The search this module ran before the bucket queue and the step flags: a binary heap of
    /// `Reverse((micrometres, cell))` over [`Clearance::steps`].
    fn binary_heap_dijkstra(clear: &Clearance, source: usize, offset: f64, res: f64) -> Vec<f64> {
        use std::cmp::Reverse;
        let key = |d: f64| (d * 1e6) as u64;
        let mut dist = vec![f64::INFINITY; clear.map().rows() * clear.map().cols()];
        let mut heap = std::collections::BinaryHeap::new();
        dist[source] = offset;
        heap.push(Reverse((key(offset), source)));
        while let Some(Reverse((k, i))) = heap.pop() {
            if k > key(dist[i]) {
                continue;
            }
            for (j, step) in clear.steps(i) {
                let cand = dist[i] + step * res;
                if cand < dist[j] - 1e-12 {
                    dist[j] = cand;
                    heap.push(Reverse((key(cand), j)));
                }
            }
        }
        dist
    }

    #[test]
    fn the_bucket_queue_search_equals_the_binary_heap_search() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(2);
        for round in 0..12 {
            // A room with random pillars and walls, at a random resolution.
            let (cols, rows) = (rng.random_range(20..90), rng.random_range(20..90));
            let mut cells = vec![CellState::Free; cols * rows];
            for _ in 0..rng.random_range(0..40) {
                let (r, c) = (rng.random_range(0..rows), rng.random_range(0..cols));
                let (h, w) = (rng.random_range(1..6), rng.random_range(1..6));
                for rr in r..(r + h).min(rows) {
                    for cc in c..(c + w).min(cols) {
                        cells[rr * cols + cc] = CellState::Occupied;
                    }
                }
            }
            let res = [0.05, 0.1, 0.0732][round % 3];
            let map = GridMap::new("pillars", cols, rows, res, Point::origin(), cells).unwrap();
            let clear = Clearance::new(&map, 2.5 * res);
            let grid = StepGrid::of(&clear);
            let mut search = Search::new(cols * rows, res);
            for _ in 0..5 {
                let source = rng.random_range(0..cols * rows);
                let offset = rng.random_range(0.0..res);
                search.dijkstra(&grid, source, offset, res);
                let expected = binary_heap_dijkstra(&clear, source, offset, res);
                let same = search.dist.iter().zip(&expected).all(|(a, b)| a.to_bits() == b.to_bits());
                assert!(same, "round {round}: the distances differ");
                search.reset();
                assert!(search.dist.iter().all(|d| d.is_infinite()), "reset for the next search");
            }
        }
    }

    #[test]
    fn distinct_points_keep_their_first_order() {
        let (p, q) = (Point::new(1.0, 2.0), Point::new(0.5, 0.5));
        let (out, ids) = distinct(&[p, q, p]);
        assert_eq!(out, vec![p, q]);
        assert_eq!(ids, vec![0, 1, 0]);
    }
}
