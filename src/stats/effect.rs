//! Effect sizes of two samples: Vargha and Delaney's `A₁₂` (its direction in its name) and
//! bootstrap confidence intervals of the difference or ratio of medians, seeded.

use super::describe::quartiles;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

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

/// What [`bootstrap_ci`] estimates of two samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Contrast {
    /// `median(a) − median(b)`.
    MedianDifference,
    /// `median(a) / median(b)` (every value of `b` must be positive).
    MedianRatio,
}

impl Contrast {
    /// The contrast of `a` and `b`.
    pub fn of(self, a: &[f64], b: &[f64]) -> f64 {
        let (ma, mb) = (quartiles(a).1, quartiles(b).1);
        match self {
            Contrast::MedianDifference => ma - mb,
            Contrast::MedianRatio => ma / mb,
        }
    }
}

/// An estimate with its confidence interval.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    /// The contrast of the samples themselves.
    pub estimate: f64,
    /// Lower end of the interval.
    pub low: f64,
    /// Upper end of the interval.
    pub high: f64,
}

/// Percentile bootstrap interval (Efron and Tibshirani 1993, ch. 13) of `contrast` at `level`
/// (e.g. 0.95) from `resamples` resamples drawn with the ChaCha8 stream of `seed`: each
/// resample draws `a` and `b` with replacement — independently, or with `paired` the same
/// indices for both, so that a replicate's two runs stay together. The ends are the
/// `(1 − level)/2` and `(1 + level)/2` quantiles of the resampled contrasts (type 7). Same
/// inputs and seed, same interval, on every platform. `None` for an empty sample, paired
/// samples of different lengths, a NaN, a level outside (0, 1), no resamples, or a ratio
/// with a value of `b` that is not positive.
pub fn bootstrap_ci(
    a: &[f64],
    b: &[f64],
    contrast: Contrast,
    paired: bool,
    level: f64,
    resamples: usize,
    seed: u64,
) -> Option<Interval> {
    let ratio_undefined = contrast == Contrast::MedianRatio && b.iter().any(|&v| v <= 0.0);
    let nan = a.iter().chain(b).any(|v| v.is_nan());
    if a.is_empty() || b.is_empty() || (paired && a.len() != b.len()) || ratio_undefined || nan {
        return None;
    }
    if !(level > 0.0 && level < 1.0) || resamples == 0 {
        return None;
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (mut ra, mut rb) = (vec![0.0; a.len()], vec![0.0; b.len()]);
    let mut stats = Vec::with_capacity(resamples);
    for _ in 0..resamples {
        if paired {
            for (i, x) in ra.iter_mut().enumerate() {
                let k = rng.random_range(0..a.len() as u64) as usize;
                *x = a[k];
                rb[i] = b[k];
            }
        } else {
            for x in ra.iter_mut() {
                *x = a[rng.random_range(0..a.len() as u64) as usize];
            }
            for x in rb.iter_mut() {
                *x = b[rng.random_range(0..b.len() as u64) as usize];
            }
        }
        stats.push(contrast.of(&ra, &rb));
    }
    stats.sort_by(f64::total_cmp);
    let q = |p: f64| super::describe::quantile_sorted(&stats, p);
    let tail = (1.0 - level) / 2.0;
    Some(Interval { estimate: contrast.of(a, b), low: q(tail), high: q(1.0 - tail) })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::family::holm;

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
    fn bootstrap_intervals_are_seeded_and_cover_the_estimate() {
        // Distinct values, so that medians of resamples vary and two seeds differ.
        let a: Vec<f64> = (0..20).map(|i| 10.0 + f64::from(i * 7 % 20) * 0.31).collect();
        let b: Vec<f64> = (0..20).map(|i| 8.0 + f64::from(i * 3 % 20) * 0.23).collect();
        for (contrast, paired) in [
            (Contrast::MedianDifference, false),
            (Contrast::MedianDifference, true),
            (Contrast::MedianRatio, false),
            (Contrast::MedianRatio, true),
        ] {
            let ci = bootstrap_ci(&a, &b, contrast, paired, 0.95, 2000, 7).unwrap();
            assert!(ci.low <= ci.estimate && ci.estimate <= ci.high, "{contrast:?} {paired}: {ci:?}");
            assert!(ci.low < ci.high, "{ci:?}");
            assert_eq!(bootstrap_ci(&a, &b, contrast, paired, 0.95, 2000, 7), Some(ci));
            assert_ne!(bootstrap_ci(&a, &b, contrast, paired, 0.95, 2000, 8), Some(ci));
            // A narrower level gives a narrower interval of the same resamples.
            let narrow = bootstrap_ci(&a, &b, contrast, paired, 0.5, 2000, 7).unwrap();
            assert!(narrow.low >= ci.low && narrow.high <= ci.high);
        }
        // Medians of 0..20 scaled: the mean of the 10th and 11th values, 9.5 steps.
        assert!((Contrast::MedianDifference.of(&a, &b) - (10.0 + 9.5 * 0.31 - 8.0 - 9.5 * 0.23)).abs() < 1e-12);
        // Identical samples: every resampled median difference of pairs is 0.
        let same = bootstrap_ci(&a, &a, Contrast::MedianDifference, true, 0.95, 500, 1).unwrap();
        assert_eq!((same.estimate, same.low, same.high), (0.0, 0.0, 0.0));
        assert!(bootstrap_ci(&a, &[0.0, 1.0], Contrast::MedianRatio, false, 0.95, 10, 1).is_none());
        assert!(bootstrap_ci(&a, &b[..3], Contrast::MedianDifference, true, 0.95, 10, 1).is_none());
        assert!(bootstrap_ci(&a, &b, Contrast::MedianDifference, false, 1.0, 10, 1).is_none());
        assert!(bootstrap_ci(&[], &b, Contrast::MedianDifference, false, 0.95, 10, 1).is_none());
    }
}
