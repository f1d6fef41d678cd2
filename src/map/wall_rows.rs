//! The non-free cells of each map row, indexed for nearest-neighbour queries along the row.
//!
//! Distance queries from a point to the non-free cells around it (clearance, fit tests) scan a
//! square window of cells. Within one row of the window the distance from the point to a cell's
//! square only grows with the column distance on either side of the point's own column, so the
//! nearest non-free cell of that row lies among the nearest on each side: two or four cells
//! per row instead of the whole row of the window. The callers' results are unchanged (every
//! cell that can be the minimum is still examined; tested against the full scan).

use super::GridMap;
use crate::geom::Point;

/// The gap along one axis from coordinate `v` to the cell spanning `[lo, lo + res]` (0 inside).
pub fn axis_gap(lo: f64, v: f64, res: f64) -> f64 {
    (lo - v).max(0.0).max(v - lo - res)
}

/// No non-free cell on that side.
const NONE: u32 = u32::MAX;

/// For every cell, the nearest non-free column of its row at or left of it and at or right of it.
#[derive(Clone, Debug)]
pub struct WallRows {
    cols: usize,
    /// `left[row·cols + c]`: the largest non-free column `≤ c` of the row, or [`NONE`].
    left: Vec<u32>,
    /// `right[row·cols + c]`: the smallest non-free column `≥ c` of the row, or [`NONE`].
    right: Vec<u32>,
    /// `before[r·(cols + 1) + c]`: the non-free cells in rows `< r` and columns `< c`, so that
    /// a window with none is answered without reading its rows.
    before: Vec<u32>,
}

impl WallRows {
    /// The index of `map`'s non-free cells, one pass over the map each way.
    pub fn new(map: &GridMap) -> Self {
        let (rows, cols) = (map.rows(), map.cols());
        let mut left = vec![NONE; rows * cols];
        let mut right = vec![NONE; rows * cols];
        for r in 0..rows {
            let mut last = NONE;
            for c in 0..cols {
                if !map.is_free(r, c) {
                    last = c as u32;
                }
                left[r * cols + c] = last;
            }
            last = NONE;
            for c in (0..cols).rev() {
                if !map.is_free(r, c) {
                    last = c as u32;
                }
                right[r * cols + c] = last;
            }
        }
        let mut before = vec![0u32; (rows + 1) * (cols + 1)];
        for r in 0..rows {
            let mut in_row = 0;
            for c in 0..cols {
                in_row += u32::from(!map.is_free(r, c));
                before[(r + 1) * (cols + 1) + c + 1] = before[r * (cols + 1) + c + 1] + in_row;
            }
        }
        Self { cols, left, right, before }
    }

    /// The non-free cells in rows `r0..=r1` and columns `c0..=c1` (valid, non-empty ranges).
    fn count_in(&self, (r0, r1): (usize, usize), (c0, c1): (usize, usize)) -> u32 {
        let at = |r: usize, c: usize| self.before[r * (self.cols + 1) + c];
        at(r1 + 1, c1 + 1) + at(r0, c0) - at(r0, c1 + 1) - at(r1 + 1, c0)
    }

    /// Calls `visit` with the non-free columns of row `row` within `lo..=hi` (valid columns)
    /// among which, for a point whose column is `at`, the nearest one lies: the nearest on each
    /// side of `at` and, where `at` itself is non-free, the nearest on each side of it too
    /// (rounding can put the point a hair outside its own cell's square). A column may be
    /// visited twice.
    pub fn candidates(&self, row: usize, at: isize, lo: usize, hi: usize, mut visit: impl FnMut(usize)) {
        if lo > hi {
            return;
        }
        let a = at.clamp(lo as isize, hi as isize) as usize;
        let base = row * self.cols;
        let left = |c: usize| Some(self.left[base + c]).filter(|&l| l != NONE && l as usize >= lo);
        let right = |c: usize| Some(self.right[base + c]).filter(|&r| r != NONE && r as usize <= hi);
        let around =
            [left(a), if a > lo { left(a - 1) } else { None }, right(a), if a < hi { right(a + 1) } else { None }];
        for c in around.into_iter().flatten() {
            visit(c as usize);
        }
    }
}

impl WallRows {
    /// The least `dist(dx, dy)` (starting from `init`) over the gaps along x and y from `p` to
    /// the square of every non-free cell that can be the nearest one in its row, over the rows
    /// and columns within `window` cells of `p`'s cell on `map` (the map this index was built
    /// from): the minimum of a scan of the whole window. `row_floor(dy)` must bound from below
    /// every `dist(dx, dy)` of a row whose gap along y is `dy`: rows are read outwards from
    /// `p`'s row, where `dy` only grows, and each direction stops at the first row whose floor
    /// reaches the least value found, since no row beyond it can go below (tested against the
    /// full scan).
    pub fn least_near(
        &self,
        map: &GridMap,
        p: Point,
        window: isize,
        init: f64,
        dist: impl Fn(f64, f64) -> f64,
        row_floor: impl Fn(f64) -> f64,
    ) -> f64 {
        let (ox, oy, res) = (map.origin().x, map.origin().y, map.resolution());
        let (cc, cr) = (((p.x - ox) / res).floor() as isize, ((p.y - oy) / res).floor() as isize);
        let (lo, hi) = ((cc - window).max(0), (cc + window).min(map.cols() as isize - 1));
        let (first, last) = ((cr - window).max(0), (cr + window).min(map.rows() as isize - 1));
        let mut best = init;
        if lo > hi || first > last || self.count_in((first as usize, last as usize), (lo as usize, hi as usize)) == 0 {
            return best;
        }
        let row = |r: isize, best: &mut f64| {
            let dy = axis_gap(oy + r as f64 * res, p.y, res);
            if row_floor(dy) >= *best {
                return false;
            }
            self.candidates(r as usize, cc, lo as usize, hi as usize, |c| {
                *best = best.min(dist(axis_gap(ox + c as f64 * res, p.x, res), dy));
            });
            true
        };
        // `p`'s row may lie outside the window's rows (a point off the map): then every row of
        // the window is on one side of it.
        let split = cr.clamp(first - 1, last);
        for r in (first..=split).rev() {
            if !row(r, &mut best) {
                break;
            }
        }
        for r in split + 1..=last {
            if !row(r, &mut best) {
                break;
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::CellState;
    use proptest::prelude::*;

    /// Row 0 holds `walls`; row 1 is free (a map needs a free cell).
    fn map_of(walls: &[bool]) -> GridMap {
        let cols = walls.len();
        let cells = walls
            .iter()
            .map(|&w| if w { CellState::Occupied } else { CellState::Free })
            .chain(std::iter::repeat_n(CellState::Free, cols))
            .collect();
        GridMap::new("row", cols, 2, 0.1, crate::geom::Point::new(0.0, 0.0), cells).unwrap()
    }

    proptest! {
        /// The candidates hold a nearest non-free cell of the row window for any column of the
        /// point, inside or outside the window, and nothing outside the window.
        #[test]
        fn candidates_hold_the_nearest(
            walls in proptest::collection::vec(proptest::bool::weighted(0.2), 24),
            at in -5isize..30,
            lo in 0usize..12,
            span in 0usize..12,
        ) {
            let m = map_of(&walls);
            let idx = WallRows::new(&m);
            let hi = (lo + span).min(23);
            let mut got = Vec::new();
            idx.candidates(0, at, lo, hi, |c| got.push(c));
            prop_assert!(got.iter().all(|&c| c >= lo && c <= hi && walls[c]));
            let dist = |c: usize| (c as isize - at).abs();
            let best = (lo..=hi).filter(|&c| walls[c]).map(dist).min();
            prop_assert_eq!(got.iter().map(|&c| dist(c)).min(), best);
        }
    }
}
