//! Coverage completion after a pattern: lanes and rings one robot width apart leave strips
//! along walls and around pillars uncovered wherever the free space is not a multiple of the
//! width wide (on SLAM maps, nearly everywhere). This pass visits what is left: repeatedly the
//! uncovered coverable cell nearest to the robot, driving to the reachable robot centre
//! nearest to it and, when the arrival did not sweep it, one short sideways move past it. A
//! cell that no such move sweeps is given up. Only uncovered patches of at least one robot
//! square (`width²`) are visited: slivers in corners cost a detour each for a few cells.
//! `[pattern] complete = false` turns the pass off.

use super::GrowingRoute;
use crate::coverage::CoverageGrid;
use crate::coverage::raster::for_each_swept_cell;
use crate::geom::Point;
use crate::map::clearance::Clearance;
use crate::map::reach::Reach;

/// Visits the uncovered coverable cells after `route`'s pattern.
pub fn complete(clear: &Clearance, reach: &Reach, width: f64, route: &mut GrowingRoute) {
    complete_patches(clear, reach, width, route, min_patch(clear.map(), width));
}

/// [`complete`], visiting uncovered patches of at least `min_patch` cells.
pub fn complete_patches(clear: &Clearance, reach: &Reach, width: f64, route: &mut GrowingRoute, min_patch: usize) {
    let map = clear.map();
    let grid = CoverageGrid::new(map);
    let raster = *grid.raster();
    let cols = map.cols();
    let mut covered = vec![false; grid.len()];
    for w in route.points.windows(2) {
        for_each_swept_cell(&raster, w[0], w[1], width, |i| covered[i] = true);
    }
    let centre = |i: usize| map.cell_centre(i / cols, i % cols);
    let mut open = OpenCells::new(map, patches(map, &covered, reach, min_patch));
    // Cells swept by the moves from `from` on are covered and no longer open.
    let sweep = |covered: &mut Vec<bool>, open: &mut OpenCells, pts: &[Point]| {
        for w in pts.windows(2) {
            for_each_swept_cell(&raster, w[0], w[1], width, |i| {
                if !covered[i] {
                    covered[i] = true;
                    open.remove(i);
                }
            });
        }
    };
    let window = (clear.radius() / map.resolution()).ceil() as isize + 2;
    let near = |i: usize, k: isize| {
        let (r, c) = ((i / cols) as isize, (i % cols) as isize);
        let mut out: Vec<usize> = Vec::new();
        for dr in -k..=k {
            for dc in -k..=k {
                let (nr, nc) = (r + dr, c + dc);
                if nr >= 0 && nc >= 0 && (nr as usize) < map.rows() && (nc as usize) < cols {
                    let j = nr as usize * cols + nc as usize;
                    if clear.centre_fits(j) {
                        out.push(j);
                    }
                }
            }
        }
        let p = centre(i);
        out.sort_by(|&a, &b| (centre(a) - p).norm().total_cmp(&(centre(b) - p).norm()).then(a.cmp(&b)));
        out
    };
    while !open.is_empty() {
        let here = route.last();
        let k = open.nearest(map, here).expect("open is not empty");
        let target = open.swap_remove(k);
        if covered[target] {
            continue;
        }
        let Some(&c) = near(target, window).first() else { continue };
        let before = route.points.len();
        route.go(clear, centre(c));
        sweep(&mut covered, &mut open, &route.points[before.saturating_sub(1)..]);
        if !covered[target] {
            // One short move from the arrival past the cell.
            let from = route.last();
            for c2 in near(c, 2) {
                let to = centre(c2);
                let mut hit = false;
                for_each_swept_cell(&raster, from, to, width, |i| hit |= i == target);
                if hit && clear.segment_fits(from, to) {
                    let before = route.points.len();
                    route.go(clear, to);
                    sweep(&mut covered, &mut open, &route.points[before.saturating_sub(1)..]);
                    break;
                }
            }
        }
    }
}

/// The open cells of the pass in the order it keeps them (the order breaks ties between
/// equally near cells), with the cells of each block of [`BLOCK`]² map cells listed so that
/// the nearest open cell is found by looking at the nearest blocks only. A cell covered on
/// the way is taken out where it stands ([`Self::remove`]): its place in `order` stays, empty,
/// which keeps the order of the others as a `Vec::retain` after each move would, without
/// a pass over every open cell per move.
struct OpenCells {
    /// The open cells in their order, and the places of cells that left.
    order: Vec<usize>,
    /// Per map cell: its position in `order`, or `u32::MAX` once it left.
    position: Vec<u32>,
    /// Per block: the cells that were open in it at the start (those gone are passed over).
    blocks: Vec<Vec<usize>>,
    /// Per block: how many of its cells are still open.
    live: Vec<u32>,
    /// Cells still open.
    open: usize,
    /// Per block, reused by [`Self::nearest`]: the least distance of its square from the point.
    bounds: Vec<f64>,
    block_cols: usize,
    /// The map's columns.
    cols: usize,
}

/// Edge of a block, in cells.
const BLOCK: usize = 16;

impl OpenCells {
    fn new(map: &crate::map::GridMap, order: Vec<usize>) -> Self {
        let block_cols = map.cols().div_ceil(BLOCK);
        let blocks_n = block_cols * map.rows().div_ceil(BLOCK);
        let position = vec![u32::MAX; map.rows() * map.cols()];
        let (blocks, live) = (vec![Vec::new(); blocks_n], vec![0u32; blocks_n]);
        let mut open = Self {
            order: Vec::new(),
            position,
            blocks,
            live,
            open: order.len(),
            bounds: Vec::new(),
            block_cols,
            cols: map.cols(),
        };
        for (k, &i) in order.iter().enumerate() {
            open.position[i] = k as u32;
            let b = open.block_of(i);
            open.blocks[b].push(i);
            open.live[b] += 1;
        }
        open.order = order;
        open
    }

    fn block_of(&self, i: usize) -> usize {
        (i / self.cols / BLOCK) * self.block_cols + i % self.cols / BLOCK
    }

    fn is_empty(&self) -> bool {
        self.open == 0
    }

    /// The position of the open cell whose centre is nearest to `here`, the first in the
    /// order among equally near ones: what a scan of the whole order with `min_by` gives. The
    /// block of least distance is read first, then every block that may hold a cell as near
    /// as the best so far (the minimum of a total order: the order blocks are read in does
    /// not change it).
    fn nearest(&mut self, map: &crate::map::GridMap, here: Point) -> Option<usize> {
        let (res, o, cols) = (map.resolution(), map.origin(), map.cols());
        let mut bounds = std::mem::take(&mut self.bounds);
        bounds.clear();
        bounds.extend((0..self.blocks.len()).map(|b| {
            if self.live[b] == 0 {
                return f64::INFINITY;
            }
            let (c0, r0) = ((b % self.block_cols) * BLOCK, (b / self.block_cols) * BLOCK);
            let (c1, r1) = ((c0 + BLOCK).min(cols) - 1, (r0 + BLOCK).min(map.rows()) - 1);
            let span = |v: f64, lo: usize, hi: usize, o: f64| {
                let (a, b) = (o + (lo as f64 + 0.5) * res, o + (hi as f64 + 0.5) * res);
                (a - v).max(0.0).max(v - b)
            };
            span(here.x, c0, c1, o.x).hypot(span(here.y, r0, r1, o.y))
        }));
        let first = (0..bounds.len())
            .filter(|&b| self.live[b] > 0)
            .min_by(|&a, &b| bounds[a].total_cmp(&bounds[b]).then(a.cmp(&b)));
        let mut best: Option<(f64, u32)> = None;
        for b in first.into_iter().chain((0..bounds.len()).filter(|&b| Some(b) != first && self.live[b] > 0)) {
            // A margin far above rounding: a block that may hold an equally near cell is read.
            if best.is_some_and(|(d, _)| bounds[b] > d * (1.0 + 1e-9) + 1e-12) {
                continue;
            }
            for &i in &self.blocks[b] {
                let k = self.position[i];
                if k == u32::MAX {
                    continue;
                }
                let d = (map.cell_centre(i / cols, i % cols) - here).norm();
                if best.is_none_or(|(bd, bk)| d.total_cmp(&bd).then(k.cmp(&bk)).is_lt()) {
                    best = Some((d, k));
                }
            }
        }
        self.bounds = bounds;
        best.map(|(_, k)| k as usize)
    }

    /// Takes the open cell at position `k` out; the last open cell takes its place
    /// (`Vec::swap_remove` on the open cells).
    fn swap_remove(&mut self, k: usize) -> usize {
        while let Some(&last) = self.order.last()
            && self.position[last] == u32::MAX
        {
            self.order.pop();
        }
        let i = self.order.swap_remove(k);
        self.leave(i);
        if let Some(&moved) = self.order.get(k) {
            self.position[moved] = k as u32;
        }
        i
    }

    fn leave(&mut self, i: usize) {
        self.position[i] = u32::MAX;
        let b = self.block_of(i);
        self.live[b] -= 1;
        self.open -= 1;
    }

    /// Takes cell `i` out if it is open, leaving its place in the order empty.
    fn remove(&mut self, i: usize) {
        if self.position[i] != u32::MAX {
            self.leave(i);
        }
    }
}

/// The smallest uncovered patch the pass visits, in cells: one robot square.
pub fn min_patch(map: &crate::map::GridMap, width: f64) -> usize {
    ((width / map.resolution()).powi(2)).ceil() as usize
}

/// The uncovered coverable cells in 8-connected patches of at least `min_patch` cells.
pub fn patches(map: &crate::map::GridMap, covered: &[bool], reach: &Reach, min_patch: usize) -> Vec<usize> {
    let (rows, cols) = (map.rows() as isize, map.cols() as isize);
    let open = |i: usize| reach.is_coverable(i) && !covered[i];
    let mut seen = vec![false; covered.len()];
    let mut out = Vec::new();
    for start in 0..covered.len() {
        if seen[start] || !open(start) {
            continue;
        }
        seen[start] = true;
        let mut patch = vec![start];
        let mut k = 0;
        while k < patch.len() {
            let i = patch[k];
            k += 1;
            let (r, c) = ((i as isize) / cols, (i as isize) % cols);
            for dr in -1..=1 {
                for dc in -1..=1 {
                    let (nr, nc) = (r + dr, c + dc);
                    if nr >= 0 && nc >= 0 && nr < rows && nc < cols {
                        let j = (nr * cols + nc) as usize;
                        if !seen[j] && open(j) {
                            seen[j] = true;
                            patch.push(j);
                        }
                    }
                }
            }
        }
        if patch.len() >= min_patch {
            out.extend(patch);
        }
    }
    out.sort_unstable();
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::presets::preset;
    use proptest::prelude::*;

    proptest! {
        /// The block index answers as the scan of the whole order with `min_by` (the first of
        /// equally near cells), through removals by position and of single cells, from
        /// points on and off cell centres (where ties are common); the open cells keep the
        /// order `Vec::swap_remove` and `Vec::retain` give.
        #[test]
        fn nearest_open_cell_is_the_scans(
            picks in proptest::collection::vec(0usize..60_000, 1..300),
            queries in proptest::collection::vec((0.0f64..30.0, 0.0f64..20.0, proptest::bool::ANY), 1..20),
            drop_every in 2usize..7,
        ) {
            let map = preset("office").unwrap();
            let mut order: Vec<usize> = picks.clone();
            order.sort_unstable();
            order.dedup();
            let mut open = OpenCells::new(&map, order.clone());
            let cols = map.cols();
            let centre = |i: usize| map.cell_centre(i / cols, i % cols);
            let open_order = |open: &OpenCells| -> Vec<usize> {
                open.order.iter().copied().filter(|&i| open.position[i] != u32::MAX).collect()
            };
            for (n, &(x, y, on_centre)) in queries.iter().enumerate() {
                if order.is_empty() {
                    prop_assert!(open.is_empty());
                    break;
                }
                let here = if on_centre { centre(map.index((y / 0.1) as usize, (x / 0.1) as usize)) } else { Point::new(x, y) };
                let scan = order
                    .iter()
                    .enumerate()
                    .min_by(|a, b| (centre(*a.1) - here).norm().total_cmp(&(centre(*b.1) - here).norm()))
                    .map(|(k, _)| order[k]);
                let k = open.nearest(&map, here);
                prop_assert_eq!(k.map(|k| open.order[k]), scan);
                let k = k.unwrap();
                let scan_k = order.iter().position(|&i| Some(i) == scan).unwrap();
                prop_assert_eq!(open.swap_remove(k), order.swap_remove(scan_k));
                if n % 2 == 1 {
                    let keep = |i: usize| !i.is_multiple_of(drop_every);
                    order.retain(|&i| keep(i));
                    for i in 0..map.rows() * cols {
                        if !keep(i) {
                            open.remove(i);
                        }
                    }
                }
                prop_assert_eq!(open_order(&open), order.clone());
                prop_assert_eq!(open.is_empty(), order.is_empty());
            }
        }
    }
}
