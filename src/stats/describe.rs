//! Descriptive statistics of a sample: mean with its confidence interval, range, quartiles,
//! the mid-ranks every rank test shares, and Spearman's rank correlation of two.

use statrs::distribution::{ContinuousCDF, StudentsT};

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

/// Mid-ranks (1-based) of `values`, ties sharing the mean rank; also `Σ (t³ − t)` over ties.
pub fn ranks(values: &[f64]) -> (Vec<f64>, f64) {
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

/// Spearman's rank correlation of paired samples: Pearson's correlation of their mid-ranks
/// (ties share a rank); `None` for fewer than two pairs or a constant sample.
pub fn spearman(a: &[f64], b: &[f64]) -> Option<f64> {
    assert_eq!(a.len(), b.len(), "paired samples");
    if a.len() < 2 {
        return None;
    }
    let (ra, rb) = (ranks(a).0, ranks(b).0);
    let mean = (a.len() as f64 + 1.0) / 2.0;
    let (mut cov, mut va, mut vb) = (0.0, 0.0, 0.0);
    for (x, y) in ra.iter().zip(&rb) {
        cov += (x - mean) * (y - mean);
        va += (x - mean).powi(2);
        vb += (y - mean).powi(2);
    }
    (va > 0.0 && vb > 0.0).then(|| cov / (va * vb).sqrt())
}

/// `(mean, min, max)` of `values`; NaN mean and infinite bounds for no values.
pub fn mean_min_max(values: &[f64]) -> (f64, f64, f64) {
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (mean, lo, hi)
}

/// The median of `v` (sorted in place): the middle value, or the mean of the two middle ones.
pub fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 { v[n / 2] } else { 0.5 * (v[n / 2 - 1] + v[n / 2]) }
}

/// Quartiles `(q1, median, q3)` by linear interpolation between order statistics (the
/// usual "type 7" definition); `NaN` for no values.
pub fn quartiles(values: &[f64]) -> (f64, f64, f64) {
    if values.is_empty() {
        return (f64::NAN, f64::NAN, f64::NAN);
    }
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    (quantile_sorted(&v, 0.25), quantile_sorted(&v, 0.5), quantile_sorted(&v, 0.75))
}

/// The `p` quantile of values sorted ascending (not empty), by linear interpolation between
/// order statistics ("type 7").
pub fn quantile_sorted(sorted: &[f64], p: f64) -> f64 {
    let h = (sorted.len() - 1) as f64 * p;
    let (lo, hi) = (h.floor() as usize, h.ceil() as usize);
    sorted[lo] + (h - lo as f64) * (sorted[hi] - sorted[lo])
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
    fn spearman_by_hand() {
        // Monotone: 1 either way; reversed: −1; constant: none.
        assert_eq!(spearman(&[1.0, 2.0, 3.0], &[10.0, 40.0, 90.0]), Some(1.0));
        assert_eq!(spearman(&[1.0, 2.0, 3.0], &[3.0, 2.0, 1.0]), Some(-1.0));
        assert_eq!(spearman(&[1.0, 1.0], &[1.0, 2.0]), None);
        // Ranks (1, 2, 3, 4) against (2, 1, 4, 3): Σd² = 4, ρ = 1 − 6·4 / (4·15) = 0.6.
        let r = spearman(&[1.0, 2.0, 3.0, 4.0], &[2.0, 1.0, 4.0, 3.0]).unwrap();
        assert!((r - 0.6).abs() < 1e-12, "{r}");
    }
}
