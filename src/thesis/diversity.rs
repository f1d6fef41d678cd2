//! Population diversity from visit-count maps (003 §3.2.3, eqs. 3.17–3.19; thesis-ga §5, R11).
//!
//! `Dist(M¹, M²) = Σ_cells |M¹ − M²|` (eq. 3.17); `Div` is its mean over unordered pairs.
//! The pair sum is accumulated cell by cell without forming pairs: for one cell,
//! `Σ_{i<j} |a_i − a_j| = Σ_{t≥1} c_t·(N − c_t)` with `c_t` the number of individuals that
//! visited the cell at least `t` times, so the cost is one pass over every individual's
//! visited cells.

use super::individual::Individual;
use super::lanes::lane_count_sums;
use crate::coverage::planes::VisitPlanes;
use rayon::prelude::*;

mod kept;
pub use kept::KeptPairSum;

/// Visit counts whose thresholds are listed without a branch per mask (four count planes).
const LOW: usize = 15;

/// Reusable buffers for [`pair_distance_sum`]: the masks "visited at least `t` times" of the
/// current word, one list per `t`.
#[derive(Default, Debug)]
pub struct DiversityScratch {
    /// `low[(t − 1)·N ..]`: the individuals' non-empty masks of cells visited `≥ t` times,
    /// for `t ≤ LOW`.
    low: Vec<u64>,
    /// `high[t − LOW − 1]`: the same for `t > LOW`.
    high: Vec<Vec<u64>>,
    /// The pair sums kept from call to call, one per channel ([`kept_pair_distance_sum`]).
    kept: Vec<KeptPairSum>,
}

/// `Σ_{i<j} Dist(M^i, M^j)` over the population (eqs. 3.17–3.18), updated from the members
/// that changed since the previous call with the same `scratch` ([`kept_pair_distance_sum`]).
pub fn pair_distance_sum(pop: &[Individual], scratch: &mut DiversityScratch) -> u64 {
    kept_pair_distance_sum(pop.len(), |i| &pop[i].visits, scratch, 0)
}

/// [`pair_distance_sum_by`], kept in `scratch` under `channel` from one call to the next: only
/// the maps that were not in the previous call's population (of the same channel) are read
/// cell by cell ([`KeptPairSum`]); where more than half the population changed, the full pass
/// is made. A caller with several populations at once (a fleet's robots) gives each its own
/// channel.
pub fn kept_pair_distance_sum<'a>(
    n: usize,
    map: impl Fn(usize) -> &'a VisitPlanes,
    scratch: &mut DiversityScratch,
    channel: usize,
) -> u64 {
    if scratch.kept.len() <= channel {
        scratch.kept.resize_with(channel + 1, KeptPairSum::default);
    }
    match scratch.kept[channel].update(n, &map) {
        Some(sum) => sum,
        None => pair_distance_sum_by(n, map, scratch),
    }
}

/// `Σ_{i<j} Dist(M^i, M^j)` over `n` visit maps, the `i`-th given by `map(i)`, in one pass
/// over every map (eqs. 3.17–3.18); the reference of [`kept_pair_distance_sum`].
///
/// For one cell, `Σ_{i<j} |a_i − a_j| = Σ_{t≥1} c_t·(N − c_t)` with `c_t` the number of
/// individuals that visited it at least `t` times. The visit maps are bit-sliced, so for 64
/// cells at once the individuals' masks "at least `t` visits" (`t = 1, 2, …` until one is
/// empty) are counted lane by lane ([`lane_count_sums`]), and `Σ c_t(N − c_t) = N·Σc_t − Σc_t²`
/// is read off the counts.
pub fn pair_distance_sum_by<'a>(
    n: usize,
    map: impl Fn(usize) -> &'a VisitPlanes,
    scratch: &mut DiversityScratch,
) -> u64 {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("popcnt") {
        // SAFETY: the CPU has just been found to support `popcnt`.
        return unsafe { pair_distance_sum_popcnt(n, map, scratch) };
    }
    pair_distance_sum_kernel(n, map, scratch)
}

/// The kernel compiled with the `popcnt` instruction, which the default x86-64 target lacks
/// (its software population count is most of the kernel's time); the result is the same.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "popcnt")]
unsafe fn pair_distance_sum_popcnt<'a>(
    n: usize,
    map: impl Fn(usize) -> &'a VisitPlanes,
    scratch: &mut DiversityScratch,
) -> u64 {
    pair_distance_sum_kernel(n, map, scratch)
}

/// Asks for the cache line of `word` ahead of its use: the kernel reads one word of every
/// individual in turn, a pattern the hardware prefetcher does not follow.
#[inline(always)]
fn prefetch(word: &u64) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch is only a hint; the address is that of a live reference.
    unsafe {
        std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>((word as *const u64).cast());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = word;
}

/// The cells of one word visited at least `t` times, from the word's count planes `pl`
/// (least significant first): a bit-sliced comparison from the most significant plane down.
/// Only the low `pl.len()` bits of `t` are read: `t` must be below `2^pl.len()`.
#[inline(always)]
fn at_least(pl: &[u64], t: usize) -> u64 {
    let (mut below, mut equal) = (0u64, u64::MAX);
    for (p, &v) in pl.iter().enumerate().rev() {
        if (t >> p) & 1 == 1 {
            below |= equal & !v;
            equal &= v;
        } else {
            equal &= !v;
        }
    }
    !below
}

/// `th[t]` = the cells visited at least `t` times, for every `t < 2^planes` (at most four
/// planes), built plane by plane: with plane `k` added, a count reaches `t < 2^k` if it did
/// before or has bit `k`, reaches `2^k` if it has bit `k`, and `2^k + t` if both.
#[inline(always)]
fn thermometer(pl: &[u64], th: &mut [u64; LOW + 1]) {
    for (k, &b) in pl.iter().enumerate() {
        let half = 1 << k;
        for t in 1..half {
            th[t + half] = b & th[t];
            th[t] |= b;
        }
        th[half] = b;
    }
}

/// Every eighth word, asks for the planes of the eight words eight ahead (`top` cache lines
/// of a map's word-major planes, `w` words of `top` planes). Reads nothing; which words it
/// names changes only how long the reads wait.
#[inline(always)]
fn prefetch_ahead(data: &[u64], w: usize, top: usize, idx: usize) {
    if idx.is_multiple_of(8) && idx + 8 < w {
        for line in 0..top {
            if let Some(word) = data.get((idx + 8) * top + line * 8) {
                prefetch(word);
            }
        }
    }
}

#[inline(always)]
fn pair_distance_sum_kernel<'a>(
    n: usize,
    map: impl Fn(usize) -> &'a VisitPlanes,
    scratch: &mut DiversityScratch,
) -> u64 {
    let mut maps: Vec<(&[u64], usize, usize)> =
        (0..n).map(&map).map(|m| (m.plane_data(), m.plane_words(), m.planes())).collect();
    // By number of planes: the number of thresholds listed per word is then predictable.
    maps.sort_by_key(|m| m.2);
    let words = maps.iter().map(|m| m.1).max().unwrap_or(0);
    if n < 2 || words == 0 {
        return 0;
    }
    if scratch.low.len() < LOW * n {
        scratch.low.resize(LOW * n, 0);
    }
    let (low, high) = (&mut scratch.low[..LOW * n], &mut scratch.high);
    let mut sum = 0u64;
    let mut pl = [0u64; 32];
    let mut th = [0u64; LOW + 1];
    for idx in 0..words {
        let mut lens = [0usize; LOW];
        let mut high_max = 0usize;
        for &(data, w, top) in &maps {
            if idx >= w {
                continue;
            }
            prefetch_ahead(data, w, top, idx);
            let mut occupied = 0;
            for (v, &word) in pl[..top].iter_mut().zip(&data[idx * top..(idx + 1) * top]) {
                *v = word;
                occupied |= word;
            }
            if occupied == 0 {
                continue;
            }
            let pl = &pl[..top];
            let listed = if top <= 4 {
                thermometer(pl, &mut th);
                (1 << top) - 1
            } else {
                for (t, m) in th.iter_mut().enumerate().skip(1) {
                    *m = at_least(pl, t);
                }
                LOW
            };
            for t in 1..=listed {
                let mask = th[t];
                low[(t - 1) * n + lens[t - 1]] = mask;
                lens[t - 1] += usize::from(mask != 0);
            }
            if top > 4 {
                // `at_least` reads only the low `top` bits of `t`: stop below `2^top`.
                for t in LOW + 1..1 << top {
                    let mask = at_least(pl, t);
                    if mask == 0 {
                        break;
                    }
                    let h = t - LOW;
                    if h > high_max {
                        high_max = h;
                        if high.len() < h {
                            high.push(Vec::new());
                        }
                        high[h - 1].clear();
                    }
                    high[h - 1].push(mask);
                }
            }
        }
        sum += word_pair_sum(n, low, &lens, &high[..high_max]);
    }
    sum
}

/// One word's share of the pair distances: for each visit threshold, the masks of the
/// individuals that reach it (`low`, `lens` per threshold up to `LOW`; `high` above it).
#[inline(always)]
fn word_pair_sum(n: usize, low: &[u64], lens: &[usize; LOW], high: &[Vec<u64>]) -> u64 {
    let mut sum = 0u64;
    // Fewer individuals reach each next threshold: the lists shrink with `t`.
    for (t, &len) in lens.iter().enumerate().take_while(|(_, len)| **len > 0) {
        let (s1, s2) = lane_count_sums(&low[t * n..t * n + len]);
        sum += n as u64 * s1 - s2;
    }
    for list in high {
        let (s1, s2) = lane_count_sums(list);
        sum += n as u64 * s1 - s2;
    }
    sum
}

fn slots(pop: &[Individual]) -> usize {
    pop.iter().map(|i| i.visits.cell_slots()).max().unwrap_or(0)
}

/// `Div = 2/(N(N−1)) Σ_{i<j} D_ij`: the mean distance over unordered pairs (R11).
pub fn diversity(pop: &[Individual], scratch: &mut DiversityScratch) -> f64 {
    let n = pop.len() as f64;
    if pop.len() < 2 {
        return 0.0;
    }
    2.0 * pair_distance_sum(pop, scratch) as f64 / (n * (n - 1.0))
}

/// `Dist(M^a, M^b)` (eq. 3.17) with a dense buffer holding `a`'s counts.
fn distance_to_dense(dense_a: &[u32], sum_a: u64, b: &VisitPlanes) -> u64 {
    let (mut sum_b, mut common) = (0u64, 0u64);
    b.for_each_count(|c, k| {
        sum_b += u64::from(k);
        common += u64::from(dense_a[c as usize].min(k));
    });
    sum_a + sum_b - 2 * common
}

fn dense_of(ind: &Individual, dense: &mut [u32]) -> u64 {
    dense_of_map(&ind.visits, dense)
}

fn dense_of_map(visits: &VisitPlanes, dense: &mut [u32]) -> u64 {
    let mut s = 0;
    visits.for_each_count(|c, k| {
        dense[c as usize] = k;
        s += u64::from(k);
    });
    s
}

/// `Dist` of one pair (eq. 3.17).
pub fn distance(a: &Individual, b: &Individual) -> u64 {
    let mut dense = vec![0u32; a.visits.cell_slots().max(b.visits.cell_slots())];
    let sa = dense_of(a, &mut dense);
    distance_to_dense(&dense, sa, &b.visits)
}

/// `Div_max = max_{i,j} D_ij` over the population (thesis-ga §12.2); `O(N²)` sparse merges, in
/// parallel. Only the adaptive parameter control needs it.
pub fn max_distance(pop: &[Individual]) -> u64 {
    max_distance_by(pop.len(), 1, |i, _| &pop[i].visits)
}

/// `Div_max` of `n` members made of `parts` visit maps each (`map(i, part)`), the distance of
/// two members being the sum of their parts' distances (eq. 3.17 over the parts' cells).
pub fn max_distance_by<'a>(n: usize, parts: usize, map: impl Fn(usize, usize) -> &'a VisitPlanes + Sync) -> u64 {
    let cells = (0..n).flat_map(|i| (0..parts).map(move |k| (i, k))).map(|(i, k)| map(i, k).cell_slots()).max();
    let cells = cells.unwrap_or(0);
    (0..n)
        .into_par_iter()
        .map_init(
            || (vec![0u32; cells], vec![0u64; n]),
            |(dense, sums), i| {
                sums[i + 1..].fill(0);
                for k in 0..parts {
                    let a = map(i, k);
                    let sa = dense_of_map(a, dense);
                    for (j, s) in sums.iter_mut().enumerate().skip(i + 1) {
                        *s += distance_to_dense(dense, sa, map(j, k));
                    }
                    a.for_each_count(|c, _| dense[c as usize] = 0);
                }
                sums[i + 1..].iter().copied().max().unwrap_or(0)
            },
        )
        .max()
        .unwrap_or(0)
}

/// The printed eq. 3.19, `2/(N(N+1)) Σ_{i=1}^{N} Σ_{j=i}^{N−1} D_ij`, which counts the zero
/// diagonal in the normaliser and leaves out the last column (kept for comparison, R11).
pub fn diversity_literal(pop: &[Individual], scratch: &mut DiversityScratch) -> f64 {
    let n = pop.len();
    if n < 2 {
        return 0.0;
    }
    let all = pair_distance_sum(pop, scratch);
    let mut dense = vec![0u32; slots(pop)];
    let last = &pop[n - 1];
    let s_last = dense_of(last, &mut dense);
    let with_last: u64 = pop[..n - 1].iter().map(|b| distance_to_dense(&dense, s_last, &b.visits)).sum();
    let nf = n as f64;
    2.0 * (all - with_last) as f64 / (nf * (nf + 1.0))
}

#[cfg(test)]
mod tests;
