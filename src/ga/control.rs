//! Parameter control schedules (003 §2.2.3.1, §3.5.2; thesis-ga §12).

use serde::{Deserialize, Serialize};

/// `SP_i = (i / Iter_max)(SP_max − SP_min) + SP_min` (003 eq. 3.25, linear in `i`, R23).
pub fn linear_ramp(iteration: u32, iter_max: u32, min: f64, max: f64) -> f64 {
    if iter_max == 0 {
        return max;
    }
    (iteration as f64 / iter_max as f64).min(1.0) * (max - min) + min
}

/// Tournament size from the ramp: rounded, at least 1 (thesis-ga §12.1).
pub fn ramp_tournament_size(iteration: u32, iter_max: u32, min: f64, max: f64) -> usize {
    linear_ramp(iteration, iter_max, min, max).round().max(1.0) as usize
}

/// `P_m,i = Iter_i / Iter_max` with `Iter_n = Σ_{k=1..n} k` (003 eq. 2.1), i.e.
/// `i(i+1) / (I_max(I_max+1))`: both the numerator and the denominator are triangular sums
/// (R23), so the schedule is normalised to reach exactly 1 at `i = I_max` and rises
/// quadratically from `2 / (I_max(I_max+1))` at the first iteration. Iterations past `I_max`
/// (none in a run) stay at 1.
pub fn muhlenbein_p_m(iteration: u32, iter_max: u32) -> f64 {
    if iter_max == 0 {
        return 1.0;
    }
    let (i, m) = (iteration.min(iter_max) as f64, iter_max as f64);
    i * (i + 1.0) / (m * (m + 1.0))
}

/// `P_c,i = 1 − P_m,i` (003 eq. 2.2).
pub fn muhlenbein_p_c(iteration: u32, iter_max: u32) -> f64 {
    1.0 - muhlenbein_p_m(iteration, iter_max)
}

/// Constants of the adaptive scheme (003 eqs. 2.3–2.6).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AdaptiveConstants {
    /// `K_1`: crossover probability at zero diversity.
    pub k1: f64,
    /// `K_2`: crossover probability at maximum diversity.
    pub k2: f64,
    /// `K`: mutation scale.
    pub k: f64,
}

impl Default for AdaptiveConstants {
    /// `K_1 = 0.4`, `K_2 = 0.8`, `K = 0.5` (thesis-ga §12.2).
    fn default() -> Self {
        Self { k1: 0.4, k2: 0.8, k: 0.5 }
    }
}

/// `Div / Div_max`, 0 when `Div_max = 0` (thesis-ga §12.2).
fn diversity_ratio(div: f64, div_max: f64) -> f64 {
    if div_max > 0.0 { (div / div_max).clamp(0.0, 1.0) } else { 0.0 }
}

/// `P_c = (Div / Div_max)(K_2 − K_1) + K_1` (003 eq. 2.3).
pub fn adaptive_p_c(div: f64, div_max: f64, c: &AdaptiveConstants) -> f64 {
    diversity_ratio(div, div_max) * (c.k2 - c.k1) + c.k1
}

/// `P_m^Diversity = ((Div_max − Div) / Div_max)·K` (003 eq. 2.4).
pub fn adaptive_p_m_diversity(div: f64, div_max: f64, c: &AdaptiveConstants) -> f64 {
    (1.0 - diversity_ratio(div, div_max)) * c.k
}

/// `P_m^Fitness = K·(f_max − f)/(f_max − f_min)`, 0 when `f_max = f_min` (003 eq. 2.5).
pub fn adaptive_p_m_fitness(f: f64, f_min: f64, f_max: f64, c: &AdaptiveConstants) -> f64 {
    if f_max > f_min { c.k * ((f_max - f) / (f_max - f_min)).clamp(0.0, 1.0) } else { 0.0 }
}

/// `P_m = (P_m^Diversity + P_m^Fitness) / 2` (003 eq. 2.6).
pub fn adaptive_p_m(p_m_diversity: f64, p_m_fitness: f64) -> f64 {
    0.5 * (p_m_diversity + p_m_fitness)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramp_ends_and_rounding() {
        assert_eq!(linear_ramp(0, 2000, 1.0, 2.0), 1.0);
        assert_eq!(linear_ramp(1000, 2000, 1.0, 2.0), 1.5);
        assert_eq!(linear_ramp(2000, 2000, 1.0, 2.0), 2.0);
        assert_eq!(ramp_tournament_size(0, 100, 1.0, 7.0), 1);
        assert_eq!(ramp_tournament_size(50, 100, 1.0, 7.0), 4);
        assert_eq!(ramp_tournament_size(100, 100, 1.0, 7.0), 7);
    }

    #[test]
    fn muhlenbein_is_triangular() {
        assert!((muhlenbein_p_m(1, 3) - 2.0 / 12.0).abs() < 1e-15);
        assert_eq!(muhlenbein_p_m(3, 3), 1.0);
        assert!((muhlenbein_p_c(2, 3) - 0.5).abs() < 1e-15);
    }

    #[test]
    fn adaptive_values() {
        let c = AdaptiveConstants::default();
        assert!((adaptive_p_c(2000.0, 4000.0, &c) - 0.6).abs() < 1e-12);
        assert_eq!(adaptive_p_c(1.0, 0.0, &c), 0.4);
        assert!((adaptive_p_m_diversity(1000.0, 4000.0, &c) - 0.375).abs() < 1e-12);
        assert_eq!(adaptive_p_m_fitness(0.9, 0.1, 0.9, &c), 0.0);
        assert!((adaptive_p_m_fitness(0.1, 0.1, 0.9, &c) - 0.5).abs() < 1e-12);
        assert_eq!(adaptive_p_m_fitness(0.5, 0.5, 0.5, &c), 0.0);
        assert_eq!(adaptive_p_m(0.2, 0.4), 0.30000000000000004);
    }
}
