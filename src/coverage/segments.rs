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

use super::bits::{BitLayers, Tally};
use super::{planes::VisitPlanes, raster::RasterGrid};
use crate::geom::Point;

/// Masks kept before the cache starts afresh (16 bytes each: 4 MiB per worker thread). 2^19
/// saves 18 % of the reference run's segment scans, yet measured no faster (the larger table
/// misses the processor's caches more often) and holds twice the memory.
pub const CACHE_MASKS: usize = 1 << 18;

/// Slots of the table (64 bytes each: 2 MiB per worker thread). At most half are filled
/// before the cache starts afresh, which keeps linear probes short. In the reference run that
/// comes before [`CACHE_MASKS`] (16 384 segments of about 12 masks); 2^16 slots measured no
/// faster.
const SLOTS: usize = 1 << 15;

/// A segment and where its masks are kept: one cache line, so that a lookup costs one memory
/// access (which [`SegmentCache::prefetch`] can start early).
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(64))]
struct Slot {
    /// The bits of the endpoints and of the width.
    key: [u64; 5],
    /// First mask in `masks`.
    start: u32,
    /// Masks of the segment.
    len: u32,
    /// Free cells of the swept rectangle (its share of `cov_pix`).
    free: u32,
    /// Obstacle cells of the swept rectangle (its share of `obj_pix`).
    obstacle: u32,
    /// The filling the slot belongs to: a slot of an earlier one is empty.
    epoch: u32,
}

/// The key of segment `a → b` swept `width` wide.
#[inline(always)]
fn key_of(a: Point, b: Point, width: f64) -> [u64; 5] {
    [a.x.to_bits(), a.y.to_bits(), b.x.to_bits(), b.y.to_bits(), width.to_bits()]
}

/// Multiply-rotate hashing of the five words of a key (the bits of coordinates, already well
/// spread), folded so that the low bits that pick the slot depend on all of them.
#[inline(always)]
fn slot_of(key: &[u64; 5]) -> usize {
    let h = key.iter().fold(0u64, |h, &w| (h.rotate_left(23) ^ w).wrapping_mul(0x9E37_79B9_7F4A_7C15));
    ((h ^ (h >> 29)) as usize) & (SLOTS - 1)
}

/// Whether two keys are equal, word by word and inlined (the array comparison calls `memcmp`).
#[inline(always)]
fn same_key(a: &[u64; 5], b: &[u64; 5]) -> bool {
    (a[0] == b[0]) & (a[1] == b[1]) & (a[2] == b[2]) & (a[3] == b[3]) & (a[4] == b[4])
}

/// Swept segments of one grid as lists of `(word index, free cells)` with their cell counts,
/// in an open-addressing table (linear probing), replayed by [`SegmentCache::apply`].
#[derive(Debug, Default)]
pub struct SegmentCache {
    /// The grid the masks belong to: its raster and the fingerprint of its walls.
    grid: Option<(RasterGrid, u64)>,
    /// `SLOTS` slots once used (allocated on the first segment).
    slots: Vec<Slot>,
    /// The current filling; slots of other epochs are empty. Starts at 1 (0 is never used).
    epoch: u32,
    /// Segments held.
    filled: usize,
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
        if self.grid != grid || self.slots.is_empty() {
            self.clear();
            self.grid = grid;
        }
        let key = key_of(a, b, width);
        let mut i = slot_of(&key);
        while self.slots[i].epoch == self.epoch && !same_key(&self.slots[i].key, &key) {
            i = (i + 1) & (SLOTS - 1);
        }
        if self.slots[i].epoch != self.epoch {
            if self.masks.len() >= CACHE_MASKS || self.filled >= SLOTS / 2 {
                self.clear();
                i = slot_of(&key);
            }
            let start = self.masks.len();
            let [free, obstacle] = layers.push_free_masks(a, b, width, &mut self.masks);
            let len = (self.masks.len() - start) as u32;
            self.slots[i] = Slot { key, start: start as u32, len, free, obstacle, epoch: self.epoch };
            self.filled += 1;
        }
        let slot = &self.slots[i];
        let masks = &self.masks[slot.start as usize..(slot.start + slot.len) as usize];
        layers.apply_free_masks::<ADD>(visits, masks, [u64::from(slot.free), u64::from(slot.obstacle)], tally);
    }

    /// Asks the processor to fetch the slot where segment `a → b` would be, so that a later
    /// [`Self::apply`] of it does not wait for memory. Changes nothing.
    #[inline(always)]
    pub fn prefetch(&self, a: Point, b: Point, width: f64) {
        #[cfg(target_arch = "x86_64")]
        if let Some(slot) = self.slots.get(slot_of(&key_of(a, b, width))) {
            // SAFETY: a prefetch is a hint; it reads nothing and faults on no address.
            unsafe {
                std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>((slot as *const Slot).cast());
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = (a, b, width);
    }

    /// Forgets every segment (keeps the allocations).
    pub fn clear(&mut self) {
        if self.slots.is_empty() {
            self.slots = vec![Slot::default(); SLOTS];
        }
        if self.epoch == u32::MAX {
            // Every epoch has been used: empty the slots for real and count again.
            self.slots.fill(Slot::default());
            self.epoch = 0;
        }
        self.epoch += 1;
        self.filled = 0;
        self.masks.clear();
    }

    /// Segments held.
    pub fn len(&self) -> usize {
        self.filled
    }

    /// Whether no segment is held.
    pub fn is_empty(&self) -> bool {
        self.filled == 0
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

    /// Past half its slots the cache starts afresh, and so it does when its epochs run out;
    /// replays stay exact throughout.
    #[test]
    fn a_full_table_starts_afresh_and_keeps_replaying_exactly() {
        let layers = BitLayers::new(&CoverageGrid::new(&preset("thesis-1").unwrap()));
        let mut cache = SegmentCache::default();
        let (mut cached, mut scanned) = (VisitPlanes::default(), VisitPlanes::default());
        cached.reset(layers.plane_words());
        scanned.reset(layers.plane_words());
        let (mut t_cached, mut t_scanned) = (Tally::default(), Tally::default());
        let segment = |k: usize| {
            let a = Point::new(1.0 + (k % 128) as f64 * 0.06, 1.0 + (k / 128) as f64 * 0.03);
            (a, Point::new(a.x + 2.0, a.y + 1.0))
        };
        for k in 0..SLOTS / 2 + 10 {
            let (a, b) = segment(k);
            cache.apply::<true>(&layers, &mut cached, a, b, 0.6, &mut t_cached);
            layers.apply::<true>(&mut scanned, a, b, 0.6, &mut t_scanned);
        }
        assert_eq!(cache.len(), 10, "the table was emptied at its half and refilled with ten");
        for k in [0, 5, SLOTS / 2 + 3] {
            let (a, b) = segment(k);
            cache.apply::<false>(&layers, &mut cached, a, b, 0.6, &mut t_cached);
            layers.apply::<false>(&mut scanned, a, b, 0.6, &mut t_scanned);
        }
        assert_eq!(t_cached, t_scanned);
        assert_eq!(cached, scanned);
        cache.epoch = u32::MAX;
        cache.clear();
        assert_eq!((cache.epoch, cache.len()), (1, 0));
        assert!(cache.slots.iter().all(|slot| slot.epoch == 0), "slots of the old epochs are emptied");
        let (a, b) = segment(7);
        cache.apply::<true>(&layers, &mut cached, a, b, 0.6, &mut t_cached);
        layers.apply::<true>(&mut scanned, a, b, 0.6, &mut t_scanned);
        assert_eq!((t_cached, cache.len()), (t_scanned, 1));
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
