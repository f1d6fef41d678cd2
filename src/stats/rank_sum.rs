//! The Mann–Whitney U (Wilcoxon rank-sum) test of two independent samples.

use super::Method;
use super::describe::ranks;
use super::exact::{subset_sum_counts, two_sided};
use statrs::distribution::{ContinuousCDF, Normal};

/// Samples of at most this many values in all get the exact test of [`mann_whitney`]; larger
/// ones the normal approximation (its counts stay exact in `f64`: C(50, 25) < 2⁵³).
pub const EXACT_MAX_N: usize = 50;

/// Result of [`mann_whitney`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RankSum {
    /// `U` of the first sample, `R₁ − n₁(n₁+1)/2`: the pairs `(a, b)` with `a > b`, ties half.
    pub u: f64,
    /// Two-sided p-value.
    pub p_value: f64,
    /// How the p-value was found.
    pub method: Method,
}

/// Two-sided Mann–Whitney U test of whether `a` and `b` come from one distribution (Mann and
/// Whitney 1947). Up to [`EXACT_MAX_N`] values in all the p-value is exact: the distribution of
/// the first sample's rank sum over every way to split the pooled mid-ranks (so ties are
/// handled, conditionally on them; without ties it is the classical exact test), two-sided as
/// twice the smaller tail, at most 1. Beyond, [`mann_whitney_u`]'s normal approximation.
/// `None` for an empty sample, a NaN, or when every value is tied.
pub fn mann_whitney(a: &[f64], b: &[f64]) -> Option<RankSum> {
    if a.is_empty() || b.is_empty() || a.iter().chain(b).any(|v| v.is_nan()) {
        return None;
    }
    let all: Vec<f64> = a.iter().chain(b).copied().collect();
    let (r, ties) = ranks(&all);
    let n = all.len() as f64;
    if ties == n * n * n - n {
        return None;
    }
    let n1 = a.len() as f64;
    let u = r[..a.len()].iter().sum::<f64>() - n1 * (n1 + 1.0) / 2.0;
    if all.len() > EXACT_MAX_N {
        let t = mann_whitney_normal(a.len(), b.len(), u, ties)?;
        return Some(RankSum { u, p_value: t.p_value, method: Method::Normal });
    }
    // Mid-ranks are whole or half numbers: doubled, they are whole.
    let doubled: Vec<usize> = r.iter().map(|x| (2.0 * x).round() as usize).collect();
    let observed: usize = doubled[..a.len()].iter().sum();
    let counts = subset_sum_counts(&doubled, a.len());
    Some(RankSum { u, p_value: two_sided(&counts, observed), method: Method::Exact })
}

/// Result of a two-sided Mann–Whitney U test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MannWhitney {
    /// `U` of the first sample: `R_1 − n_1(n_1+1)/2`.
    pub u: f64,
    /// The standardised statistic (continuity- and tie-corrected).
    pub z: f64,
    /// Two-sided p-value from the normal approximation.
    pub p_value: f64,
}

/// Two-sided Mann–Whitney U test of whether `a` and `b` come from one distribution, with the
/// normal approximation `z = (|U − n₁n₂/2| − ½) / σ`,
/// `σ² = n₁n₂/12 · ((N+1) − Σ(t³−t)/(N(N−1)))`. `None` when a sample has fewer than two
/// values or every value is tied.
pub fn mann_whitney_u(a: &[f64], b: &[f64]) -> Option<MannWhitney> {
    if a.len() < 2 || b.len() < 2 {
        return None;
    }
    let all: Vec<f64> = a.iter().chain(b).copied().collect();
    let (r, ties) = ranks(&all);
    let n1 = a.len() as f64;
    let u = r[..a.len()].iter().sum::<f64>() - n1 * (n1 + 1.0) / 2.0;
    mann_whitney_normal(a.len(), b.len(), u, ties)
}

/// The normal approximation of [`mann_whitney_u`] for sizes `n1`, `n2`, statistic `u` and the
/// ties' `Σ(t³ − t)`.
fn mann_whitney_normal(n1: usize, n2: usize, u: f64, ties: f64) -> Option<MannWhitney> {
    let (n1, n2) = (n1 as f64, n2 as f64);
    let n = n1 + n2;
    let var = n1 * n2 / 12.0 * ((n + 1.0) - ties / (n * (n - 1.0)));
    if var <= 0.0 {
        return None;
    }
    let z = ((u - n1 * n2 / 2.0).abs() - 0.5).max(0.0) / var.sqrt();
    let p_value = (2.0 * (1.0 - Normal::new(0.0, 1.0).expect("standard normal").cdf(z))).min(1.0);
    Some(MannWhitney { u, z, p_value })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mann_whitney_by_hand() {
        // a = {1,2,3}, b = {4,5,6}: R_a = 6, U = 0, σ² = 9/12·7 = 5.25, z = (4.5 − 0.5)/√5.25.
        let t = mann_whitney_u(&[1.0, 2.0, 3.0], &[4.0, 5.0, 6.0]).unwrap();
        assert_eq!(t.u, 0.0);
        assert!((t.z - 4.0 / 5.25f64.sqrt()).abs() < 1e-12);
        assert!((t.p_value - 0.080_855_598).abs() < 1e-8, "{}", t.p_value);
        // Symmetric in the p-value; U of the other side is n1 n2 − U.
        let back = mann_whitney_u(&[4.0, 5.0, 6.0], &[1.0, 2.0, 3.0]).unwrap();
        assert_eq!(back.u, 9.0);
        assert!((back.p_value - t.p_value).abs() < 1e-15);
        assert!(mann_whitney_u(&[1.0], &[2.0, 3.0]).is_none());
        assert!(mann_whitney_u(&[2.0, 3.0], &[1.0]).is_none());
        assert!(mann_whitney_u(&[2.0, 3.0], &[]).is_none());
        // Unequal sizes, two values each side allowed: a = {1,2,3}, b = {4,5,6,7}: U = 0,
        // n1 n2 / 2 = 6, σ² = 12/12 · 8 = 8, z = (6 − 0.5)/√8.
        let t = mann_whitney_u(&[1.0, 2.0, 3.0], &[4.0, 5.0, 6.0, 7.0]).unwrap();
        assert_eq!(t.u, 0.0);
        assert!((t.z - 5.5 / 8f64.sqrt()).abs() < 1e-12, "{}", t.z);
        // Two against two: R_a = 3, U = 0, σ² = 4/12 · 5, z = (2 − 0.5)/√(5/3).
        let t = mann_whitney_u(&[1.0, 2.0], &[3.0, 4.0]).unwrap();
        assert!((t.z - 1.5 / (5.0f64 / 3.0).sqrt()).abs() < 1e-12, "{}", t.z);
        assert!(mann_whitney_u(&[1.0, 1.0], &[1.0, 1.0]).is_none());
        // With ties: a = {1,2,2}, b = {2,3,3,4}: mid-ranks 1 | 3 3 3 | 5.5 5.5 | 7, R_a = 7,
        // U = 7 − 6 = 1, Σ(t³−t) = 24 + 6 = 30, σ² = 12/12 · (8 − 30/42), z = (5 − 0.5)/σ.
        let t = mann_whitney_u(&[1.0, 2.0, 2.0], &[2.0, 3.0, 3.0, 4.0]).unwrap();
        assert_eq!(t.u, 1.0);
        assert!((t.z - 4.5 / (8.0f64 - 30.0 / 42.0).sqrt()).abs() < 1e-12, "{}", t.z);
    }
}
