//! Statistics across runs (what 003 §5.3 says was missing): mean and 95 % confidence interval
//! over seeds, and the Kruskal–Wallis test with its effect size.

use statrs::distribution::{ChiSquared, ContinuousCDF, StudentsT};

/// Mean and the half-width of its 95 % confidence interval (Student's t, `n − 1` degrees of
/// freedom); the half-width is `NaN` for fewer than two values.
pub fn mean_ci95(values: &[f64]) -> (f64, f64) {
    let n = values.len();
    if n == 0 {
        return (f64::NAN, f64::NAN);
    }
    let mean = values.iter().sum::<f64>() / n as f64;
    if n < 2 {
        return (mean, f64::NAN);
    }
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n as f64 - 1.0);
    let t = StudentsT::new(0.0, 1.0, n as f64 - 1.0).expect("n > 1").inverse_cdf(0.975);
    (mean, t * (var / n as f64).sqrt())
}

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

/// Mid-ranks (1-based) of `values`, ties sharing the mean rank; also `Σ (t³ − t)` over ties.
fn ranks(values: &[f64]) -> (Vec<f64>, f64) {
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    let mut r = vec![0.0; values.len()];
    let mut ties = 0.0;
    let mut k = 0;
    while k < order.len() {
        let mut end = k + 1;
        while end < order.len() && values[order[end]] == values[order[k]] {
            end += 1;
        }
        let mid = (k + 1 + end) as f64 / 2.0;
        for &i in &order[k..end] {
            r[i] = mid;
        }
        let t = (end - k) as f64;
        ties += t * t * t - t;
        k = end;
    }
    (r, ties)
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
    let p_value = 1.0 - ChiSquared::new(df as f64).expect("df > 0").cdf(h.max(0.0));
    Some(KruskalWallis { h, df, p_value, epsilon_squared: h / (n - 1.0) })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn confidence_interval_by_hand() {
        // mean 2, s = 1, n = 3: t_{0.975, 2} = 4.302653 → half-width 4.302653/√3.
        let (m, h) = mean_ci95(&[1.0, 2.0, 3.0]);
        assert_eq!(m, 2.0);
        assert!((h - 4.302_652_729_911_275 / 3f64.sqrt()).abs() < 1e-9);
        assert!(mean_ci95(&[5.0]).1.is_nan());
    }

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
    }
}
