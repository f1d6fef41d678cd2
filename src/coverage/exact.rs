//! Test support: inputs placed ulp by ulp so that a scan's own arithmetic lands exactly on a
//! boundary (the half-open ends of thesis-ga §3.3), where only an exact comparison decides.

use super::raster::{RASTER_EPS, RasterGrid};
use crate::geom::Point;

/// The `x` within 64 ulps of `start` (positive) for which `f(x) == target` exactly; `f` is
/// increasing or decreasing in `x`.
pub(crate) fn solve(f: impl Fn(f64) -> f64, increasing: bool, target: f64, start: f64) -> Option<f64> {
    let mut x = start;
    for _ in 0..64 {
        let y = f(x);
        if y == target {
            return Some(x);
        }
        x = f64::from_bits(if (y < target) == increasing { x.to_bits() + 1 } else { x.to_bits() - 1 });
    }
    None
}

/// A grid of 20 × 20 cells of 0.25 m from the origin, and a segment `a → b` along row 5 from
/// column 0's centre whose far end `t = L − ε` lies exactly on column 3's centre (`L` as
/// `(b − a).norm()` computes it): the cells swept are columns 0 to 2 of row 5.
pub(crate) fn far_end_on_a_centre() -> (RasterGrid, Point, Point) {
    let g = RasterGrid { cols: 20, rows: 20, resolution: 0.25, origin_x: 0.0, origin_y: 0.0 };
    let centre = |k: usize| (k as f64 + 0.5) * g.resolution;
    let a = Point::new(centre(0), centre(5));
    let t_end = |bx: f64| (Point::new(bx, a.y) - a).norm() - RASTER_EPS;
    let bx = solve(t_end, true, centre(3) - a.x, centre(3) + RASTER_EPS).expect("an exact far end in t");
    (g, a, Point::new(bx, a.y))
}
