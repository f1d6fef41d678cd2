//! Row-by-row scan conversion of the swept rectangle (the cell rule of [`super::raster`]),
//! for consumers that work on whole rows at once: the bit-row evaluator of the thesis GA.
//!
//! Unlike [`super::raster::for_each_swept_run`], which scans along a segment's major axis,
//! this always scans rows: the members of one row are one interval of columns whatever the
//! direction, and a row's interval costs the same to use whether it holds one cell or forty
//! when the consumer handles it as a bit mask. Each of the two constraints `0 ≤ t < L` and
//! `−w/2 ≤ s < w/2` is linear in the column; where its coefficient vanishes (a constraint
//! parallel to the rows) it is decided once per row instead, and interval ends that come
//! within a small margin of a cell centre are settled with the exact membership test.

use super::raster::{RASTER_EPS, RasterGrid, SETTLE_MARGIN, floor_i, larger, settle_interval, smaller};
use crate::geom::{Point, ZERO_LENGTH};

/// Below this magnitude a constraint's column coefficient is treated as unreliable: its
/// interval is not used and both ends of the row are settled with the exact test.
const TINY_COEFFICIENT: f64 = 1e-9;

/// One linear constraint `lo ≤ coef·dx + k0 + k1·row < hi` on the column of a row, as the
/// interval `[lo.0 + lo.1·row, hi.0 + hi.1·row]` of fractional column positions it allows.
/// A constraint that cannot be divided by its coefficient allows every column (±∞) and is
/// decided by the exact test instead: `flat` when the coefficient is 0 (decided once per
/// row), `tiny` when it is too small to divide by (both ends settled exactly).
#[derive(Clone, Copy)]
struct Constraint {
    lo: (f64, f64),
    hi: (f64, f64),
    flat: bool,
    tiny: bool,
}

impl Constraint {
    /// `bounds.0 ≤ coef·dx + k0 + k1·row < bounds.1`, with `dx = (f − pos_a)·res`.
    fn new(coef: f64, k0: f64, k1: f64, bounds: (f64, f64), pos_a: f64, inv_res: f64) -> Self {
        if coef.abs() < TINY_COEFFICIENT {
            let open = Self { lo: (f64::NEG_INFINITY, 0.0), hi: (f64::INFINITY, 0.0), flat: false, tiny: false };
            return if coef == 0.0 { Self { flat: true, ..open } } else { Self { tiny: true, ..open } };
        }
        let scale = inv_res / coef;
        let end = |bound: f64| (pos_a + (bound - k0) * scale, -k1 * scale);
        let (mut lo, mut hi) = (end(bounds.0), end(bounds.1));
        if coef < 0.0 {
            std::mem::swap(&mut lo, &mut hi);
        }
        Self { lo, hi, flat: false, tiny: false }
    }
}

/// Calls `run(row, first_col, last_col)` (inclusive) for every row holding cells of the swept
/// rectangle of `a → b` with robot width `width` (thesis-ga §3.3): the same cells as
/// [`super::raster::for_each_swept_cell`], grouped by row. Cells off the grid are ignored;
/// a zero-length segment sweeps nothing.
pub fn for_each_swept_row(grid: &RasterGrid, a: Point, b: Point, width: f64, mut run: impl FnMut(usize, usize, usize)) {
    let v = b - a;
    let len = v.norm();
    if len < ZERO_LENGTH || grid.cols == 0 || grid.rows == 0 {
        return;
    }
    let (ux, uy) = (v.x / len, v.y / len);
    let hw = 0.5 * width;
    let res = grid.resolution;
    let inv_res = 1.0 / res;
    // Rows whose centre may lie within the rectangle's vertical extent (one of margin).
    let ext = hw * ux.abs();
    let (lo_y, hi_y) = (a.y.min(b.y) - ext, a.y.max(b.y) + ext);
    let row_lo = floor_i((lo_y - grid.origin_y) * inv_res - 0.5).max(0);
    let row_hi = (floor_i((hi_y - grid.origin_y) * inv_res - 0.5) + 1).min(grid.rows as i64 - 1);
    if row_hi < row_lo {
        return;
    }
    let t_hi = len - RASTER_EPS;
    let (s_lo, s_hi) = (-hw - RASTER_EPS, hw - RASTER_EPS);
    let last = grid.cols as i64 - 1;
    let margin = SETTLE_MARGIN * inv_res;
    let pos_a = (a.x - grid.origin_x) * inv_res - 0.5;
    // dy(row) = dy0 + row·res.
    let dy0 = grid.origin_y + 0.5 * res - a.y;
    // t = dx·ux + dy·uy and s = −dx·uy + dy·ux.
    let t = Constraint::new(ux, dy0 * uy, res * uy, (-RASTER_EPS, t_hi), pos_a, inv_res);
    let s = Constraint::new(-uy, dy0 * ux, res * ux, (s_lo, s_hi), pos_a, inv_res);
    let settle_always = t.tiny || s.tiny;
    let any_flat = t.flat || s.flat;
    let last_f = last as f64;
    for row in row_lo as usize..=row_hi as usize {
        let rf = row as f64;
        let dy = dy0 + rf * res;
        // The exact membership test of thesis-ga §3.3.
        let inside = |col: i64| {
            let dx = grid.origin_x + (col as f64 + 0.5) * res - a.x;
            let tt = dx * ux + dy * uy;
            let ss = -dx * uy + dy * ux;
            tt >= -RASTER_EPS && tt < t_hi && ss >= s_lo && ss < s_hi
        };
        let f0 = larger(t.lo.0 + t.lo.1 * rf, s.lo.0 + s.lo.1 * rf);
        let f1 = smaller(t.hi.0 + t.hi.1 * rf, s.hi.0 + s.hi.1 * rf);
        if any_flat {
            let (tv, sv) = (dy * uy, dy * ux);
            if (t.flat && !(tv >= -RASTER_EPS && tv < t_hi)) || (s.flat && !(sv >= s_lo && sv < s_hi)) {
                continue;
            }
        }
        if f0 > f1 + 1.0 || f1 < -1.0 || f0 > last_f + 1.0 {
            continue;
        }
        if let Some((lo, hi)) = settle_interval(f0, f1, last, margin, settle_always, inside) {
            run(row, lo as usize, hi as usize);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::raster::swept_cells_brute_force;
    use proptest::prelude::*;

    fn grid() -> RasterGrid {
        RasterGrid { cols: 55, rows: 55, resolution: 0.2, origin_x: 0.0, origin_y: 0.0 }
    }

    fn rows(g: &RasterGrid, a: Point, b: Point, w: f64) -> Vec<usize> {
        let mut v = Vec::new();
        let mut last_row = None;
        for_each_swept_row(g, a, b, w, |row, lo, hi| {
            assert!(last_row.is_none_or(|r| r < row), "rows ascend, each once");
            assert!(lo <= hi && hi < g.cols);
            last_row = Some(row);
            v.extend((lo..=hi).map(|c| row * g.cols + c));
        });
        v
    }

    #[test]
    fn vertical_and_horizontal_lanes() {
        // 3 m at 0.2 m = 15 rows, 0.6 m wide = 3 columns; and the same lying down.
        let up = rows(&grid(), Point::new(1.3, 1.3), Point::new(1.3, 4.3), 0.6);
        assert_eq!(up.len(), 45);
        let flat = rows(&grid(), Point::new(1.3, 1.3), Point::new(4.3, 1.3), 0.6);
        assert_eq!(flat.len(), 45);
        assert!(rows(&grid(), Point::new(2.0, 2.0), Point::new(2.0, 2.0), 0.6).is_empty());
    }

    #[test]
    fn centres_exactly_on_the_far_ends_are_outside() {
        use crate::coverage::exact::{far_end_on_a_centre, solve};
        // thesis-ga §3.3 is half-open: a cell belongs when t < L − ε and s < w/2 − ε. Each segment
        // is placed, ulp by ulp, so that the scan's own arithmetic puts whole cell centres
        // exactly on one of those ends; those cells are out, as the brute-force rule says.
        // t: along row 5 from column 0's centre; column 3's centre lies at t = L − ε.
        let (g, a, b) = far_end_on_a_centre();
        let centre = |k: usize| (k as f64 + 0.5) * g.resolution;
        let swept = rows(&g, a, b, 0.3);
        assert_eq!(swept, vec![100, 101, 102], "columns 0 to 2 of row 5, not 3");
        assert_eq!(swept, swept_cells_brute_force(&g, a, b, 0.3));
        // s: up from row 2's centre, 1 m, 0.45 m wide (a width for which an exact start
        // exists); column 0's centre lies at s = w/2 − ε (s = −dx for a segment pointing up).
        let s_hi = 0.5 * 0.45 - RASTER_EPS;
        let s_of_column_0 = |ax: f64| -((g.origin_x + 0.5 * g.resolution) - ax);
        let ax = solve(s_of_column_0, true, s_hi, centre(0) + s_hi).expect("an exact far end in s");
        let (a, b) = (Point::new(ax, centre(2)), Point::new(ax, centre(2) + 1.0));
        let swept = rows(&g, a, b, 0.45);
        assert_eq!(swept, vec![41, 61, 81, 101], "column 1 of rows 2 to 5, not column 0");
        assert_eq!(swept, swept_cells_brute_force(&g, a, b, 0.45));
        // The same ends for constraints parallel to the rows, decided once per row. t: up
        // column 5 from row 0's centre; row 3's centre lies at t = L − ε.
        let a = Point::new(centre(5), centre(0));
        let t_end = |by: f64| (Point::new(a.x, by) - a).norm() - RASTER_EPS;
        let by = solve(t_end, true, centre(3) - a.y, centre(3) + RASTER_EPS).expect("an exact far end in t");
        let swept = rows(&g, a, Point::new(a.x, by), 0.3);
        assert_eq!(swept, vec![5, 25, 45], "rows 0 to 2 of column 5, not 3");
        assert_eq!(swept, swept_cells_brute_force(&g, a, Point::new(a.x, by), 0.3));
        // s: along the rows, 1 m from 0.1 m before column 2's centre (so that no column is
        // near an end in t and the row's test alone decides), 0.45 m wide; row 1's centre lies
        // at s = w/2 − ε (s = dy for a segment pointing right), as the scan computes dy.
        let s_of_row_1 = |ay: f64| ((g.origin_y + 0.5 * g.resolution) - ay) + 1.0 * g.resolution;
        let ay = solve(s_of_row_1, false, s_hi, centre(1) - s_hi).expect("an exact far end in s");
        let (a, b) = (Point::new(centre(2) - 0.1, ay), Point::new(centre(2) + 0.9, ay));
        let swept = rows(&g, a, b, 0.45);
        assert_eq!(swept, vec![2, 3, 4, 5], "columns 2 to 5 of row 0, not row 1");
        assert_eq!(swept, swept_cells_brute_force(&g, a, b, 0.45));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]
        #[test]
        fn rows_equal_brute_force(ax in -1.0..12.0f64, ay in -1.0..12.0f64, bx in -1.0..12.0f64, by in -1.0..12.0f64, w in 0.05..1.5f64) {
            let (a, b) = (Point::new(ax, ay), Point::new(bx, by));
            prop_assert_eq!(rows(&grid(), a, b, w), swept_cells_brute_force(&grid(), a, b, w));
        }

        #[test]
        fn nearly_axis_aligned_rows_match_brute_force(ax in 0.0..11.0f64, ay in 0.0..11.0f64, quarter in 0..8u8, tilt in -1e-7..1e-7f64, exact in proptest::bool::ANY, len in 0.1..10.0f64) {
            let angle = f64::from(quarter) * std::f64::consts::FRAC_PI_4 + if exact { 0.0 } else { tilt };
            let a = Point::new((ax * 5.0).round() / 5.0 + 0.1, (ay * 5.0).round() / 5.0 + 0.1);
            let b = a + crate::geom::Vector::new(angle.cos(), angle.sin()) * len;
            prop_assert_eq!(rows(&grid(), a, b, 0.6), swept_cells_brute_force(&grid(), a, b, 0.6));
        }

        #[test]
        fn grid_aligned_rows_match_brute_force(ax in 0..55i32, ay in 0..55i32, bx in 0..55i32, by in 0..55i32, w in 1..5u8) {
            let (a, b) = (Point::new(ax as f64 * 0.1, ay as f64 * 0.2), Point::new(bx as f64 * 0.2, by as f64 * 0.1));
            let w = f64::from(w) * 0.2;
            prop_assert_eq!(rows(&grid(), a, b, w), swept_cells_brute_force(&grid(), a, b, w));
        }

        #[test]
        fn wide_grids_with_offset_origins_match(ax in -5.0..30.0f64, ay in -5.0..8.0f64, bx in -5.0..30.0f64, by in -5.0..8.0f64, w in 0.05..1.5f64) {
            // 150 columns: rows span three 64-bit words.
            let g = RasterGrid { cols: 150, rows: 30, resolution: 0.17, origin_x: -1.3, origin_y: 0.4 };
            let (a, b) = (Point::new(ax, ay), Point::new(bx, by));
            prop_assert_eq!(rows(&g, a, b, w), swept_cells_brute_force(&g, a, b, w));
        }

        /// Cells larger than a metre on a grid whose origin lies below and left of zero: the
        /// range of rows is found in cell units from the grid's origin, not in metres from zero.
        #[test]
        fn coarse_grids_below_zero_match(ax in -6.0..24.0f64, ay in -5.0..14.0f64, bx in -6.0..24.0f64, by in -5.0..14.0f64, w in 0.05..4.0f64) {
            let g = RasterGrid { cols: 20, rows: 12, resolution: 1.25, origin_x: -3.7, origin_y: -2.9 };
            let (a, b) = (Point::new(ax, ay), Point::new(bx, by));
            prop_assert_eq!(rows(&g, a, b, w), swept_cells_brute_force(&g, a, b, w));
        }
    }
}
