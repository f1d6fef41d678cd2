//! The comparisons of [`super`] pooled over the strata: every pair of every stratum, as one
//! sample of pair effects per value. A study with many strata and few seeds per stratum (a
//! slice of Table 4.3 with five seeds) cannot show anything stratum by stratum after the
//! correction; pooled, the question becomes "does the value move the result, whatever the
//! other parameters are", and each pair still differs in the compared parameter only.
//!
//! The pair effect is the metric's own contrast taken pair by pair: coverage as the difference
//! `value − baseline`, time as the ratio `value / baseline`, so that a pair on a large map
//! weighs as much as one on a small map. The estimate is the median pair effect with a paired
//! bootstrap interval; the test is the two-sided Wilcoxon signed-rank test of the differences
//! (of the log-ratios for time, a test of ratios about 1), Holm-corrected over the values'
//! pooled comparisons of the metric: a family of its own, apart from the strata's.

use super::{BOOTSTRAP_SEED, Comparison, LEVEL, Metric, RESAMPLES, Row, p_text};
use crate::stats::{Contrast, Family, Interval, SignedRank, bootstrap_ci, sign_test, wilcoxon_signed_rank};
use std::fmt::Write as _;

/// The pairs of every stratum for one value.
pub(super) struct Pooled {
    value: String,
    strata: usize,
    row: Row,
}

/// Pools `rows` (stratum by stratum, each value against the baseline) by value, in the order
/// the values first appear.
pub(super) fn pool(rows: &[Row]) -> Vec<Pooled> {
    let mut out: Vec<Pooled> = Vec::new();
    for r in rows {
        let at = match out.iter().position(|p| p.value == r.value) {
            Some(i) => i,
            None => {
                let row = Row {
                    stratum: "pooled".into(),
                    value: r.value.clone(),
                    runs: (0, 0),
                    executable: (0, 0),
                    pairs: Vec::new(),
                };
                out.push(Pooled { value: r.value.clone(), strata: 0, row });
                out.len() - 1
            }
        };
        let p = &mut out[at];
        p.strata += 1;
        p.row.runs = (p.row.runs.0 + r.runs.0, p.row.runs.1 + r.runs.1);
        p.row.executable = (p.row.executable.0 + r.executable.0, p.row.executable.1 + r.executable.1);
        p.row.pairs.extend_from_slice(&r.pairs);
    }
    out
}

/// "1 value", "2 values": how many values a family compares.
fn values(pooled: &[Pooled]) -> String {
    match pooled.len() {
        1 => "1 value".into(),
        n => format!("{n} values"),
    }
}

/// The executable plans of each value against the baseline's over every stratum's pairs: the
/// exact McNemar (sign) test of the discordant pairs. `pooled` pairs hold 1 or 0.
pub(super) fn executability(md: &mut String, csv: &mut String, pooled: &[Pooled], cmp: &Comparison) {
    let mut family =
        Family::new(format!("executability pooled over the strata ({} against `{}`)", values(pooled), cmp.baseline));
    let split = |p: &Pooled| {
        let gained = p.row.pairs.iter().filter(|(b, v)| v > b).count();
        let lost = p.row.pairs.iter().filter(|(b, v)| v < b).count();
        (gained, lost)
    };
    let tests: Vec<Option<f64>> = pooled
        .iter()
        .map(|p| {
            let (gained, lost) = split(p);
            let signs: Vec<f64> = std::iter::repeat_n(1.0, gained).chain(std::iter::repeat_n(-1.0, lost)).collect();
            sign_test(&signs, 0.0)
        })
        .collect();
    for (p, t) in pooled.iter().zip(&tests) {
        if let Some(t) = t {
            family.push(p.value.clone(), *t);
        }
    }
    let mut adjusted = family.adjusted().into_iter();
    let _ = writeln!(md, "## Executable plans, pooled over the strata\n");
    let _ = writeln!(
        md,
        "| value | strata | executable (baseline, value) | pairs | only the value's executable | only the baseline's executable | p (exact McNemar) | p (Holm) | finding |"
    );
    let _ = writeln!(md, "| --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    for (p, t) in pooled.iter().zip(&tests) {
        let (gained, lost) = split(p);
        let holm = t.map(|_| adjusted.next().expect("one adjusted p per test"));
        let finding = match holm {
            _ if p.row.pairs.is_empty() => "no pair: not compared".to_string(),
            None => "the same in every pair: not tested".to_string(),
            Some(h) if h < 1.0 - LEVEL => format!(
                "{} often executable than {} (shown)",
                if gained > lost { "more" } else { "less" },
                cmp.baseline
            ),
            Some(_) => "not shown".to_string(),
        };
        let r = &p.row;
        let _ = writeln!(
            md,
            "| {} | {} | {}/{}, {}/{} | {} | {gained} | {lost} | {} | {} | {finding} |",
            p.value,
            p.strata,
            r.executable.0,
            r.runs.0,
            r.executable.1,
            r.runs.1,
            r.pairs.len(),
            t.map_or("–".into(), p_text),
            holm.map_or("–".into(), p_text),
        );
        let field = |x: Option<f64>| x.map_or(String::new(), |x| format!("{x}"));
        let _ = writeln!(
            csv,
            "{},,,,,,,{gained},{lost},,{},{},{},{}",
            r.lead_csv("executable"),
            if t.is_some() { "mcnemar exact" } else { "" },
            field(*t),
            field(holm),
            super::quoted(&finding),
        );
    }
    let _ = writeln!(md, "\n{}\n", family.statement());
}

/// One pooled comparison's numbers.
struct PooledStats {
    better: usize,
    worse: usize,
    ci: Option<Interval>,
    test: Option<SignedRank>,
}

/// The pair effects, the interval of their median and the signed-rank test of `p` for `m`.
fn pooled_stats(m: &Metric, p: &Pooled) -> PooledStats {
    let pairs = &p.row.pairs;
    let better = pairs.iter().filter(|(b, v)| if m.higher_is_better { v > b } else { v < b }).count();
    let worse = pairs.iter().filter(|(b, v)| if m.higher_is_better { v < b } else { v > b }).count();
    let (ci, test) = match m.contrast {
        Contrast::MedianDifference => {
            let d: Vec<f64> = pairs.iter().map(|(b, v)| v - b).collect();
            let zeros = vec![0.0; d.len()];
            let (b, v): (Vec<f64>, Vec<f64>) = pairs.iter().copied().unzip();
            (
                bootstrap_ci(&d, &zeros, Contrast::MedianDifference, true, LEVEL, RESAMPLES, BOOTSTRAP_SEED),
                wilcoxon_signed_rank(&v, &b),
            )
        }
        Contrast::MedianRatio => {
            // A ratio needs two positive values; a pair with a zero or negative time has none.
            let positive: Vec<(f64, f64)> = pairs.iter().copied().filter(|&(b, v)| b > 0.0 && v > 0.0).collect();
            let ratios: Vec<f64> = positive.iter().map(|(b, v)| v / b).collect();
            let ones = vec![1.0; ratios.len()];
            let (lb, lv): (Vec<f64>, Vec<f64>) = positive.iter().map(|(b, v)| (b.ln(), v.ln())).unzip();
            (
                bootstrap_ci(&ratios, &ones, Contrast::MedianRatio, true, LEVEL, RESAMPLES, BOOTSTRAP_SEED),
                wilcoxon_signed_rank(&lv, &lb),
            )
        }
    };
    PooledStats { better, worse, ci, test }
}

/// The pooled table and findings of one metric.
pub(super) fn section(md: &mut String, csv: &mut String, m: &Metric, pooled: &[Pooled], cmp: &Comparison) {
    let stats: Vec<PooledStats> = pooled.iter().map(|p| pooled_stats(m, p)).collect();
    let mut family =
        Family::new(format!("`{}` pooled over the strata ({} against `{}`)", m.column, values(pooled), cmp.baseline));
    for (p, s) in pooled.iter().zip(&stats) {
        if let Some(t) = s.test {
            family.push(p.value.clone(), t.p_value);
        }
    }
    let mut adjusted = family.adjusted().into_iter();
    let effect = match m.contrast {
        Contrast::MedianDifference => "median pair difference",
        Contrast::MedianRatio => "median pair ratio",
    };
    let _ = writeln!(md, "## `{}`, pooled over the strata\n", m.column);
    let _ = writeln!(
        md,
        "| value | strata | pairs | {effect} [{:.0} % CI] | value better in | worse in | p | p (Holm) | finding |",
        LEVEL * 100.0
    );
    let _ = writeln!(md, "| --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    for (p, s) in pooled.iter().zip(&stats) {
        let holm = s.test.map(|_| adjusted.next().expect("one adjusted p per test"));
        let finding = match holm {
            _ if p.row.pairs.is_empty() => "no pair: not compared".to_string(),
            None => "equal in every pair: not tested".to_string(),
            Some(h) if h < 1.0 - LEVEL => {
                format!("{} than {} (shown)", if s.better > s.worse { "better" } else { "worse" }, cmp.baseline)
            }
            Some(_) => "not shown".to_string(),
        };
        let ci_text = match (s.ci, m.contrast) {
            (Some(c), Contrast::MedianRatio) => format!("{:.3}× [{:.3}, {:.3}]", c.estimate, c.low, c.high),
            (Some(c), Contrast::MedianDifference) => format!("{:+.4} [{:+.4}, {:+.4}]", c.estimate, c.low, c.high),
            (None, _) => "–".into(),
        };
        let _ = writeln!(
            md,
            "| {} | {} | {} | {ci_text} | {} | {} | {} | {} | {finding} |",
            p.value,
            p.strata,
            p.row.pairs.len(),
            s.better,
            s.worse,
            s.test.map_or("–".into(), |t| format!("{} ({})", p_text(t.p_value), t.method.name())),
            holm.map_or("–".into(), p_text),
        );
        let field = |x: Option<f64>| x.map_or(String::new(), |x| format!("{x}"));
        let _ = writeln!(
            csv,
            "{},,,{},{},{},{},{},{},,{},{},{},{}",
            p.row.lead_csv(m.column),
            match m.contrast {
                Contrast::MedianDifference => "pair difference",
                Contrast::MedianRatio => "pair ratio",
            },
            field(s.ci.map(|c| c.estimate)),
            field(s.ci.map(|c| c.low)),
            field(s.ci.map(|c| c.high)),
            s.better,
            s.worse,
            s.test.map_or(String::new(), |t| format!("wilcoxon {}", t.method.name())),
            field(s.test.map(|t| t.p_value)),
            field(holm),
            super::quoted(&finding),
        );
    }
    let _ = writeln!(md, "\n{}\n", family.statement());
}
