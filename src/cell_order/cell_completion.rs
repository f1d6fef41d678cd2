//! Completion inside each cell: a candidate sweep's lanes leave strips along its region's walls
//! and clutter, and driving them right after the lanes, from where the lanes end, makes the
//! completion part of the candidate. Its time then enters the tour's cost exactly, and the
//! choice of direction and entry corner per cell shapes the completion too — where a global
//! pass after the tour, whose time depends on every cell's choice at once, can only be
//! guessed from the area left (which ranked plans badly: see `results/cell-order`).
//!
//! Each sweep gets the boundary chains ([`super::boundary::chains_within`]) near the coverable
//! cells of its own region that its lanes leave, ordered from the lanes' exit with the end
//! left free, joined by wall-free routes. What the chains still miss is left to the plan's
//! completion pass after the tour.

use super::boundary::{chains_within, order};
use super::sweeps::Sweep;
use crate::lanes::GrowingRoute;
use crate::map::clearance::Clearance;
use rayon::prelude::*;
use std::ops::Range;

/// Extends every sweep of `cells` (cell `k`'s region: the map cells labelled `k` in `labels`)
/// with the boundary completion of the coverable cells of its region that it leaves, for a
/// robot `width` wide driving at `speed` (which orders the chains).
pub fn extend(clear: &Clearance, width: f64, labels: &[u32], coverable: &[bool], speed: f64, cells: &mut [Vec<Sweep>]) {
    let map = clear.map();
    let margin = (width / map.resolution()).ceil() as usize + 1;
    let windows = region_windows(map, labels, cells.len(), margin);
    let grid = crate::coverage::CoverageGrid::new(map);
    cells.par_iter_mut().enumerate().for_each(|(k, cell)| {
        for sweep in cell.iter_mut() {
            let targets = left_in_region(&grid, width, labels, coverable, k as u32, sweep, &windows[k]);
            let chains = chains_within(clear, &targets, windows[k].clone());
            if chains.is_empty() {
                continue;
            }
            let mut route = GrowingRoute::new(sweep.end());
            for chain in order(&chains, sweep.end(), None, speed) {
                for p in chain {
                    route.go(clear, p);
                }
            }
            let mut points = std::mem::take(&mut sweep.points);
            points.extend_from_slice(&route.points()[1..]);
            *sweep = Sweep { split: sweep.split, ..Sweep::new(sweep.direction_deg, sweep.entry, points) };
        }
    });
}

/// Per region, the map rows and columns it spans, widened by `margin` cells (clamped).
fn region_windows(
    map: &crate::map::GridMap,
    labels: &[u32],
    regions: usize,
    margin: usize,
) -> Vec<(Range<usize>, Range<usize>)> {
    let cols = map.cols();
    let mut bounds = vec![(usize::MAX, 0usize, usize::MAX, 0usize); regions];
    for (i, &l) in labels.iter().enumerate() {
        if l == u32::MAX {
            continue;
        }
        let (r, c) = (i / cols, i % cols);
        let b = &mut bounds[l as usize];
        *b = (b.0.min(r), b.1.max(r), b.2.min(c), b.3.max(c));
    }
    bounds
        .into_iter()
        .map(|(r0, r1, c0, c1)| {
            if r0 == usize::MAX {
                return (0..0, 0..0);
            }
            let rows = r0.saturating_sub(margin)..(r1 + margin + 1).min(map.rows());
            let cols = c0.saturating_sub(margin)..(c1 + margin + 1).min(map.cols());
            (rows, cols)
        })
        .collect()
}

/// The coverable cells of region `k` that `sweep` leaves unswept (one flag per map cell).
fn left_in_region(
    grid: &crate::coverage::CoverageGrid,
    width: f64,
    labels: &[u32],
    coverable: &[bool],
    k: u32,
    sweep: &Sweep,
    window: &(Range<usize>, Range<usize>),
) -> Vec<bool> {
    let cols = grid.raster().cols;
    let mut targets = vec![false; labels.len()];
    for r in window.0.clone() {
        for c in window.1.clone() {
            let i = r * cols + c;
            targets[i] = labels[i] == k && coverable[i];
        }
    }
    for w in sweep.points.windows(2) {
        crate::coverage::raster::for_each_swept_cell(grid.raster(), w[0], w[1], width, |i| targets[i] = false);
    }
    targets
}

#[cfg(test)]
mod tests {
    use super::super::sweeps::CellSweeps;
    use crate::geom::Point;
    use crate::map::clearance::Clearance;
    use crate::map::presets::preset;
    use crate::map::reach::Reach;

    /// On the disc map every sweep leaves strips round the discs; completing them inside the
    /// cell leaves fewer cells of the region, never more, and keeps every move fitting.
    #[test]
    fn completion_in_cells_leaves_less_and_keeps_every_move_fitting() {
        let m = preset("thesis-2").unwrap();
        let mut clear = Clearance::new(&m, 0.6);
        let reach = Reach::new(&clear, &[Point::new(1.3, 1.3)]);
        clear.restrict(reach.centres().to_vec());
        let before = CellSweeps::new(
            &clear,
            0.6,
            &[0.0, 90.0],
            reach.coverable(),
            super::super::merged_lanes::LaneLayout::SPLIT,
        );
        let mut after = before.clone();
        after.complete_in_cells(&clear, 0.6, reach.coverable(), 0.2);
        let (mut left_before, mut left_after) = (0, 0);
        for (a, b) in before.cells.iter().flatten().zip(after.cells.iter().flatten()) {
            assert!(b.missed_cells <= a.missed_cells, "{} {}", a.missed_cells, b.missed_cells);
            assert_eq!(&b.points[..a.points.len()], &a.points[..], "the lanes come first, unchanged");
            for w in b.points.windows(2) {
                assert!(clear.segment_fits(w[0], w[1]), "{:?}", w);
            }
            left_before += a.missed_cells;
            left_after += b.missed_cells;
        }
        assert!(3 * left_after < left_before, "{left_after} of {left_before} left");
    }
}
