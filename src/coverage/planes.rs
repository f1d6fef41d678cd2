//! Visit-count maps stored bit-sliced (003 Listing 3.1's visit counts, for [`super::bits`]):
//! bit `p` of every cell's count in plane `p`, so that one visit to 64 cells is a ripple-carry
//! add across the planes and one visit removed a ripple-borrow subtract.
//!
//! The planes are stored word-major: the planes of cell word `idx` lie next to each other,
//! usually in one cache line. An edit of a word then checks one index and touches one line,
//! and for the usual numbers of planes its ripple is unrolled (`VisitPlanes::edit`).

/// Plane counts up to which an edit's ripple is unrolled (a map of more planes, counts of 256
/// and above, takes a loop).
const UNROLLED_PLANES: usize = 8;

use std::sync::atomic::{AtomicU64, Ordering};

/// A visit-count map stored bit-sliced: plane `p` holds bit `p` of every free cell's count,
/// laid out like [`BitLayers`](super::bits::BitLayers), word-major: bit `p` of word `idx`'s
/// counts is at `idx · planes() + p`. Only the planes in use are stored.
///
/// A map also carries a [`stamp`](Self::stamp) of its content: two maps with the same stamp
/// hold the same counts (a copy keeps the stamp, any change drops it).
#[derive(Debug, Default)]
pub struct VisitPlanes {
    words: usize,
    planes: Vec<u64>,
    top: usize,
    /// The content's stamp, 0 until asked for after the last change.
    stamp: AtomicU64,
}

impl Clone for VisitPlanes {
    fn clone(&self) -> Self {
        Self { words: self.words, planes: self.planes.clone(), top: self.top, stamp: AtomicU64::new(self.stamp()) }
    }
}

/// Maps are equal when their counts are (the stamps are not compared).
impl PartialEq for VisitPlanes {
    fn eq(&self, other: &Self) -> bool {
        self.words == other.words && self.top == other.top && self.planes == other.planes
    }
}

impl Eq for VisitPlanes {}

/// Stamps handed out so far, in blocks of [`STAMP_BLOCK`] per thread.
static STAMPS: AtomicU64 = AtomicU64::new(1);

/// Stamps a thread takes from [`STAMPS`] at a time.
const STAMP_BLOCK: u64 = 1 << 20;

thread_local! {
    /// The next stamp of this thread's block, and the end of the block.
    static NEXT_STAMP: std::cell::Cell<(u64, u64)> = const { std::cell::Cell::new((0, 0)) };
}

/// A stamp no map has had before (never 0).
fn fresh_stamp() -> u64 {
    NEXT_STAMP.with(|next| {
        let (mut at, mut end) = next.get();
        if at == end {
            at = STAMPS.fetch_add(STAMP_BLOCK, Ordering::Relaxed);
            end = at + STAMP_BLOCK;
        }
        next.set((at + 1, end));
        at
    })
}

impl VisitPlanes {
    /// The stamp of the map's content: maps with equal stamps hold equal counts, so a reader
    /// that kept a map's stamp knows, without reading it, whether the map is unchanged. A
    /// clone or a [`copy_from`](Self::copy_from) keeps the stamp; a change drops it and the
    /// next call hands out one never used before.
    pub fn stamp(&self) -> u64 {
        let now = self.stamp.load(Ordering::Relaxed);
        if now != 0 {
            return now;
        }
        let fresh = fresh_stamp();
        match self.stamp.compare_exchange(0, fresh, Ordering::Relaxed, Ordering::Relaxed) {
            Ok(_) => fresh,
            Err(set) => set,
        }
    }

    /// Marks the content changed.
    #[inline(always)]
    fn changed(&mut self) {
        *self.stamp.get_mut() = 0;
    }

    /// Empties the map for a grid of `words` words per plane (keeps the allocation).
    pub fn reset(&mut self, words: usize) {
        self.changed();
        self.words = words;
        self.planes.clear();
        self.top = 0;
    }

    /// Becomes a copy of `other` (keeps the allocation), with room for one more plane: a
    /// child's first visit that carries into a new plane then grows the map without moving it
    /// to a new allocation.
    pub fn copy_from(&mut self, other: &VisitPlanes) {
        *self.stamp.get_mut() = other.stamp();
        self.words = other.words;
        self.top = other.top;
        self.planes.clear();
        self.planes.reserve((other.top + 1) * other.words);
        self.planes.extend_from_slice(&other.planes);
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
        if p < self.top { self.word_planes(idx)[p] } else { 0 }
    }

    /// The planes in use of word `idx`, least significant first.
    #[inline(always)]
    pub fn word_planes(&self, idx: usize) -> &[u64] {
        assert!(idx < self.words);
        &self.planes[idx * self.top..(idx + 1) * self.top]
    }

    /// The cells of word `idx` visited at least once (the union of its planes).
    #[inline]
    pub fn visited_word(&self, idx: usize) -> u64 {
        self.word_planes(idx).iter().fold(0, |any, &w| any | w)
    }

    /// Distinct cells of `mask` (bit rows in this layout) visited at least once.
    pub fn visited_in(&self, mask: &[u64]) -> u64 {
        (0..self.words.min(mask.len())).map(|idx| u64::from((self.visited_word(idx) & mask[idx]).count_ones())).sum()
    }

    /// The planes in use, word-major: word `idx`'s planes at `idx · planes()` onwards
    /// (`planes()` × `plane_words()` words).
    pub fn plane_data(&self) -> &[u64] {
        &self.planes
    }

    /// [`Self::word_planes`], writable.
    #[inline(always)]
    fn word_planes_mut(&mut self, idx: usize) -> &mut [u64] {
        assert!(idx < self.words);
        &mut self.planes[idx * self.top..(idx + 1) * self.top]
    }

    /// Adds a plane, zero everywhere but for the carry out of the top plane in word `idx`.
    /// Every word's planes move up to their new place, the last word first, so that none is
    /// overwritten before it has moved.
    #[cold]
    fn push_plane(&mut self, idx: usize, carry: u64) {
        let (old, new) = (self.top, self.top + 1);
        self.planes.resize(self.words * new, 0);
        for w in (0..self.words).rev() {
            self.planes.copy_within(w * old..(w + 1) * old, w * new);
            self.planes[w * new + old] = 0;
        }
        self.top = new;
        self.planes[idx * new + old] = carry;
    }

    /// Adds one visit to every cell of `mask` in word `idx`; returns the cells that were
    /// unvisited before.
    #[inline(always)]
    pub(super) fn add(&mut self, idx: usize, mask: u64) -> u64 {
        self.changed();
        let (fresh, carry) = add_word(self.word_planes_mut(idx), mask);
        if carry != 0 {
            self.push_plane(idx, carry);
        }
        fresh
    }

    /// Removes one visit from every cell of `mask` in word `idx` (each must have one); returns
    /// the cells left unvisited.
    #[inline(always)]
    pub(super) fn remove(&mut self, idx: usize, mask: u64) -> u64 {
        self.changed();
        remove_word(self.word_planes_mut(idx), mask)
    }

    /// Adds (`ADD`) or removes one visit to or from every cell of each `(word index, cells)`
    /// of `masks`, in order; returns how many cells of `countable` (one word per word of the
    /// map) were unvisited before (`ADD`) or are left unvisited. The same as [`Self::add`] or
    /// [`Self::remove`] mask by mask; a run of masks between two new planes is edited with the
    /// number of planes known at compile time (up to [`UNROLLED_PLANES`]), so that each
    /// word's ripple is unrolled and its index checked once.
    #[inline(always)]
    pub(super) fn edit<const ADD: bool>(&mut self, masks: &[(u32, u64)], countable: &[u64]) -> u64 {
        self.changed();
        let (mut k, mut flipped) = (0, 0);
        while k < masks.len() {
            let (planes, rest) = (&mut self.planes[..], &masks[k..]);
            let run = match self.top {
                1 => edit_run::<ADD, 1>(planes, rest, countable),
                2 => edit_run::<ADD, 2>(planes, rest, countable),
                3 => edit_run::<ADD, 3>(planes, rest, countable),
                4 => edit_run::<ADD, 4>(planes, rest, countable),
                5 => edit_run::<ADD, 5>(planes, rest, countable),
                6 => edit_run::<ADD, 6>(planes, rest, countable),
                7 => edit_run::<ADD, 7>(planes, rest, countable),
                UNROLLED_PLANES => edit_run::<ADD, UNROLLED_PLANES>(planes, rest, countable),
                top => edit_run_any::<ADD>(planes, self.words, top, rest, countable),
            };
            k += run.masks;
            flipped += run.flipped;
            if let Some((idx, carry)) = run.carry_out {
                self.push_plane(idx, carry);
            }
        }
        flipped
    }

    /// Calls `f(cell, visits)` for every visited cell, with cells numbered `word·64 + bit` in
    /// the layout of [`BitLayers`](super::bits::BitLayers) (row-major, rows padded to whole words).
    pub fn for_each_count(&self, mut f: impl FnMut(u32, u32)) {
        for idx in 0..self.words {
            let planes = self.word_planes(idx);
            let mut nz = planes.iter().fold(0, |any, &w| any | w);
            while nz != 0 {
                let bit = nz.trailing_zeros();
                let count = planes.iter().enumerate().fold(0u32, |c, (p, &w)| c | (((w >> bit) & 1) as u32) << p);
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

/// What [`edit_run`] did.
struct Run {
    /// Masks applied.
    masks: usize,
    /// Countable cells flipped between unvisited and visited.
    flipped: u64,
    /// The carry out of the top plane that ended the run, with its word index.
    carry_out: Option<(usize, u64)>,
}

/// Edits `planes` (`P` planes per word, word-major) by `masks` as [`VisitPlanes::edit`] does,
/// up to the first add that carries out of the top plane. The word index is checked once, by
/// the chunking (each word's `P` planes are one array), and `countable` is cut to the map's
/// length, so that the same check covers it.
#[inline(always)]
fn edit_run<const ADD: bool, const P: usize>(planes: &mut [u64], masks: &[(u32, u64)], countable: &[u64]) -> Run {
    let words = planes.as_chunks_mut::<P>().0;
    let countable = &countable[..words.len()];
    let mut flipped = 0;
    for (k, &(idx, cells)) in masks.iter().enumerate() {
        let idx = idx as usize;
        let word = &mut words[idx];
        if ADD {
            let (fresh, carry) = add_word(word, cells);
            flipped += u64::from((fresh & countable[idx]).count_ones());
            if carry != 0 {
                return Run { masks: k + 1, flipped, carry_out: Some((idx, carry)) };
            }
        } else {
            flipped += u64::from((remove_word(word, cells) & countable[idx]).count_ones());
        }
    }
    Run { masks: masks.len(), flipped, carry_out: None }
}

/// [`edit_run`] for any number of planes `top` (none, or more than [`UNROLLED_PLANES`]), with
/// `words` words per plane.
#[inline(always)]
fn edit_run_any<const ADD: bool>(
    planes: &mut [u64],
    words: usize,
    top: usize,
    masks: &[(u32, u64)],
    countable: &[u64],
) -> Run {
    let mut flipped = 0;
    for (k, &(idx, cells)) in masks.iter().enumerate() {
        let idx = idx as usize;
        assert!(idx < words);
        let word = &mut planes[idx * top..(idx + 1) * top];
        if ADD {
            let (fresh, carry) = add_word(word, cells);
            flipped += u64::from((fresh & countable[idx]).count_ones());
            if carry != 0 {
                return Run { masks: k + 1, flipped, carry_out: Some((idx, carry)) };
            }
        } else {
            flipped += u64::from((remove_word(word, cells) & countable[idx]).count_ones());
        }
    }
    Run { masks: masks.len(), flipped, carry_out: None }
}

/// Adds one visit to the cells of `mask` in one word's planes `word` (least significant
/// first); returns the cells that were unvisited and the carry out of the top plane (cells
/// whose count needs a new plane).
///
/// One pass over every plane: the carry is added and the old words ORed (for the unvisited
/// cells) together, with no exit when the carry dies out, whose branch the processor cannot
/// predict (the carry's length varies from cell word to cell word).
#[inline(always)]
pub(crate) fn add_word(word: &mut [u64], mask: u64) -> (u64, u64) {
    let (mut any, mut carry) = (0, mask);
    for plane in word {
        let old = *plane;
        any |= old;
        *plane = old ^ carry;
        carry &= old;
    }
    (mask & !any, carry)
}

/// Removes one visit from the cells of `mask` in one word's planes `word` (each must have
/// one); returns the cells left unvisited. One pass over every plane, as [`add_word`].
#[inline(always)]
pub(crate) fn remove_word(word: &mut [u64], mask: u64) -> u64 {
    let (mut any, mut borrow) = (0, mask);
    for plane in word {
        let old = *plane;
        let new = old ^ borrow;
        *plane = new;
        any |= new;
        borrow &= !old;
    }
    debug_assert_eq!(borrow, 0, "removed a visit that was never added");
    mask & !any
}

#[cfg(test)]
mod tests;
