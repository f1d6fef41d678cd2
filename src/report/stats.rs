//! Statistics across runs (what 003 §5.3 says was missing): mean and 95 % confidence interval
//! over seeds, and the Kruskal–Wallis test with its effect size.

use statrs::distribution::{ChiSquared, ContinuousCDF, Normal, StudentsT};

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
pub(crate) fn ranks(values: &[f64]) -> (Vec<f64>, f64) {
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
    // The survival function keeps p-values far below 1e-16, where `1 − cdf` rounds to 0.
    let p_value = ChiSquared::new(df as f64).expect("df > 0").sf(h.max(0.0));
    Some(KruskalWallis { h, df, p_value, epsilon_squared: h / (n - 1.0) })
}

/// `(mean, min, max)` of `values`; NaN mean and infinite bounds for no values.
pub fn mean_min_max(values: &[f64]) -> (f64, f64, f64) {
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (mean, lo, hi)
}

/// Quartiles `(q1, median, q3)` by linear interpolation between order statistics (the
/// usual "type 7" definition); `NaN` for no values.
pub fn quartiles(values: &[f64]) -> (f64, f64, f64) {
    if values.is_empty() {
        return (f64::NAN, f64::NAN, f64::NAN);
    }
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let q = |p: f64| {
        let h = (v.len() - 1) as f64 * p;
        let (lo, hi) = (h.floor() as usize, h.ceil() as usize);
        v[lo] + (h - lo as f64) * (v[hi] - v[lo])
    };
    (q(0.25), q(0.5), q(0.75))
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
    let (n1, n2) = (a.len() as f64, b.len() as f64);
    let n = n1 + n2;
    let r1: f64 = r[..a.len()].iter().sum();
    let u = r1 - n1 * (n1 + 1.0) / 2.0;
    let var = n1 * n2 / 12.0 * ((n + 1.0) - ties / (n * (n - 1.0)));
    if var <= 0.0 {
        return None;
    }
    let z = ((u - n1 * n2 / 2.0).abs() - 0.5).max(0.0) / var.sqrt();
    let p_value = (2.0 * (1.0 - Normal::new(0.0, 1.0).expect("standard normal").cdf(z))).min(1.0);
    Some(MannWhitney { u, z, p_value })
}

/// Holm's step-down adjustment of p-values (family-wise error), in the input order.
pub fn holm(p: &[f64]) -> Vec<f64> {
    let m = p.len();
    let mut order: Vec<usize> = (0..m).collect();
    order.sort_by(|&x, &y| p[x].total_cmp(&p[y]));
    let mut adjusted = vec![0.0; m];
    let mut running: f64 = 0.0;
    for (k, &i) in order.iter().enumerate() {
        running = running.max(((m - k) as f64 * p[i]).min(1.0));
        adjusted[i] = running;
    }
    adjusted
}

/// Vargha–Delaney `A₁₂`: the probability that a value of `a` exceeds one of `b`, ties counting
/// half (0.5 = no effect; 0.56 / 0.64 / 0.71 are the usual small / medium / large thresholds).
pub fn vargha_delaney_a12(a: &[f64], b: &[f64]) -> f64 {
    let mut wins = 0.0;
    for &x in a {
        for &y in b {
            wins += if x > y {
                1.0
            } else if x == y {
                0.5
            } else {
                0.0
            };
        }
    }
    wins / (a.len() * b.len()) as f64
}

/// The usual words for an `A₁₂` (symmetric around 0.5).
pub fn a12_magnitude(a12: f64) -> &'static str {
    let d = (a12 - 0.5).abs();
    if d < 0.06 {
        "negligible"
    } else if d < 0.14 {
        "small"
    } else if d < 0.21 {
        "medium"
    } else {
        "large"
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quartiles_by_hand() {
        assert_eq!(quartiles(&[4.0, 1.0, 3.0, 2.0, 5.0]), (2.0, 3.0, 4.0));
        // n = 4: positions 0.75, 1.5, 2.25.
        assert_eq!(quartiles(&[1.0, 2.0, 3.0, 4.0]), (1.75, 2.5, 3.25));
    }

    #[test]
    fn mann_whitney_by_hand() {
        // a = {1,2,3}, b = {4,5,6}: R1 = 6, U = 0, σ² = 9/12·7 = 5.25, z = (4.5 − 0.5)/√5.25.
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
        // Two against two: R1 = 3, U = 0, σ² = 4/12 · 5, z = (2 − 0.5)/√(5/3).
        let t = mann_whitney_u(&[1.0, 2.0], &[3.0, 4.0]).unwrap();
        assert!((t.z - 1.5 / (5.0f64 / 3.0).sqrt()).abs() < 1e-12, "{}", t.z);
        assert!(mann_whitney_u(&[1.0, 1.0], &[1.0, 1.0]).is_none());
        // With ties: a = {1,2,2}, b = {2,3,3,4}: mid-ranks 1 | 3 3 3 | 5.5 5.5 | 7, R1 = 7,
        // U = 7 − 6 = 1, Σ(t³−t) = 24 + 6 = 30, σ² = 12/12 · (8 − 30/42), z = (5 − 0.5)/σ.
        let t = mann_whitney_u(&[1.0, 2.0, 2.0], &[2.0, 3.0, 3.0, 4.0]).unwrap();
        assert_eq!(t.u, 1.0);
        assert!((t.z - 4.5 / (8.0f64 - 30.0 / 42.0).sqrt()).abs() < 1e-12, "{}", t.z);
    }

    #[test]
    fn holm_and_a12_by_hand() {
        // Sorted 0.01, 0.02, 0.04 → ×3, ×2, ×1 = 0.03, 0.04, 0.04 (monotone).
        let adj = holm(&[0.04, 0.01, 0.02]);
        assert!((adj[0] - 0.04).abs() < 1e-15 && (adj[1] - 0.03).abs() < 1e-15 && (adj[2] - 0.04).abs() < 1e-15);
        assert_eq!(holm(&[0.6, 0.5]), vec![1.0, 1.0]);
        assert_eq!(vargha_delaney_a12(&[3.0, 4.0], &[1.0, 3.0]), 3.5 / 4.0);
        assert_eq!(vargha_delaney_a12(&[1.0], &[2.0]), 0.0);
        // One against two: 2 wins of 1 × 2 pairs.
        assert_eq!(vargha_delaney_a12(&[3.0], &[1.0, 2.0]), 1.0);
        assert_eq!(vargha_delaney_a12(&[3.0, 0.0, 0.0], &[1.0, 2.0]), 2.0 / 6.0);
        // Thresholds 0.06, 0.14, 0.21 of |A − 0.5|, each the lower bound of the next word
        // (0.44 and 0.36 are exactly 0.06 and 0.14 from 0.5 in binary floating point).
        for (a12, word) in [
            (0.5, "negligible"),
            (0.45, "negligible"),
            (0.44, "small"),
            (0.38, "small"),
            (0.36, "medium"),
            (0.64, "medium"),
            (0.65, "medium"),
            (0.2, "large"),
            (0.8, "large"),
        ] {
            assert_eq!(a12_magnitude(a12), word, "{a12}");
        }
    }

    #[test]
    fn confidence_interval_by_hand() {
        // mean 2, s = 1, n = 3: t_{0.975, 2} = 4.302653 → half-width 4.302653/√3.
        let (m, h) = mean_ci95(&[1.0, 2.0, 3.0]);
        assert_eq!(m, 2.0);
        assert!((h - 4.302_652_729_911_275 / 3f64.sqrt()).abs() < 1e-9);
        assert!(mean_ci95(&[5.0]).1.is_nan());
        // Two values: mean 2, s² = 2, t_{0.975, 1} = 12.7062047 → half-width 12.7062047.
        let (m, h) = mean_ci95(&[1.0, 3.0]);
        assert_eq!(m, 2.0);
        assert!((h - 12.706_204_736_174_7).abs() < 1e-6, "{h}");
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
        // {1..100} against {101..200}: H = 12/(200·201)·(5050² + 15050²)/100 − 603 = 149.25,
        // p = erfc(√(H/2)) ≈ 2.6e-34, which `1 − cdf` would round to 0.
        let low: Vec<f64> = (1..=100).map(f64::from).collect();
        let high: Vec<f64> = (101..=200).map(f64::from).collect();
        let kw = kruskal_wallis(&[low, high]).unwrap();
        assert!((kw.h - 149.253_731_343).abs() < 1e-6, "{}", kw.h);
        assert!(kw.p_value > 1e-35 && kw.p_value < 1e-33, "{}", kw.p_value);
    }

    #[test]
    fn sign_test_by_hand() {
        // 10 of 10 above: 2 · 2⁻¹⁰; 8 of 10: 2 · (1 + 10 + 45) / 1024; ties dropped.
        let ten: Vec<f64> = (1..=10).map(f64::from).collect();
        assert!((sign_test(&ten, 0.0).unwrap() - 2.0 / 1024.0).abs() < 1e-15);
        assert!((sign_test(&ten, 2.5).unwrap() - 2.0 * 56.0 / 1024.0).abs() < 1e-15);
        assert!((sign_test(&[1.0, 2.0, 2.0], 2.0).unwrap() - 1.0).abs() < 1e-15);
        assert_eq!(sign_test(&[3.0, 3.0], 3.0), None);
    }
}
