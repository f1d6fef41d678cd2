//! Exact null distributions of rank statistics, by counting: the rank sums of every subset of a
//! given size (the rank-sum test) or of every subset at all (the signed-rank test). Ranks are
//! doubled mid-ranks, whole numbers, so ties are counted exactly; counts are `f64`, exact
//! below 2⁵³, which the callers' size limits keep.

/// `counts[s]`: how many `k`-element subsets of `values` sum to `s`.
pub fn subset_sum_counts(values: &[usize], k: usize) -> Vec<f64> {
    let total: usize = values.iter().sum();
    // ways[j][s], flattened: j chosen so far, sum s.
    let width = total + 1;
    let mut ways = vec![0.0f64; (k + 1) * width];
    ways[0] = 1.0;
    for (seen, &v) in values.iter().enumerate() {
        for j in (1..=k.min(seen + 1)).rev() {
            let (below, here) = ways.split_at_mut(j * width);
            let from = &below[(j - 1) * width..];
            for s in (v..width).rev() {
                here[s] += from[s - v];
            }
        }
    }
    ways[k * width..].to_vec()
}

/// `counts[s]`: how many subsets of `values` (of any size) sum to `s`.
pub fn any_subset_sum_counts(values: &[usize]) -> Vec<f64> {
    let total: usize = values.iter().sum();
    let mut ways = vec![0.0f64; total + 1];
    ways[0] = 1.0;
    for &v in values {
        for s in (v..=total).rev() {
            ways[s] += ways[s - v];
        }
    }
    ways
}

/// Two-sided p-value of `observed` under the distribution `counts` (symmetric, as both of the
/// above are): twice the smaller tail, each tail including `observed`, at most 1.
pub fn two_sided(counts: &[f64], observed: usize) -> f64 {
    let total: f64 = counts.iter().sum();
    let lower: f64 = counts[..=observed.min(counts.len() - 1)].iter().sum();
    let upper: f64 = counts[observed.min(counts.len())..].iter().sum();
    (2.0 * lower.min(upper) / total).min(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_by_hand() {
        // Ranks 1..4 doubled (2, 4, 6, 8), pairs: sums 6, 8, 10, 10, 12, 14.
        let c = subset_sum_counts(&[2, 4, 6, 8], 2);
        let nonzero: Vec<(usize, f64)> = c.iter().copied().enumerate().filter(|&(_, n)| n > 0.0).collect();
        assert_eq!(nonzero, vec![(6, 1.0), (8, 1.0), (10, 2.0), (12, 1.0), (14, 1.0)]);
        // Every subset of {1, 2, 3}: sums 0, 1, 2, 3, 3, 4, 5, 6.
        assert_eq!(any_subset_sum_counts(&[1, 2, 3]), vec![1.0, 1.0, 1.0, 2.0, 1.0, 1.0, 1.0]);
        // The smallest sum of pairs: 2 · 1 / 6.
        assert!((two_sided(&c, 6) - 2.0 / 6.0).abs() < 1e-15);
        // The middle: both tails hold more than half, capped at 1.
        assert_eq!(two_sided(&c, 10), 1.0);
    }
}
