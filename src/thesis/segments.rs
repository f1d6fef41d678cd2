//! A cache of swept segments as bit-row masks, for the incremental evaluator.
//!
//! A child of the thesis GA is its parent's visit map minus the parent's segments it does not
//! share plus its own ([`crate::coverage::bits`]). The parent's segments were swept when the parent was
//! evaluated, and most of a crossover child's new segments are copied from the other parent
//! (only the segments at the cut points are new): the same segments are swept over and over.
//! Scanning a segment's rows costs about as much as applying them, so a segment's masks are
//! kept, keyed by its endpoints bit for bit and the robot's width, and replayed.
//!
//! The cache changes no result: the masks of a segment depend only on its endpoints, the width
//! and the grid's geometry, and a replay applies exactly the masks a scan would produce (tested
//! below against [`BitLayers::apply`]).

use crate::coverage::bits::{BitLayers, Tally};
use crate::coverage::planes::VisitPlanes;
use crate::geom::Point;

/// Masks kept in one generation of the cache (16 bytes each: 4 MiB per generation).
pub const CACHE_MASKS: usize = 1 << 18;

/// Slots of one generation's table (64 bytes each: 2 MiB). At most half are filled before a
/// new generation starts, which keeps linear probes short. In the reference run that comes
/// before [`CACHE_MASKS`] (16 384 segments of about 12 masks); 2^16 slots measured no faster.
const SLOTS: usize = 1 << 15;

/// Bytes a cache holds at most once both its generations are full: what one worker thread
/// of a thesis run adds to the run's memory.
pub const CACHE_BYTES: usize =
    2 * (SLOTS * std::mem::size_of::<Slot>() + CACHE_MASKS * std::mem::size_of::<(u32, u64)>());

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

/// Where the probe for a segment's key starts, in either generation's table: the key's hash,
/// computed once by [`SegmentCache::prefetch`] and handed to [`SegmentCache::apply_from`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Home(usize);

/// Whether two keys are equal, word by word and inlined (the array comparison calls `memcmp`).
#[inline(always)]
fn same_key(a: &[u64; 5], b: &[u64; 5]) -> bool {
    (a[0] == b[0]) & (a[1] == b[1]) & (a[2] == b[2]) & (a[3] == b[3]) & (a[4] == b[4])
}

/// One generation of the cache: swept segments as lists of `(word index, free cells)` with
/// their cell counts, in an open-addressing table (linear probing).
#[derive(Debug, Default)]
struct Generation {
    /// `SLOTS` slots once used (allocated on the first segment).
    slots: Vec<Slot>,
    /// The current filling; slots of other epochs are empty. Starts at 1 (0 is never used).
    epoch: u32,
    /// Segments held.
    filled: usize,
    masks: Vec<(u32, u64)>,
}

impl Generation {
    /// The slot holding `key` (`Ok`), or the empty slot where it would go (`Err`), probing from
    /// the key's home slot. The table must be allocated.
    #[inline(always)]
    fn find(&self, key: &[u64; 5], home: Home) -> Result<usize, usize> {
        debug_assert_eq!(home.0, slot_of(key), "the home of another key");
        let mut i = home.0;
        while self.slots[i].epoch == self.epoch {
            if same_key(&self.slots[i].key, key) {
                return Ok(i);
            }
            i = (i + 1) & (SLOTS - 1);
        }
        Err(i)
    }

    /// The masks of the segment in slot `i`.
    #[inline(always)]
    fn masks_of(&self, i: usize) -> &[(u32, u64)] {
        let slot = &self.slots[i];
        &self.masks[slot.start as usize..(slot.start + slot.len) as usize]
    }

    /// Forgets every segment (keeps the allocations; allocates the table and room for
    /// `mask_limit` masks on first use, so that the masks never grow past it).
    fn clear(&mut self, mask_limit: usize) {
        if self.slots.is_empty() {
            self.slots = vec![Slot::default(); SLOTS];
            self.masks.reserve_exact(mask_limit);
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
}

/// Swept segments of one grid, replayed by [`SegmentCache::apply`], kept in two generations.
/// New segments go into the current one; when it is full, it becomes the previous one and a
/// new current one starts empty. A segment found only in the previous generation is copied
/// into the current one, not scanned again: the segments still in use (those of the
/// population) move along, and only those no longer met are dropped. A cache emptied at once
/// when full had to scan every live segment again: 37 % of the reference run's scans.
#[derive(Debug)]
pub struct SegmentCache {
    /// The grid the masks belong to: the fingerprint of its raster and walls.
    grid: Option<u64>,
    current: Generation,
    previous: Generation,
    /// Masks one generation holds at most ([`CACHE_MASKS`]; smaller in tests).
    mask_limit: usize,
    /// The masks of the segment being put in, before it is known which generation takes it.
    fresh: Vec<(u32, u64)>,
    /// Segments scanned (not found in either generation).
    scans: u64,
}

impl Default for SegmentCache {
    fn default() -> Self {
        Self::with_mask_limit(CACHE_MASKS)
    }
}

impl Clone for SegmentCache {
    /// A clone starts empty: a cache is a per-worker speed-up, never state.
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl SegmentCache {
    /// An empty cache whose generations hold at most `mask_limit` masks each (a segment of
    /// more masks is applied without being kept). Nothing is allocated before the first
    /// segment.
    fn with_mask_limit(mask_limit: usize) -> Self {
        Self {
            grid: None,
            current: Generation::default(),
            previous: Generation::default(),
            mask_limit,
            fresh: Vec::new(),
            scans: 0,
        }
    }

    /// Adds (`ADD`) or removes the swept rectangle of `a → b` to or from `visits`, as
    /// [`BitLayers::apply`] does, scanning the segment only the first time it is seen.
    #[inline(always)]
    pub fn apply<const ADD: bool>(
        &mut self,
        layers: &BitLayers,
        visits: &mut VisitPlanes,
        a: Point,
        b: Point,
        width: f64,
        tally: &mut Tally,
    ) {
        let home = Home(slot_of(&key_of(a, b, width)));
        self.apply_from::<ADD>(layers, visits, a, b, width, home, tally);
    }

    /// [`Self::apply`] with the segment's home slot (from [`Self::prefetch`] of the same
    /// segment), so that its key is not hashed again.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn apply_from<const ADD: bool>(
        &mut self,
        layers: &BitLayers,
        visits: &mut VisitPlanes,
        a: Point,
        b: Point,
        width: f64,
        home: Home,
        tally: &mut Tally,
    ) {
        // Masks hold the free cells of the grid they were scanned on: another grid (or the same
        // raster with other walls) starts afresh.
        let grid = Some(layers.layout_id());
        if self.grid != grid || self.current.slots.is_empty() {
            self.clear();
            self.grid = grid;
        }
        let key = key_of(a, b, width);
        let i = match self.current.find(&key, home) {
            Ok(i) => i,
            Err(i) => match self.insert(layers, key, home, a, b, width, i) {
                Ok(i) => i,
                Err(counts) => return layers.apply_free_masks::<ADD>(visits, &self.fresh, counts, tally),
            },
        };
        let slot = &self.current.slots[i];
        let counts = [u64::from(slot.free), u64::from(slot.obstacle)];
        layers.apply_free_masks::<ADD>(visits, self.current.masks_of(i), counts, tally);
    }

    /// Puts segment `a → b` (key `key`, not in the current generation) into empty slot `i` of
    /// the current generation, or of a new one if it is full, copied from the previous
    /// generation or scanned; returns its slot. A segment of more masks than a generation
    /// holds is left in `fresh`, and its counts returned (`Err`). Out of line: most segments
    /// are found.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn insert(
        &mut self,
        layers: &BitLayers,
        key: [u64; 5],
        home: Home,
        a: Point,
        b: Point,
        width: f64,
        mut i: usize,
    ) -> Result<usize, [u64; 2]> {
        let previous = &self.previous;
        let promoted = if previous.slots.is_empty() { None } else { previous.find(&key, home).ok() };
        self.fresh.clear();
        let [free, obstacle] = match promoted {
            Some(j) => {
                self.fresh.extend_from_slice(previous.masks_of(j));
                [previous.slots[j].free, previous.slots[j].obstacle]
            }
            None => {
                self.scans += 1;
                layers.push_free_masks(a, b, width, &mut self.fresh)
            }
        };
        let len = self.fresh.len();
        if len > self.mask_limit {
            return Err([u64::from(free), u64::from(obstacle)]);
        }
        if self.current.filled >= SLOTS / 2 || self.current.masks.len() + len > self.mask_limit {
            std::mem::swap(&mut self.current, &mut self.previous);
            self.current.clear(self.mask_limit);
            i = home.0;
        }
        let current = &mut self.current;
        let start = current.masks.len();
        current.masks.extend_from_slice(&self.fresh);
        current.slots[i] = Slot { key, start: start as u32, len: len as u32, free, obstacle, epoch: current.epoch };
        current.filled += 1;
        Ok(i)
    }

    /// Asks the processor to fetch the slots of both generations where segment `a → b` would
    /// be, so that a later [`Self::apply_from`] of it does not wait for memory; returns the
    /// segment's home slot for it. Changes nothing. The previous generation's slot is probed
    /// only for a segment missing from the current one, but that probe, left to wait, took
    /// 85 % of the insertions' time.
    #[inline(always)]
    pub fn prefetch(&self, a: Point, b: Point, width: f64) -> Home {
        let home = Home(slot_of(&key_of(a, b, width)));
        #[cfg(target_arch = "x86_64")]
        {
            let i = home.0;
            for slot in [self.current.slots.get(i), self.previous.slots.get(i)].into_iter().flatten() {
                // SAFETY: a prefetch is a hint; it reads nothing and faults on no address.
                unsafe {
                    std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>((slot as *const Slot).cast());
                }
            }
        }
        home
    }

    /// Forgets every segment of both generations (keeps the allocations).
    pub fn clear(&mut self) {
        self.current.clear(self.mask_limit);
        if !self.previous.slots.is_empty() {
            self.previous.clear(self.mask_limit);
        }
    }

    /// Segments scanned so far: those found in neither generation (or not kept).
    pub fn scans(&self) -> u64 {
        self.scans
    }

    /// Segments held, in both generations (a segment promoted from the previous generation
    /// counts twice).
    pub fn len(&self) -> usize {
        self.current.filled + self.previous.filled
    }

    /// Whether no segment is held.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
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

    /// Two generations of 2^15 slots of 64 bytes (2 MiB) and 2^18 masks of 16 bytes (4 MiB):
    /// the 12 MiB per evaluation thread the memory estimate counts.
    #[test]
    fn a_cache_holds_at_most_twelve_mebibytes() {
        assert_eq!(std::mem::size_of::<Slot>(), 64);
        assert_eq!(CACHE_BYTES, 12 << 20);
    }

    /// Segment `k` of a family of distinct segments on thesis-1.
    fn segment(k: usize) -> (Point, Point) {
        let a = Point::new(1.0 + (k % 128) as f64 * 0.06, 1.0 + (k / 128) as f64 * 0.03);
        (a, Point::new(a.x + 2.0, a.y + 1.0))
    }

    /// A cache and the scan side by side: every apply through one is done by the other.
    struct Twin {
        layers: BitLayers,
        cache: SegmentCache,
        cached: (VisitPlanes, Tally),
        scanned: (VisitPlanes, Tally),
    }

    impl Twin {
        fn new(cache: SegmentCache) -> Self {
            let layers = BitLayers::new(&CoverageGrid::new(&preset("thesis-1").unwrap()));
            let mut v = VisitPlanes::default();
            v.reset(layers.plane_words());
            Self { layers, cache, cached: (v.clone(), Tally::default()), scanned: (v, Tally::default()) }
        }

        fn apply<const ADD: bool>(&mut self, k: usize) {
            let (a, b) = segment(k);
            self.cache.apply::<ADD>(&self.layers, &mut self.cached.0, a, b, 0.6, &mut self.cached.1);
            self.layers.apply::<ADD>(&mut self.scanned.0, a, b, 0.6, &mut self.scanned.1);
            assert_eq!(self.cached.1, self.scanned.1, "segment {k}");
        }
    }

    /// Past half its slots the current generation becomes the previous one and a new one
    /// starts; a segment of the previous generation is copied, not scanned again; a third
    /// generation drops the first. Replays stay exact throughout, and so they do when the
    /// epochs run out.
    #[test]
    fn generations_keep_the_segments_in_use_and_replay_exactly() {
        let mut twin = Twin::new(SegmentCache::default());
        for k in 0..SLOTS / 2 + 10 {
            twin.apply::<true>(k);
        }
        assert_eq!((twin.cache.current.filled, twin.cache.previous.filled), (10, SLOTS / 2), "a second generation");
        assert_eq!(twin.cache.scans(), (SLOTS / 2 + 10) as u64);
        for k in [0, 5, SLOTS / 2 + 3] {
            twin.apply::<false>(k);
        }
        assert_eq!(twin.cache.scans(), (SLOTS / 2 + 10) as u64, "0 and 5 copied from the previous generation");
        assert_eq!(twin.cache.current.filled, 12);
        for k in SLOTS / 2 + 10..SLOTS + 8 {
            twin.apply::<true>(k);
        }
        assert_eq!(twin.cache.current.filled, 10, "a third generation; the first is dropped");
        let scans = twin.cache.scans();
        twin.apply::<true>(0);
        assert_eq!(twin.cache.scans(), scans, "0 moved on with the second generation");
        twin.apply::<true>(7);
        assert_eq!(twin.cache.scans(), scans + 1, "7 was in the first generation only");
        assert_eq!(twin.cached.0, twin.scanned.0);
        twin.cache.current.epoch = u32::MAX;
        twin.cache.clear();
        assert_eq!((twin.cache.current.epoch, twin.cache.len()), (1, 0));
        assert!(twin.cache.current.slots.iter().all(|slot| slot.epoch == 0), "slots of the old epochs are emptied");
        twin.apply::<true>(7);
        assert_eq!(twin.cache.len(), 1);
        assert_eq!(twin.cached.0, twin.scanned.0);
    }

    /// A generation holds at most its mask limit: a segment that does not fit starts a new
    /// generation, one longer than the limit is applied without being kept, and the masks
    /// never outgrow the room reserved for them.
    #[test]
    fn the_mask_limit_bounds_every_generation() {
        let layers = BitLayers::new(&CoverageGrid::new(&preset("thesis-1").unwrap()));
        let lens: Vec<usize> = (0..3)
            .map(|k| {
                let (a, b) = segment(k);
                let mut masks = Vec::new();
                layers.push_free_masks(a, b, 0.6, &mut masks);
                masks.len()
            })
            .collect();
        let per_segment = lens[0];
        assert!(per_segment > 2 && lens.iter().all(|&n| n == per_segment), "{lens:?}");
        // Two segments fill the limit exactly, and a full generation still holds them both.
        let mut twin = Twin::new(SegmentCache::with_mask_limit(2 * per_segment));
        twin.apply::<true>(0);
        twin.apply::<true>(1);
        assert_eq!((twin.cache.current.filled, twin.cache.previous.filled), (2, 0), "both fit exactly");
        twin.apply::<true>(2);
        assert_eq!((twin.cache.current.filled, twin.cache.previous.filled), (1, 2), "the third did not fit");
        assert_eq!(twin.cache.len(), 3, "both generations count");
        assert!(twin.cache.current.masks.capacity() <= 2 * per_segment);
        // A segment of exactly the limit is kept; one mask more than the limit is not.
        let mut exact = Twin::new(SegmentCache::with_mask_limit(per_segment));
        exact.apply::<true>(0);
        exact.apply::<true>(0);
        assert_eq!((exact.cache.len(), exact.cache.scans()), (1, 1), "as long as the limit: kept");
        let mut small = Twin::new(SegmentCache::with_mask_limit(per_segment - 1));
        small.apply::<true>(0);
        small.apply::<true>(0);
        assert_eq!((small.cache.len(), small.cache.scans()), (0, 2), "too long to keep: scanned each time");
        assert_eq!(small.cached.0, small.scanned.0);
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
