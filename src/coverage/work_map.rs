//! The working raster of the waypoint planner (000 §II-B.1, waypoint §2): the map resampled to
//! the pixel scale `s`, its occluded mask, the Euclidean distance transform and the safety
//! buffer band. All geometry is in pixel units (W13); pixel `(col, row)` has its centre at
//! `(col + 0.5, row + 0.5)`, row 0 at the bottom as in [`crate::map::GridMap`].

use crate::map::GridMap;

/// The map as the waypoint planner sees it.
#[derive(Clone, Debug)]
pub struct WorkMap {
    /// Pixels across.
    pub width: usize,
    /// Pixels up.
    pub height: usize,
    /// Metres per pixel `s`.
    pub scale: f64,
    /// World position of pixel (0, 0)'s lower-left corner.
    pub origin: (f64, f64),
    /// `O`: occluded pixels.
    pub occluded: Vec<bool>,
    /// `D`: distance (px) from each pixel centre to the nearest occluded pixel centre
    /// (the outside of the map counts as occluded).
    pub dist: Vec<f64>,
}

impl WorkMap {
    /// Resamples `map` to `scale` metres per pixel; a working pixel is occluded if any map cell
    /// under it is not free or it reaches outside the map (W1).
    pub fn new(map: &GridMap, scale: f64) -> Self {
        Self::new_until(map, scale, &|| false).expect("never stopped")
    }

    /// [`Self::new`] that gives up (`None`) as soon as `stop` says so, asked every
    /// [`STOP_EVERY`] rows of the resampling and lines of the distance transform: a large map at
    /// a fine scale takes a noticeable time, and an interrupted run should not wait for it.
    pub fn new_until(map: &GridMap, scale: f64, stop: &dyn Fn() -> bool) -> Option<Self> {
        let res = map.resolution();
        let width = (map.width_m() / scale - 1e-9).ceil().max(1.0) as usize;
        let height = (map.height_m() / scale - 1e-9).ceil().max(1.0) as usize;
        let mut occluded = vec![false; width * height];
        for row in 0..height {
            if row % STOP_EVERY == 0 && stop() {
                return None;
            }
            for col in 0..width {
                let (x0, x1) = (col as f64 * scale, (col + 1) as f64 * scale);
                let (y0, y1) = (row as f64 * scale, (row + 1) as f64 * scale);
                let (c0, c1) = ((x0 / res + 1e-9).floor() as usize, ((x1 / res - 1e-9).ceil() as usize).max(1));
                let (r0, r1) = ((y0 / res + 1e-9).floor() as usize, ((y1 / res - 1e-9).ceil() as usize).max(1));
                let outside = c1 > map.cols() || r1 > map.rows();
                let blocked =
                    outside || (r0..r1.min(map.rows())).any(|r| (c0..c1.min(map.cols())).any(|c| !map.is_free(r, c)));
                occluded[row * width + col] = blocked;
            }
        }
        let dist = distance_transform_until(width, height, &occluded, stop)?;
        Some(Self { width, height, scale, origin: (map.origin().x, map.origin().y), occluded, dist })
    }

    /// Row-major index of a pixel.
    pub fn index(&self, col: usize, row: usize) -> usize {
        row * self.width + col
    }
    /// Whether `(col, row)` (possibly outside) is occluded; the outside is.
    pub fn is_occluded(&self, col: i64, row: i64) -> bool {
        col < 0
            || row < 0
            || col >= self.width as i64
            || row >= self.height as i64
            || self.occluded[row as usize * self.width + col as usize]
    }
    /// The pixel containing a point in px coordinates.
    pub fn pixel_of(&self, p: (f64, f64)) -> (i64, i64) {
        (p.0.floor() as i64, p.1.floor() as i64)
    }
    /// `D` at the pixel containing `p` (0 outside or on occluded pixels).
    pub fn clearance(&self, p: (f64, f64)) -> f64 {
        let (c, r) = self.pixel_of(p);
        if self.is_occluded(c, r) { 0.0 } else { self.dist[r as usize * self.width + c as usize] }
    }
    /// Metres to pixels.
    pub fn px(&self, metres: f64) -> f64 {
        metres / self.scale
    }
    /// A world point (metres) in pixel coordinates.
    pub fn to_px(&self, x: f64, y: f64) -> (f64, f64) {
        ((x - self.origin.0) / self.scale, (y - self.origin.1) / self.scale)
    }
    /// A pixel-coordinate point in world metres.
    pub fn to_world(&self, p: (f64, f64)) -> (f64, f64) {
        (self.origin.0 + p.0 * self.scale, self.origin.1 + p.1 * self.scale)
    }
    /// Explorable pixels `F`.
    pub fn free_count(&self) -> usize {
        self.occluded.iter().filter(|o| !**o).count()
    }
    /// Safety buffer band `B = {p ∈ F : D(p) ≤ b}` (waypoint §2).
    pub fn band(&self, b: f64) -> Vec<bool> {
        self.occluded.iter().zip(&self.dist).map(|(&o, &d)| !o && d <= b).collect()
    }
    /// Whether the straight segment `a → b` (px) passes through an occluded pixel: every pixel
    /// the segment touches is tested (supercover traversal, W7).
    pub fn segment_hits(&self, a: (f64, f64), b: (f64, f64)) -> bool {
        let (mut c, mut r) = self.pixel_of(a);
        let end = self.pixel_of(b);
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (sx, sy) = (dx.signum() as i64, dy.signum() as i64);
        let t_dx = if dx != 0.0 { 1.0 / dx.abs() } else { f64::INFINITY };
        let t_dy = if dy != 0.0 { 1.0 / dy.abs() } else { f64::INFINITY };
        let next = |p: f64, s: i64, cell: i64| if s > 0 { (cell + 1) as f64 - p } else { p - cell as f64 };
        let mut t_x = if dx != 0.0 { next(a.0, sx, c) * t_dx } else { f64::INFINITY };
        let mut t_y = if dy != 0.0 { next(a.1, sy, r) * t_dy } else { f64::INFINITY };
        for _ in 0..(self.width + self.height) * 4 {
            if self.is_occluded(c, r) {
                return true;
            }
            if (c, r) == end {
                return false;
            }
            if (t_x - t_y).abs() < 1e-12 {
                // Through a corner: both side pixels count (supercover).
                if self.is_occluded(c + sx, r) || self.is_occluded(c, r + sy) {
                    return true;
                }
                c += sx;
                r += sy;
                t_x += t_dx;
                t_y += t_dy;
            } else if t_x < t_y {
                c += sx;
                t_x += t_dx;
            } else {
                r += sy;
                t_y += t_dy;
            }
        }
        false
    }
}

/// 1-D squared distance transform (Felzenszwalb–Huttenlocher lower envelope).
fn dt_1d(f: &[f64], out: &mut [f64]) {
    let n = f.len();
    let mut v = vec![0usize; n];
    let mut z = vec![0f64; n + 1];
    let mut k = 0;
    z[0] = f64::NEG_INFINITY;
    z[1] = f64::INFINITY;
    let first = f.iter().position(|x| x.is_finite());
    let Some(first) = first else {
        out.iter_mut().for_each(|o| *o = f64::INFINITY);
        return;
    };
    v[0] = first;
    for q in first + 1..n {
        if !f[q].is_finite() {
            continue;
        }
        loop {
            let p = v[k];
            let s = ((f[q] + (q * q) as f64) - (f[p] + (p * p) as f64)) / (2.0 * (q as f64 - p as f64));
            if s <= z[k] && k > 0 {
                k -= 1;
                continue;
            }
            if s <= z[k] {
                v[0] = q;
                z[0] = f64::NEG_INFINITY;
                z[1] = f64::INFINITY;
                break;
            }
            k += 1;
            v[k] = q;
            z[k] = s;
            z[k + 1] = f64::INFINITY;
            break;
        }
    }
    let mut k = 0;
    for (q, o) in out.iter_mut().enumerate() {
        while z[k + 1] < q as f64 {
            k += 1;
        }
        let p = v[k];
        *o = (q as f64 - p as f64).powi(2) + f[p];
    }
}

/// Rows or lines of work between two questions to a `stop` of [`WorkMap::new_until`].
pub const STOP_EVERY: usize = 64;

/// Exact Euclidean distance transform to the nearest occluded pixel centre, with a ring of
/// occluded pixels around the raster (the outside is occluded).
pub fn distance_transform(width: usize, height: usize, occluded: &[bool]) -> Vec<f64> {
    distance_transform_until(width, height, occluded, &|| false).expect("never stopped")
}

/// [`distance_transform`] that gives up (`None`) as soon as `stop` says so, asked every
/// [`STOP_EVERY`] lines of each pass.
fn distance_transform_until(
    width: usize,
    height: usize,
    occluded: &[bool],
    stop: &dyn Fn() -> bool,
) -> Option<Vec<f64>> {
    let (w, h) = (width + 2, height + 2);
    let mut grid = vec![0f64; w * h];
    for r in 0..h {
        for c in 0..w {
            let inside = r >= 1 && c >= 1 && r <= height && c <= width;
            let occ = !inside || occluded[(r - 1) * width + (c - 1)];
            grid[r * w + c] = if occ { 0.0 } else { f64::INFINITY };
        }
    }
    let mut col = vec![0f64; h];
    let mut out_col = vec![0f64; h];
    for c in 0..w {
        if c % STOP_EVERY == 0 && stop() {
            return None;
        }
        for r in 0..h {
            col[r] = grid[r * w + c];
        }
        dt_1d(&col, &mut out_col);
        for r in 0..h {
            grid[r * w + c] = out_col[r];
        }
    }
    let mut row_out = vec![0f64; w];
    for r in 0..h {
        if r % STOP_EVERY == 0 && stop() {
            return None;
        }
        dt_1d(&grid[r * w..(r + 1) * w], &mut row_out);
        grid[r * w..(r + 1) * w].copy_from_slice(&row_out);
    }
    let mut d = vec![0f64; width * height];
    for r in 0..height {
        for c in 0..width {
            d[r * width + c] = grid[(r + 1) * w + (c + 1)].sqrt();
        }
    }
    Some(d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_transform_matches_brute_force() {
        let (w, h) = (9, 7);
        let mut occ = vec![false; w * h];
        for &(c, r) in &[(3usize, 3usize), (6, 1), (0, 5)] {
            occ[r * w + c] = true;
        }
        let d = distance_transform(w, h, &occ);
        for r in 0..h {
            for c in 0..w {
                let mut best = f64::INFINITY;
                for rr in -1..=h as i64 {
                    for cc in -1..=w as i64 {
                        let inside = rr >= 0 && cc >= 0 && rr < h as i64 && cc < w as i64;
                        if !inside || occ[rr as usize * w + cc as usize] {
                            best = best.min((((cc - c as i64).pow(2) + (rr - r as i64).pow(2)) as f64).sqrt());
                        }
                    }
                }
                assert!((d[r * w + c] - best).abs() < 1e-9, "({c},{r}): {} vs {best}", d[r * w + c]);
            }
        }
    }

    #[test]
    fn resampled_thesis_map_and_segments() {
        let m = crate::map::presets::preset("thesis-2").unwrap();
        let wm = WorkMap::new(&m, 0.2);
        assert_eq!((wm.width, wm.height), (55, 55));
        assert_eq!(wm.free_count(), 1720);
        assert!(wm.segment_hits((10.0, 27.5), (45.0, 27.5)), "through the disc");
        assert!(!wm.segment_hits((10.0, 10.0), (45.0, 10.0)));
        let coarse = WorkMap::new(&m, 0.3);
        assert!(coarse.free_count() < 1720 * 4 / 9 + 10);
    }
}
