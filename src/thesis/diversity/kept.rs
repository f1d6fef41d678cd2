//! The pair sum of eq. 3.18 kept from one generation to the next (003 §3.2.3).
//!
//! A generation of the thesis GA replaces only a few members: in the reference run about 4 %
//! of the population after the first 200 iterations. [`KeptPairSum`] therefore keeps, for
//! every threshold `t`, the number `c_t` of members that visited each cell at least `t` times,
//! and with them `S₁ = Σ_cells Σ_t c_t` and `S₂ = Σ_cells Σ_t c_t²`. The pair sum is
//! `Σ_cells Σ_t c_t(N − c_t) = N·S₁ − S₂` (the identity of [`super::pair_distance_sum_by`]), and
//! a member that joins or leaves changes `S₁` and `S₂` only in the cells it visited, by
//! `(c + 1)² − c² = 2c + 1` per cell and threshold. The counts are bit-sliced like the visit
//! maps, so 64 cells move at once. The result is the exact integer the full pass computes.

use super::{LOW, at_least, thermometer};
use crate::coverage::planes::VisitPlanes;

/// One member as the sum holds it: a copy of its visit map, recognised by content.
#[derive(Default, Debug, Clone)]
struct Kept {
    fingerprint: u64,
    words: usize,
    planes: usize,
    data: Vec<u64>,
}

impl Kept {
    fn holds(&self, map: &VisitPlanes) -> bool {
        self.words == map.plane_words() && self.planes == map.planes() && self.data == map.plane_data()
    }
}

/// A summary of a visit map's content: equal maps have equal fingerprints. It only narrows the
/// search (members are matched by comparing their maps), so it is made of sums that need no
/// chain of multiplications from word to word.
fn fingerprint(map: &VisitPlanes) -> u64 {
    let data = map.plane_data();
    let sum = data.iter().fold(0u64, |a, &w| a.wrapping_add(w));
    let xor = data.iter().fold(0u64, |a, &w| a ^ w);
    let shape = (map.plane_words() as u64) << 8 | map.planes() as u64;
    (sum ^ xor.rotate_left(32) ^ shape).wrapping_mul(0x9E37_79B9_7F4A_7C15)
}

/// `Σ_{i<j} Dist(M^i, M^j)` of a population, updated from the members that left and joined
/// since the previous call (see the module documentation).
#[derive(Default, Debug, Clone)]
pub struct KeptPairSum {
    /// Bit planes of each count: every `c_t` stays below `2^levels`.
    levels: usize,
    /// Words per count plane.
    words: usize,
    /// `counts[t − 1][word · levels + q]`: bit `q` of `c_t` for the 64 cells of `word`.
    counts: Vec<Vec<u64>>,
    s1: u64,
    s2: u64,
    members: Vec<Kept>,
    spare: Vec<Kept>,
    /// Reused per call: `(fingerprint, member)` sorted, and which members are still present.
    order: Vec<(u64, usize)>,
    present: Vec<bool>,
    joining: Vec<usize>,
}

impl KeptPairSum {
    /// The pair sum of the `n` maps `map(0) … map(n − 1)`, after bringing the kept counts from
    /// the previous population to this one. Equals [`super::pair_distance_sum_by`].
    pub fn update<'a>(&mut self, n: usize, map: impl Fn(usize) -> &'a VisitPlanes) -> u64 {
        self.order.clear();
        self.order.extend(self.members.iter().enumerate().map(|(i, m)| (m.fingerprint, i)));
        self.order.sort_unstable();
        self.present.clear();
        self.present.resize(self.members.len(), false);
        self.joining.clear();
        for i in 0..n {
            let m = map(i);
            let fp = fingerprint(m);
            let from = self.order.partition_point(|&(f, _)| f < fp);
            let found = self.order[from..]
                .iter()
                .take_while(|&&(f, _)| f == fp)
                .map(|&(_, k)| k)
                .find(|&k| !self.present[k] && self.members[k].holds(m));
            match found {
                Some(k) => self.present[k] = true,
                None => self.joining.push(i),
            }
        }
        // Those who left, last first so that `swap_remove` keeps the indices still to visit.
        for k in (0..self.members.len()).rev() {
            if !self.present[k] {
                let gone = self.members.swap_remove(k);
                self.apply::<false>(&gone.data, gone.words, gone.planes);
                self.spare.push(gone);
            }
        }
        if n >= 1 << self.levels {
            self.recount(usize::BITS as usize - n.leading_zeros() as usize);
        }
        for j in 0..self.joining.len() {
            let m = map(self.joining[j]);
            let mut kept = self.spare.pop().unwrap_or_default();
            kept.fingerprint = fingerprint(m);
            (kept.words, kept.planes) = (m.plane_words(), m.planes());
            kept.data.clear();
            kept.data.extend_from_slice(m.plane_data());
            self.apply::<true>(&kept.data, kept.words, kept.planes);
            self.members.push(kept);
        }
        debug_assert_eq!(self.members.len(), n);
        n as u64 * self.s1 - self.s2
    }

    /// Starts the counts afresh with `levels` bit planes and adds the members kept so far.
    fn recount(&mut self, levels: usize) {
        self.levels = levels;
        self.counts.iter_mut().for_each(Vec::clear);
        self.counts.iter_mut().for_each(|c| c.resize(self.words * levels, 0));
        (self.s1, self.s2) = (0, 0);
        let members = std::mem::take(&mut self.members);
        for m in &members {
            self.apply::<true>(&m.data, m.words, m.planes);
        }
        self.members = members;
    }

    /// Adds (`JOIN`) or removes one member's map (`words` words of `planes` planes, word-major).
    fn apply<const JOIN: bool>(&mut self, data: &[u64], words: usize, planes: usize) {
        if words > self.words {
            self.words = words;
            let len = words * self.levels;
            self.counts.iter_mut().for_each(|c| c.resize(len, 0));
        }
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("popcnt") {
            // SAFETY: the CPU has just been found to support `popcnt`.
            unsafe { self.apply_popcnt::<JOIN>(data, words, planes) };
            return;
        }
        self.apply_kernel::<JOIN>(data, words, planes);
    }

    /// [`Self::apply_kernel`] compiled with the `popcnt` instruction; the result is the same.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "popcnt")]
    unsafe fn apply_popcnt<const JOIN: bool>(&mut self, data: &[u64], words: usize, planes: usize) {
        self.apply_kernel::<JOIN>(data, words, planes);
    }

    #[inline(always)]
    fn apply_kernel<const JOIN: bool>(&mut self, data: &[u64], words: usize, planes: usize) {
        let mut th = [0u64; LOW + 1];
        for (idx, pl) in data.chunks_exact(planes.max(1)).take(words).enumerate() {
            if planes == 0 || pl.iter().all(|&w| w == 0) {
                continue;
            }
            // The masks shrink as `t` grows: the first empty one ends the word.
            if planes <= 4 {
                thermometer(pl, &mut th);
                for (t, &mask) in th.iter().enumerate().take(1 << planes).skip(1) {
                    if mask == 0 {
                        break;
                    }
                    self.count::<JOIN>(idx, t, mask);
                }
            } else {
                for t in 1..1usize << planes {
                    let mask = at_least(pl, t);
                    if mask == 0 {
                        break;
                    }
                    self.count::<JOIN>(idx, t, mask);
                }
            }
        }
    }

    /// Adds one (`JOIN`) to `c_t` of the cells of `mask` in word `idx`, or takes one away, with
    /// `S₁` and `S₂`.
    #[inline(always)]
    fn count<const JOIN: bool>(&mut self, idx: usize, t: usize, mask: u64) {
        let levels = self.levels;
        if self.counts.len() < t {
            self.counts.push(vec![0; self.words * levels]);
        }
        let count = &mut self.counts[t - 1][idx * levels..(idx + 1) * levels];
        let cells = u64::from(mask.count_ones());
        if JOIN {
            // Σ over the mask's cells of c before the member joins; then c += 1.
            let before = masked_sum(count, mask);
            self.s1 += cells;
            self.s2 += 2 * before + cells;
            let mut carry = mask;
            for level in count.iter_mut() {
                let old = *level;
                *level = old ^ carry;
                carry &= old;
                if carry == 0 {
                    break;
                }
            }
        } else {
            // c −= 1; then Σ over the mask's cells of c after the member left.
            let mut borrow = mask;
            for level in count.iter_mut() {
                let old = *level;
                *level = old ^ borrow;
                borrow &= !old;
                if borrow == 0 {
                    break;
                }
            }
            let after = masked_sum(count, mask);
            self.s1 -= cells;
            self.s2 -= 2 * after + cells;
        }
    }
}

/// `Σ` over the cells of `mask` of the bit-sliced count `levels` (least significant first).
#[inline(always)]
fn masked_sum(levels: &[u64], mask: u64) -> u64 {
    levels.iter().enumerate().map(|(q, &l)| u64::from((l & mask).count_ones()) << q).sum()
}

#[cfg(test)]
mod tests;
