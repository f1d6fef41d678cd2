//! The pair sum of eq. 3.18 kept from one generation to the next (003 §3.2.3).
//!
//! A generation of the Elite families replaces only a few members: in the reference run about
//! 4 % of the population after the first 200 iterations. [`KeptPairSum`] therefore keeps, for
//! every threshold `t`, the number `c_t` of members that visited each cell at least `t` times,
//! and with them `S₁ = Σ_cells Σ_t c_t` and `S₂ = Σ_cells Σ_t c_t²`. The pair sum is
//! `Σ_cells Σ_t c_t(N − c_t) = N·S₁ − S₂` (the identity of [`super::pair_distance_sum_by`]), and
//! a member that joins or leaves changes `S₁` and `S₂` only in the cells it visited, by
//! `(c + 1)² − c² = 2c + 1` per cell and threshold. The counts are bit-sliced like the visit
//! maps, so 64 cells move at once. The result is the exact integer the full pass computes.
//!
//! Members are told apart by their maps' [stamps](VisitPlanes::stamp): equal stamps, equal
//! counts. A member costs about one and a half times as much to add or remove as to read in the
//! full pass, so where more than half the population changed since the previous call (a
//! generation of architecture (a) replaces nearly everyone) the caller makes the full pass
//! instead and the counts are dropped; they are made again once a call finds the population
//! changing little.

use super::{LOW, at_least, thermometer};
use crate::coverage::planes::{VisitPlanes, add_word, remove_word};

/// One member as the sum holds it: a copy of its visit map (needed to take it out again).
#[derive(Default, Debug, Clone)]
struct Kept {
    stamp: u64,
    words: usize,
    planes: usize,
    data: Vec<u64>,
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
    /// Whether the counts hold `members`, the previous call's population.
    valid: bool,
    /// The members counted, by stamp (when `valid`).
    members: Vec<Kept>,
    spare: Vec<Kept>,
    /// The previous call's population's stamps, in order.
    previous: Vec<u64>,
    /// Reused per call: this population's `(stamp, member)` in order, and the changes.
    now: Vec<(u64, usize)>,
    leaving: Vec<usize>,
    joining: Vec<usize>,
}

impl KeptPairSum {
    /// The pair sum of the `n` maps `map(0) … map(n − 1)` from the kept counts, brought from
    /// the previous call's population to this one; `None` when the full pass is cheaper (then
    /// [`super::pair_distance_sum_by`] is the answer). Equals the full pass's sum.
    pub fn update<'a>(&mut self, n: usize, map: impl Fn(usize) -> &'a VisitPlanes) -> Option<u64> {
        self.now.clear();
        self.now.extend((0..n).map(|i| (map(i).stamp(), i)));
        self.now.sort_unstable();
        self.changes();
        let few = 2 * (self.leaving.len() + self.joining.len()) <= n;
        let sum = if !few {
            self.valid = false;
            self.spare.append(&mut self.members);
            None
        } else if self.valid {
            self.apply_changes(map);
            Some(n as u64 * self.s1 - self.s2)
        } else {
            // The counts are made afresh, with every member joining.
            self.spare.append(&mut self.members);
            self.recount(self.levels);
            self.leaving.clear();
            self.joining.clear();
            self.joining.extend(0..n);
            self.apply_changes(map);
            self.valid = true;
            Some(n as u64 * self.s1 - self.s2)
        };
        self.previous.clear();
        self.previous.extend(self.now.iter().map(|&(stamp, _)| stamp));
        sum
    }

    /// `leaving`: the places in `previous` of the stamps not in this population; `joining`:
    /// the members of this population whose stamps were not in `previous` (as multisets).
    fn changes(&mut self) {
        self.leaving.clear();
        self.joining.clear();
        let (mut a, mut b) = (0, 0);
        while a < self.previous.len() || b < self.now.len() {
            match (self.previous.get(a), self.now.get(b)) {
                (Some(x), Some((y, _))) if x == y => (a, b) = (a + 1, b + 1),
                (Some(x), Some((y, _))) if x < y => {
                    self.leaving.push(a);
                    a += 1;
                }
                (_, Some(&(_, i))) => {
                    self.joining.push(i);
                    b += 1;
                }
                (Some(_), None) => {
                    self.leaving.push(a);
                    a += 1;
                }
                (None, None) => unreachable!("the loop runs while one list has more"),
            }
        }
    }

    /// Takes the `leaving` members out of the counts and adds the `joining` ones; the members
    /// then stay in stamp order, as `previous` will.
    fn apply_changes<'a>(&mut self, map: impl Fn(usize) -> &'a VisitPlanes) {
        // `leaving` ascends: the last first, so that the places still to visit stay put.
        for k in (0..self.leaving.len()).rev() {
            let gone = self.members.remove(self.leaving[k]);
            self.apply::<false>(&gone.data, gone.words, gone.planes);
            self.spare.push(gone);
        }
        let n = self.members.len() + self.joining.len();
        if n >= 1 << self.levels {
            self.recount(usize::BITS as usize - n.leading_zeros() as usize);
        }
        for j in 0..self.joining.len() {
            let m = map(self.joining[j]);
            let mut kept = self.spare.pop().unwrap_or_default();
            kept.stamp = m.stamp();
            (kept.words, kept.planes) = (m.plane_words(), m.planes());
            kept.data.clear();
            kept.data.extend_from_slice(m.plane_data());
            self.apply::<true>(&kept.data, kept.words, kept.planes);
            self.members.push(kept);
        }
        self.members.sort_by_key(|m| m.stamp);
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
            // Σ over the mask's cells of c before the member joins; then c += 1 (the counts'
            // planes hold every count up to the population's size: nothing carries out).
            let before = masked_sum(count, mask);
            self.s1 += cells;
            self.s2 += 2 * before + cells;
            let (_, carry) = add_word(count, mask);
            debug_assert_eq!(carry, 0, "a count outgrew its planes");
        } else {
            // c −= 1; then Σ over the mask's cells of c after the member left.
            remove_word(count, mask);
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
