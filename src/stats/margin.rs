//! Margins, not only significance: the signed-rank test of unit ratios against a stated margin
//! (one-sided: "at least 5 % faster" is the ratio's test against 0.95), and the handling of
//! units whose effect is exactly zero.
//!
//! A unit that ties (its effect is zero) says nothing about the direction, and the rank tests
//! differ on what to do with it: Wilcoxon (1945) drops it before ranking (`zero_method =
//! "wilcox"`, the rule the comparisons use); Pratt (1959) ranks it with the others and then
//! drops its rank, so that the ties still push the other ranks up (`zero_method = "pratt"`, the
//! sensitivity line beside it). Where a design builds in ties (a search seeded with a control's
//! plan returns it), the two can differ, and a finding that rests on one rule only says so.

use super::describe::ranks;
use super::exact::any_subset_sum_counts;
use super::paired::EXACT_MAX_PAIRS;
use statrs::distribution::{ContinuousCDF, Normal};

/// How a signed-rank test treats the values that are exactly zero.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Zeros {
    /// Dropped before ranking (Wilcoxon 1945).
    Wilcoxon,
    /// Ranked with the others, then their ranks dropped (Pratt 1959).
    Pratt,
}

impl Zeros {
    /// The rule in words, for a table.
    pub fn name(self) -> &'static str {
        match self {
            Zeros::Wilcoxon => "zeros dropped (Wilcoxon)",
            Zeros::Pratt => "zeros ranked, then dropped (Pratt)",
        }
    }
}

/// Which tail a one-sided test looks at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tail {
    /// The values lie below zero (`W⁺` small).
    Below,
    /// Either way (twice the smaller tail).
    Both,
}

/// The signed-rank p of `d` (differences against zero) under `zeros`, on `tail`: exact over
/// every sign pattern of the non-zero ranks up to [`EXACT_MAX_PAIRS`] of them, else the normal
/// approximation (no continuity correction). `None` with no non-zero value or a NaN.
pub fn signed_rank_p(d: &[f64], zeros: Zeros, tail: Tail) -> Option<f64> {
    if d.iter().any(|x| x.is_nan()) {
        return None;
    }
    let ranked: Vec<f64> = match zeros {
        Zeros::Wilcoxon => d.iter().copied().filter(|&x| x != 0.0).collect(),
        Zeros::Pratt => d.to_vec(),
    };
    let (r, _) = ranks(&ranked.iter().map(|x| x.abs()).collect::<Vec<_>>());
    let kept: Vec<(f64, f64)> = r.into_iter().zip(ranked).filter(|&(_, x)| x != 0.0).collect();
    if kept.is_empty() {
        return None;
    }
    let w_plus: f64 = kept.iter().filter(|(_, x)| *x > 0.0).map(|(r, _)| r).sum();
    let p = if kept.len() <= EXACT_MAX_PAIRS {
        let doubled: Vec<usize> = kept.iter().map(|(r, _)| (2.0 * r).round() as usize).collect();
        let counts = any_subset_sum_counts(&doubled);
        let total: f64 = counts.iter().sum();
        let observed = ((2.0 * w_plus).round() as usize).min(counts.len() - 1);
        let lower = counts[..=observed].iter().sum::<f64>() / total;
        let upper = counts[observed..].iter().sum::<f64>() / total;
        match tail {
            Tail::Below => lower,
            Tail::Both => (2.0 * lower.min(upper)).min(1.0),
        }
    } else {
        let mean = kept.iter().map(|(r, _)| r).sum::<f64>() / 2.0;
        let var = kept.iter().map(|(r, _)| r * r).sum::<f64>() / 4.0;
        let z = (w_plus - mean) / var.sqrt();
        let normal = Normal::new(0.0, 1.0).expect("standard normal");
        match tail {
            Tail::Below => normal.cdf(z),
            Tail::Both => (2.0 * normal.sf(z.abs())).min(1.0),
        }
    };
    Some(p)
}

/// The one-sided test that the ratios `ratios` (one per unit, each positive) lie below the
/// margin `margin`: the signed-rank test of `ln ratio − ln margin`, lower tail, zeros dropped.
/// `None` without a usable ratio.
pub fn below_margin(ratios: &[f64], margin: f64) -> Option<f64> {
    let d: Vec<f64> = ratios.iter().filter(|r| **r > 0.0).map(|r| r.ln() - margin.ln()).collect();
    signed_rank_p(&d, Zeros::Wilcoxon, Tail::Below)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::wilcoxon_signed_rank;

    #[test]
    fn the_rules_by_hand() {
        // 7 better, 1 worse (the third smallest), 6 tied. Dropped: W⁺ = 3 of ranks 1–8, and 5 of
        // the 256 sign patterns give W⁺ ≤ 3 ({}, {1}, {2}, {3}, {1, 2}): p = 2 · 5/256. Pratt
        // ranks the ties 1–6 and the others 7–14: W⁺ = 9, and 4 patterns give W⁺ ≤ 9.
        let mut d = vec![-0.005, -0.008, 0.01, -0.03, -0.04, -0.05, -0.06, -0.07];
        d.extend([0.0; 6]);
        let wilcoxon = signed_rank_p(&d, Zeros::Wilcoxon, Tail::Both).unwrap();
        assert!((wilcoxon - 2.0 * 5.0 / 256.0).abs() < 1e-12, "{wilcoxon}");
        let reference = wilcoxon_signed_rank(&d, &vec![0.0; d.len()]).unwrap().p_value;
        assert!((wilcoxon - reference).abs() < 1e-12, "one rule with the test the comparisons use");
        let pratt = signed_rank_p(&d, Zeros::Pratt, Tail::Both).unwrap();
        assert!((pratt - 2.0 * 4.0 / 256.0).abs() < 1e-12, "{pratt}");
        // Lower tail: every value below zero, 2⁻ⁿ; every value above, 1.
        let below = signed_rank_p(&[-1.0, -2.0, -3.0], Zeros::Wilcoxon, Tail::Below).unwrap();
        assert!((below - 0.125).abs() < 1e-15);
        assert_eq!(signed_rank_p(&[1.0, 2.0, 3.0], Zeros::Wilcoxon, Tail::Below), Some(1.0));
        assert_eq!(signed_rank_p(&[0.0, 0.0], Zeros::Pratt, Tail::Both), None);
    }

    #[test]
    fn a_margin_is_a_shifted_test() {
        // Ratios all at 0.90: below a 0.95 margin in every unit; all at 0.97: above it.
        let fast = below_margin(&[0.9; 6], 0.95).unwrap();
        assert!((fast - 1.0 / 64.0).abs() < 1e-15, "{fast}");
        assert_eq!(below_margin(&[0.97; 6], 0.95), Some(1.0));
        assert!(below_margin(&[], 0.95).is_none());
        // Large samples take the normal tail and stay within (0, 1).
        let many: Vec<f64> = (0..80).map(|i| 0.9 + 0.001 * f64::from(i)).collect();
        let p = below_margin(&many, 0.95).unwrap();
        assert!(p > 0.0 && p < 1.0);
    }
}
