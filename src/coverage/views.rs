//! What 000's camera (§II-C.1, eq. 1) sees along a plan, for the common scorer and for planners
//! that optimise it: the working raster with its wall band and the free pixels connected to
//! the stations ([`CameraLayer`]), and the views of each straight segment kept as a sparse
//! bitset ([`SegmentViews`]), so that a plan's camera coverage is an OR of word lists and a
//! population count, and a segment shared by many plans is viewed once.
//!
//! The camera is posed at both ends of a segment and every [`CAMERA_STEP_M`] between, looking
//! along it. A segment's views depend on its endpoints only, so the union of the segments'
//! masks is exactly the union of the views pose by pose ([`CameraLayer::coverage_by_pose`],
//! the reference; tested).

use super::camera::{Camera, ViewShape};
use super::score::{CAMERA_STEP_M, CameraSpec};
use crate::coverage::work_map::WorkMap;
use crate::geom::Point;
use crate::map::GridMap;
use std::collections::HashMap;

/// Mask words a [`SegmentViews`] keeps before it starts afresh (16 bytes each: 64 MiB).
pub const VIEW_CACHE_WORDS: usize = 1 << 22;

/// Bytes a [`SegmentViews`] may hold: its words with a growing vector's slack (twice), and
/// the table of its segments (a few bytes per word).
pub const VIEW_CACHE_BYTES: usize = 2 * 16 * VIEW_CACHE_WORDS + 8 * VIEW_CACHE_WORDS;

/// The camera side of the scorer: working raster, wall band, connected free pixels.
pub struct CameraLayer {
    /// The working raster.
    pub(crate) map: WorkMap,
    /// The camera in pixel units.
    pub(crate) camera: Camera,
    /// Free pixels in the wall band, one bit per pixel.
    band: Vec<u64>,
    /// Free pixels connected to a station.
    reach: Vec<u64>,
    /// `[walls_free, open_free, walls_reach, open_reach]` denominators.
    pub(crate) counts: [usize; 4],
    /// This layer's identity: masks cached for another layer are in other pixels.
    id: u64,
}

/// Identities of [`CameraLayer`]s, one per layer made.
static LAYERS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

impl CameraLayer {
    /// The layer of `map` for the camera `spec`, with the free pixels 8-connected to `stations`.
    pub fn new(map: &GridMap, spec: &CameraSpec, stations: &[Point]) -> Self {
        let wm = WorkMap::new(map, spec.scale);
        let band = wm.band(spec.band_m / spec.scale);
        let reach = connected_free(&wm, stations);
        let free = wm.occluded.iter().filter(|o| !**o).count();
        let counts = [
            band.iter().filter(|b| **b).count(),
            free,
            band.iter().zip(&reach).filter(|(b, r)| **b && **r).count(),
            reach.iter().filter(|r| **r).count(),
        ];
        let camera = Camera {
            d_min: spec.d_min / spec.scale,
            d_max: spec.d_max / spec.scale,
            fov: spec.fov_deg.to_radians(),
            sections: spec.sections,
            // The common scorer measures every planner with eq. 1 as written.
            shape: ViewShape::Sections,
        };
        let id = LAYERS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Self { camera, band: bitset(&band), reach: bitset(&reach), counts, map: wm, id }
    }

    /// Words of a bitset over the raster.
    pub fn words(&self) -> usize {
        (self.map.width * self.map.height).div_ceil(64)
    }

    /// Whether pixel `i` is in the wall band (free pixels within the band of an obstacle).
    pub fn in_band(&self, i: usize) -> bool {
        self.band[i / 64] >> (i % 64) & 1 == 1
    }

    /// `[walls_free, open_free, walls_reach, open_reach]` of a plan, each segment's views
    /// taken from (or added to) `views`.
    pub fn coverage<P: AsRef<[Point]>>(&self, paths: &[P], views: &mut SegmentViews) -> [f64; 4] {
        views.begin(self.id, self.words());
        for path in paths {
            for w in path.as_ref().windows(2) {
                views.add_segment(self, w[0], w[1]);
            }
        }
        self.fractions(views.counts(self))
    }

    /// [`Self::coverage`] pose by pose into one flag per pixel, with no masks: the reference
    /// the masks are tested against, and the scorer's method for a plan seen once. The poses
    /// are split into one run of consecutive poses per worker thread, whose flags are joined
    /// at the end: a union, the same for any number of threads.
    pub fn coverage_by_pose(&self, paths: &[Vec<Point>]) -> [f64; 4] {
        use rayon::prelude::*;
        let wm = &self.map;
        let mut poses = Vec::new();
        for path in paths {
            for w in path.windows(2) {
                for_each_pose(w[0], w[1], |p, psi| poses.push((wm.to_px(p.x, p.y), psi)));
            }
        }
        let run = poses.len().div_ceil(rayon::current_num_threads().max(1)).max(1);
        let view_run = |run: &[((f64, f64), f64)]| {
            let mut seen = vec![false; wm.occluded.len()];
            for &(pos, psi) in run {
                self.camera.view_into(wm.width, wm.height, |c, r| wm.is_occluded(c, r), pos, psi, &mut seen);
            }
            seen
        };
        let seen = poses
            .par_chunks(run)
            .map(view_run)
            .reduce_with(|mut a, b| {
                a.iter_mut().zip(b).for_each(|(x, y)| *x |= y);
                a
            })
            .unwrap_or_else(|| vec![false; wm.occluded.len()]);
        let mut hit = [0usize; 4];
        for i in (0..seen.len()).filter(|&i| seen[i]) {
            let (b, r) = (self.in_band(i), self.reach[i / 64] >> (i % 64) & 1 == 1);
            hit[0] += usize::from(b);
            hit[1] += 1;
            hit[2] += usize::from(b && r);
            hit[3] += usize::from(r);
        }
        self.fractions(hit)
    }

    /// Seen pixels `hit` as shares of the layer's four denominators (0 where one is empty).
    fn fractions(&self, hit: [usize; 4]) -> [f64; 4] {
        std::array::from_fn(|k| if self.counts[k] > 0 { hit[k] as f64 / self.counts[k] as f64 } else { 0.0 })
    }
}

/// Calls `pose(p, psi)` at both ends of segment `a → b` and every [`CAMERA_STEP_M`] between
/// (none for a segment under a nanometre), `psi` its heading.
fn for_each_pose(a: Point, b: Point, mut pose: impl FnMut(Point, f64)) {
    let d = b - a;
    let len = d.norm();
    if len < 1e-9 {
        return;
    }
    let psi = d.y.atan2(d.x);
    let steps = (len / CAMERA_STEP_M).ceil() as usize;
    for k in 0..=steps {
        pose(a + d * (k as f64 / steps as f64), psi);
    }
}

/// The free pixels of `wm` 8-connected to a station's pixel.
fn connected_free(wm: &WorkMap, stations: &[Point]) -> Vec<bool> {
    let mut reach = vec![false; wm.occluded.len()];
    let mut stack: Vec<usize> = Vec::new();
    for s in stations {
        let (c, r) = wm.pixel_of(wm.to_px(s.x, s.y));
        if !wm.is_occluded(c, r) {
            let i = wm.index(c as usize, r as usize);
            reach[i] = true;
            stack.push(i);
        }
    }
    while let Some(i) = stack.pop() {
        let (c, r) = ((i % wm.width) as i64, (i / wm.width) as i64);
        for (dc, dr) in [(-1, 0), (1, 0), (0, -1), (0, 1), (-1, -1), (-1, 1), (1, -1), (1, 1)] {
            let (nc, nr) = (c + dc, r + dr);
            if !wm.is_occluded(nc, nr) {
                let j = wm.index(nc as usize, nr as usize);
                if !reach[j] {
                    reach[j] = true;
                    stack.push(j);
                }
            }
        }
    }
    reach
}

/// A full bitset of a boolean raster: bit `i % 64` of word `i / 64` for flag `i`.
pub fn bitset(flags: &[bool]) -> Vec<u64> {
    let mut w = vec![0u64; flags.len().div_ceil(64)];
    for (i, _) in flags.iter().enumerate().filter(|(_, f)| **f) {
        w[i / 64] |= 1 << (i % 64);
    }
    w
}

/// The key of segment `a → b`: its endpoints bit for bit.
fn key_of(a: Point, b: Point) -> [u64; 4] {
    [a.x.to_bits(), a.y.to_bits(), b.x.to_bits(), b.y.to_bits()]
}

/// Segments' views as `(word, bits)` lists over one [`CameraLayer`]'s raster, and the union of
/// a plan's being built. Keep one per thread; used with another layer, it starts afresh (the
/// masks are in its layer's pixels).
#[derive(Clone, Debug, Default)]
pub struct SegmentViews {
    /// Where each segment's words lie in `masks`.
    table: HashMap<[u64; 4], (u32, u32)>,
    /// The segments' words, one list after another.
    masks: Vec<(u32, u64)>,
    /// A segment's views being gathered (zero outside `touched`).
    bits: Vec<u64>,
    touched: Vec<u32>,
    /// The plan's union (zero outside `union_touched`).
    union: Vec<u64>,
    union_touched: Vec<u32>,
    /// Segments viewed (not found in the table).
    viewed: u64,
    /// Mask words kept before starting afresh (0: [`VIEW_CACHE_WORDS`]).
    max_words: usize,
    /// The layer the masks belong to (0: none yet).
    layer: u64,
}

impl SegmentViews {
    /// An empty cache that keeps at most `max_words` mask words before starting afresh.
    pub fn with_max_words(max_words: usize) -> Self {
        Self { max_words: max_words.max(1), ..Self::default() }
    }

    /// Segments whose views were computed rather than found.
    pub fn viewed(&self) -> u64 {
        self.viewed
    }

    /// Starts an empty union over `words` words of `layer`.
    fn begin(&mut self, layer: u64, words: usize) {
        if self.layer != layer {
            // Masks of another layer lie in its pixels: start afresh.
            self.layer = layer;
            self.table.clear();
            self.masks.clear();
        }
        if self.union.len() != words {
            self.union = vec![0; words];
            self.bits = vec![0; words];
            self.union_touched.clear();
        }
        for &w in &self.union_touched {
            self.union[w as usize] = 0;
        }
        self.union_touched.clear();
    }

    /// ORs the views of segment `a → b` into the union, viewing it first if it is new.
    fn add_segment(&mut self, layer: &CameraLayer, a: Point, b: Point) {
        let key = key_of(a, b);
        let (start, len) = match self.table.get(&key) {
            Some(&range) => range,
            None => self.view_segment(layer, key, a, b),
        };
        for &(w, x) in &self.masks[start as usize..(start + len) as usize] {
            let word = &mut self.union[w as usize];
            if *word == 0 {
                self.union_touched.push(w);
            }
            *word |= x;
        }
    }

    /// Views segment `a → b` pose by pose into `bits` and keeps its words.
    fn view_segment(&mut self, layer: &CameraLayer, key: [u64; 4], a: Point, b: Point) -> (u32, u32) {
        self.viewed += 1;
        let wm = &layer.map;
        let (bits, touched) = (&mut self.bits, &mut self.touched);
        for_each_pose(a, b, |p, psi| {
            let pos = wm.to_px(p.x, p.y);
            layer.camera.view_into_bits(wm.width, wm.height, |c, r| wm.is_occluded(c, r), pos, psi, bits, touched);
        });
        self.touched.sort_unstable();
        let limit = if self.max_words == 0 { VIEW_CACHE_WORDS } else { self.max_words };
        if self.masks.len() + self.touched.len() > limit {
            self.table.clear();
            self.masks.clear();
        }
        let start = self.masks.len() as u32;
        for &w in &self.touched {
            self.masks.push((w, std::mem::take(&mut self.bits[w as usize])));
        }
        self.touched.clear();
        let range = (start, self.masks.len() as u32 - start);
        self.table.insert(key, range);
        range
    }

    /// `[walls_free, open_free, walls_reach, open_reach]` pixel counts of the union.
    fn counts(&self, layer: &CameraLayer) -> [usize; 4] {
        let mut hit = [0u32; 4];
        for &w in &self.union_touched {
            let (u, b, r) = (self.union[w as usize], layer.band[w as usize], layer.reach[w as usize]);
            hit[0] += (u & b).count_ones();
            hit[1] += u.count_ones();
            hit[2] += (u & b & r).count_ones();
            hit[3] += (u & r).count_ones();
        }
        hit.map(|h| h as usize)
    }
}

#[cfg(test)]
mod tests;
