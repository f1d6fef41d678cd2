//! The claims of 003 §5.1 about its GA operators, each checked on a Table 4.3 study with a
//! stated test: the runs of map 1 without rotation cost (the subset the thesis's Figs.
//! 4.2–4.5 show), two groups compared by a two-sided Mann–Whitney U test with the
//! Vargha–Delaney A₁₂ as effect size, or by a two-proportion z-test for outlier rates.
//!
//! Metrics per run: the final diversity (mean of `history.csv`'s diversity over the last tenth
//! of the iterations), the spread of the best individuals (a run's absolute deviation of
//! `cov_final` from its group's median, the Brown–Forsythe idea with ranks), the distance from
//! the diagonal `abs(cov_final − t_final)`, and outliers (`cov_final` below `Q1 − 1.5·IQR` of the
//! figure panel the run belongs to).

use crate::stats::{a12_magnitude, mann_whitney_u, quartiles};
use crate::study::records::RunsTable;
use statrs::distribution::{ContinuousCDF, Normal};
use std::fmt::Write as _;

/// What a verdict says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// The difference is significant (p < 0.05) and in the claimed direction.
    Holds,
    /// Significant the other way, or no difference although both groups have ≥ 30 runs.
    DoesNotHold,
    /// Too few runs (or no histories) to tell.
    CannotSay,
}

impl Verdict {
    fn text(self) -> &'static str {
        match self {
            Verdict::Holds => "holds",
            Verdict::DoesNotHold => "does not hold",
            Verdict::CannotSay => "cannot say",
        }
    }
}

/// How the two groups of a claim should differ.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Expect {
    /// Group A's values are lower than group B's.
    Lower,
    /// Group A's values are higher.
    Higher,
    /// Group A's values are not lower (a significant decrease refutes the claim; no significant
    /// difference supports it).
    NotLower,
}

/// The outcome of one two-group comparison.
#[derive(Clone, Debug, PartialEq)]
pub struct ClaimTest {
    /// Runs in A and B.
    pub n: (usize, usize),
    /// `P(a > b) + ½P(a = b)` (A₁₂), or for rates the difference `rate_a − rate_b`.
    pub effect: f64,
    /// Two-sided p-value.
    pub p: f64,
    /// The verdict for the expectation.
    pub verdict: Verdict,
}

/// Verdict of a two-sided test whose effect `> 0.5` (or `> 0`) means "A higher".
fn judge(expect: Expect, a_higher: bool, p: f64, n: (usize, usize)) -> Verdict {
    let significant = p < 0.05;
    let enough = n.0 >= 30 && n.1 >= 30;
    match expect {
        Expect::Lower | Expect::Higher => {
            let wanted = (expect == Expect::Higher) == a_higher;
            if significant && wanted {
                Verdict::Holds
            } else if significant || enough {
                Verdict::DoesNotHold
            } else {
                Verdict::CannotSay
            }
        }
        Expect::NotLower => {
            if significant && !a_higher {
                Verdict::DoesNotHold
            } else if significant || enough {
                Verdict::Holds
            } else {
                Verdict::CannotSay
            }
        }
    }
}

/// Mann–Whitney comparison of `a` against `b` for `expect`.
pub fn compare(a: &[f64], b: &[f64], expect: Expect) -> ClaimTest {
    let n = (a.len(), b.len());
    match mann_whitney_u(a, b) {
        Some(mw) => {
            let a12 = mw.u / (a.len() * b.len()) as f64;
            ClaimTest { n, effect: a12, p: mw.p_value, verdict: judge(expect, a12 > 0.5, mw.p_value, n) }
        }
        None => ClaimTest { n, effect: f64::NAN, p: f64::NAN, verdict: Verdict::CannotSay },
    }
}

/// Two-proportion z-test of `k_a/n_a` against `k_b/n_b` (pooled variance) for `expect`.
pub fn compare_rates((ka, na): (usize, usize), (kb, nb): (usize, usize), expect: Expect) -> ClaimTest {
    let n = (na, nb);
    if na == 0 || nb == 0 {
        return ClaimTest { n, effect: f64::NAN, p: f64::NAN, verdict: Verdict::CannotSay };
    }
    let (pa, pb) = (ka as f64 / na as f64, kb as f64 / nb as f64);
    let pool = (ka + kb) as f64 / (na + nb) as f64;
    let se = (pool * (1.0 - pool) * (1.0 / na as f64 + 1.0 / nb as f64)).sqrt();
    let p = if se > 0.0 {
        let z = (pa - pb).abs() / se;
        (2.0 * (1.0 - Normal::new(0.0, 1.0).expect("standard normal").cdf(z))).min(1.0)
    } else {
        1.0
    };
    ClaimTest { n, effect: pa - pb, p, verdict: judge(expect, pa > pb, p, n) }
}

/// The runs of the thesis figures (map 1, `R_rot` = 0) with what the claims read.
struct Runs<'a> {
    t: &'a RunsTable,
    rows: Vec<usize>,
    diversity: Vec<Option<f64>>,
}

impl Runs<'_> {
    fn get(&self, r: usize, c: &str) -> &str {
        self.t.col(c).map_or("", |i| self.t.rows[r][i].as_str())
    }
    fn num(&self, r: usize, c: &str) -> f64 {
        self.t.num(&self.t.rows[r], c).unwrap_or(f64::NAN)
    }
    /// Rows (indices into `self.rows`) where every `(column, value)` matches.
    fn select(&self, filter: &[(&str, &str)]) -> Vec<usize> {
        (0..self.rows.len())
            .filter(|&k| {
                filter.iter().all(|(c, v)| {
                    let cell = self.get(self.rows[k], c);
                    match (cell.parse::<f64>(), v.parse::<f64>()) {
                        (Ok(a), Ok(b)) => a == b,
                        _ => cell == *v,
                    }
                })
            })
            .collect()
    }
    fn diversity(&self, sel: &[usize]) -> Vec<f64> {
        sel.iter().filter_map(|&k| self.diversity[k]).collect()
    }
    fn metric(&self, sel: &[usize], f: impl Fn(f64, f64) -> f64) -> Vec<f64> {
        sel.iter().map(|&k| f(self.num(self.rows[k], "cov_final_free"), self.num(self.rows[k], "t_final"))).collect()
    }
    /// Absolute deviations of `cov_final` from the group's median.
    fn spread(&self, sel: &[usize]) -> Vec<f64> {
        let cov = self.metric(sel, |c, _| c);
        let med = quartiles(&cov).1;
        cov.iter().map(|c| (c - med).abs()).collect()
    }
    /// Low outliers of `cov_final` within the group: (count, runs).
    fn outliers(&self, sel: &[usize]) -> (usize, usize) {
        let cov = self.metric(sel, |c, _| c);
        let (q1, _, q3) = quartiles(&cov);
        (cov.iter().filter(|&&c| c < q1 - 1.5 * (q3 - q1)).count(), cov.len())
    }
}

/// One row of the claims table.
struct Row {
    claim: &'static str,
    test: String,
    result: ClaimTest,
    rate: bool,
}

/// The claims about the selection schemes and the projection (003 §5.1).
fn selection_claims(runs: &Runs, out: &mut Vec<Row>) {
    let sel = |f: &[(&str, &str)]| runs.select(f);
    let mut push = |claim, test: String, result, rate| out.push(Row { claim, test, result, rate });
    let elite = sel(&[("thesis.selection", "elite")]);
    for other in ["tournament", "prws", "rrws"] {
        let o = sel(&[("thesis.selection", other)]);
        push(
            "Elite loses the most diversity",
            format!("final diversity, Elite vs {other}"),
            compare(&runs.diversity(&elite), &runs.diversity(&o), Expect::Lower),
            false,
        );
        push(
            "Elite's best individuals lie in a small distribution",
            format!("distance of cov_final from the group median, Elite vs {other}"),
            compare(&runs.spread(&elite), &runs.spread(&o), Expect::Lower),
            false,
        );
    }
    for sel_name in ["tournament", "prws", "rrws"] {
        let s = |p| sel(&[("thesis.selection", sel_name), ("scorer.projection", p)]);
        push(
            "f2 moves the population towards the diagonal (non-Elite)",
            format!("distance from the diagonal, abs(cov_final − t_final), {sel_name}: f2 vs f1"),
            compare(
                &runs.metric(&s("f2"), |c, t| (c - t).abs()),
                &runs.metric(&s("f1"), |c, t| (c - t).abs()),
                Expect::Lower,
            ),
            false,
        );
    }
}

/// The claims about the tournament size, the selection pressure, the chromosome length, the
/// child types and the mutation rates (003 §5.1).
fn parameter_claims(runs: &Runs, out: &mut Vec<Row>) {
    let sel = |f: &[(&str, &str)]| runs.select(f);
    let mut push = |claim, test: String, result, rate| out.push(Row { claim, test, result, rate });
    let ts = |v| sel(&[("thesis.selection", "tournament"), ("thesis.tournament_size", v)]);
    push(
        "Higher TS lowers diversity",
        "final diversity, TS 7 vs TS 3".into(),
        compare(&runs.diversity(&ts("7")), &runs.diversity(&ts("3")), Expect::Lower),
        false,
    );
    let ts_f2 =
        |v| sel(&[("thesis.selection", "tournament"), ("thesis.tournament_size", v), ("scorer.projection", "f2")]);
    push(
        "Higher TS with f2 gives more outliers",
        "outlier rate, TS 7 vs TS 3, f2".into(),
        compare_rates(runs.outliers(&ts_f2("7")), runs.outliers(&ts_f2("3")), Expect::Higher),
        true,
    );
    let sp = |v| sel(&[("thesis.selection", "rrws"), ("thesis.selection_pressure", v)]);
    push(
        "RRWS keeps its diversity under higher SP",
        "final diversity, SP 2 vs SP 1.4".into(),
        compare(&runs.diversity(&sp("2")), &runs.diversity(&sp("1.4")), Expect::NotLower),
        false,
    );
    let sp_f2 = |v| sel(&[("thesis.selection", "rrws"), ("thesis.selection_pressure", v), ("scorer.projection", "f2")]);
    push(
        "Higher SP with f2 gives fewer outliers",
        "outlier rate, SP 2 vs SP 1.4, f2".into(),
        compare_rates(runs.outliers(&sp_f2("2")), runs.outliers(&sp_f2("1.4")), Expect::Lower),
        true,
    );
    let small = sel(&[("thesis.c_len", "0.2")]);
    let long: Vec<usize> = ["0.4", "0.6", "0.8"].iter().flat_map(|v| sel(&[("thesis.c_len", v)])).collect();
    push(
        "Small C_len lowers diversity",
        "final diversity, C_len 0.2 vs 0.4–0.8".into(),
        compare(&runs.diversity(&small), &runs.diversity(&long), Expect::Lower),
        false,
    );
    push(
        "Small C_len spreads the individuals less",
        "distance of cov_final from the group median, C_len 0.2 vs 0.8".into(),
        compare(&runs.spread(&small), &runs.spread(&sel(&[("thesis.c_len", "0.8")])), Expect::Lower),
        false,
    );
    let both = sel(&[("thesis.c_child", "2")]);
    let single: Vec<usize> = ["0", "1"].iter().flat_map(|v| sel(&[("thesis.c_child", v)])).collect();
    push(
        "Both child types (C_child = 2) give fewer outliers",
        "outlier rate, C_child 2 vs 0 and 1".into(),
        compare_rates(runs.outliers(&both), runs.outliers(&single), Expect::Lower),
        true,
    );
    for other in ["0", "0.01"] {
        push(
            "P_mI = 0.1 gives the highest diversity",
            format!("final diversity, P_mI 0.1 vs {other}"),
            compare(
                &runs.diversity(&sel(&[("thesis.p_mi", "0.1")])),
                &runs.diversity(&sel(&[("thesis.p_mi", other)])),
                Expect::Higher,
            ),
            false,
        );
    }
    let both_high = sel(&[("thesis.p_mi", "0.1"), ("thesis.p_ma", "0.1")]);
    let both_off = sel(&[("thesis.p_mi", "0"), ("thesis.p_ma", "0")]);
    push(
        "Both mutations at 0.1 give higher diversity than none",
        "final diversity, P_mA = P_mI = 0.1 vs both 0".into(),
        compare(&runs.diversity(&both_high), &runs.diversity(&both_off), Expect::Higher),
        false,
    );
}

/// The claims section of the thesis report, for the runs of `t`, their final diversity read
/// through `folders`.
pub fn section(t: &RunsTable, folders: &crate::report::analysis::folder_record::FolderRecords) -> String {
    let mut md = String::from("\n## The claims of 003 §5.1, checked\n\n");
    let rows: Vec<usize> = (0..t.rows.len())
        .filter(|&r| {
            let row = &t.rows[r];
            t.col("map.source").is_none_or(|c| row[c] == "thesis-1")
                && t.num(row, "robot.rot_speed").is_none_or(|v| v == 0.0)
        })
        .collect();
    let run_id = t.col("run_id");
    let diversity = rows.iter().map(|&r| run_id.and_then(|c| folders.final_diversity(&t.rows[r][c]))).collect();
    let runs = Runs { t, rows, diversity };
    let _ = writeln!(
        md,
        "On the {} runs of map 1 without rotation cost ({} with a history for the diversity). Two-sided tests, \
         p < 0.05; A₁₂ = P(A > B); \"does not hold\" also when groups of ≥ 30 runs show no difference.\n",
        runs.rows.len(),
        runs.diversity.iter().flatten().count()
    );
    let mut out: Vec<Row> = Vec::new();
    selection_claims(&runs, &mut out);
    parameter_claims(&runs, &mut out);
    let _ = writeln!(md, "| claim | test (A vs B) | runs A / B | effect | p | verdict |\n|---|---|---|---|---|---|");
    for r in out {
        let effect = if r.rate {
            format!("rate difference {:+.3}", r.result.effect)
        } else if r.result.effect.is_finite() {
            format!("A₁₂ = {:.3} ({})", r.result.effect, a12_magnitude(r.result.effect))
        } else {
            "–".into()
        };
        let p = match r.result.p {
            0.0 => "< 1e-15".to_string(),
            p if p.is_finite() => format!("{p:.2e}"),
            _ => "–".into(),
        };
        let _ = writeln!(
            md,
            "| {} | {} | {} / {} | {effect} | {p} | {} |",
            r.claim,
            r.test,
            r.result.n.0,
            r.result.n.1,
            r.result.verdict.text()
        );
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn verdicts_follow_direction_significance_and_size() {
        let low: Vec<f64> = (0..40).map(f64::from).collect();
        let high: Vec<f64> = (20..60).map(f64::from).collect();
        let c = compare(&low, &high, Expect::Lower);
        assert_eq!(c.verdict, Verdict::Holds);
        assert!(c.effect < 0.5 && c.p < 0.05);
        assert_eq!(compare(&low, &high, Expect::Higher).verdict, Verdict::DoesNotHold);
        assert_eq!(compare(&low, &high, Expect::NotLower).verdict, Verdict::DoesNotHold);
        assert_eq!(compare(&high, &low, Expect::NotLower).verdict, Verdict::Holds);
        // Equal groups: no difference; large groups refute a directional claim, small ones
        // cannot tell.
        assert_eq!(compare(&low, &low, Expect::Lower).verdict, Verdict::DoesNotHold);
        assert_eq!(compare(&low[..5], &low[..5], Expect::Lower).verdict, Verdict::CannotSay);
        assert_eq!(compare(&low, &low, Expect::NotLower).verdict, Verdict::Holds);
        assert_eq!(compare(&[], &low, Expect::Lower).verdict, Verdict::CannotSay);
    }

    #[test]
    fn two_proportion_test_by_hand() {
        // 30/100 vs 15/100: pooled 0.225, se = √(0.225·0.775·0.02) = 0.059055, z = 2.5400,
        // p = 2·(1 − Φ(2.54)) = 0.011085.
        let c = compare_rates((30, 100), (15, 100), Expect::Higher);
        assert!((c.effect - 0.15).abs() < 1e-12);
        assert!((c.p - 0.011_085).abs() < 1e-5, "{}", c.p);
        assert_eq!(c.verdict, Verdict::Holds);
        assert_eq!(compare_rates((30, 100), (15, 100), Expect::Lower).verdict, Verdict::DoesNotHold);
        assert_eq!(compare_rates((0, 0), (1, 2), Expect::Lower).verdict, Verdict::CannotSay);
    }
}
