//! Tests of samples paired by seed (the same replicate under two settings), and of one sample
//! against a constant: the sign test and the Wilcoxon signed-rank test.

use super::Method;
use super::describe::ranks;
use super::exact::{any_subset_sum_counts, two_sided};
use statrs::distribution::{ContinuousCDF, Normal};

/// Pairs of at most this many non-zero differences get the exact signed-rank test (2⁵⁰ sign
/// patterns, counted exactly in `f64`); more, the normal approximation.
pub const EXACT_MAX_PAIRS: usize = 50;

/// Two-sided exact sign test of `values` against the constant `c`: ties are dropped, and the
/// p-value is the probability under Binomial(n, ½) of a split at least as uneven as the observed
/// one. `None` when every value ties with `c`.
pub fn sign_test(values: &[f64], c: f64) -> Option<f64> {
    let above = values.iter().filter(|&&v| v > c).count();
    let below = values.iter().filter(|&&v| v < c).count();
    let n = above + below;
    if n == 0 {
        return None;
    }
    let k = above.min(below);
    // Σ_{i ≤ k} C(n, i) / 2^n, in floating point (n is a number of seeds).
    let (mut term, mut tail) = (0.5f64.powi(n as i32), 0.0);
    for i in 0..=k {
        tail += term;
        term *= (n - i) as f64 / (i + 1) as f64;
    }
    Some((2.0 * tail).min(1.0))
}

/// Two-sided exact sign test of pairs: [`sign_test`] of the differences `a[i] − b[i]` against
/// 0 (pairs that tie dropped). `None` when the lengths differ or every pair ties.
pub fn sign_test_paired(a: &[f64], b: &[f64]) -> Option<f64> {
    if a.len() != b.len() {
        return None;
    }
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    sign_test(&d, 0.0)
}

/// Result of [`wilcoxon_signed_rank`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SignedRank {
    /// `W⁺`: the sum of the ranks of `|a[i] − b[i]|` over the pairs where `a` is larger.
    pub w_plus: f64,
    /// Pairs that do not tie (the test's `n`).
    pub pairs: usize,
    /// Two-sided p-value.
    pub p_value: f64,
    /// How the p-value was found.
    pub method: Method,
}

/// Two-sided Wilcoxon signed-rank test of pairs (Wilcoxon 1945): whether the differences
/// `a[i] − b[i]` are symmetric about 0. Pairs that tie are dropped (Wilcoxon's convention,
/// scipy's `zero_method="wilcox"`), the rest ranked by `|difference|` with mid-ranks. Up to
/// [`EXACT_MAX_PAIRS`] pairs, exact: `W⁺` over all 2ⁿ sign patterns, conditional on ties;
/// beyond, `z = (W⁺ − n(n+1)/4) / σ` with `σ² = n(n+1)(2n+1)/24 − Σ(t³−t)/48`, no continuity
/// correction. `None` when the lengths differ, a value is NaN, or every pair ties.
pub fn wilcoxon_signed_rank(a: &[f64], b: &[f64]) -> Option<SignedRank> {
    if a.len() != b.len() || a.iter().chain(b).any(|v| v.is_nan()) {
        return None;
    }
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).filter(|&d| d != 0.0).collect();
    let n = d.len();
    if n == 0 {
        return None;
    }
    let magnitudes: Vec<f64> = d.iter().map(|x| x.abs()).collect();
    let (r, ties) = ranks(&magnitudes);
    let w_plus: f64 = r.iter().zip(&d).filter(|&(_, &x)| x > 0.0).map(|(r, _)| r).sum();
    if n <= EXACT_MAX_PAIRS {
        let doubled: Vec<usize> = r.iter().map(|x| (2.0 * x).round() as usize).collect();
        let observed = (2.0 * w_plus).round() as usize;
        let p_value = two_sided(&any_subset_sum_counts(&doubled), observed);
        return Some(SignedRank { w_plus, pairs: n, p_value, method: Method::Exact });
    }
    let nf = n as f64;
    let var = nf * (nf + 1.0) * (2.0 * nf + 1.0) / 24.0 - ties / 48.0;
    if var <= 0.0 {
        return None;
    }
    let z = (w_plus - nf * (nf + 1.0) / 4.0) / var.sqrt();
    let p_value = (2.0 * Normal::new(0.0, 1.0).expect("standard normal").sf(z.abs())).min(1.0);
    Some(SignedRank { w_plus, pairs: n, p_value, method: Method::Normal })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sign_test_by_hand() {
        // 10 of 10 above: 2 · 2⁻¹⁰; 8 of 10: 2 · (1 + 10 + 45) / 1024; ties dropped.
        let ten: Vec<f64> = (1..=10).map(f64::from).collect();
        assert!((sign_test(&ten, 0.0).unwrap() - 2.0 / 1024.0).abs() < 1e-15);
        assert!((sign_test(&ten, 2.5).unwrap() - 2.0 * 56.0 / 1024.0).abs() < 1e-15);
        assert!((sign_test(&[1.0, 2.0, 2.0], 2.0).unwrap() - 1.0).abs() < 1e-15);
        assert_eq!(sign_test(&[3.0, 3.0], 3.0), None);
    }

    #[test]
    fn signed_rank_by_hand() {
        // Differences 1, 2, 3, −4 (and a tie, dropped): W⁺ = 6 of 10; of the 16 sign patterns,
        // W⁺ ≥ 6 in 7 (sums of subsets of {1,2,3,4}: 0,1,2,3,3,4,4,5,5,6,6,7,7,8,9,10), ≤ 6
        // in 11: p = 2 · 7/16.
        let t = wilcoxon_signed_rank(&[2.0, 4.0, 6.0, 1.0, 3.0], &[1.0, 2.0, 3.0, 5.0, 3.0]).unwrap();
        assert_eq!((t.w_plus, t.pairs, t.method), (6.0, 4, Method::Exact));
        assert_eq!(t.p_value, 14.0 / 16.0);
        // Ten pairs, all a > b: 2 · 2⁻¹⁰, as the sign test.
        let a: Vec<f64> = (1..=10).map(f64::from).collect();
        let zero = vec![0.0; 10];
        let t = wilcoxon_signed_rank(&a, &zero).unwrap();
        assert_eq!(t.w_plus, 55.0);
        assert!((t.p_value - 2.0 / 1024.0).abs() < 1e-15);
        assert_eq!(sign_test_paired(&a, &zero), Some(2.0 / 1024.0));
        assert!(wilcoxon_signed_rank(&a, &a).is_none());
        assert!(wilcoxon_signed_rank(&a, &zero[..3]).is_none());
        // 60 pairs: the normal approximation, symmetric in the order of the samples.
        let big: Vec<f64> = (0..60).map(|i| f64::from(i % 7) - 2.5).collect();
        let t = wilcoxon_signed_rank(&big, &vec![0.0; 60]).unwrap();
        let back = wilcoxon_signed_rank(&vec![0.0; 60], &big).unwrap();
        assert_eq!(t.method, Method::Normal);
        assert!((t.p_value - back.p_value).abs() < 1e-15 && t.p_value > 0.0 && t.p_value < 1.0);
    }
}
