//! The margin of a pooled time comparison ([`super::pooled`]): is the value at least 5 %
//! faster? The units' ratios (each the exponential of its median log-ratio) described by their
//! mean and median with a bootstrap interval over the units, and tested against [`MARGIN`] with
//! the one-sided signed-rank test ([`crate::stats::margin`]), Holm over the values; beside it,
//! the test of any difference with Pratt's handling of ties, the sensitivity line of the rule the
//! comparisons use (Wilcoxon's: ties dropped).

use super::pooled::{Pooled, values};
use super::units::Units;
use super::{BOOTSTRAP_SEED, Comparison, LEVEL, Metric, RESAMPLES, p_text};
use crate::stats::design::cluster_bootstrap_ci;
use crate::stats::{Family, Interval};
use std::fmt::Write as _;

/// The margin a time comparison tests: "at least 5 % faster" is a unit ratio below 0.95.
pub(super) const MARGIN: f64 = 0.95;

/// A time comparison's margin: the units' ratios described and tested against [`MARGIN`].
#[derive(Clone, Copy)]
pub(super) struct MarginStats {
    /// Mean of the unit ratios.
    mean: f64,
    /// Median of the unit ratios with its bootstrap interval over the units.
    median: Interval,
    /// Units below the margin, and at or above it.
    below: usize,
    above: usize,
    /// One-sided signed-rank p of the unit ratios against the margin (zeros dropped).
    p: Option<f64>,
    /// The test of any difference with Pratt's handling of zeros (the sensitivity line).
    p_pratt: Option<f64>,
}

/// The margin of the unit effects `effects` (log-ratios): `None` without one.
pub(super) fn margin_stats(effects: &[f64]) -> Option<MarginStats> {
    use crate::stats::margin::{Tail, Zeros, below_margin, signed_rank_p};
    let ratios: Vec<f64> = effects.iter().map(|e| e.exp()).collect();
    if ratios.is_empty() {
        return None;
    }
    let singletons: Vec<Vec<f64>> = ratios.iter().map(|&r| vec![r]).collect();
    let median = cluster_bootstrap_ci(&singletons, crate::stats::median, LEVEL, RESAMPLES, BOOTSTRAP_SEED)?;
    Some(MarginStats {
        mean: ratios.iter().sum::<f64>() / ratios.len() as f64,
        median,
        below: ratios.iter().filter(|&&r| r < MARGIN).count(),
        above: ratios.iter().filter(|&&r| r >= MARGIN).count(),
        p: below_margin(&ratios, MARGIN),
        p_pratt: signed_rank_p(effects, Zeros::Pratt, Tail::Both),
    })
}

/// The margin table's heading, the paragraph on how it is made and the table's header row.
fn heading(md: &mut String, m: &Metric, units: &Units) {
    let (_, unit_plural) = units.kind.names();
    let _ = writeln!(
        md,
        "## `{}` against a margin of {:.0} %, pooled over the {unit_plural}\n",
        m.column,
        (1.0 - MARGIN) * 100.0
    );
    let _ = writeln!(
        md,
        "Is the value at least {:.0} % faster? Each {}'s ratio is the exponential of its effect above (the median \
         log-ratio of its pairs); the test is the one-sided signed-rank test that the ratios lie below {MARGIN} \
         (zeros dropped, Wilcoxon's rule), Holm over the values. Beside it, the two-sided test of any difference \
         above with Pratt's handling of zeros (ties ranked, then dropped), as a sensitivity line: a finding that \
         rests on the ties a design builds in (a search seeded with its control's plan returns it) moves with it.\n",
        (1.0 - MARGIN) * 100.0,
        units.kind.names().0
    );
    let _ = writeln!(
        md,
        "| value | {unit_plural} | mean ratio | median ratio [{:.0} % CI, {unit_plural} resampled] | below {MARGIN} | at or above | p (ratio < {MARGIN}, one-sided) | p (Holm) | finding | p (any difference, Pratt's zeros) |",
        LEVEL * 100.0
    );
    let _ = writeln!(md, "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
}

/// The margin table of a time comparison: per value, the mean and median unit ratio with its
/// interval over the units, the one-sided test of the ratio against [`MARGIN`] (Holm over the
/// values) and, as the sensitivity line of the test of any difference, its p with Pratt's
/// handling of zeros.
pub(super) fn section(
    md: &mut String,
    csv: &mut String,
    m: &Metric,
    (pooled, margins): (&[Pooled], &[Option<MarginStats>]),
    (cmp, units): (&Comparison, &Units),
) {
    let (_, unit_plural) = units.kind.names();
    let mut family = Family::new(format!(
        "`{}` against the margin {MARGIN} over the {unit_plural} ({} against `{}`)",
        m.column,
        values(pooled),
        cmp.baseline
    ));
    for (p, g) in pooled.iter().zip(margins) {
        if let Some(x) = g.and_then(|g| g.p) {
            family.push(p.value.clone(), x);
        }
    }
    let mut adjusted = family.adjusted().into_iter();
    heading(md, m, units);
    let field = |x: Option<f64>| x.map_or(String::new(), |x| format!("{x}"));
    for (p, g) in pooled.iter().zip(margins) {
        let Some(g) = *g else { continue };
        let holm = g.p.map(|_| adjusted.next().expect("one adjusted p per test"));
        let finding = match holm {
            Some(h) if h < 1.0 - LEVEL => format!("at least {:.0} % faster (shown)", (1.0 - MARGIN) * 100.0),
            Some(_) => format!("not shown at least {:.0} % faster", (1.0 - MARGIN) * 100.0),
            None => "no unit: not tested".to_string(),
        };
        let _ = writeln!(
            md,
            "| {} | {} | {:.3}× | {:.3}× [{:.3}, {:.3}] | {} | {} | {} | {} | {finding} | {} |",
            p.value,
            p.by_unit.len(),
            g.mean,
            g.median.estimate,
            g.median.low,
            g.median.high,
            g.below,
            g.above,
            g.p.map_or("–".into(), p_text),
            holm.map_or("–".into(), p_text),
            g.p_pratt.map_or("–".into(), p_text),
        );
        let note = format!(
            "{finding}; mean unit ratio {:.3}; any difference with Pratt's zeros p {}",
            g.mean,
            g.p_pratt.map_or("–".into(), p_text)
        );
        let _ = writeln!(
            csv,
            "{},,,unit ratio against {MARGIN},{},{},{},{},{},,wilcoxon one-sided,{},{},,{}",
            p.lead_csv(&format!("{} margin", m.column), units),
            g.median.estimate,
            g.median.low,
            g.median.high,
            g.below,
            g.above,
            field(g.p),
            field(holm),
            super::quoted(&note),
        );
    }
    let _ = writeln!(md, "\n{}\n", family.statement());
}
