//! What a design can show before it is run: the smallest p-value a rank test over a number of
//! independent units can reach, what a family's correction makes of it, and how many units a
//! comparison needs to be able to show an effect of a given size. A report says so where a
//! design cannot reach the level, instead of reporting "not shown".
//!
//! The unit is what is independent: a seed where both sides read common seeds, a stratum where
//! one side runs once per stratum, a map where strata share one. Its effect is one number per
//! unit ([`unit_effects`]); intervals resample units, not pairs ([`cluster_bootstrap_ci`]).

use super::effect::Interval;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use statrs::distribution::{ContinuousCDF, Normal};

/// The smallest two-sided p-value of an exact signed-rank (or sign) test over `n` units: every
/// difference on one side, `2 · 2⁻ⁿ` (1 for no unit).
pub fn signed_rank_min_p(n: usize) -> f64 {
    (2.0 * 0.5f64.powi(i32::try_from(n).unwrap_or(i32::MAX))).min(1.0)
}

/// The smallest two-sided p-value of an exact rank-sum test of `a` against `b` units: the two
/// groups apart, `2 / C(a + b, a)`.
pub fn rank_sum_min_p(a: usize, b: usize) -> f64 {
    let ways = (1..=a.min(b)).fold(1.0f64, |c, k| c * (a + b + 1 - k) as f64 / k as f64);
    (2.0 / ways).min(1.0)
}

/// The smallest Holm-adjusted p-value of a family of `tests` tests that each reach at best
/// `min_p`: Holm multiplies the smallest raw p by the family's size (Holm 1979).
pub fn holm_min_p(min_p: f64, tests: usize) -> f64 {
    (min_p * tests.max(1) as f64).min(1.0)
}

/// Units a paired comparison needs so that a family of `tests` tests, corrected by Holm, can
/// reach `alpha` at all: the smallest `n` with `tests · 2 · 2⁻ⁿ ≤ alpha`.
pub fn units_to_reach(alpha: f64, tests: usize) -> usize {
    (1..=64).find(|&n| holm_min_p(signed_rank_min_p(n), tests) <= alpha).unwrap_or(usize::MAX)
}

/// Units a paired comparison needs to show a standardised effect `d` (the mean of the unit
/// effects over their standard deviation) with probability `power`, in a family of `tests`
/// tests corrected by Holm (planned for its worst case, Bonferroni's `alpha / tests`): the
/// normal approximation `((z₁₋α/(2m) + z_power) / d)²`, divided by the signed-rank test's
/// asymptotic efficiency against the t-test under normality, `3/π` (Lehmann 1975), and never
/// fewer than [`units_to_reach`]. `None` for `d` ≤ 0 or a probability outside (0, 1).
pub fn units_for_effect(d: f64, alpha: f64, power: f64, tests: usize) -> Option<usize> {
    let valid = |p: f64| p > 0.0 && p < 1.0;
    if d.is_nan() || d <= 0.0 || !valid(alpha) || !valid(power) {
        return None;
    }
    let z = Normal::new(0.0, 1.0).expect("standard normal");
    let per_test = alpha / tests.max(1) as f64;
    let n = ((z.inverse_cdf(1.0 - per_test / 2.0) + z.inverse_cdf(power)) / d).powi(2) / (3.0 / std::f64::consts::PI);
    Some((n.ceil() as usize).max(units_to_reach(alpha, tests)))
}

/// Samples of these sizes lying wholly apart, each group above the one before: the most extreme
/// data a rank test of groups of these sizes can see, so that the test's p on them is the
/// smallest it can give (exact or approximate, as the test computes it).
pub fn groups_apart(sizes: &[usize]) -> Vec<Vec<f64>> {
    let mut next = 0.0;
    sizes
        .iter()
        .map(|&n| {
            (0..n)
                .map(|_| {
                    next += 1.0;
                    next
                })
                .collect()
        })
        .collect()
}

/// One effect per unit: the median of `contrast` over the pairs of each unit, units in the
/// order they first appear. `pairs` holds `(unit, a, b)`.
pub fn unit_effects<U: PartialEq + Clone>(pairs: &[(U, f64, f64)], contrast: fn(f64, f64) -> f64) -> Vec<(U, f64)> {
    let mut units: Vec<(U, Vec<f64>)> = Vec::new();
    for (unit, a, b) in pairs {
        let value = contrast(*a, *b);
        match units.iter_mut().find(|(u, _)| u == unit) {
            Some((_, values)) => values.push(value),
            None => units.push((unit.clone(), vec![value])),
        }
    }
    units.into_iter().map(|(u, mut values)| (u, super::median(&mut values))).collect()
}

/// The log-ratio `ln(a / b)` of a pair (NaN unless both are positive).
pub fn log_ratio(a: f64, b: f64) -> f64 {
    if a > 0.0 && b > 0.0 { (a / b).ln() } else { f64::NAN }
}

/// Percentile bootstrap interval of `statistic` over clustered values: each resample draws
/// whole clusters with replacement (as many as there are) and applies `statistic` to their
/// values together, so that values of one cluster never count as independent (Davison and
/// Hinkley 1997, §3.8). Drawn with the ChaCha8 stream of `seed`; quantiles of type 7. `None`
/// without a cluster, with an empty cluster, a NaN, a level outside (0, 1) or no resamples.
pub fn cluster_bootstrap_ci(
    clusters: &[Vec<f64>],
    statistic: fn(&mut [f64]) -> f64,
    level: f64,
    resamples: usize,
    seed: u64,
) -> Option<Interval> {
    let bad = clusters.is_empty() || clusters.iter().any(|c| c.is_empty() || c.iter().any(|v| v.is_nan()));
    if bad || !(level > 0.0 && level < 1.0) || resamples == 0 {
        return None;
    }
    let mut all: Vec<f64> = clusters.concat();
    let estimate = statistic(&mut all);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut drawn = Vec::with_capacity(all.len());
    let mut stats = Vec::with_capacity(resamples);
    for _ in 0..resamples {
        drawn.clear();
        for _ in 0..clusters.len() {
            drawn.extend_from_slice(&clusters[rng.random_range(0..clusters.len() as u64) as usize]);
        }
        stats.push(statistic(&mut drawn));
    }
    stats.sort_by(f64::total_cmp);
    let q = |p: f64| super::describe::quantile_sorted(&stats, p);
    let tail = (1.0 - level) / 2.0;
    Some(Interval { estimate, low: q(tail), high: q(1.0 - tail) })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::paired::wilcoxon_signed_rank;
    use crate::stats::rank_sum::mann_whitney;

    #[test]
    fn groups_apart_give_the_rank_tests_their_extremes() {
        assert_eq!(groups_apart(&[2, 1]), vec![vec![1.0, 2.0], vec![3.0]]);
        let g = groups_apart(&[3, 3]);
        let exact = mann_whitney(&g[0], &g[1]).unwrap().p_value;
        assert!((exact - rank_sum_min_p(3, 3)).abs() < 1e-12);
    }

    /// The floors are what the exact tests give when every unit points one way.
    #[test]
    fn the_smallest_p_values_are_the_exact_tests_extremes() {
        for n in [1usize, 4, 7, 10, 16] {
            let a: Vec<f64> = (1..=n).map(|k| k as f64 + 0.5).collect();
            let b = vec![0.0; n];
            let exact = wilcoxon_signed_rank(&a, &b).unwrap().p_value;
            assert!((exact - signed_rank_min_p(n)).abs() < 1e-15, "{n}: {exact}");
        }
        for (na, nb) in [(3usize, 3usize), (5, 4), (10, 10)] {
            let a: Vec<f64> = (0..na).map(|k| 100.0 + k as f64).collect();
            let b: Vec<f64> = (0..nb).map(|k| k as f64).collect();
            let exact = mann_whitney(&a, &b).unwrap().p_value;
            assert!((exact - rank_sum_min_p(na, nb)).abs() < 1e-12, "{na}, {nb}: {exact}");
        }
    }

    /// The numbers: 10 seeds reach 2⁻⁹ per stratum, 0.246 after Holm over 126 tests,
    /// so nothing can be shown stratum by stratum; 48 strata reach far below 0.05.
    #[test]
    fn what_ten_seeds_and_forty_eight_strata_can_show() {
        assert!((signed_rank_min_p(10) - 2f64.powi(-9)).abs() < 1e-18);
        assert!((holm_min_p(signed_rank_min_p(10), 126) - 0.24609375).abs() < 1e-12);
        assert_eq!(units_to_reach(0.05, 126), 13, "126 · 2⁻¹² = 0.031; 126 · 2⁻¹¹ = 0.062");
        assert_eq!(units_to_reach(0.05, 1), 6, "2⁻⁵ = 0.031; 2⁻⁴ = 0.0625");
        assert!(holm_min_p(signed_rank_min_p(48), 3) < 1e-12);
    }

    /// A medium effect (d = 0.5) at 0.05 with power 0.8: the normal approximation gives 31.4
    /// pairs for a t-test, 32.9 for the signed-rank test; a family of 10 needs more.
    #[test]
    fn units_for_an_effect_follow_the_normal_approximation() {
        assert_eq!(units_for_effect(0.5, 0.05, 0.8, 1), Some(33));
        let ten = units_for_effect(0.5, 0.05, 0.8, 10).unwrap();
        // z(1 − 0.0025) = 2.807: ((2.807 + 0.842) / 0.5)² / (3/π) = 55.7.
        assert_eq!(ten, 56);
        assert_eq!(units_for_effect(3.0, 0.05, 0.8, 126), Some(13), "a huge effect still needs 13 units");
        assert_eq!(units_for_effect(0.0, 0.05, 0.8, 1), None);
        assert_eq!(units_for_effect(0.5, 1.5, 0.8, 1), None);
    }

    #[test]
    fn unit_effects_are_medians_per_unit_in_order_of_appearance() {
        let pairs = [("b", 2.0, 1.0), ("a", 1.0, 1.0), ("b", 4.0, 1.0), ("b", 8.0, 1.0), ("a", 1.0, 2.0)];
        let effects = unit_effects(&pairs, log_ratio);
        assert_eq!(effects[0].0, "b");
        assert!((effects[0].1 - 4f64.ln()).abs() < 1e-15);
        assert_eq!(effects[1].0, "a");
        assert!((effects[1].1 - 0.5f64.ln() / 2.0).abs() < 1e-15, "{effects:?}");
        assert!(log_ratio(0.0, 1.0).is_nan());
    }

    /// Resampling clusters widens the interval of a median when values within a cluster agree:
    /// ten clusters of ten equal values hold ten units' worth of information, not a hundred's.
    #[test]
    fn a_cluster_bootstrap_resamples_whole_clusters() {
        let clusters: Vec<Vec<f64>> = (0..10).map(|k| vec![f64::from(k); 10]).collect();
        let clustered = cluster_bootstrap_ci(&clusters, crate::stats::median, 0.95, 2000, 1).unwrap();
        let singletons: Vec<Vec<f64>> = clusters.concat().into_iter().map(|v| vec![v]).collect();
        let naive = cluster_bootstrap_ci(&singletons, crate::stats::median, 0.95, 2000, 1).unwrap();
        assert_eq!(clustered.estimate, naive.estimate);
        assert!(
            clustered.high - clustered.low > 1.5 * (naive.high - naive.low),
            "clustered {clustered:?}, pairs as units {naive:?}"
        );
        assert_eq!(cluster_bootstrap_ci(&clusters, crate::stats::median, 0.95, 2000, 1), Some(clustered));
        assert_eq!(cluster_bootstrap_ci(&[], crate::stats::median, 0.95, 10, 1), None);
        assert_eq!(cluster_bootstrap_ci(&[vec![]], crate::stats::median, 0.95, 10, 1), None);
    }
}
