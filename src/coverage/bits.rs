//! Listing 3.1 of 003 on bit rows: the counts of [`super::sweep`] with every row of the map
//! held as 64-bit words and every visit-count map held bit-sliced.
//!
//! A row interval of a swept rectangle ([`super::rows`]) becomes one mask per word, so
//! `cov_pix` and `obj_pix` are popcounts and a visit is a ripple-carry add across the count's
//! bit planes. Because the counts of Listing 3.1 depend only on the final visit-count map
//! (`cov_pix` and `obj_pix` are sums over segments, `unique` is the number of countable
//! cells visited at least once), a map can also be edited: removing a segment is a
//! ripple-borrow subtract. That is what lets a child be evaluated from its parent's map.

use super::planes::VisitPlanes;
use super::raster::RasterGrid;
use super::rows::for_each_swept_row;
use super::sweep::{CoverageGrid, SweepCounts};
use crate::geom::Point;

/// The map as bit rows: which cells are free, and which free cells still count towards
/// `A_pix` (not pre-marked, R25).
#[derive(Clone, Debug)]
pub struct BitLayers {
    raster: RasterGrid,
    words: usize,
    free: Vec<u64>,
    countable: Vec<u64>,
    /// A fingerprint of the raster and of `free` (see [`Self::layout_id`]).
    layout_id: u64,
}

impl BitLayers {
    /// The layers of a coverage grid (obstacles and pre-marks as they stand).
    pub fn new(grid: &CoverageGrid) -> Self {
        let raster = *grid.raster();
        let words = raster.cols.div_ceil(64).max(1);
        let mut free = vec![0u64; raster.rows * words];
        let mut countable = free.clone();
        for r in 0..raster.rows {
            for c in 0..raster.cols {
                let i = r * raster.cols + c;
                let (w, bit) = (r * words + c / 64, 1u64 << (c % 64));
                if !grid.is_blocked(i) {
                    free[w] |= bit;
                    if !grid.is_premarked(i) {
                        countable[w] |= bit;
                    }
                }
            }
        }
        let mix = |h: u64, w: u64| crate::ga::rng::mix64(h ^ w);
        let RasterGrid { cols, rows, resolution, origin_x, origin_y } = raster;
        let geometry = [cols as u64, rows as u64, resolution.to_bits(), origin_x.to_bits(), origin_y.to_bits()];
        let layout_id = free.iter().fold(geometry.into_iter().fold(0, mix), |h, &w| mix(h, w));
        Self { raster, words, free, countable, layout_id }
    }

    /// Words in one bit plane (rows × words per row).
    pub fn plane_words(&self) -> usize {
        self.free.len()
    }

    /// The grid geometry the rows are laid out on.
    pub fn raster(&self) -> &RasterGrid {
        &self.raster
    }

    /// The cells flagged in `flags` (one flag per cell, row-major, as a [`CoverageGrid`]
    /// numbers them) as bit rows in the layout of the planes, for
    /// [`VisitPlanes::visited_in`].
    pub fn mask_of(&self, flags: &[bool]) -> Vec<u64> {
        let (rows, cols) = (self.raster.rows, self.raster.cols);
        assert_eq!(flags.len(), rows * cols, "one flag per cell");
        let mut mask = vec![0u64; rows * self.words];
        for (i, _) in flags.iter().enumerate().filter(|(_, f)| **f) {
            let (r, c) = (i / cols, i % cols);
            mask[r * self.words + c / 64] |= 1u64 << (c % 64);
        }
        mask
    }

    /// Calls `mask(word index, bits)` for every word of every row the swept rectangle of
    /// `a → b` touches: the cells of the segment, in the layout of the planes.
    #[inline]
    pub fn for_each_mask(&self, a: Point, b: Point, width: f64, mut mask: impl FnMut(usize, u64)) {
        let words = self.words;
        for_each_swept_row(&self.raster, a, b, width, |row, lo, hi| {
            let base = row * words;
            let (w0, w1) = (lo / 64, hi / 64);
            for w in w0..=w1 {
                let mut bits = u64::MAX;
                if w == w0 {
                    bits &= u64::MAX << (lo % 64);
                }
                if w == w1 {
                    bits &= u64::MAX >> (63 - hi % 64);
                }
                mask(base + w, bits);
            }
        });
    }

    /// One word of a segment: counts its free and obstacle cells and adds or removes a visit.
    #[inline(always)]
    fn apply_word<const ADD: bool>(&self, visits: &mut VisitPlanes, idx: usize, mask: u64, counts: &mut [u64; 3]) {
        let free = mask & self.free[idx];
        let n_free = u64::from(free.count_ones());
        counts[0] += n_free;
        counts[1] += u64::from(mask.count_ones()) - n_free;
        if free != 0 {
            let flipped = if ADD { visits.add(idx, free) } else { visits.remove(idx, free) };
            counts[2] += u64::from((flipped & self.countable[idx]).count_ones());
        }
    }

    #[inline(always)]
    fn settle<const ADD: bool>(tally: &mut Tally, [cov, obj, changed]: [u64; 3]) {
        if ADD {
            tally.cov_pix += cov;
            tally.obj_pix += obj;
            tally.unique += changed;
        } else {
            tally.cov_pix -= cov;
            tally.obj_pix -= obj;
            tally.unique -= changed;
        }
    }

    /// Adds (`ADD`) or removes the swept rectangle of `a → b` to or from `visits`, updating
    /// `tally`. Removing is only meaningful for a segment that was added before.
    #[inline]
    pub fn apply<const ADD: bool>(&self, visits: &mut VisitPlanes, a: Point, b: Point, width: f64, tally: &mut Tally) {
        let mut counts = [0u64; 3];
        self.for_each_mask(a, b, width, |idx, mask| self.apply_word::<ADD>(visits, idx, mask, &mut counts));
        Self::settle::<ADD>(tally, counts);
    }

    /// The obstacle cells (cells not free) in the swept rectangle of `a → b`: the segment's
    /// share of `obj_pix`, without touching any visit map.
    pub fn obstacle_cells(&self, a: Point, b: Point, width: f64) -> u64 {
        let mut n = 0u64;
        self.for_each_mask(a, b, width, |idx, mask| n += u64::from((mask & !self.free[idx]).count_ones()));
        n
    }

    /// A 64-bit fingerprint of the raster geometry and the free cells: grids of other
    /// geometries, or of one raster with other walls, differ in it (but for a 2⁻⁶⁴ chance), so
    /// a cache of free-cell masks can tell them apart with one comparison.
    pub fn layout_id(&self) -> u64 {
        self.layout_id
    }

    /// Appends to `out` the free cells of every word of the swept rectangle of `a → b`, words
    /// without free cells left out (what [`Self::apply_free_masks`] takes); returns the
    /// rectangle's `[free cells, obstacle cells]`.
    pub fn push_free_masks(&self, a: Point, b: Point, width: f64, out: &mut Vec<(u32, u64)>) -> [u32; 2] {
        let start = out.len();
        self.for_each_mask(a, b, width, |idx, mask| out.push((idx as u32, mask)));
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("popcnt") {
            // SAFETY: the CPU has just been found to support `popcnt`.
            return unsafe { self.keep_free_cells_popcnt(out, start) };
        }
        self.keep_free_cells(out, start)
    }

    /// Replaces the masks of `out[start..]` by their free cells, drops those left empty, and
    /// returns the free and the obstacle cells counted. A pass of its own over the masks, so
    /// that the scan of the rows (not compiled with `popcnt`) counts nothing.
    #[inline(always)]
    fn keep_free_cells(&self, out: &mut Vec<(u32, u64)>, start: usize) -> [u32; 2] {
        let (mut free, mut obstacle, mut kept) = (0, 0, start);
        for k in start..out.len() {
            let (idx, mask) = out[k];
            let cells = mask & self.free[idx as usize];
            free += cells.count_ones();
            obstacle += (mask & !cells).count_ones();
            if cells != 0 {
                out[kept] = (idx, cells);
                kept += 1;
            }
        }
        out.truncate(kept);
        [free, obstacle]
    }

    /// [`Self::keep_free_cells`] with the `popcnt` instruction; the same result.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "popcnt")]
    unsafe fn keep_free_cells_popcnt(&self, out: &mut Vec<(u32, u64)>, start: usize) -> [u32; 2] {
        self.keep_free_cells(out, start)
    }

    /// [`Self::apply`] for a segment given by the free cells of its words (from
    /// [`Self::push_free_masks`]) and its counts `[free cells, obstacle cells]`.
    #[inline]
    pub fn apply_free_masks<const ADD: bool>(
        &self,
        visits: &mut VisitPlanes,
        masks: &[(u32, u64)],
        [free, obstacle]: [u64; 2],
        tally: &mut Tally,
    ) {
        #[cfg(target_arch = "x86_64")]
        let changed = if std::arch::is_x86_feature_detected!("popcnt") {
            // SAFETY: the CPU has just been found to support `popcnt`.
            unsafe { self.changed_cells_popcnt::<ADD>(visits, masks) }
        } else {
            self.changed_cells::<ADD>(visits, masks)
        };
        #[cfg(not(target_arch = "x86_64"))]
        let changed = self.changed_cells::<ADD>(visits, masks);
        Self::settle::<ADD>(tally, [free, obstacle, changed]);
    }

    /// Applies the free cells `masks`; returns how many countable cells became visited (`ADD`)
    /// or unvisited.
    #[inline(always)]
    fn changed_cells<const ADD: bool>(&self, visits: &mut VisitPlanes, masks: &[(u32, u64)]) -> u64 {
        visits.edit::<ADD>(masks, &self.countable)
    }

    /// [`Self::changed_cells`] with the `popcnt` instruction (not in the default x86-64
    /// target); the same result.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "popcnt")]
    unsafe fn changed_cells_popcnt<const ADD: bool>(&self, visits: &mut VisitPlanes, masks: &[(u32, u64)]) -> u64 {
        self.changed_cells::<ADD>(visits, masks)
    }

    /// Sweeps a whole polyline into cleared `visits` and returns its tally.
    pub fn sweep(&self, visits: &mut VisitPlanes, points: &[Point], width: f64) -> Tally {
        visits.reset(self.plane_words());
        let mut tally = Tally::default();
        for w in points.windows(2) {
            self.apply::<true>(visits, w[0], w[1], width, &mut tally);
        }
        tally
    }
}

/// `cov_pix`, `obj_pix` and the number of distinct countable cells visited (`unique`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    /// `cov_pix`.
    pub cov_pix: u64,
    /// `obj_pix`.
    pub obj_pix: u64,
    /// `cov_pix − cross_pix`.
    pub unique: u64,
}

impl Tally {
    /// The counts of Listing 3.1.
    pub fn counts(&self) -> SweepCounts {
        SweepCounts { cov_pix: self.cov_pix, cross_pix: self.cov_pix - self.unique, obj_pix: self.obj_pix }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::SweepScratch;
    use crate::map::presets::preset;
    use proptest::prelude::*;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    #[test]
    fn spec_cases_on_bit_rows() {
        // The hand-computed cases of thesis-ga §3.3 (see coverage::tests): cov, cross, obj.
        let grid = CoverageGrid::new(&preset("thesis-1").unwrap());
        let layers = BitLayers::new(&grid);
        let mut v = VisitPlanes::default();
        let cases: [(&[Point], u64, u64, u64); 5] = [
            (&[p(1.3, 1.3), p(4.3, 1.3)], 45, 0, 0),
            (&[p(1.3, 1.3), p(4.3, 1.3), p(4.3, 4.3)], 90, 2, 0),
            (&[p(1.3, 1.3), p(4.3, 1.3), p(1.3, 1.3)], 90, 42, 0),
            (&[p(1.3, 1.3), p(4.3, 1.3), p(4.3, 4.3), p(1.3, 1.3)], 165, 14, 0),
            (&[p(1.3, 1.3), p(0.5, 1.3)], 6, 0, 6),
        ];
        for (i, (path, cov, cross, obj)) in cases.into_iter().enumerate() {
            let c = layers.sweep(&mut v, path, 0.6).counts();
            assert_eq!((c.cov_pix, c.cross_pix, c.obj_pix), (cov, cross, obj), "case {i}");
        }
        // Out and back: the return's 45 cells are 42 revisits, so 3 cells carry two visits.
        let mut twos = 0;
        v = VisitPlanes::default();
        layers.sweep(&mut v, &[p(1.3, 1.3), p(4.3, 1.3), p(1.3, 1.3)], 0.6);
        v.for_each_count(|_, k| twos += usize::from(k == 2));
        assert_eq!(twos, 42);
    }

    #[test]
    fn premarked_cells_are_revisits_on_bit_rows() {
        let mut grid = CoverageGrid::new(&preset("thesis-1").unwrap());
        grid.premark_rect(1.0, 1.0, 2.0, 2.0);
        let layers = BitLayers::new(&grid);
        let c = layers.sweep(&mut VisitPlanes::default(), &[p(1.3, 1.3), p(4.3, 1.3)], 0.6).counts();
        assert_eq!(c, SweepCounts { cov_pix: 45, cross_pix: 12, obj_pix: 0 });
    }

    fn path(seed: u64, n: usize, lo: f64, hi: f64) -> Vec<Point> {
        let mut rng = crate::ga::rng::stream(seed, crate::ga::rng::Purpose::Main, &[]);
        use rand::Rng;
        (0..n).map(|_| p(rng.random_range(lo..hi), rng.random_range(lo..hi))).collect()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]
        /// Bit rows count exactly what the cell-by-cell sweep counts, visit map included, on
        /// the map with obstacles, with pre-marks, and with paths leaving the grid.
        #[test]
        fn bit_rows_equal_the_cell_sweep(seed in 0u64..100_000, n in 2usize..60, w in 0.1..1.2f64, map in 0usize..3, premark in proptest::bool::ANY) {
            let name = ["thesis-1", "thesis-2", "office"][map];
            let m = preset(name).unwrap();
            let mut grid = CoverageGrid::new(&m);
            if premark {
                grid.premark_rect(m.origin().x + 2.0, m.origin().y + 2.0, m.origin().x + 6.0, m.origin().y + 5.0);
            }
            let (lo, hi) = (m.origin().x - 1.0, m.origin().x + m.width_m().min(m.height_m()) + 1.0);
            let pts = path(seed, n, lo, hi);
            let mut scratch = SweepScratch::new(&grid);
            let expected = scratch.sweep(&grid, &pts, w);
            let layers = BitLayers::new(&grid);
            let mut v = VisitPlanes::default();
            prop_assert_eq!(layers.sweep(&mut v, &pts, w).counts(), expected);
            let cols = m.cols();
            let mut got: Vec<(u32, u32)> = Vec::new();
            v.for_each_count(|slot, k| {
                let (row, col) = (slot as usize / (v.cell_slots() / m.rows()), slot as usize % (v.cell_slots() / m.rows()));
                got.push(((row * cols + col) as u32, k));
            });
            let mut want: Vec<(u32, u32)> = scratch.visit_counts().collect();
            got.sort_unstable();
            want.sort_unstable();
            prop_assert_eq!(got, want);
        }

        /// Removing segments and adding others gives exactly the sweep of the edited path.
        #[test]
        fn edits_equal_a_fresh_sweep(seed in 0u64..100_000, n in 3usize..40, cut in 0usize..40, len in 0usize..6, ins in 0usize..6) {
            let grid = CoverageGrid::new(&preset("thesis-2").unwrap());
            let layers = BitLayers::new(&grid);
            let old = path(seed, n, -0.5, 11.5);
            let (c0, c1) = (cut % (n - 1), (cut % (n - 1) + len + 1).min(n - 1));
            let mut new: Vec<Point> = old[..=c0].to_vec();
            new.extend(path(seed + 1, ins, 0.0, 11.0));
            new.extend_from_slice(&old[c1..]);
            let mut v = VisitPlanes::default();
            let mut tally = layers.sweep(&mut v, &old, 0.6);
            for w in old[c0..=c1].windows(2) {
                layers.apply::<false>(&mut v, w[0], w[1], 0.6, &mut tally);
            }
            for w in new[c0..=c0 + ins + 1].windows(2) {
                layers.apply::<true>(&mut v, w[0], w[1], 0.6, &mut tally);
            }
            let mut fresh = VisitPlanes::default();
            prop_assert_eq!(tally, layers.sweep(&mut fresh, &new, 0.6));
            let (mut a, mut b) = (Vec::new(), Vec::new());
            v.for_each_count(|c, k| a.push((c, k)));
            fresh.for_each_count(|c, k| b.push((c, k)));
            prop_assert_eq!(a, b);
        }
    }
}
