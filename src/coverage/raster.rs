//! Swept-rectangle rasterisation (003 §3.1.2, Fig. 3.2b; cell rule of thesis-ga §3.3 / R4).
//!
//! A segment `a → b` of length `L` swept by a robot of width `w` covers the cells whose centre
//! `c` satisfies `0 ≤ t < L` and `−w/2 ≤ s < w/2`, with `t = (c − a)·û`, `s = (c − a)·n̂`,
//! `n̂ = (−û_y, û_x)`, both half-open with a 1e-9 m tolerance and no end caps. Half-open
//! intervals make collinear consecutive segments and exactly adjacent lanes tile without
//! double counting.
//!
//! The scan visits one row at a time and solves the two linear constraints for the column
//! interval, then confirms each candidate with the exact test, so the work is proportional to
//! the swept cells plus two per row.

use crate::geom::{Point, ZERO_LENGTH};

/// Tolerance of the half-open membership test (thesis-ga §3.3).
pub const RASTER_EPS: f64 = 1e-9;

/// The geometry of a grid as the rasteriser needs it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RasterGrid {
    /// Columns.
    pub cols: usize,
    /// Rows.
    pub rows: usize,
    /// Cell edge in metres.
    pub resolution: f64,
    /// World x of the grid's left edge.
    pub origin_x: f64,
    /// World y of the grid's bottom edge.
    pub origin_y: f64,
}

impl RasterGrid {
    /// The raster geometry of a map.
    pub fn of(map: &crate::map::GridMap) -> Self {
        Self {
            cols: map.cols(),
            rows: map.rows(),
            resolution: map.resolution(),
            origin_x: map.origin().x,
            origin_y: map.origin().y,
        }
    }
}

/// `floor` without a libm call (the default x86-64 target has no rounding instruction).
#[inline(always)]
pub(super) fn floor_i(x: f64) -> i64 {
    let i = x as i64;
    if (i as f64) > x { i - 1 } else { i }
}

/// The larger of two numbers, neither of them NaN (one comparison; `f64::max` also handles
/// NaN, which the scans never meet: their bounds are finite or ±∞ and never summed to NaN).
#[inline(always)]
pub(super) fn larger(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

/// The smaller of two numbers, neither of them NaN (see [`larger`]).
#[inline(always)]
pub(super) fn smaller(a: f64, b: f64) -> f64 {
    if a < b { a } else { b }
}

/// A cell centre closer than this (metres) to an interval end is settled with the exact test;
/// farther ones are decided by the interval, whose rounding error is many orders smaller.
pub(super) const SETTLE_MARGIN: f64 = 1e-6;

/// The members of one scan line: the cells `lo ..= hi` (of `0 ..= last`) whose centres lie in
/// the fractional interval `[f0, f1]`, where an end within `margin` of a centre (or every end,
/// with `always`) is settled with the exact membership test `inside`. `None` when empty.
#[inline(always)]
pub(super) fn settle_interval(
    f0: f64,
    f1: f64,
    last: i64,
    margin: f64,
    always: bool,
    inside: impl Fn(i64) -> bool,
) -> Option<(i64, i64)> {
    // First centre at or after f0, last at or before f1 (the ends kept finite).
    let mut lo = -floor_i(-larger(f0, -1.0));
    let mut hi = floor_i(smaller(f1, last as f64 + 1.0));
    let lo_near = always || (lo as f64 - f0) < margin || (f0 - (lo - 1) as f64) < margin;
    let hi_near = always || (f1 - hi as f64) < margin || ((hi + 1) as f64 - f1) < margin;
    // As `clamp`, without its check that the bounds are in order (`last` ≥ 0 here).
    lo = lo.max(0).min(last + 1);
    hi = hi.max(-1).min(last);
    if lo_near {
        while lo > 0 && inside(lo - 1) {
            lo -= 1;
        }
        while lo <= hi && !inside(lo) {
            lo += 1;
        }
    }
    if hi_near {
        while hi < last && inside(hi + 1) {
            hi += 1;
        }
        while hi >= lo && !inside(hi) {
            hi -= 1;
        }
    }
    (lo <= hi).then_some((lo, hi))
}

/// Calls `visit(row-major index)` once for every cell of the swept rectangle of `a → b` with
/// robot width `width` (thesis-ga §3.3). Cells off the grid are ignored; a zero-length segment
/// sweeps nothing. The scan runs along the segment's major axis (rows for flat segments,
/// columns for steep ones), so each scan line holds many cells; the order within a segment is
/// therefore not row-major, which the counting of Listing 3.1 does not depend on.
#[inline]
pub fn for_each_swept_cell(grid: &RasterGrid, a: Point, b: Point, width: f64, mut visit: impl FnMut(usize)) {
    for_each_swept_run(grid, a, b, width, |first, count, stride| {
        for k in 0..count {
            visit(first + k * stride);
        }
    });
}

/// Like [`for_each_swept_cell`], but hands over whole runs of one scan line:
/// `run(first_index, count, stride)` covers `first_index + k·stride` for `k < count`, with
/// `stride` 1 (a row) or the number of columns (a column). Consumers keep their counters in
/// registers within a run, which is what makes the evaluator fast.
#[inline]
pub fn for_each_swept_run(grid: &RasterGrid, a: Point, b: Point, width: f64, run: impl FnMut(usize, usize, usize)) {
    let v = b - a;
    if v.x.abs() >= v.y.abs() {
        scan::<false>(grid, a, b, width, run);
    } else {
        scan::<true>(grid, a, b, width, run);
    }
}

/// Scan conversion of one segment. Lines are rows (`STEEP = false`) or columns (`true`); along
/// a line both constraints `0 ≤ t < L` and `−w/2 ≤ s < w/2` are linear, so the members of a
/// line are one run between the two interval ends. The ends are affine in the line index;
/// where a cell centre lies within [`SETTLE_MARGIN`] of an end (or the slope is too small to
/// trust the division), the end is settled with the exact test.
#[inline(always)]
fn scan<const STEEP: bool>(
    grid: &RasterGrid,
    a: Point,
    b: Point,
    width: f64,
    mut run: impl FnMut(usize, usize, usize),
) {
    let Some(ScanLines {
        lines: (line_lo, line_hi),
        t_ends: (t_a, t_b),
        s_ends: (s_a, s_b),
        s_flat,
        s_tiny,
        dl0,
        res,
        along: (a_org, a_start, ua, sigma),
        unit: (ux, uy),
        bounds: (t_hi, s_lo, s_hi),
        last,
        margin,
    }) = scan_lines::<STEEP>(grid, a, b, width)
    else {
        return;
    };
    let cols = grid.cols;
    for line in line_lo..=line_hi {
        let lf = line as f64;
        let dl = dl0 + lf * res;
        // The exact membership test of the swept rectangle (003 §3.1), written on world dx, dy.
        let inside = |k: i64| {
            let da = a_org + (k as f64 + 0.5) * res - a_start;
            let (dx, dy) = if STEEP { (dl, da) } else { (da, dl) };
            let t = dx * ux + dy * uy;
            let s = -dx * uy + dy * ux;
            t >= -RASTER_EPS && t < t_hi && s >= s_lo && s < s_hi
        };
        let (mut f0, mut f1) = (t_a.0 + t_a.1 * lf, t_b.0 + t_b.1 * lf);
        if s_flat {
            let s = sigma * dl * ua;
            if !(s >= s_lo && s < s_hi) {
                continue;
            }
        } else if !s_tiny {
            f0 = f0.max(s_a.0 + s_a.1 * lf);
            f1 = f1.min(s_b.0 + s_b.1 * lf);
        }
        if f0 > f1 + 1.0 || f1 < -1.0 || f0 > last as f64 + 1.0 {
            continue;
        }
        let Some((lo, hi)) = settle_interval(f0, f1, last, margin, s_tiny, inside) else {
            continue;
        };
        let count = (hi - lo + 1) as usize;
        if STEEP {
            run(lo as usize * cols + line, count, cols);
        } else {
            run(line * cols + lo as usize, count, 1);
        }
    }
}

/// An interval end along a scan line, affine in the line index: `(c0, c1)` for `c0 + c1·line`.
type Affine = (f64, f64);

/// What the scan of one segment needs, worked out once: the lines it may touch, the affine
/// interval ends along a line (from `t`: `t_a`, `t_b`; from `s`: `s_a`, `s_b`), and the terms
/// of the exact test. See [`scan`].
struct ScanLines {
    lines: (usize, usize),
    t_ends: (Affine, Affine),
    s_ends: (Affine, Affine),
    s_flat: bool,
    s_tiny: bool,
    dl0: f64,
    res: f64,
    along: (f64, f64, f64, f64),
    unit: (f64, f64),
    bounds: (f64, f64, f64),
    last: i64,
    margin: f64,
}

/// The set-up of [`scan`]; `None` when the segment touches no line of the grid.
#[inline(always)]
fn scan_lines<const STEEP: bool>(grid: &RasterGrid, a: Point, b: Point, width: f64) -> Option<ScanLines> {
    let v = b - a;
    let len = v.norm();
    if len < ZERO_LENGTH || grid.cols == 0 || grid.rows == 0 {
        return None;
    }
    let (ux, uy) = (v.x / len, v.y / len);
    let hw = 0.5 * width;
    let res = grid.resolution;
    let inv_res = 1.0 / res;
    // Axis along the scan line (a) and across lines (l), in world terms.
    let (a_org, l_org, a_start, l_start, l_end, a_n, l_n) = if STEEP {
        (grid.origin_y, grid.origin_x, a.y, a.x, b.x, grid.rows as i64, grid.cols as i64)
    } else {
        (grid.origin_x, grid.origin_y, a.x, a.y, b.y, grid.cols as i64, grid.rows as i64)
    };
    let (ua, ul) = if STEEP { (uy, ux) } else { (ux, uy) };
    // t = d_a·ua + d_l·ul;  s = −dx·uy + dy·ux = σ·(d_l·ua − d_a·ul), σ = −1 when steep.
    let sigma = if STEEP { -1.0 } else { 1.0 };
    // Lines whose centre may lie within the rectangle's extent across lines (one of margin).
    let ext = hw * ua.abs();
    let (lo_l, hi_l) = (l_start.min(l_end) - ext, l_start.max(l_end) + ext);
    let line_lo = floor_i((lo_l - l_org) * inv_res - 0.5).max(0);
    let line_hi = (floor_i((hi_l - l_org) * inv_res - 0.5) + 1).min(l_n - 1);
    if line_hi < line_lo {
        return None;
    }
    let t_hi = len - RASTER_EPS;
    let (s_lo, s_hi) = (-hw - RASTER_EPS, hw - RASTER_EPS);
    let last = a_n - 1;
    let margin = SETTLE_MARGIN * inv_res;
    let pos_of_a = (a_start - a_org) * inv_res - 0.5;
    // dl(line) = dl0 + line·res.
    let dl0 = l_org + 0.5 * res - l_start;
    // Interval ends in fractional cell positions along the line, affine in the line index:
    // end(line) = c0 + c1·line. From t: d_a = (bound − dl·ul)/ua.
    let t_scale = inv_res / ua;
    let affine = |bound: f64, slope_num: f64, scale: f64| {
        (pos_of_a + (bound - dl0 * slope_num) * scale, -res * slope_num * scale)
    };
    let (mut t_a, mut t_b) = (affine(-RASTER_EPS, ul, t_scale), affine(t_hi, ul, t_scale));
    if ua < 0.0 {
        std::mem::swap(&mut t_a, &mut t_b);
    }
    // From s: d_a = (σ·dl·ua − bound)/ul·… ; written as bound' = −σ·bound, slope −σ·ua... :
    // s = σ·dl·ua − σ·d_a·ul  ⇒  d_a = (σ·dl·ua − s)/(σ·ul).
    let s_flat = ul == 0.0;
    let s_tiny = !s_flat && ul.abs() < 1e-9;
    let (mut s_a, mut s_b) = ((0.0, 0.0), (0.0, 0.0));
    if !s_flat && !s_tiny {
        let scale = inv_res / (sigma * ul);
        // d_a·inv_res = (σ·ua·dl − s)·scale = (−s − dl·(−σ·ua))·scale.
        s_a = affine(-s_hi, -sigma * ua, scale);
        s_b = affine(-s_lo, -sigma * ua, scale);
        if scale < 0.0 {
            std::mem::swap(&mut s_a, &mut s_b);
        }
    }
    Some(ScanLines {
        lines: (line_lo as usize, line_hi as usize),
        t_ends: (t_a, t_b),
        s_ends: (s_a, s_b),
        s_flat,
        s_tiny,
        dl0,
        res,
        along: (a_org, a_start, ua, sigma),
        unit: (ux, uy),
        bounds: (t_hi, s_lo, s_hi),
        last,
        margin,
    })
}

/// Reference implementation: tests every cell of the grid. Used to check the scan.
pub fn swept_cells_brute_force(grid: &RasterGrid, a: Point, b: Point, width: f64) -> Vec<usize> {
    let v = b - a;
    let len = v.norm();
    let mut out = Vec::new();
    if len < ZERO_LENGTH {
        return out;
    }
    let (ux, uy) = (v.x / len, v.y / len);
    let hw = 0.5 * width;
    for r in 0..grid.rows {
        for c in 0..grid.cols {
            let dx = grid.origin_x + (c as f64 + 0.5) * grid.resolution - a.x;
            let dy = grid.origin_y + (r as f64 + 0.5) * grid.resolution - a.y;
            let t = dx * ux + dy * uy;
            let s = -dx * uy + dy * ux;
            if t >= -RASTER_EPS && t < len - RASTER_EPS && s >= -hw - RASTER_EPS && s < hw - RASTER_EPS {
                out.push(r * grid.cols + c);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn grid() -> RasterGrid {
        RasterGrid { cols: 55, rows: 55, resolution: 0.2, origin_x: 0.0, origin_y: 0.0 }
    }

    fn scan(a: Point, b: Point, w: f64) -> Vec<usize> {
        scan_on(&grid(), a, b, w)
    }

    /// The cells the scan visits, in row-major order.
    fn scan_on(g: &RasterGrid, a: Point, b: Point, w: f64) -> Vec<usize> {
        let mut v = Vec::new();
        for_each_swept_cell(g, a, b, w, |i| v.push(i));
        v.sort_unstable();
        v
    }

    #[test]
    fn axis_aligned_lane_is_three_cells_wide() {
        // 3 m at 0.2 m = 15 columns, 0.6 m wide = 3 rows.
        let cells = scan(Point::new(1.3, 1.3), Point::new(4.3, 1.3), 0.6);
        assert_eq!(cells.len(), 45);
        // Adjacent lanes 0.6 m apart tile without overlap.
        let next = scan(Point::new(1.3, 1.9), Point::new(4.3, 1.9), 0.6);
        assert!(cells.iter().all(|c| !next.contains(c)));
    }

    #[test]
    fn ends_near_a_centre_are_settled_by_the_exact_test() {
        // `inside` plays the exact rule of thesis-ga §3.3, which knows nothing of the line's ends
        // (cells 0 ..= 9 here); the interval [f0, f1] is its rounded image, off by
        // δ = 1e-9 (far below SETTLE_MARGIN) where rounding could put it.
        // Table: (f0, f1, always, the cells the rule admits, the run expected).
        let d = 1e-9;
        // A run of cells, first and last.
        type Run = (i64, i64);
        let cases: [(f64, f64, bool, Run, Option<Run>); 15] = [
            (2.0 + d, 6.5, false, (2, 6), Some((2, 6))),  // centre 2 just below f0, in
            (3.0 - d, 6.5, false, (4, 6), Some((4, 6))),  // centre 3 just above f0, out
            (1.5, 6.0 - d, false, (2, 6), Some((2, 6))),  // centre 6 just above f1, in
            (1.5, 5.0 + d, false, (2, 4), Some((2, 4))),  // centre 5 just below f1, out
            (2.0 + d, 3.5, false, (2, 3), Some((2, 3))),  // a run of two, its first just below f0
            (2.0 + d, 2.5, false, (2, 2), Some((2, 2))),  // a run of one just below f0
            (2.5, 3.0 - d, false, (3, 3), Some((3, 3))),  // a run of one just above f1
            (2.5, 5.5, false, (3, 5), Some((3, 5))),      // no end near a centre
            (3.2, 3.7, false, (4, 3), None),              // no centre between the ends
            (3.0 - d, 3.0 + d, false, (4, 3), None),      // both ends near 3, which is out
            (-3.2, 40.0, false, (-3, 40), Some((0, 9))),  // ends off the line
            (d, 6.5, false, (-3, 6), Some((0, 6))),       // the rule goes on below the line
            (2.5, 9.0 - d, false, (3, 12), Some((3, 9))), // and above it
            (0.5, 8.5, true, (3, 5), Some((3, 5))),       // `always`: the rule alone decides
            (0.5, 8.5, true, (-2, 11), Some((0, 9))),     // the rule beyond the interval: to the line's ends
        ];
        for (i, (f0, f1, always, (lo, hi), expected)) in cases.into_iter().enumerate() {
            let inside = |k: i64| (lo..=hi).contains(&k);
            assert_eq!(settle_interval(f0, f1, 9, SETTLE_MARGIN, always, inside), expected, "case {i}");
        }
    }

    #[test]
    fn an_edge_through_a_row_of_centres_keeps_that_row() {
        // The s = −w/2 edge belongs (thesis-ga §3.3). It lies on the side of growing y for flat
        // segments pointing left, of falling y pointing right, of growing x for steep ones
        // pointing up and of falling x pointing down. With that edge through a line of
        // centres (the grid's last line too), the line is kept, whatever rounding does to the
        // range of lines.
        let g = grid();
        let centre = |k: usize| (k as f64 + 0.5) * g.resolution;
        for k in 0..g.rows {
            for hw in [0.1, 0.2, 0.3, 0.4, 0.5, 0.7, 1.1] {
                let (below, above) = (centre(k) - hw, centre(k) + hw);
                let segments = [
                    (Point::new(8.0, below), Point::new(2.0, below)),
                    (Point::new(2.0, above), Point::new(8.0, above)),
                    (Point::new(below, 2.0), Point::new(below, 8.0)),
                    (Point::new(above, 8.0), Point::new(above, 2.0)),
                ];
                for (a, b) in segments {
                    assert_eq!(
                        scan(a, b, 2.0 * hw),
                        swept_cells_brute_force(&g, a, b, 2.0 * hw),
                        "line {k}, w/2 = {hw}"
                    );
                }
            }
        }
    }

    /// A segment that crosses the lines by less than 1e-9 of its length, down to a subnormal
    /// amount (whose division overflows to infinity), is scanned by the exact rule: the
    /// brute-force cells, rows and columns, both ways. The line range around it holds a line
    /// outside the rectangle (centre 0.375 m off the axis, half-width 0.3 m), which only the
    /// `s` constraint leaves out.
    #[test]
    fn segments_crossing_lines_by_a_tiny_amount_match_brute_force() {
        let g = RasterGrid { cols: 40, rows: 40, resolution: 0.25, origin_x: -3.0, origin_y: -3.0 };
        for tilt in [1e-320, -1e-320, 5e-300, -2e-12, 4e-10] {
            for (a, d) in [
                (Point::new(-1.3, 0.0), (4.1, tilt)),
                (Point::new(2.8, 0.0), (-4.1, tilt)),
                (Point::new(0.0, -1.3), (tilt, 4.1)),
                (Point::new(0.0, 2.8), (tilt, -4.1)),
            ] {
                let b = Point::new(a.x + d.0, a.y + d.1);
                let cells = scan_on(&g, a, b, 0.6);
                assert_eq!(cells.len(), 2 * 16, "{a:?} → {b:?}: two lines of 16 cells");
                assert_eq!(cells, swept_cells_brute_force(&g, a, b, 0.6), "{a:?} → {b:?}");
            }
        }
    }

    /// thesis-ga §3.3 is half-open: a cell belongs when `t < L − ε` and `s < w/2 − ε`. A segment
    /// (or a width) is placed ulp by ulp so that the exact test's own arithmetic puts a cell
    /// centre exactly on one of those ends: that cell is out, as the brute-force rule says, and
    /// in once the end moves past it.
    #[test]
    fn centres_exactly_on_the_far_ends_are_outside() {
        use crate::coverage::exact::{far_end_on_a_centre, solve};
        // t: along row 5 from column 0's centre; column 3's centre lies at t = L − ε.
        let (g, a, b) = far_end_on_a_centre();
        let centre = |k: usize| (k as f64 + 0.5) * g.resolution;
        assert_eq!(scan_on(&g, a, b, 0.2), vec![100, 101, 102], "columns 0 to 2 of row 5, not 3");
        assert_eq!(scan_on(&g, a, b, 0.2), swept_cells_brute_force(&g, a, b, 0.2));
        let past = Point::new(b.x + 1e-6, a.y);
        assert_eq!(scan_on(&g, a, past, 0.2), vec![100, 101, 102, 103]);
        // s: along (4, 3) from (0.125, 0.125); the centre of column 6, row 7 lies at
        // s = −dx·uy + dy·ux (dx = 1.5, dy = 1.75, exact) with the width solved so that
        // w/2 − ε is exactly that s.
        let (a, b) = (Point::new(0.125, 0.125), Point::new(4.125, 3.125));
        let v = b - a;
        let (ux, uy) = (v.x / v.norm(), v.y / v.norm());
        let s = -1.5 * uy + 1.75 * ux;
        let w = solve(|w| 0.5 * w - RASTER_EPS, true, s, 2.0 * (s + RASTER_EPS)).expect("an exact far end in s");
        let cell = 7 * 20 + 6;
        let swept = scan_on(&g, a, b, w);
        assert!(!swept.contains(&cell), "the centre on s = w/2 − ε is out");
        assert_eq!(swept, swept_cells_brute_force(&g, a, b, w));
        assert!(scan_on(&g, a, b, w + 1e-6).contains(&cell));
        // s of a segment parallel to the lines, decided once per line: along row 0, 0.45 m
        // wide, with row 1's centre at s = w/2 − ε as the scan computes it (dl0 + 1·res).
        let s_hi = 0.5 * 0.45 - RASTER_EPS;
        let s_of_row_1 = |ay: f64| ((g.origin_y + 0.5 * g.resolution) - ay) + 1.0 * g.resolution;
        let ay = solve(s_of_row_1, false, s_hi, centre(1) - s_hi).expect("an exact far end in s");
        let (a, b) = (Point::new(centre(2) - 0.1, ay), Point::new(centre(2) + 0.9, ay));
        assert_eq!(scan_on(&g, a, b, 0.45), vec![2, 3, 4, 5], "columns 2 to 5 of row 0, not row 1");
        assert_eq!(scan_on(&g, a, b, 0.45), swept_cells_brute_force(&g, a, b, 0.45));
    }

    #[test]
    fn zero_length_sweeps_nothing() {
        assert!(scan(Point::new(2.0, 2.0), Point::new(2.0, 2.0), 0.6).is_empty());
        // Shorter than ZERO_LENGTH (0.5 nm), yet column 10's centres lie in its t range
        // [−ε, L − ε) (t = −0.8 nm): nothing, in the scan and in the brute-force rule; at 2 nm
        // the rule takes the three of them in the 0.6 m band.
        let a = Point::new(2.1 + 0.8e-9, 2.1);
        for (len, cells) in [(0.5e-9, vec![]), (2e-9, vec![9 * 55 + 10, 10 * 55 + 10, 11 * 55 + 10])] {
            let b = Point::new(a.x + len, a.y);
            assert_eq!(swept_cells_brute_force(&grid(), a, b, 0.6), cells, "{len} m");
        }
        assert!(scan(a, Point::new(a.x + 0.5e-9, a.y), 0.6).is_empty());
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]
        #[test]
        fn scan_equals_brute_force(ax in -1.0..12.0f64, ay in -1.0..12.0f64, bx in -1.0..12.0f64, by in -1.0..12.0f64, w in 0.05..1.5f64) {
            let (a, b) = (Point::new(ax, ay), Point::new(bx, by));
            prop_assert_eq!(scan(a, b, w), swept_cells_brute_force(&grid(), a, b, w));
        }

        #[test]
        fn nearly_axis_aligned_segments_match_brute_force(ax in 0.0..11.0f64, ay in 0.0..11.0f64, quarter in 0..4u8, tilt in -1e-7..1e-7f64, exact in proptest::bool::ANY, len in 0.1..10.0f64) {
            let angle = f64::from(quarter) * std::f64::consts::FRAC_PI_2 + if exact { 0.0 } else { tilt };
            let a = Point::new((ax * 5.0).round() / 5.0 + 0.1, (ay * 5.0).round() / 5.0 + 0.1);
            let b = a + crate::geom::Vector::new(angle.cos(), angle.sin()) * len;
            prop_assert_eq!(scan(a, b, 0.6), swept_cells_brute_force(&grid(), a, b, 0.6));
        }

        /// On a grid of cells larger than a metre whose origin is below or above zero, the
        /// range of lines is found in cell units from the grid's origin, not in metres from zero.
        #[test]
        fn coarse_grids_off_zero_match(ax in -6.0..30.0f64, ay in -5.0..20.0f64, bx in -6.0..30.0f64, by in -5.0..20.0f64, w in 0.05..4.0f64, below in proptest::bool::ANY) {
            let (origin_x, origin_y) = if below { (-3.7, -2.9) } else { (2.3, 1.7) };
            let g = RasterGrid { cols: 20, rows: 12, resolution: 1.25, origin_x, origin_y };
            let (a, b) = (Point::new(ax, ay), Point::new(bx, by));
            prop_assert_eq!(scan_on(&g, a, b, w), swept_cells_brute_force(&g, a, b, w));
        }

        #[test]
        fn grid_aligned_points_match_brute_force(ax in 0..55i32, ay in 0..55i32, bx in 0..55i32, by in 0..55i32) {
            // Endpoints on cell corners and centres stress the half-open tolerance.
            let (a, b) = (Point::new(ax as f64 * 0.1, ay as f64 * 0.2), Point::new(bx as f64 * 0.2, by as f64 * 0.1));
            prop_assert_eq!(scan(a, b, 0.6), swept_cells_brute_force(&grid(), a, b, 0.6));
        }
    }
}
