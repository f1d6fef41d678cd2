//! Visit-count maps stored bit-sliced (003 Listing 3.1's visit counts, for [`super::bits`]):
//! bit `p` of every cell's count in plane `p`, so that one visit to 64 cells is a ripple-carry
//! add across the planes and one visit removed a ripple-borrow subtract.

/// A visit-count map stored bit-sliced: plane `p` holds bit `p` of every free cell's count,
/// laid out like [`BitLayers`](super::bits::BitLayers). Only the planes in use are stored.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct VisitPlanes {
    words: usize,
    planes: Vec<u64>,
    top: usize,
}

impl VisitPlanes {
    /// Empties the map for a grid of `words` words per plane (keeps the allocation).
    pub fn reset(&mut self, words: usize) {
        self.words = words;
        self.planes.clear();
        self.top = 0;
    }

    /// Becomes a copy of `other` (keeps the allocation), with room for one more plane: a
    /// child's first visit that carries into a new plane then grows the map without moving it.
    pub fn copy_from(&mut self, other: &VisitPlanes) {
        self.words = other.words;
        self.top = other.top;
        self.planes.clear();
        self.planes.reserve((other.top + 1) * other.words);
        self.planes.extend_from_slice(&other.planes[..other.top * other.words]);
    }

    /// Bit planes in use (counts are below `2^planes`).
    pub fn planes(&self) -> usize {
        self.top
    }

    /// Words per plane.
    pub fn plane_words(&self) -> usize {
        self.words
    }

    /// Word `idx` of plane `p` (zero above the planes in use).
    #[inline(always)]
    pub fn word(&self, p: usize, idx: usize) -> u64 {
        if p < self.top { self.planes[p * self.words + idx] } else { 0 }
    }

    /// The planes in use, plane after plane (`planes()` × `plane_words()` words).
    pub fn plane_data(&self) -> &[u64] {
        &self.planes[..self.top * self.words]
    }

    /// Word `idx` of every plane in use, checked against the plane length once: word `idx` of
    /// plane `p` is then at `idx + p × words`, below the slice's length for every plane. The
    /// planes are walked by stride, not by `chunks_exact` (or `step_by` on a range), whose set-up
    /// divides by the plane length: a `div` on every word edited, about a sixth of the edits'
    /// time.
    #[inline(always)]
    fn used_words(&self, idx: usize) -> &[u64] {
        assert!(idx < self.words);
        &self.planes[..self.top * self.words]
    }

    /// [`Self::used_words`], writable.
    #[inline(always)]
    fn used_words_mut(&mut self, idx: usize) -> &mut [u64] {
        assert!(idx < self.words);
        &mut self.planes[..self.top * self.words]
    }

    /// The cells of word `idx` visited at least once.
    #[inline(always)]
    fn occupied(&self, idx: usize) -> u64 {
        let used = self.used_words(idx);
        let (mut any, mut i) = (0, idx);
        while i < used.len() {
            any |= used[i];
            i += self.words;
        }
        any
    }

    /// Puts the carry out of the top plane into a new plane.
    #[cold]
    fn push_plane(&mut self, idx: usize, carry: u64) {
        self.top += 1;
        self.planes.resize(self.top * self.words, 0);
        self.planes[(self.top - 1) * self.words + idx] = carry;
    }

    /// Adds one visit to every cell of `mask` in word `idx`; returns the cells that were
    /// unvisited before.
    #[inline(always)]
    pub(super) fn add(&mut self, idx: usize, mask: u64) -> u64 {
        let words = self.words;
        let (fresh, carry) = add_word(self.used_words_mut(idx), words, idx, mask);
        if carry != 0 {
            self.push_plane(idx, carry);
        }
        fresh
    }

    /// Removes one visit from every cell of `mask` in word `idx` (each must have one); returns
    /// the cells left unvisited.
    #[inline(always)]
    pub(super) fn remove(&mut self, idx: usize, mask: u64) -> u64 {
        let words = self.words;
        remove_word(self.used_words_mut(idx), words, idx, mask)
    }

    /// Adds (`ADD`) or removes one visit to or from every cell of each `(word index, cells)`
    /// of `masks`, in order, and calls `flipped(word index, cells)` with the cells that were
    /// unvisited before (`ADD`) or are left unvisited. The same as [`Self::add`] or
    /// [`Self::remove`] mask by mask, with the planes looked up once per run of masks instead
    /// of once per mask (a new plane ends a run).
    #[inline(always)]
    pub(super) fn edit<const ADD: bool>(&mut self, masks: &[(u32, u64)], mut flipped: impl FnMut(usize, u64)) {
        let words = self.words;
        let mut k = 0;
        while k < masks.len() {
            let used = &mut self.planes[..self.top * words];
            let mut carry_out = None;
            while k < masks.len() {
                let (idx, cells) = (masks[k].0 as usize, masks[k].1);
                k += 1;
                assert!(idx < words);
                if ADD {
                    let (fresh, carry) = add_word(used, words, idx, cells);
                    flipped(idx, fresh);
                    if carry != 0 {
                        carry_out = Some((idx, carry));
                        break;
                    }
                } else {
                    flipped(idx, remove_word(used, words, idx, cells));
                }
            }
            if let Some((idx, carry)) = carry_out {
                self.push_plane(idx, carry);
            }
        }
    }

    /// Calls `f(cell, visits)` for every visited cell, with cells numbered `word·64 + bit` in
    /// the layout of [`BitLayers`](super::bits::BitLayers) (row-major, rows padded to whole words).
    pub fn for_each_count(&self, mut f: impl FnMut(u32, u32)) {
        for idx in 0..self.words {
            let mut nz = self.occupied(idx);
            while nz != 0 {
                let bit = nz.trailing_zeros();
                let mut count = 0u32;
                for p in 0..self.top {
                    count |= (((self.planes[p * self.words + idx] >> bit) & 1) as u32) << p;
                }
                f(idx as u32 * 64 + bit, count);
                nz &= nz - 1;
            }
        }
    }

    /// A map of `words` words per plane holding `counts` (`(cell, visits)` in the numbering of
    /// [`Self::for_each_count`]).
    pub fn from_counts(words: usize, counts: &[(u32, u32)]) -> Self {
        let mut v = VisitPlanes::default();
        v.reset(words);
        for &(cell, k) in counts {
            for _ in 0..k {
                v.add(cell as usize / 64, 1u64 << (cell % 64));
            }
        }
        v
    }

    /// Number of cells in the padded numbering of [`Self::for_each_count`].
    pub fn cell_slots(&self) -> usize {
        self.words * 64
    }
}

/// Adds one visit to the cells of `mask` in word `idx` of the planes `used` (`words` words
/// each); returns the cells that were unvisited and the carry out of the top plane (cells
/// whose count needs a new plane).
///
/// One pass over every plane: the carry is added and the old words ORed (for the unvisited
/// cells) together, with no exit when the carry dies out, whose branch the processor cannot
/// predict (the carry's length varies from cell word to cell word).
#[inline(always)]
fn add_word(used: &mut [u64], words: usize, idx: usize, mask: u64) -> (u64, u64) {
    let (mut any, mut carry, mut i) = (0, mask, idx);
    while i < used.len() {
        let old = used[i];
        any |= old;
        used[i] = old ^ carry;
        carry &= old;
        i += words;
    }
    (mask & !any, carry)
}

/// Removes one visit from the cells of `mask` in word `idx` of the planes `used` (each must
/// have one); returns the cells left unvisited. One pass over every plane, as [`add_word`].
#[inline(always)]
fn remove_word(used: &mut [u64], words: usize, idx: usize, mask: u64) -> u64 {
    let (mut any, mut borrow, mut i) = (0, mask, idx);
    while i < used.len() {
        let old = used[i];
        let new = old ^ borrow;
        used[i] = new;
        any |= new;
        borrow &= !old;
        i += words;
    }
    debug_assert_eq!(borrow, 0, "removed a visit that was never added");
    mask & !any
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn counts(v: &VisitPlanes) -> Vec<(u32, u32)> {
        let mut c = Vec::new();
        v.for_each_count(|cell, k| c.push((cell, k)));
        c
    }

    #[test]
    fn visits_carry_into_new_planes_and_borrow_back() {
        let mut v = VisitPlanes::default();
        v.reset(2);
        assert_eq!(v.add(0, 0b11), 0b11, "cells 0 and 1 were unvisited");
        assert_eq!(v.planes(), 1);
        assert_eq!(v.add(0, 0b01), 0, "cell 0 goes to 2: a carry into a new plane");
        assert_eq!(v.planes(), 2);
        assert_eq!(v.add(0, 0b01), 0);
        assert_eq!(v.add(1, 0b10), 0b10);
        assert_eq!(counts(&v), [(0, 3), (1, 1), (65, 1)]);
        // Cell 0 holds 3 = 0b11, cell 1 holds 1, cell 65 (word 1, bit 1) holds 1.
        assert_eq!([v.word(0, 0), v.word(1, 0), v.word(0, 1), v.word(1, 1), v.word(2, 0)], [0b11, 0b01, 0b10, 0, 0]);
        assert_eq!(v.plane_data(), [0b11, 0b10, 0b01, 0]);
        // 3 → 2 borrows nothing past plane 0 and leaves cell 0 visited; cell 1 is left unvisited.
        assert_eq!(v.remove(0, 0b11), 0b10);
        assert_eq!(counts(&v), [(0, 2), (65, 1)]);
        assert_eq!(v.remove(0, 0b01), 0, "2 → 1 borrows from plane 1");
        assert_eq!(v.remove(0, 0b01), 0b01);
        assert_eq!(counts(&v), [(65, 1)]);
        assert_eq!(v.planes(), 2, "planes stay once made");
        let mut copy = VisitPlanes::default();
        copy.copy_from(&v);
        assert_eq!(copy, v);
        assert_eq!(VisitPlanes::from_counts(2, &[(0, 3), (1, 1), (65, 1)]).plane_data(), [0b11, 0b10, 0b01, 0]);
    }

    fn mask() -> impl Strategy<Value = u64> {
        prop_oneof![Just(u64::MAX), Just(1u64), Just(0u64), Just(0x8000_0000_0000_0001), any::<u64>()]
    }

    proptest! {
        /// An edit gives the map, and reports the cells, that adding or removing its masks one
        /// by one gives, and both agree with a count per cell: a new plane in the middle of an
        /// edit included.
        #[test]
        fn an_edit_equals_its_masks_one_by_one_and_a_count_per_cell(
            words in 1usize..4,
            edits in proptest::collection::vec((0usize..4, mask(), any::<bool>()), 0..80),
        ) {
            let masks: Vec<(u32, u64)> = edits.iter().map(|&(i, m, _)| ((i % words) as u32, m)).collect();
            let removed: Vec<(u32, u64)> = masks.iter().zip(&edits).filter(|(_, e)| e.2).map(|(m, _)| *m).rev().collect();
            let mut model = vec![0u32; words * 64];
            let (mut edited, mut single) = (VisitPlanes::default(), VisitPlanes::default());
            edited.reset(words);
            single.reset(words);
            let mut by_edit = Vec::new();
            edited.edit::<true>(&masks, |i, cells| by_edit.push((i, cells)));
            for (k, &(i, m)) in masks.iter().enumerate() {
                let i = i as usize;
                let fresh = (0..64).filter(|b| m >> b & 1 == 1 && model[i * 64 + b] == 0).fold(0, |f, b| f | 1 << b);
                (0..64).filter(|b| m >> b & 1 == 1).for_each(|b| model[i * 64 + b] += 1);
                prop_assert_eq!(single.add(i, m), fresh);
                prop_assert_eq!(by_edit[k], (i, fresh));
            }
            prop_assert_eq!(by_edit.len(), masks.len());
            prop_assert_eq!(&edited, &single);
            let mut by_edit = Vec::new();
            edited.edit::<false>(&removed, |i, cells| by_edit.push((i, cells)));
            for (k, &(i, m)) in removed.iter().enumerate() {
                let i = i as usize;
                (0..64).filter(|b| m >> b & 1 == 1).for_each(|b| model[i * 64 + b] -= 1);
                let left = (0..64).filter(|b| m >> b & 1 == 1 && model[i * 64 + b] == 0).fold(0, |f, b| f | 1 << b);
                prop_assert_eq!(single.remove(i, m), left);
                prop_assert_eq!(by_edit[k], (i, left));
            }
            prop_assert_eq!(&edited, &single);
            let want: Vec<(u32, u32)> = model.iter().enumerate().filter(|c| *c.1 > 0).map(|(c, &k)| (c as u32, k)).collect();
            prop_assert_eq!(counts(&edited), want);
        }
    }
}
