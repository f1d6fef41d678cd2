//! The two hand-made paths of the fitness test of 003 §3.2.2 (Tables 3.1 and 3.2, Fig. 3.4): a
//! boustrophedon and an inward spiral over a rectangular free area, with lanes one robot width
//! apart, starting and ending at the station and returning to it in a straight line.
//!
//! Unlike [`super::boustrophedon`] and [`super::spiral`], which plan around obstacles on any
//! map, these paths ignore obstacles on purpose: the thesis places an obstacle under the path
//! afterwards to see what sweeping it costs (`covga eval --obstacle … --obstacle-in-area`).

use crate::geom::Point;
use crate::map::GridMap;

/// Which hand-made path.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HandMade {
    /// Lanes along +x, alternating direction, one width apart (Table 3.1).
    Boustrophedon,
    /// Rings one width apart from the outside in, first along +x (Table 3.2).
    Spiral,
}

/// Why a hand-made path cannot be drawn on a map.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum HandMadeError {
    /// The free cells are not one full rectangle.
    #[error(
        "the hand-made test paths of 003 §3.2.2 need a map whose free cells form one rectangle (as thesis-1's do); {map} has {free} free cells in a bounding box of {boxed}"
    )]
    NotRectangular {
        /// Map name.
        map: String,
        /// Free cells.
        free: usize,
        /// Cells of their bounding box.
        boxed: usize,
    },
    /// The robot is wider than the free rectangle.
    #[error("a robot {width} m wide does not fit the free rectangle of {w} m × {h} m")]
    TooWide {
        /// Robot width.
        width: f64,
        /// Rectangle width.
        w: f64,
        /// Rectangle height.
        h: f64,
    },
}

/// Centres of `n` lanes one `width` apart from `lo` to `hi` (the last lane on `hi` when the span
/// is not a whole number of widths).
fn lane_centres(lo: f64, hi: f64, width: f64) -> Vec<f64> {
    let n = ((hi - lo) / width + 1e-9).floor() as usize + 1;
    let mut c: Vec<f64> = (0..n).map(|k| lo + k as f64 * width).collect();
    if hi - c[n - 1] > 1e-9 {
        c.push(hi);
    }
    c
}

/// The hand-made `kind` of path over the free rectangle of `map` for a robot `width` wide, from
/// and back to `station` (003 §3.2.2). Lane centres lie half a width inside the rectangle.
pub fn hand_made(map: &GridMap, kind: HandMade, width: f64, station: Point) -> Result<Vec<Point>, HandMadeError> {
    let (mut r0, mut r1, mut c0, mut c1) = (usize::MAX, 0, usize::MAX, 0);
    for r in 0..map.rows() {
        for c in 0..map.cols() {
            if map.is_free(r, c) {
                (r0, r1, c0, c1) = (r0.min(r), r1.max(r), c0.min(c), c1.max(c));
            }
        }
    }
    let boxed = (r1 + 1 - r0) * (c1 + 1 - c0);
    if boxed != map.free_count() {
        return Err(HandMadeError::NotRectangular { map: map.name().into(), free: map.free_count(), boxed });
    }
    let res = map.resolution();
    let (lo, hi) = (map.cell_centre(r0, c0), map.cell_centre(r1, c1));
    let (x0, y0, x1, y1) = (lo.x - res / 2.0, lo.y - res / 2.0, hi.x + res / 2.0, hi.y + res / 2.0);
    if width > x1 - x0 || width > y1 - y0 {
        return Err(HandMadeError::TooWide { width, w: x1 - x0, h: y1 - y0 });
    }
    let half = width / 2.0;
    let xs = lane_centres(x0 + half, x1 - half, width);
    let ys = lane_centres(y0 + half, y1 - half, width);
    let corners = match kind {
        HandMade::Boustrophedon => boustrophedon_corners(xs.len(), ys.len()),
        HandMade::Spiral => spiral_corners(xs.len(), ys.len()),
    };
    let mut path = vec![station];
    for (i, j) in corners {
        let p = Point::new(xs[i], ys[j]);
        if p != *path.last().expect("non-empty") {
            path.push(p);
        }
    }
    path.push(station);
    Ok(path)
}

/// Lane-grid corners of a boustrophedon: along x on every lane row, up one lane at each end.
fn boustrophedon_corners(nx: usize, ny: usize) -> Vec<(usize, usize)> {
    let mut v = Vec::with_capacity(2 * ny);
    for j in 0..ny {
        let (a, b) = if j % 2 == 0 { (0, nx - 1) } else { (nx - 1, 0) };
        v.push((a, j));
        v.push((b, j));
    }
    v
}

/// Lane-grid corners of an inward spiral: right along the bottom, up, left along the top, down
/// to one lane above the bottom, and again one lane further in, until the rings meet.
fn spiral_corners(nx: usize, ny: usize) -> Vec<(usize, usize)> {
    let (mut left, mut right, mut bottom, mut top) = (0usize, nx - 1, 0usize, ny - 1);
    let mut v = vec![(0, 0)];
    loop {
        v.push((right, bottom));
        bottom += 1;
        if bottom > top {
            break;
        }
        v.push((right, top));
        if right == left {
            break;
        }
        right -= 1;
        v.push((left, top));
        if top == bottom {
            break;
        }
        top -= 1;
        v.push((left, bottom));
        left += 1;
        if left > right {
            break;
        }
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::presets::preset;

    fn corners(path: &[Point]) -> Vec<(i64, i64)> {
        path.iter().map(|p| ((p.x * 10.0).round() as i64, (p.y * 10.0).round() as i64)).collect()
    }

    #[test]
    fn boustrophedon_on_map_1_has_fifteen_lanes_from_and_back_to_the_station() {
        let s = Point::new(1.3, 1.3);
        let p = hand_made(&preset("thesis-1").unwrap(), HandMade::Boustrophedon, 0.6, s).unwrap();
        let c = corners(&p);
        // station = first lane corner; 15 lanes × 2 ends; straight back from (9.7, 9.7).
        assert_eq!(c.len(), 31);
        assert_eq!(&c[..5], &[(13, 13), (97, 13), (97, 19), (13, 19), (13, 25)]);
        assert_eq!(&c[28..], &[(13, 97), (97, 97), (13, 13)]);
    }

    #[test]
    fn spiral_on_map_1_closes_in_on_the_centre() {
        let s = Point::new(1.3, 1.3);
        let p = hand_made(&preset("thesis-1").unwrap(), HandMade::Spiral, 0.6, s).unwrap();
        let c = corners(&p);
        assert_eq!(&c[..6], &[(13, 13), (97, 13), (97, 97), (13, 97), (13, 19), (91, 19)]);
        assert_eq!(&c[c.len() - 6..], &[(61, 49), (61, 61), (49, 61), (49, 55), (55, 55), (13, 13)]);
        assert_eq!(c.len(), 31);
        // Every leg is axis-parallel except the return.
        for w in p[..p.len() - 1].windows(2) {
            assert!(w[0].x == w[1].x || w[0].y == w[1].y, "{w:?}");
        }
    }

    #[test]
    fn spiral_corners_of_small_lane_grids() {
        assert_eq!(spiral_corners(1, 1), vec![(0, 0), (0, 0)]);
        assert_eq!(spiral_corners(2, 2), vec![(0, 0), (1, 0), (1, 1), (0, 1)]);
        assert_eq!(spiral_corners(3, 3), vec![(0, 0), (2, 0), (2, 2), (0, 2), (0, 1), (1, 1)]);
        assert_eq!(spiral_corners(3, 1), vec![(0, 0), (2, 0)]);
        assert_eq!(lane_centres(1.3, 9.7, 0.6).len(), 15);
        assert_eq!(lane_centres(0.0, 1.0, 0.6), vec![0.0, 0.6, 1.0]);
    }

    #[test]
    fn maps_that_are_not_one_rectangle_are_refused() {
        let err = hand_made(&preset("thesis-2").unwrap(), HandMade::Spiral, 0.6, Point::new(1.3, 1.3)).unwrap_err();
        assert!(matches!(err, HandMadeError::NotRectangular { free: 1720, boxed: 2025, .. }), "{err}");
        let err = hand_made(&preset("thesis-1").unwrap(), HandMade::Spiral, 9.5, Point::new(5.5, 5.5)).unwrap_err();
        assert!(matches!(err, HandMadeError::TooWide { .. }), "{err}");
    }
}
