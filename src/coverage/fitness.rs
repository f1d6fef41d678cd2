//! The thesis fitness (003 §3.2.1, eqs. 3.4–3.16), one small function per equation.
//!
//! Areas are computed in square metres from cell counts (eqs. 3.4–3.6) so that the formulas
//! read as in the thesis; `M_res`, `R_speed` and `R_width` enter exactly where it puts them.

use super::{Footprint, PathMetrics, SweepCounts};
use serde::{Deserialize, Serialize};

/// The projection `f(x, y)` of the two objectives onto one number (003 eqs. 3.14–3.15).
/// `f2` is the default (thesis-ga §4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Hash, Default)]
#[serde(rename_all = "lowercase")]
pub enum Projection {
    /// `f1 = 0.5·x + 0.5·y` (eq. 3.14).
    F1,
    /// `f2 = x·y` (eq. 3.15).
    #[default]
    F2,
}

/// `cov_[m²] = cov_pix·M_res²` (and likewise cross and A; 003 eqs. 3.4–3.6).
pub fn area_m2(cells: u64, m_res: f64) -> f64 {
    cells as f64 * m_res * m_res
}

/// `cov_actual = cov_[m²] − cross_[m²]` (003 eq. 3.9).
pub fn cov_actual(cov_m2: f64, cross_m2: f64) -> f64 {
    cov_m2 - cross_m2
}

/// `cov_final = cov_actual / A_[m²]` (003 eq. 3.10).
pub fn cov_final(cov_actual: f64, area_m2: f64) -> f64 {
    if area_m2 > 0.0 { cov_actual / area_m2 } else { 0.0 }
}

/// `t_optimal = cov_actual / (R_speed·R_width)` (003 eq. 3.11).
pub fn t_optimal(cov_actual: f64, r_speed: f64, r_width: f64) -> f64 {
    cov_actual / (r_speed * r_width)
}

/// `t_actual = cov_[m²] / (R_speed·R_width)` (003 eq. 3.12).
pub fn t_actual(cov_m2: f64, r_speed: f64, r_width: f64) -> f64 {
    cov_m2 / (r_speed * r_width)
}

/// `t_final = t_optimal / (t_actual + T_rot)` (003 eq. 3.13); 0 when nothing was covered
/// (R10).
pub fn t_final(t_optimal: f64, t_actual: f64, t_rot: f64) -> f64 {
    if t_actual <= 0.0 { 0.0 } else { t_optimal / (t_actual + t_rot) }
}

/// `f1(x, y) = 0.5x + 0.5y` (003 eq. 3.14), `x = t_final`, `y = cov_final`.
pub fn f1(x: f64, y: f64) -> f64 {
    0.5 * x + 0.5 * y
}

/// `f2(x, y) = x·y` (003 eq. 3.15).
pub fn f2(x: f64, y: f64) -> f64 {
    x * y
}

/// `f_obstacle = f(x, y) / (2·obj_pix)`, and `f(x, y)` when `obj_pix = 0` (003 eq. 3.16,
/// R9).
pub fn f_obstacle(f: f64, obj_pix: u64) -> f64 {
    if obj_pix == 0 { f } else { f / (2.0 * obj_pix as f64) }
}

impl Projection {
    /// Applies the projection to `(x, y) = (t_final, cov_final)`.
    pub fn apply(self, t_final: f64, cov_final: f64) -> f64 {
        match self {
            Projection::F1 => f1(t_final, cov_final),
            Projection::F2 => f2(t_final, cov_final),
        }
    }
}

/// The thesis objectives of one path.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct ThesisScore {
    /// `cov_final` in [0, 1].
    pub cov_final: f64,
    /// `t_final` in [0, 1].
    pub t_final: f64,
    /// `f1(t_final, cov_final)` before the obstacle penalty.
    pub f1: f64,
    /// `f2(t_final, cov_final)` before the obstacle penalty.
    pub f2: f64,
    /// `f_obstacle` under the chosen projection (maximised).
    pub fitness: f64,
}

/// Scores measured path metrics (003 eqs. 3.4–3.16) with cell size `m_res`.
pub fn score(metrics: &PathMetrics, robot: &Footprint, m_res: f64, projection: Projection) -> ThesisScore {
    score_counts(&metrics.counts(), metrics.area_cells, metrics.t_rot_s, robot, m_res, projection)
}

/// Scores the counts of Listing 3.1 on `A_pix = area_cells` with rotation time `t_rot_s`
/// (003 eqs. 3.4–3.16) with cell size `m_res`.
pub fn score_counts(
    counts: &SweepCounts,
    area_cells: u64,
    t_rot_s: f64,
    robot: &Footprint,
    m_res: f64,
    projection: Projection,
) -> ThesisScore {
    let cov_m2 = area_m2(counts.cov_pix, m_res);
    let cross_m2 = area_m2(counts.cross_pix, m_res);
    let actual = cov_actual(cov_m2, cross_m2);
    let cov = cov_final(actual, area_m2(area_cells, m_res));
    let t = t_final(t_optimal(actual, robot.speed, robot.width), t_actual(cov_m2, robot.speed, robot.width), t_rot_s);
    let (f1v, f2v) = (f1(t, cov), f2(t, cov));
    let f = match projection {
        Projection::F1 => f1v,
        Projection::F2 => f2v,
    };
    ThesisScore { cov_final: cov, t_final: t, f1: f1v, f2: f2v, fitness: f_obstacle(f, counts.obj_pix) }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// All 16 rows of 003 Tables 3.1/3.2 (thesis-ga §16.1): (obj_pix, projection, f_obstacle,
    /// cov_final, t_final).
    const TABLES_3_1_3_2: [(u64, Projection, f64, f64, f64); 16] = [
        (0, Projection::F1, 0.922019, 0.96, 0.884038),
        (0, Projection::F1, 0.91871, 0.96, 0.87742),
        (0, Projection::F2, 0.848677, 0.96, 0.884038),
        (0, Projection::F2, 0.842323, 0.96, 0.87742),
        (44, Projection::F1, 0.010444, 0.947654, 0.890487),
        (44, Projection::F1, 0.0104053, 0.947654, 0.883685),
        (44, Projection::F2, 0.00958948, 0.947654, 0.890487),
        (44, Projection::F2, 0.00951623, 0.947654, 0.883685),
        (0, Projection::F1, 0.953991, 0.973827, 0.934154),
        (0, Projection::F1, 0.950108, 0.973827, 0.92639),
        (0, Projection::F2, 0.909705, 0.973827, 0.934154),
        (0, Projection::F2, 0.902144, 0.973827, 0.92639),
        (36, Projection::F1, 0.013216, 0.962469, 0.940637),
        (36, Projection::F1, 0.0131625, 0.962469, 0.932929),
        (36, Projection::F2, 0.0125741, 0.962469, 0.940637),
        (36, Projection::F2, 0.0124711, 0.962469, 0.932929),
    ];

    /// F1 and F2 by hand (003 eqs. 3.14–3.15); the score uses the chosen one.
    #[test]
    fn projections_by_hand() {
        for (t, cov, f1v, f2v) in [(0.5, 0.8, 0.65, 0.4), (1.0, 0.0, 0.5, 0.0), (0.25, 0.25, 0.25, 0.0625)] {
            assert!((Projection::F1.apply(t, cov) - f1v).abs() < 1e-15);
            assert!((Projection::F2.apply(t, cov) - f2v).abs() < 1e-15);
        }
        // The score uses the chosen projection.
        let m = PathMetrics { cells_swept: 300, crossings: 30, area_cells: 2025, ..Default::default() };
        let s2 = score(&m, &Footprint::default(), 0.2, Projection::F2);
        let s1 = score(&m, &Footprint::default(), 0.2, Projection::F1);
        assert!((s2.fitness - s2.t_final * s2.cov_final).abs() < 1e-15);
        assert!((s1.fitness - 0.5 * (s1.t_final + s1.cov_final)).abs() < 1e-15);
    }

    #[test]
    fn tables_3_1_and_3_2_reproduce_f_obstacle() {
        for (i, (obj, proj, expected, cov, t)) in TABLES_3_1_3_2.into_iter().enumerate() {
            let got = f_obstacle(proj.apply(t, cov), obj);
            // The printed inputs and outputs carry six significant digits.
            assert!(((got - expected) / expected).abs() < 5e-6, "row {i}: {got} vs {expected}");
        }
    }

    #[test]
    fn boustrophedon_cell_counts_give_table_3_1() {
        // thesis-ga §16.1: unique 1944, cov_pix 2199 on A_pix = 2025, R_rot = 0.
        let m = PathMetrics { cells_swept: 2199, crossings: 255, area_cells: 2025, ..Default::default() };
        let s = score(&m, &Footprint::default(), 0.2, Projection::F1);
        assert!((s.cov_final - 0.96).abs() < 1e-12);
        assert!((s.t_final - 0.884038).abs() < 1e-6);
        assert!((s.fitness - 0.922019).abs() < 1e-6);
    }

    #[test]
    fn one_cell_of_sweep_costs_a_third_of_a_second() {
        // thesis-ga §4: M_res = 0.2, R_speed = 0.2, R_width = 0.6 → t_final = unique/(cov_pix + 3·T_rot).
        let m = PathMetrics { cells_swept: 300, crossings: 30, area_cells: 2025, t_rot_s: 10.0, ..Default::default() };
        let s = score(&m, &Footprint::default(), 0.2, Projection::F2);
        assert!((s.t_final - 270.0 / 330.0).abs() < 1e-12);
    }

    #[test]
    fn nothing_covered_scores_zero() {
        let m = PathMetrics { area_cells: 2025, ..Default::default() };
        let s = score(&m, &Footprint::default(), 0.2, Projection::F1);
        assert_eq!((s.t_final, s.cov_final, s.fitness), (0.0, 0.0, 0.0));
        // An empty area (refused by validation, see `retrain.region`) scores 0, never NaN.
        assert_eq!(cov_final(0.0, 0.0), 0.0);
        assert_eq!(cov_final(1.0, 0.0), 0.0);
    }

    #[test]
    fn obstacle_penalty_halves_per_cell() {
        assert_eq!(f_obstacle(0.8, 0), 0.8);
        assert_eq!(f_obstacle(0.8, 1), 0.4);
        assert_eq!(f_obstacle(0.8, 4), 0.1);
    }
}
