//! Population diversity from visit-count maps (003 §3.2.3, eqs. 3.17–3.19; spec §5, R11).
//!
//! `Dist(M¹, M²) = Σ_cells |M¹ − M²|` (eq. 3.17); `Div` is its mean over unordered pairs.
//! The pair sum is accumulated cell by cell without forming pairs: for one cell,
//! `Σ_{i<j} |a_i − a_j| = Σ_{t≥1} c_t·(N − c_t)` with `c_t` the number of individuals that
//! visited the cell at least `t` times, so the cost is one pass over every individual's
//! visited cells.

use super::individual::Individual;
use rayon::prelude::*;

/// Reusable buffers for [`pair_distance_sum`].
#[derive(Default, Debug)]
pub struct DiversityScratch {
    /// `hist[k·cells + c]`: individuals that visited cell `c` exactly `k` times (row 0 unused).
    hist: Vec<u32>,
    /// Running `c_t` per cell while `t` descends.
    at_least: Vec<u32>,
}

/// `Σ_{i<j} Dist(M^i, M^j)` over the population (eqs. 3.17–3.18). The histogram is laid out
/// count-major, so the common small counts stay in a few compact rows.
pub fn pair_distance_sum(pop: &[Individual], cells: usize, scratch: &mut DiversityScratch) -> u64 {
    let n = pop.len() as u64;
    let top = pop.iter().flat_map(|i| i.counts.iter().map(|&(_, k)| k)).max().unwrap_or(0) as usize;
    if top == 0 || n < 2 {
        return 0;
    }
    let DiversityScratch { hist, at_least } = scratch;
    hist.clear();
    hist.resize((top + 1) * cells, 0);
    at_least.clear();
    at_least.resize(cells, 0);
    for ind in pop {
        for &(c, k) in &ind.counts {
            hist[k as usize * cells + c as usize] += 1;
        }
    }
    let mut sum = 0u64;
    for t in (1..=top).rev() {
        let row = &hist[t * cells..(t + 1) * cells];
        for (acc, &h) in at_least.iter_mut().zip(row) {
            *acc += h;
            let c = u64::from(*acc);
            sum += c * (n - c);
        }
    }
    sum
}

/// `Div = 2/(N(N−1)) Σ_{i<j} D_ij`: the mean distance over unordered pairs (R11).
pub fn diversity(pop: &[Individual], cells: usize, scratch: &mut DiversityScratch) -> f64 {
    let n = pop.len() as f64;
    if pop.len() < 2 {
        return 0.0;
    }
    2.0 * pair_distance_sum(pop, cells, scratch) as f64 / (n * (n - 1.0))
}

/// `Dist(M^a, M^b)` (eq. 3.17) with a dense buffer holding `a`'s counts.
fn distance_to_dense(dense_a: &[u32], sum_a: u64, b: &Individual) -> u64 {
    let sum_b: u64 = b.counts.iter().map(|&(_, k)| u64::from(k)).sum();
    let common: u64 = b.counts.iter().map(|&(c, k)| u64::from(dense_a[c as usize].min(k))).sum();
    sum_a + sum_b - 2 * common
}

fn dense_of(ind: &Individual, dense: &mut [u32]) -> u64 {
    let mut s = 0;
    for &(c, k) in &ind.counts {
        dense[c as usize] = k;
        s += u64::from(k);
    }
    s
}

fn clear_dense(ind: &Individual, dense: &mut [u32]) {
    for &(c, _) in &ind.counts {
        dense[c as usize] = 0;
    }
}

/// `Dist` of one pair (eq. 3.17).
pub fn distance(a: &Individual, b: &Individual, cells: usize) -> u64 {
    let mut dense = vec![0u32; cells];
    let sa = dense_of(a, &mut dense);
    distance_to_dense(&dense, sa, b)
}

/// `Div_max = max_{i,j} D_ij` over the population (spec §12.2); `O(N²)` sparse merges, in
/// parallel. Only the adaptive parameter control needs it.
pub fn max_distance(pop: &[Individual], cells: usize) -> u64 {
    (0..pop.len())
        .into_par_iter()
        .map_init(
            || vec![0u32; cells],
            |dense, i| {
                let sa = dense_of(&pop[i], dense);
                let m = pop[i + 1..].iter().map(|b| distance_to_dense(dense, sa, b)).max().unwrap_or(0);
                clear_dense(&pop[i], dense);
                m
            },
        )
        .max()
        .unwrap_or(0)
}

/// The printed eq. 3.19, `2/(N(N+1)) Σ_{i=1}^{N} Σ_{j=i}^{N−1} D_ij`, which counts the zero
/// diagonal in the normaliser and leaves out the last column (kept for comparison, R11).
pub fn diversity_literal(pop: &[Individual], cells: usize, scratch: &mut DiversityScratch) -> f64 {
    let n = pop.len();
    if n < 2 {
        return 0.0;
    }
    let all = pair_distance_sum(pop, cells, scratch);
    let mut dense = vec![0u32; cells];
    let last = &pop[n - 1];
    let s_last = dense_of(last, &mut dense);
    let with_last: u64 = pop[..n - 1].iter().map(|b| distance_to_dense(&dense, s_last, b)).sum();
    let nf = n as f64;
    2.0 * (all - with_last) as f64 / (nf * (nf + 1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ind(counts: &[(u32, u32)]) -> Individual {
        Individual { counts: counts.to_vec(), ..Default::default() }
    }

    #[test]
    fn hand_computed_distances() {
        // Maps over 4 cells: a = [1,2,0,0], b = [0,1,3,0], c = [1,0,0,1].
        let a = ind(&[(0, 1), (1, 2)]);
        let b = ind(&[(1, 1), (2, 3)]);
        let c = ind(&[(0, 1), (3, 1)]);
        assert_eq!(distance(&a, &b, 4), 1 + 1 + 3);
        assert_eq!(distance(&a, &c, 4), 2 + 1);
        assert_eq!(distance(&b, &c, 4), 1 + 1 + 3 + 1);
        let pop = vec![a, b, c];
        let mut s = DiversityScratch::default();
        assert_eq!(pair_distance_sum(&pop, 4, &mut s), 5 + 3 + 6);
        assert!((diversity(&pop, 4, &mut s) - 14.0 / 3.0).abs() < 1e-12);
        assert_eq!(max_distance(&pop, 4), 6);
        // Literal eq. 3.19: pairs without the last individual: D_ab = 5; 2·5/(3·4).
        assert!((diversity_literal(&pop, 4, &mut s) - 10.0 / 12.0).abs() < 1e-12);
    }

    #[test]
    fn identical_maps_have_zero_diversity() {
        let pop = vec![ind(&[(0, 2), (5, 1)]); 4];
        assert_eq!(diversity(&pop, 6, &mut DiversityScratch::default()), 0.0);
    }
}
