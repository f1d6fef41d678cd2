//! The dominant orientations of a map's walls, for lane directions that run along them: a
//! building's walls are mostly parallel to a few directions, which need not be the map's axes
//! (a SLAM map is drawn in whatever frame the robot started in). Boustrophedon lanes parallel
//! to the walls leave the fewest short lanes and strips (Bähnemann et al. 2019 choose sweep
//! directions per cell for the same reason).
//!
//! Each wall cell next to free space votes for the orientation of the wall there — the
//! principal axis of the wall cells around it, weighted by how line-like they lie, so corners
//! and speckle count little — into a histogram of 1° bins over [0°, 180°); the peaks, at
//! least [`PEAK_SEPARATION_DEG`] apart, are the dominant orientations. A raster wall at any
//! angle is a staircase of axis-aligned steps, which is why the orientation is read from the
//! cells around each one rather than from its own edges.

use super::GridMap;

/// Wall cells within this many cells of a boundary cell shape its local orientation.
const WINDOW_CELLS: isize = 4;

/// Two dominant orientations are at least this far apart, in degrees.
pub const PEAK_SEPARATION_DEG: f64 = 15.0;

/// The `count` strongest wall orientations of `map`, in degrees in [0, 180), strongest first,
/// each to 0.1°; fewer where the map's walls hold fewer peaks.
pub fn wall_orientations(map: &GridMap, count: usize) -> Vec<f64> {
    let histogram = orientation_histogram(map);
    peaks(&histogram, count)
}

/// Whether map cell `(r, c)` is a wall (not free) with a free 4-neighbour.
fn is_boundary(map: &GridMap, r: usize, c: usize) -> bool {
    if map.is_free(r, c) {
        return false;
    }
    let (rows, cols) = (map.rows() as isize, map.cols() as isize);
    [(-1, 0), (1, 0), (0, -1), (0, 1)].iter().any(|&(dr, dc)| {
        let (nr, nc) = (r as isize + dr, c as isize + dc);
        nr >= 0 && nc >= 0 && nr < rows && nc < cols && map.is_free(nr as usize, nc as usize)
    })
}

/// Votes of every boundary wall cell, 1° bins over [0°, 180°).
fn orientation_histogram(map: &GridMap) -> [f64; 180] {
    let (rows, cols) = (map.rows(), map.cols());
    let boundary: Vec<bool> = (0..rows * cols).map(|i| is_boundary(map, i / cols, i % cols)).collect();
    let mut histogram = [0.0; 180];
    for (i, _) in boundary.iter().enumerate().filter(|(_, b)| **b) {
        let (r0, c0) = ((i / cols) as isize, (i % cols) as isize);
        let (mut n, mut sx, mut sy, mut sxx, mut syy, mut sxy) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        for dr in -WINDOW_CELLS..=WINDOW_CELLS {
            for dc in -WINDOW_CELLS..=WINDOW_CELLS {
                let (r, c) = (r0 + dr, c0 + dc);
                if r < 0
                    || c < 0
                    || r >= rows as isize
                    || c >= cols as isize
                    || !boundary[r as usize * cols + c as usize]
                {
                    continue;
                }
                let (x, y) = (dc as f64, dr as f64);
                n += 1.0;
                (sx, sy, sxx, syy, sxy) = (sx + x, sy + y, sxx + x * x, syy + y * y, sxy + x * y);
            }
        }
        if n < 3.0 {
            continue;
        }
        let (cxx, cyy, cxy) = (sxx / n - (sx / n).powi(2), syy / n - (sy / n).powi(2), sxy / n - sx * sy / (n * n));
        let (angle_deg, line_likeness) = principal_axis(cxx, cyy, cxy);
        histogram[(angle_deg.floor() as usize).min(179)] += line_likeness;
    }
    histogram
}

/// The principal axis of a 2 × 2 covariance, in degrees in [0, 180), and how line-like the
/// points lie: (λ₁ − λ₂) / (λ₁ + λ₂), 1 on a line, 0 for a round blob.
fn principal_axis(cxx: f64, cyy: f64, cxy: f64) -> (f64, f64) {
    let angle = 0.5 * (2.0 * cxy).atan2(cxx - cyy);
    let spread = ((cxx - cyy).powi(2) + 4.0 * cxy * cxy).sqrt();
    let total = cxx + cyy;
    let line = if total > 0.0 { spread / total } else { 0.0 };
    (angle.to_degrees().rem_euclid(180.0), line)
}

/// The `count` highest peaks of the circular `histogram` (smoothed over ±2 bins), each at
/// least [`PEAK_SEPARATION_DEG`] from the others, refined to the weighted mean of the bins
/// within 2° and rounded to 0.1°.
fn peaks(histogram: &[f64; 180], count: usize) -> Vec<f64> {
    let at = |k: isize| histogram[k.rem_euclid(180) as usize];
    let smooth: Vec<f64> = (0..180isize).map(|k| (-2..=2).map(|d| at(k + d)).sum()).collect();
    let apart = |a: f64, b: f64| {
        let d = (a - b).rem_euclid(180.0);
        d.min(180.0 - d) >= PEAK_SEPARATION_DEG
    };
    let mut order: Vec<usize> = (0..180).collect();
    order.sort_by(|&a, &b| smooth[b].total_cmp(&smooth[a]).then(a.cmp(&b)));
    let mut out: Vec<f64> = Vec::new();
    for k in order {
        if out.len() == count || smooth[k] <= 0.0 {
            break;
        }
        let (mut weight, mut sum) = (0.0, 0.0);
        for d in -2..=2isize {
            let w = at(k as isize + d);
            weight += w;
            sum += w * (k as f64 + 0.5 + d as f64);
        }
        let angle = ((sum / weight).rem_euclid(180.0) * 10.0).round() / 10.0 % 180.0;
        if out.iter().all(|&a| apart(a, angle)) {
            out.push(angle);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point;
    use crate::map::CellState;

    /// A room whose walls are a square turned by `turn_deg` about the map's centre.
    fn turned_room(turn_deg: f64) -> GridMap {
        let (cols, rows) = (120, 120);
        let (s, c) = turn_deg.to_radians().sin_cos();
        let cells = (0..rows * cols)
            .map(|i| {
                let (x, y) = ((i % cols) as f64 - 60.0, (i / cols) as f64 - 60.0);
                let (u, v) = (c * x + s * y, -s * x + c * y);
                if u.abs() < 40.0 && v.abs() < 40.0 { CellState::Free } else { CellState::Occupied }
            })
            .collect();
        GridMap::new("turned", cols, rows, 0.05, Point::origin(), cells).unwrap()
    }

    #[test]
    fn the_walls_of_a_turned_room_give_its_turn_and_the_right_angle() {
        for turn in [0.0, 12.0, 30.0, 67.0] {
            let found = wall_orientations(&turned_room(turn), 2);
            assert_eq!(found.len(), 2, "{turn}: {found:?}");
            let near = |a: f64, b: f64| {
                let d = (a - b).rem_euclid(180.0);
                d.min(180.0 - d) <= 1.5
            };
            assert!(found.iter().any(|&a| near(a, turn)), "{turn}: {found:?}");
            assert!(found.iter().any(|&a| near(a, turn + 90.0)), "{turn}: {found:?}");
        }
    }

    #[test]
    fn principal_axes_by_hand() {
        // Points along y = x: variance equal in x and y, full covariance: 45°, a line.
        let (a, l) = principal_axis(1.0, 1.0, 1.0);
        assert!((a - 45.0).abs() < 1e-9 && (l - 1.0).abs() < 1e-9);
        // A round blob: no direction.
        assert_eq!(principal_axis(1.0, 1.0, 0.0).1, 0.0);
        // Along y: 90°.
        assert!((principal_axis(0.0, 2.0, 0.0).0 - 90.0).abs() < 1e-9);
    }
}
