//! A cache of swept segments as bit-row masks, for the incremental evaluator.
//!
//! A child of the thesis GA is its parent's visit map minus the parent's segments it does not
//! share plus its own ([`super::bits`]). The parent's segments were swept when the parent was
//! evaluated, and most of a crossover child's new segments are copied from the other parent
//! (only the segments at the cut points are new): the same segments are swept over and over.
//! Scanning a segment's rows costs about as much as applying them, so a segment's masks are
//! kept, keyed by its endpoints bit for bit and the robot's width, and replayed.
//!
//! The cache changes no result: the masks of a segment depend only on its endpoints, the width
//! and the grid's geometry, and a replay applies exactly the masks a scan would produce (tested
//! below against [`BitLayers::apply`]).

use super::bits::{BitLayers, Tally, VisitPlanes};
use super::raster::RasterGrid;
use crate::geom::Point;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// Masks kept before the cache starts afresh (16 bytes each: 4 MiB per worker thread). 2^19
/// saves 18 % of the reference run's segment scans, yet measured no faster (the larger table
/// misses the processor's caches more often) and holds twice the memory.
pub const CACHE_MASKS: usize = 1 << 18;

/// A segment: the bits of its endpoints and of the width.
#[derive(Clone, Copy, Debug)]
struct Key([u64; 5]);

impl std::hash::Hash for Key {
    fn hash<H: Hasher>(&self, state: &mut H) {
        for word in self.0 {
            state.write_u64(word);
        }
    }
}

impl PartialEq for Key {
    /// Word by word and inlined (the array comparison calls `memcmp`).
    fn eq(&self, other: &Self) -> bool {
        let (a, b) = (&self.0, &other.0);
        (a[0] == b[0]) & (a[1] == b[1]) & (a[2] == b[2]) & (a[3] == b[3]) & (a[4] == b[4])
    }
}

impl Eq for Key {}

/// Where a segment's masks are kept, and its cell counts, which do not depend on the map it is
/// added to or removed from.
#[derive(Clone, Copy, Debug)]
struct Span {
    start: u32,
    len: u32,
    /// Free cells of the swept rectangle (its share of `cov_pix`).
    free: u64,
    /// Obstacle cells of the swept rectangle (its share of `obj_pix`).
    obstacle: u64,
}

/// Multiply-rotate hashing of the five words of a key: the keys are the bits of coordinates,
/// already well spread; SipHash would cost more than the lookup saves.
#[derive(Default)]
struct KeyHasher(u64);

impl Hasher for KeyHasher {
    fn finish(&self) -> u64 {
        // Fold the high bits down: the table indexes by the low ones.
        self.0 ^ (self.0 >> 29)
    }
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(word));
        }
    }
    fn write_u64(&mut self, word: u64) {
        self.0 = (self.0.rotate_left(23) ^ word).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}

/// Swept segments of one grid as lists of `(word index, free cells)` with their cell counts,
/// replayed by [`SegmentCache::apply`].
#[derive(Debug, Default)]
pub struct SegmentCache {
    /// The grid the masks belong to: its raster and the fingerprint of its walls.
    grid: Option<(RasterGrid, u64)>,
    spans: HashMap<Key, Span, BuildHasherDefault<KeyHasher>>,
    masks: Vec<(u32, u64)>,
}

impl Clone for SegmentCache {
    /// A clone starts empty: a cache is a per-worker speed-up, never state.
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl SegmentCache {
    /// Adds (`ADD`) or removes the swept rectangle of `a → b` to or from `visits`, as
    /// [`BitLayers::apply`] does, scanning the segment only the first time it is seen.
    pub fn apply<const ADD: bool>(
        &mut self,
        layers: &BitLayers,
        visits: &mut VisitPlanes,
        a: Point,
        b: Point,
        width: f64,
        tally: &mut Tally,
    ) {
        // Masks hold the free cells of the grid they were scanned on: another grid (or the same
        // raster with other walls) starts afresh.
        let grid = Some((*layers.raster(), layers.walls_id()));
        if self.grid != grid {
            self.clear();
            self.grid = grid;
        }
        let key = Key([a.x.to_bits(), a.y.to_bits(), b.x.to_bits(), b.y.to_bits(), width.to_bits()]);
        let span = match self.spans.get(&key) {
            Some(&span) => span,
            None => {
                if self.masks.len() >= CACHE_MASKS {
                    self.clear();
                }
                let start = self.masks.len();
                let (mut free, mut obstacle) = (0, 0);
                layers.for_each_mask(a, b, width, |idx, mask| {
                    let f = layers.free_cells(idx, mask);
                    free += u64::from(f.count_ones());
                    obstacle += u64::from((mask & !f).count_ones());
                    if f != 0 {
                        self.masks.push((idx as u32, f));
                    }
                });
                let len = (self.masks.len() - start) as u32;
                let span = Span { start: start as u32, len, free, obstacle };
                self.spans.insert(key, span);
                span
            }
        };
        let masks = &self.masks[span.start as usize..(span.start + span.len) as usize];
        layers.apply_free_masks::<ADD>(visits, masks, [span.free, span.obstacle], tally);
    }

    /// Forgets every segment (keeps the allocations).
    pub fn clear(&mut self) {
        self.spans.clear();
        self.masks.clear();
    }

    /// Segments held.
    pub fn len(&self) -> usize {
        self.spans.len()
    }

    /// Whether no segment is held.
    pub fn is_empty(&self) -> bool {
        self.spans.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::CoverageGrid;
    use crate::map::presets::preset;
    use proptest::prelude::*;

    /// A cache used on one grid and then on another (same raster or not, other walls) replays
    /// nothing of the first: every tally equals a fresh scan's.
    #[test]
    fn a_cache_moved_to_another_grid_gives_that_grid_s_counts() {
        let grids: Vec<BitLayers> = ["thesis-1", "thesis-2", "office"]
            .iter()
            .map(|m| BitLayers::new(&CoverageGrid::new(&preset(m).unwrap())))
            .collect();
        let mut cache = SegmentCache::default();
        assert!(cache.is_empty());
        let (a, b) = (Point::new(1.3, 1.3), Point::new(9.3, 7.1));
        for layers in grids.iter().chain(&grids[..1]) {
            let (mut cached, mut scanned) = (VisitPlanes::default(), VisitPlanes::default());
            cached.reset(layers.plane_words());
            scanned.reset(layers.plane_words());
            let (mut t_cached, mut t_scanned) = (Tally::default(), Tally::default());
            cache.apply::<true>(layers, &mut cached, a, b, 0.6, &mut t_cached);
            layers.apply::<true>(&mut scanned, a, b, 0.6, &mut t_scanned);
            assert_eq!(t_cached, t_scanned);
            assert_eq!(cached, scanned);
            assert!(!cache.is_empty());
        }
        assert_eq!(grids[0].raster(), grids[1].raster(), "the thesis maps share a raster, not their walls");
    }

    #[test]
    fn a_replayed_segment_is_not_scanned_again_and_a_new_grid_starts_afresh() {
        let g = CoverageGrid::new(&preset("thesis-1").unwrap());
        let layers = BitLayers::new(&g);
        let mut cache = SegmentCache::default();
        let mut v = VisitPlanes::default();
        v.reset(layers.plane_words());
        let mut t = Tally::default();
        let (a, b) = (Point::new(1.3, 1.3), Point::new(4.3, 2.1));
        cache.apply::<true>(&layers, &mut v, a, b, 0.6, &mut t);
        cache.apply::<true>(&layers, &mut v, a, b, 0.6, &mut t);
        assert_eq!(cache.len(), 1);
        cache.apply::<true>(&layers, &mut v, a, b, 0.4, &mut t);
        assert_eq!(cache.len(), 2, "the width is part of the key");
        let other = BitLayers::new(&CoverageGrid::new(&preset("thesis-2").unwrap()));
        let mut w = VisitPlanes::default();
        w.reset(other.plane_words());
        let mut u = Tally::default();
        cache.apply::<true>(&other, &mut w, a, b, 0.6, &mut u);
        if other.raster() != layers.raster() {
            assert_eq!(cache.len(), 1, "another grid's masks are dropped");
        }
        assert!(u.cov_pix > 0);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        /// Adding and removing segments through the cache, some of them twice, leaves the same
        /// visit map and tally as the scan, step by step.
        #[test]
        fn replays_equal_scans(seed in 0u64..100_000, n in 2usize..40, map in 0usize..3) {
            use rand::{Rng, SeedableRng};
            let name = ["thesis-1", "thesis-2", "office"][map];
            let m = preset(name).unwrap();
            let g = CoverageGrid::new(&m);
            let layers = BitLayers::new(&g);
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
            let (w, h) = (m.width_m(), m.height_m());
            let pts: Vec<Point> = (0..n).map(|_| Point::new(rng.random_range(-0.5..w + 0.5), rng.random_range(-0.5..h + 0.5))).collect();
            let mut cache = SegmentCache::default();
            let (mut v1, mut v2) = (VisitPlanes::default(), VisitPlanes::default());
            v1.reset(layers.plane_words());
            v2.reset(layers.plane_words());
            let (mut t1, mut t2) = (Tally::default(), Tally::default());
            for round in 0..2 {
                for s in pts.windows(2) {
                    layers.apply::<true>(&mut v1, s[0], s[1], 0.6, &mut t1);
                    cache.apply::<true>(&layers, &mut v2, s[0], s[1], 0.6, &mut t2);
                    prop_assert_eq!(t1, t2, "round {}", round);
                }
            }
            for s in pts.windows(2).step_by(2) {
                layers.apply::<false>(&mut v1, s[0], s[1], 0.6, &mut t1);
                cache.apply::<false>(&layers, &mut v2, s[0], s[1], 0.6, &mut t2);
                prop_assert_eq!(t1, t2);
            }
            prop_assert_eq!(v1, v2);
        }
    }
}
