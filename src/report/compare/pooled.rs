//! The comparisons of [`super`] pooled over the strata. A study with many strata and few
//! seeds per stratum cannot show anything stratum by stratum after the correction; pooled, the
//! question becomes "does the value move the result across the settings", and each pair still
//! differs in the compared parameter only.
//!
//! The units are what varies independently ([`super::units`]): the strata, or the floor plans
//! they stand on. The pair effect is the metric's own contrast within a pair — coverage as the
//! difference `value − baseline`, time as the ratio `value / baseline` (so that a pair on a large
//! map weighs as much as one on a small map) — and a unit's effect the median of its pairs'
//! (of their log-ratios for time). The test is the two-sided Wilcoxon signed-rank test of the
//! unit effects, Holm-corrected over the values' pooled comparisons of the metric; the estimate
//! is the median pair effect with a bootstrap interval that resamples whole units (Davison and
//! Hinkley 1997, §3.8). The pairs themselves are described, not tested.

use super::margin::{MarginStats, margin_stats};
use super::text::{Floor, floor};
use super::units::Units;
use super::{BOOTSTRAP_SEED, Comparison, LEVEL, Metric, RESAMPLES, Row, p_text};
use crate::stats::design::{cluster_bootstrap_ci, log_ratio};
use crate::stats::{Contrast, Family, Interval, SignedRank, wilcoxon_signed_rank};
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// `(baseline, value)` of each pair of one unit, by unit label.
type UnitPairs = BTreeMap<String, Vec<(f64, f64)>>;
/// A pair's effect from `(baseline, value)`.
type PairEffect = fn(f64, f64) -> f64;

/// The pairs of every stratum for one value, by unit.
pub(super) struct Pooled {
    pub(super) value: String,
    strata: usize,
    /// Every pair of every stratum (the description's).
    row: Row,
    /// The pairs of each unit that has any, in the units' order.
    pub(super) by_unit: Vec<Vec<(f64, f64)>>,
    /// Those units' labels, in the same order.
    pub(super) unit_names: Vec<String>,
}

impl Pooled {
    pub(super) fn lead_csv(&self, metric: &str, units: &Units) -> String {
        self.row.lead_csv(metric, units.kind.names().0, self.by_unit.len())
    }
}

/// Pools `rows` (stratum by stratum, each value against the baseline) by value, in the order
/// the values first appear, and by `units` within each value.
pub(super) fn pool(rows: &[Row], units: &Units) -> Vec<Pooled> {
    let mut out: Vec<(Pooled, UnitPairs)> = Vec::new();
    for r in rows {
        let at = match out.iter().position(|(p, _)| p.value == r.value) {
            Some(i) => i,
            None => {
                let row = Row {
                    stratum: "pooled".into(),
                    value: r.value.clone(),
                    runs: (0, 0),
                    executable: (0, 0),
                    pairs: Vec::new(),
                };
                let pooled =
                    Pooled { value: r.value.clone(), strata: 0, row, by_unit: Vec::new(), unit_names: Vec::new() };
                out.push((pooled, BTreeMap::new()));
                out.len() - 1
            }
        };
        let (p, by_unit) = &mut out[at];
        p.strata += 1;
        p.row.runs = (p.row.runs.0 + r.runs.0, p.row.runs.1 + r.runs.1);
        p.row.executable = (p.row.executable.0 + r.executable.0, p.row.executable.1 + r.executable.1);
        p.row.pairs.extend_from_slice(&r.pairs);
        if !r.pairs.is_empty() {
            let unit = units.of.get(&r.stratum).cloned().unwrap_or_else(|| r.stratum.clone());
            by_unit.entry(unit).or_default().extend_from_slice(&r.pairs);
        }
    }
    out.into_iter()
        .map(|(mut p, by_unit)| {
            p.unit_names = by_unit.keys().cloned().collect();
            p.by_unit = by_unit.into_values().collect();
            p
        })
        .collect()
}

/// "1 value", "2 values": how many values a family compares.
pub(super) fn values(pooled: &[Pooled]) -> String {
    match pooled.len() {
        1 => "1 value".into(),
        n => format!("{n} values"),
    }
}

/// The signed-rank test of unit effects against zero.
fn test_units(effects: &[f64]) -> Option<SignedRank> {
    wilcoxon_signed_rank(effects, &vec![0.0; effects.len()])
}

/// The finding of a pooled row: `holm` its adjusted p (none when not tested), `direction` the
/// words for a shown effect, `floor` its family's.
fn finding(
    (pairs, units): (usize, usize),
    holm: Option<f64>,
    untested: &str,
    direction: String,
    floor: Option<&Floor>,
) -> String {
    let alpha = 1.0 - LEVEL;
    match holm {
        _ if pairs == 0 => "no pair: not compared".to_string(),
        None => untested.to_string(),
        Some(h) if h < alpha => format!("{direction} (shown)"),
        Some(_) if floor.is_some_and(|f| !f.reachable) => "cannot show by design".to_string(),
        Some(_) if crate::stats::design::signed_rank_min_p(units) >= alpha => {
            format!("not shown: {units} units cannot reach p < {alpha:.2}")
        }
        Some(_) => "not shown".to_string(),
    }
}

/// The executable plans of each value against the baseline's, pooled: each unit's effect is the
/// share of the value's plans that are executable minus the baseline's, over the unit's pairs,
/// tested over the units. `pooled` pairs hold 1 or 0. A value whose plans are executable by
/// construction (`built` gives why) is stated, not tested.
pub(super) fn executability(
    md: &mut String,
    csv: &mut String,
    pooled: &[Pooled],
    (cmp, units): (&Comparison, &Units),
    built: &dyn Fn(&str) -> Option<&'static str>,
) {
    let (_, unit_plural) = units.kind.names();
    let mut family = Family::new(format!(
        "executability pooled over the {unit_plural} ({} against `{}`)",
        values(pooled),
        cmp.baseline
    ));
    let share = |pairs: &[(f64, f64)]| {
        let n = pairs.len() as f64;
        pairs.iter().map(|(b, v)| v - b).sum::<f64>() / n
    };
    let effects: Vec<Vec<f64>> = pooled.iter().map(|p| p.by_unit.iter().map(|u| share(u)).collect()).collect();
    let tests: Vec<Option<SignedRank>> = pooled
        .iter()
        .zip(&effects)
        .map(|(p, e)| if built(&p.value).is_some() || built(&cmp.baseline).is_some() { None } else { test_units(e) })
        .collect();
    for (p, t) in pooled.iter().zip(&tests) {
        if let Some(t) = t {
            family.push(p.value.clone(), t.p_value);
        }
    }
    let best = pooled.iter().zip(&tests).filter(|(_, t)| t.is_some()).map(|(p, _)| p.by_unit.len()).max();
    let floor = best.and_then(|n| floor(&family, n, unit_plural));
    let mut adjusted = family.adjusted().into_iter();
    let _ = writeln!(md, "## Executable plans, pooled over the {unit_plural}\n");
    let _ = writeln!(
        md,
        "| value | {unit_plural} | pairs | executable (baseline, value) | only the value's executable | only the baseline's executable | {unit_plural} more often executable | less often | p (signed-rank over {unit_plural}) | p (Holm) | finding |"
    );
    let _ = writeln!(md, "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    for ((p, t), e) in pooled.iter().zip(&tests).zip(&effects) {
        let gained = p.row.pairs.iter().filter(|(b, v)| v > b).count();
        let lost = p.row.pairs.iter().filter(|(b, v)| v < b).count();
        let (more, less) = (e.iter().filter(|&&x| x > 0.0).count(), e.iter().filter(|&&x| x < 0.0).count());
        let holm = t.map(|_| adjusted.next().expect("one adjusted p per test"));
        let untested = match built(&p.value).or(built(&cmp.baseline)) {
            Some(why) => format!("executable by construction ({why}): stated, not tested"),
            None => "the same in every unit: not tested".to_string(),
        };
        let direction = format!("{} often executable than {}", if more > less { "more" } else { "less" }, cmp.baseline);
        let finding = finding((p.row.pairs.len(), p.by_unit.len()), holm, &untested, direction, floor.as_ref());
        let r = &p.row;
        let _ = writeln!(
            md,
            "| {} | {} | {} | {}/{}, {}/{} | {gained} | {lost} | {more} | {less} | {} | {} | {finding} |",
            p.value,
            p.by_unit.len(),
            r.pairs.len(),
            r.executable.0,
            r.runs.0,
            r.executable.1,
            r.runs.1,
            t.map_or("–".into(), |t| format!("{} ({})", p_text(t.p_value), t.method.name())),
            holm.map_or("–".into(), p_text),
        );
        let field = |x: Option<f64>| x.map_or(String::new(), |x| format!("{x}"));
        let _ = writeln!(
            csv,
            "{},,,share difference,,,,{more},{less},,{},{},{},{},{}",
            p.lead_csv("executable", units),
            t.map_or(String::new(), |t| format!("wilcoxon {}", t.method.name())),
            field(t.map(|t| t.p_value)),
            field(holm),
            field(floor.as_ref().map(|f| f.p)),
            super::quoted(&finding),
        );
    }
    let _ = writeln!(md, "\n{}{}\n", family.statement(), floor.map_or(String::new(), |f| format!(" {}", f.sentence)));
}

/// One pooled comparison's numbers.
struct PooledStats {
    /// Pairs better and worse (described).
    pairs_better: usize,
    pairs_worse: usize,
    /// Units better and worse (tested).
    better: usize,
    worse: usize,
    ci: Option<Interval>,
    test: Option<SignedRank>,
    /// For time, the unit ratios against [`MARGIN`].
    margin: Option<MarginStats>,
}

/// The pair effects and their interval (units resampled), and the signed-rank test of the unit
/// effects of `p` for `m`.
fn pooled_stats(m: &Metric, p: &Pooled) -> PooledStats {
    let oriented = |b: f64, v: f64| if m.higher_is_better { v.total_cmp(&b) } else { b.total_cmp(&v) };
    let pairs_better = p.row.pairs.iter().filter(|(b, v)| oriented(*b, *v).is_gt()).count();
    let pairs_worse = p.row.pairs.iter().filter(|(b, v)| oriented(*b, *v).is_lt()).count();
    // A ratio needs two positive values; a pair with a zero or negative time has none.
    let usable = |&(b, v): &(f64, f64)| m.contrast == Contrast::MedianDifference || (b > 0.0 && v > 0.0);
    let (pair_effect, unit_scale): (PairEffect, PairEffect) = match m.contrast {
        Contrast::MedianDifference => (|b, v| v - b, |b, v| v - b),
        Contrast::MedianRatio => (|b, v| v / b, |b, v| log_ratio(v, b)),
    };
    let clusters: Vec<Vec<f64>> = p
        .by_unit
        .iter()
        .map(|u| u.iter().filter(|x| usable(x)).map(|&(b, v)| pair_effect(b, v)).collect::<Vec<f64>>())
        .filter(|c| !c.is_empty())
        .collect();
    let effects: Vec<f64> = p
        .by_unit
        .iter()
        .filter_map(|u| {
            let mut e: Vec<f64> = u.iter().filter(|x| usable(x)).map(|&(b, v)| unit_scale(b, v)).collect();
            (!e.is_empty()).then(|| crate::stats::median(&mut e))
        })
        .collect();
    let sign = if m.higher_is_better { 1.0 } else { -1.0 };
    PooledStats {
        pairs_better,
        pairs_worse,
        better: effects.iter().filter(|&&e| sign * e > 0.0).count(),
        worse: effects.iter().filter(|&&e| sign * e < 0.0).count(),
        ci: cluster_bootstrap_ci(&clusters, crate::stats::median, LEVEL, RESAMPLES, BOOTSTRAP_SEED),
        test: test_units(&effects),
        margin: (m.contrast == Contrast::MedianRatio).then(|| margin_stats(&effects)).flatten(),
    }
}

/// The CSV row of pooled comparison `p` of metric `m`: its numbers `s`, its Holm-adjusted p, its
/// family's floor and its finding.
fn csv_row(
    m: &Metric,
    p: &Pooled,
    s: &PooledStats,
    units: &Units,
    (holm, floor, finding): (Option<f64>, Option<&Floor>, &str),
) -> String {
    let field = |x: Option<f64>| x.map_or(String::new(), |x| format!("{x}"));
    format!(
        "{},,,{},{},{},{},{},{},,{},{},{},{},{}",
        p.lead_csv(m.column, units),
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
        field(floor.map(|f| f.p)),
        super::quoted(finding),
    )
}

/// The pooled table and findings of one metric.
pub(super) fn section(
    md: &mut String,
    csv: &mut String,
    m: &Metric,
    pooled: &[Pooled],
    (cmp, units): (&Comparison, &Units),
) {
    let (_, unit_plural) = units.kind.names();
    let stats: Vec<PooledStats> = pooled.iter().map(|p| pooled_stats(m, p)).collect();
    let mut family = Family::new(format!(
        "`{}` pooled over the {unit_plural} ({} against `{}`)",
        m.column,
        values(pooled),
        cmp.baseline
    ));
    for (p, s) in pooled.iter().zip(&stats) {
        if let Some(t) = s.test {
            family.push(p.value.clone(), t.p_value);
        }
    }
    let best = pooled.iter().zip(&stats).filter(|(_, s)| s.test.is_some()).map(|(p, _)| p.by_unit.len()).max();
    let floor = best.and_then(|n| floor(&family, n, unit_plural));
    let mut adjusted = family.adjusted().into_iter();
    let effect = match m.contrast {
        Contrast::MedianDifference => "median pair difference",
        Contrast::MedianRatio => "median pair ratio",
    };
    let _ = writeln!(md, "## `{}`, pooled over the {unit_plural}\n", m.column);
    let _ = writeln!(
        md,
        "| value | {unit_plural} | pairs | {effect} [{:.0} % CI, {unit_plural} resampled] | pairs better | worse | {unit_plural} better | worse | p (signed-rank over {unit_plural}) | p (Holm) | finding |",
        LEVEL * 100.0
    );
    let _ = writeln!(md, "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    for (p, s) in pooled.iter().zip(&stats) {
        let holm = s.test.map(|_| adjusted.next().expect("one adjusted p per test"));
        let direction = format!("{} than {}", if s.better > s.worse { "better" } else { "worse" }, cmp.baseline);
        let finding = finding(
            (p.row.pairs.len(), p.by_unit.len()),
            holm,
            "equal in every unit: not tested",
            direction,
            floor.as_ref(),
        );
        let ci_text = match (s.ci, m.contrast) {
            (Some(c), Contrast::MedianRatio) => format!("{:.3}× [{:.3}, {:.3}]", c.estimate, c.low, c.high),
            (Some(c), Contrast::MedianDifference) => format!("{:+.4} [{:+.4}, {:+.4}]", c.estimate, c.low, c.high),
            (None, _) => "–".into(),
        };
        let _ = writeln!(
            md,
            "| {} | {} | {} | {ci_text} | {} | {} | {} | {} | {} | {} | {finding} |",
            p.value,
            p.by_unit.len(),
            p.row.pairs.len(),
            s.pairs_better,
            s.pairs_worse,
            s.better,
            s.worse,
            s.test.map_or("–".into(), |t| format!("{} ({})", p_text(t.p_value), t.method.name())),
            holm.map_or("–".into(), p_text),
        );
        let _ = writeln!(csv, "{}", csv_row(m, p, s, units, (holm, floor.as_ref(), &finding)));
    }
    let _ = writeln!(md, "\n{}{}\n", family.statement(), floor.map_or(String::new(), |f| format!(" {}", f.sentence)));
    if stats.iter().any(|s| s.margin.is_some()) {
        let margins: Vec<Option<MarginStats>> = stats.iter().map(|s| s.margin).collect();
        super::margin::section(md, csv, m, (pooled, &margins), (cmp, units));
    }
}
