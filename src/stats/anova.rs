//! The analysis of variance 003 §5.3 asks for: a linear model of a run metric over the swept
//! factors (main effects and two-way interactions), solved by least squares with a QR
//! factorisation (`faer`), F-tests (`statrs`), each factor's share of the total sum of squares
//! (η²), a rank-transformed refit for when the residuals are far from normal, and the spread
//! between seeds of one configuration beside the parameter effects.
//!
//! Sums of squares are sequential (type I) in the order of the terms: main effects first, then
//! interactions. For balanced, crossed grids (every combination of the unconditional factors,
//! each with the same replicates) they equal the type II and III sums; the report fits only
//! such grids and says why it fits none otherwise (`report::tables::anova`).

use crate::stats::ranks;
use faer::Mat;
use statrs::distribution::{ChiSquared, ContinuousCDF, FisherSnedecor};
use std::collections::BTreeSet;

/// One categorical factor: its name and the level of every observation (`""` = does not
/// apply, a level of its own).
#[derive(Clone, Debug)]
pub struct Factor {
    /// Column name.
    pub name: String,
    /// Level per observation.
    pub levels: Vec<String>,
}

/// A term of the model: a factor's main effect or a two-way interaction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TermSpec {
    /// Main effect of factor `i`.
    Main(usize),
    /// Interaction of factors `i` and `j`.
    Pair(usize, usize),
}

/// The test of one term.
#[derive(Clone, Debug, PartialEq)]
pub struct TermTest {
    /// `a` or `a × b`.
    pub name: String,
    /// Degrees of freedom (columns not aliased with earlier terms).
    pub df: usize,
    /// Sequential sum of squares.
    pub ss: f64,
    /// `F = (SS/df) / (SS_res/df_res)`.
    pub f: f64,
    /// `P(F(df, df_res) > F)`.
    pub p: f64,
    /// `η² = SS / SS_total`.
    pub eta2: f64,
    /// p of the same term when the model is fitted to the ranks of the metric.
    pub rank_p: f64,
}

/// The fitted model and its tests.
#[derive(Clone, Debug, PartialEq)]
pub struct Anova {
    /// Observations.
    pub n: usize,
    /// Tests per term, in model order.
    pub terms: Vec<TermTest>,
    /// Residual sum of squares and degrees of freedom.
    pub residual: (f64, usize),
    /// Total sum of squares about the mean.
    pub total_ss: f64,
    /// Jarque–Bera p-value of the residuals (small = far from normal; then read `rank_p`).
    pub normality_p: f64,
}

/// Treatment-coded columns of a factor: one 0/1 column per level after the first (sorted).
fn dummies(f: &Factor) -> Vec<Vec<f64>> {
    let levels: Vec<&String> = f.levels.iter().collect::<BTreeSet<_>>().into_iter().collect();
    levels[1..].iter().map(|&l| f.levels.iter().map(|x| if x == l { 1.0 } else { 0.0 }).collect()).collect()
}

/// A thin QR of the columns that are not linear combinations of earlier ones.
struct Fit {
    /// Orthonormal basis, one column per kept column.
    q: Mat<f64>,
    /// Term index of each kept column (`usize::MAX` for the intercept).
    owner: Vec<usize>,
}

/// Factors `columns` (with their term owners), dropping each column whose `R` diagonal is
/// negligible beside its norm (aliased with earlier columns) and refactoring until none is.
fn fit(n: usize, mut columns: Vec<(usize, Vec<f64>)>) -> Fit {
    loop {
        let x = Mat::from_fn(n, columns.len(), |i, j| columns[j].1[i]);
        let qr = x.qr();
        let r = qr.thin_R();
        let aliased: Vec<usize> = (0..columns.len())
            .filter(|&j| {
                let norm = columns[j].1.iter().map(|v| v * v).sum::<f64>().sqrt();
                r[(j, j)].abs() <= 1e-9 * norm.max(1e-300)
            })
            .collect();
        if aliased.is_empty() {
            return Fit { q: qr.compute_thin_Q(), owner: columns.iter().map(|c| c.0).collect() };
        }
        // Drop the first aliased column only: later "aliased" verdicts may depend on it.
        columns.remove(aliased[0]);
    }
}

/// Effects `Qᵀy`.
fn effects(q: &Mat<f64>, y: &[f64]) -> Vec<f64> {
    (0..q.ncols()).map(|j| (0..y.len()).map(|i| q[(i, j)] * y[i]).sum()).collect()
}

/// Sequential sums of squares per term (and the residual) from the effects.
fn sums(fit: &Fit, y: &[f64], terms: usize) -> (Vec<(usize, f64)>, f64, Vec<f64>) {
    let e = effects(&fit.q, y);
    let mut per = vec![(0usize, 0.0); terms];
    for (j, &o) in fit.owner.iter().enumerate() {
        if o != usize::MAX {
            per[o].0 += 1;
            per[o].1 += e[j] * e[j];
        }
    }
    let residuals: Vec<f64> =
        (0..y.len()).map(|i| y[i] - (0..e.len()).map(|j| fit.q[(i, j)] * e[j]).sum::<f64>()).collect();
    let rss = residuals.iter().map(|r| r * r).sum();
    (per, rss, residuals)
}

/// `P(F(d1, d2) > f)`.
fn f_tail(f: f64, d1: usize, d2: usize) -> f64 {
    if d1 == 0 || d2 == 0 || !f.is_finite() {
        return f64::NAN;
    }
    FisherSnedecor::new(d1 as f64, d2 as f64).map(|d| d.sf(f.max(0.0))).unwrap_or(f64::NAN)
}

/// Jarque–Bera test of normality: `JB = n/6 (S² + (K − 3)²/4)` against χ²(2).
pub fn jarque_bera_p(x: &[f64]) -> f64 {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let m2 = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
    if m2 <= 0.0 {
        return 1.0;
    }
    let m3 = x.iter().map(|v| (v - mean).powi(3)).sum::<f64>() / n;
    let m4 = x.iter().map(|v| (v - mean).powi(4)).sum::<f64>() / n;
    let (s, k) = (m3 / m2.powf(1.5), m4 / (m2 * m2));
    let jb = n / 6.0 * (s * s + (k - 3.0).powi(2) / 4.0);
    1.0 - ChiSquared::new(2.0).expect("df 2").cdf(jb)
}

/// Fits `y` over `terms` of `factors` and tests every term. `Err` when there are no more
/// observations than model columns.
pub fn anova(factors: &[Factor], terms: &[TermSpec], y: &[f64]) -> Result<Anova, String> {
    let n = y.len();
    let dummy: Vec<Vec<Vec<f64>>> = factors.iter().map(dummies).collect();
    let mut columns = vec![(usize::MAX, vec![1.0; n])];
    for (k, t) in terms.iter().enumerate() {
        match *t {
            TermSpec::Main(i) => columns.extend(dummy[i].iter().map(|c| (k, c.clone()))),
            TermSpec::Pair(i, j) => {
                for a in &dummy[i] {
                    for b in &dummy[j] {
                        columns.push((k, a.iter().zip(b).map(|(x, y)| x * y).collect()));
                    }
                }
            }
        }
    }
    if columns.len() >= n {
        return Err(format!("{} observations for {} model columns", n, columns.len()));
    }
    let fit = fit(n, columns);
    let df_res = n - fit.q.ncols();
    let name = |t: &TermSpec| match *t {
        TermSpec::Main(i) => factors[i].name.clone(),
        TermSpec::Pair(i, j) => format!("{} × {}", factors[i].name, factors[j].name),
    };
    let mean = y.iter().sum::<f64>() / n as f64;
    let total_ss = y.iter().map(|v| (v - mean).powi(2)).sum::<f64>();
    let (per, rss, residuals) = sums(&fit, y, terms.len());
    let (rank_y, _) = ranks(y);
    let (rank_per, rank_rss, _) = sums(&fit, &rank_y, terms.len());
    let mse = rss / df_res as f64;
    let rank_mse = rank_rss / df_res as f64;
    let tests = terms
        .iter()
        .zip(per.iter().zip(&rank_per))
        .map(|(t, (&(df, ss), &(_, rank_ss)))| {
            let f = if df > 0 { ss / df as f64 / mse } else { f64::NAN };
            let rank_f = if df > 0 { rank_ss / df as f64 / rank_mse } else { f64::NAN };
            TermTest {
                name: name(t),
                df,
                ss,
                f,
                p: f_tail(f, df, df_res),
                eta2: if total_ss > 0.0 { ss / total_ss } else { 0.0 },
                rank_p: f_tail(rank_f, df, df_res),
            }
        })
        .collect();
    Ok(Anova { n, terms: tests, residual: (rss, df_res), total_ss, normality_p: jarque_bera_p(&residuals) })
}

/// The spread between replicates of one configuration: the sum of squares of every observation
/// about its configuration's mean (the "pure error" no parameter can explain), and its share of
/// the total sum of squares.
pub fn replicate_spread(configs: &[String], y: &[f64]) -> (f64, f64) {
    let mut by: std::collections::BTreeMap<&str, (f64, usize)> = std::collections::BTreeMap::new();
    for (c, v) in configs.iter().zip(y) {
        let e = by.entry(c).or_default();
        e.0 += v;
        e.1 += 1;
    }
    let ss: f64 = configs
        .iter()
        .zip(y)
        .map(|(c, v)| {
            let (s, k) = by[c.as_str()];
            (v - s / k as f64).powi(2)
        })
        .sum();
    let mean = y.iter().sum::<f64>() / y.len() as f64;
    let total: f64 = y.iter().map(|v| (v - mean).powi(2)).sum();
    (ss, if total > 0.0 { ss / total } else { 0.0 })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn factor(name: &str, levels: &[&str]) -> Factor {
        Factor { name: name.into(), levels: levels.iter().map(|s| s.to_string()).collect() }
    }

    /// A 2 × 3 design with two replicates, worked by hand:
    /// cells (a, b) → values; grand mean 6.
    ///   a1: b1 [3, 5]  b2 [6, 6]  b3 [8, 8]      a1 mean 6
    ///   a2: b1 [2, 4]  b2 [5, 7]  b3 [11, 7]     a2 mean 6
    /// SS_A = 0; b means 3.5, 6, 8.5 → SS_B = 4·(6.25 + 0 + 6.25) = 50;
    /// cell means 4, 6, 8 / 3, 6, 9 → SS_AB = 2·Σ(cell − a − b + grand)² = 2·(0.25+0+0.25+0.25+0+0.25) = 2;
    /// SS_within = 2 + 0 + 0 + 2 + 2 + 8 = 14; total = 66.
    fn worked() -> (Vec<Factor>, Vec<f64>, Vec<String>) {
        let a = factor("a", &["a1", "a1", "a1", "a1", "a1", "a1", "a2", "a2", "a2", "a2", "a2", "a2"]);
        let b = factor("b", &["b1", "b1", "b2", "b2", "b3", "b3", "b1", "b1", "b2", "b2", "b3", "b3"]);
        let y = vec![3.0, 5.0, 6.0, 6.0, 8.0, 8.0, 2.0, 4.0, 5.0, 7.0, 11.0, 7.0];
        let configs = a.levels.iter().zip(&b.levels).map(|(x, z)| format!("{x}{z}")).collect();
        (vec![a, b], y, configs)
    }

    #[test]
    fn two_factor_anova_by_hand() {
        let (f, y, configs) = worked();
        let r = anova(&f, &[TermSpec::Main(0), TermSpec::Main(1), TermSpec::Pair(0, 1)], &y).unwrap();
        let ss: Vec<f64> = r.terms.iter().map(|t| t.ss).collect();
        let df: Vec<usize> = r.terms.iter().map(|t| t.df).collect();
        assert_eq!(df, vec![1, 2, 2]);
        for (got, want) in ss.iter().zip([0.0, 50.0, 2.0]) {
            assert!((got - want).abs() < 1e-9, "{ss:?}");
        }
        assert!((r.residual.0 - 14.0).abs() < 1e-9 && r.residual.1 == 6);
        assert!((r.total_ss - 66.0).abs() < 1e-9);
        // F_B = (50/2)/(14/6) = 10.714…; for d1 = 2 the tail is (1 + 2F/d2)^(−d2/2) = 4.5714^−3 = 0.010467.
        assert!((r.terms[1].f - 25.0 / (14.0 / 6.0)).abs() < 1e-9);
        assert!((r.terms[1].p - 4.571_428_571_f64.powi(-3)).abs() < 1e-9, "{}", r.terms[1].p);
        assert!((r.terms[1].eta2 - 50.0 / 66.0).abs() < 1e-12);
        // The replicate spread is the within-cell sum of squares here (full model).
        let (within, share) = replicate_spread(&configs, &y);
        assert!((within - 14.0).abs() < 1e-12 && (share - 14.0 / 66.0).abs() < 1e-12);
    }

    #[test]
    fn an_aliased_factor_gets_no_degrees_of_freedom() {
        let (mut f, y, _) = worked();
        // "c" repeats "a" under other names: its column adds nothing after a.
        let c = Factor { name: "c".into(), levels: f[0].levels.iter().map(|l| format!("x{l}")).collect() };
        f.push(c);
        let r = anova(&f, &[TermSpec::Main(0), TermSpec::Main(2), TermSpec::Main(1)], &y).unwrap();
        assert_eq!(r.terms.iter().map(|t| t.df).collect::<Vec<_>>(), vec![1, 0, 2]);
        assert!(r.terms[1].ss.abs() < 1e-12 && r.terms[1].p.is_nan());
        assert!((r.terms[2].ss - 50.0).abs() < 1e-9);
    }

    #[test]
    fn too_few_observations_are_refused() {
        let f = vec![factor("a", &["x", "y"])];
        assert!(anova(&f, &[TermSpec::Main(0)], &[1.0, 2.0]).is_err());
    }

    #[test]
    fn jarque_bera_separates_normal_from_skewed() {
        // Evenly spaced normal quantiles (inverse CDF at (i − 0.5)/n) vs. their squares.
        use statrs::distribution::Normal;
        let n = Normal::new(0.0, 1.0).unwrap();
        let q: Vec<f64> = (1..=400).map(|i| n.inverse_cdf((i as f64 - 0.5) / 400.0)).collect();
        assert!(jarque_bera_p(&q) > 0.5);
        let sq: Vec<f64> = q.iter().map(|v| v * v).collect();
        assert!(jarque_bera_p(&sq) < 1e-6);
    }
}
