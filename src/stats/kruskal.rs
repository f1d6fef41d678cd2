//! The Kruskal–Wallis test of k independent groups, with its effect size.

use super::describe::ranks;
use statrs::distribution::{ChiSquared, ContinuousCDF};

/// Result of a Kruskal–Wallis test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KruskalWallis {
    /// The tie-corrected statistic `H`.
    pub h: f64,
    /// Degrees of freedom `k − 1`.
    pub df: usize,
    /// `P(χ²_{k−1} ≥ H)`.
    pub p_value: f64,
    /// Effect size `ε² = H / (N − 1)`.
    pub epsilon_squared: f64,
}

/// Kruskal–Wallis H test of whether the groups come from one distribution:
/// `H = 12/(N(N+1)) Σ R_i²/n_i − 3(N+1)`, divided by `1 − Σ(t³−t)/(N³−N)` for ties.
/// `None` with fewer than two non-empty groups or when every value is tied.
pub fn kruskal_wallis(groups: &[Vec<f64>]) -> Option<KruskalWallis> {
    let groups: Vec<&Vec<f64>> = groups.iter().filter(|g| !g.is_empty()).collect();
    if groups.len() < 2 {
        return None;
    }
    let all: Vec<f64> = groups.iter().flat_map(|g| g.iter().copied()).collect();
    let n = all.len() as f64;
    let (r, ties) = ranks(&all);
    let correction = 1.0 - ties / (n * n * n - n);
    if correction <= 0.0 {
        return None;
    }
    let mut offset = 0;
    let mut sum = 0.0;
    for g in &groups {
        let rs: f64 = r[offset..offset + g.len()].iter().sum();
        sum += rs * rs / g.len() as f64;
        offset += g.len();
    }
    let h = (12.0 / (n * (n + 1.0)) * sum - 3.0 * (n + 1.0)) / correction;
    let df = groups.len() - 1;
    // The survival function keeps p-values far below 1e-16, where `1 − cdf` rounds to 0.
    let p_value = ChiSquared::new(df as f64).expect("df > 0").sf(h.max(0.0));
    Some(KruskalWallis { h, df, p_value, epsilon_squared: h / (n - 1.0) })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kruskal_wallis_by_hand() {
        // Groups {1,2,3}, {4,5,6}: rank sums 6 and 15, N = 6:
        // H = 12/42·(36/3 + 225/3) − 21 = 3.857142…, df 1, p = 0.04953.
        let kw = kruskal_wallis(&[vec![1.0, 2.0, 3.0], vec![4.0, 5.0, 6.0]]).unwrap();
        assert!((kw.h - 27.0 / 7.0).abs() < 1e-12);
        assert_eq!(kw.df, 1);
        assert!((kw.p_value - 0.049_534_613).abs() < 1e-6, "{}", kw.p_value);
        assert!((kw.epsilon_squared - 27.0 / 35.0).abs() < 1e-12);
        // Ties: {1,1,2}, {2,3,3} — mid-ranks 1.5,1.5,3.5 | 3.5,5.5,5.5.
        let kw = kruskal_wallis(&[vec![1.0, 1.0, 2.0], vec![2.0, 3.0, 3.0]]).unwrap();
        let raw = 12.0 / 42.0 * (6.5f64.powi(2) / 3.0 + 14.5f64.powi(2) / 3.0) - 21.0;
        assert!((kw.h - raw / (1.0 - 18.0 / 210.0)).abs() < 1e-12);
        assert!(kruskal_wallis(&[vec![1.0, 1.0], vec![1.0]]).is_none());
        assert!(kruskal_wallis(&[vec![1.0, 2.0]]).is_none());
        // {1..100} against {101..200}: H = 12/(200·201)·(5050² + 15050²)/100 − 603 = 149.25,
        // p = erfc(√(H/2)) ≈ 2.6e-34, which `1 − cdf` would round to 0.
        let low: Vec<f64> = (1..=100).map(f64::from).collect();
        let high: Vec<f64> = (101..=200).map(f64::from).collect();
        let kw = kruskal_wallis(&[low, high]).unwrap();
        assert!((kw.h - 149.253_731_343).abs() < 1e-6, "{}", kw.h);
        assert!(kw.p_value > 1e-35 && kw.p_value < 1e-33, "{}", kw.p_value);
    }
}
