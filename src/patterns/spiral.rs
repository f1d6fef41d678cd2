//! Inward rectangular spiral (the hand-made pattern of 003 Table 3.2, generalised): rings one
//! robot width apart around the bounding box of the free area, starting at the corner nearest
//! the start station; ring pieces where the robot does not fit are skipped and bridged by
//! collision-free connecting moves.

use super::clearance::Clearance;
use super::{PatternError, Route};
use crate::geom::Point;

/// The spiral's corner points in a frame where the start corner is the lower-left one.
fn spiral_corners(x0: f64, y0: f64, x1: f64, y1: f64, width: f64) -> Vec<(f64, f64)> {
    let mut pts = Vec::new();
    let mut d = 0.5 * width;
    loop {
        let (l, b, r, t) = (x0 + d, y0 + d, x1 - d, y1 - d);
        if l > r + 1e-9 || b > t + 1e-9 {
            break;
        }
        pts.push((l, b));
        pts.push((r, b));
        if t - b < 1e-9 {
            break;
        }
        pts.push((r, t));
        if r - l < 1e-9 {
            break;
        }
        pts.push((l, t));
        let next_b = b + width;
        if next_b > t - 1e-9 {
            break;
        }
        pts.push((l, next_b));
        d += width;
    }
    pts
}

/// Plans the spiral from `start` inwards, then to `end`.
pub fn plan(clear: &Clearance, width: f64, start: Point, end: Point) -> Result<Route, PatternError> {
    let map = clear.map();
    let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    let half = 0.5 * map.resolution();
    for r in 0..map.rows() {
        for c in 0..map.cols() {
            if map.is_free(r, c) {
                let p = map.cell_centre(r, c);
                x0 = x0.min(p.x - half);
                y0 = y0.min(p.y - half);
                x1 = x1.max(p.x + half);
                y1 = y1.max(p.y + half);
            }
        }
    }
    // Mirror so that the corner nearest the start becomes the spiral's first corner.
    let flip_x = (start.x - x0).abs() > (x1 - start.x).abs();
    let flip_y = (start.y - y0).abs() > (y1 - start.y).abs();
    let to_world =
        |(x, y): (f64, f64)| Point::new(if flip_x { x0 + x1 - x } else { x }, if flip_y { y0 + y1 - y } else { y });
    let corners: Vec<Point> = spiral_corners(x0, y0, x1, y1, width).into_iter().map(to_world).collect();
    if corners.is_empty() {
        return Err(PatternError::NoRoom { width });
    }
    let mut route = Route::new(start);
    let mut covered_any = false;
    for w in corners.windows(2) {
        for (t0, t1) in clear.fitting_intervals(w[0], w[1], 0.0) {
            route.go(clear, w[0] + (w[1] - w[0]) * t0)?;
            route.go(clear, w[0] + (w[1] - w[0]) * t1)?;
            covered_any = true;
        }
    }
    if !covered_any {
        return Err(PatternError::NoRoom { width });
    }
    route.go(clear, end)?;
    Ok(route)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corners_of_a_square_spiral() {
        let pts = spiral_corners(0.0, 0.0, 3.0, 3.0, 1.0);
        assert_eq!(pts[..5], [(0.5, 0.5), (2.5, 0.5), (2.5, 2.5), (0.5, 2.5), (0.5, 1.5)]);
        assert_eq!(pts[5..], [(1.5, 1.5), (1.5, 1.5)]);
    }
}
