//! What a comparison's design can show (`covga report --compare … --design`): for each family of
//! tests, the smallest p it can reach after its correction, and how many units a comparison
//! needs to show an effect of a given size — within a stratum the seeds, pooled the units of
//! [`super::units`]. Written from the runs a study has, so that a study stopped early (or a
//! small pilot) tells how many seeds, maps or settings the full study needs.

use super::units::Units;
use super::{LEVEL, Metric, Row, p_text};
use crate::stats::Contrast;
use crate::stats::design::{holm_min_p, log_ratio, signed_rank_min_p, unit_effects, units_for_effect, units_to_reach};
use std::fmt::Write as _;

/// Standardised effects (mean over standard deviation of the unit effects) the table plans for:
/// Cohen's small, medium and large, and a very large one.
const EFFECTS: [f64; 4] = [0.2, 0.5, 0.8, 1.2];
/// The probability of showing an effect the table plans for.
const POWER: f64 = 0.8;

/// "n" for a number of units, "–" where none suffices within 64.
fn count(n: Option<usize>) -> String {
    match n {
        Some(n) if n != usize::MAX => n.to_string(),
        _ => "–".into(),
    }
}

/// The standardised effect of unit effects: their mean over their standard deviation (`None`
/// for fewer than two, or no spread).
fn standardised(effects: &[f64]) -> Option<f64> {
    let n = effects.len();
    if n < 2 {
        return None;
    }
    let mean = effects.iter().sum::<f64>() / n as f64;
    let var = effects.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    (var > 0.0).then(|| mean / var.sqrt())
}

/// One level's line: tests in the family, the largest comparison's units, the floors, whether the
/// family can show anything, and the units it needs to reach the level at all and to show each
/// of [`EFFECTS`].
fn level_row(what: &str, tests: usize, units: usize) -> String {
    let alpha = 1.0 - LEVEL;
    let raw = signed_rank_min_p(units);
    let holm = holm_min_p(raw, tests);
    let needed: Vec<String> = EFFECTS.iter().map(|&d| count(units_for_effect(d, alpha, POWER, tests))).collect();
    format!(
        "| {what} | {tests} | {units} | {} | {} | {} | {} | {} |",
        p_text(raw),
        p_text(holm),
        if holm < alpha { "yes" } else { "**no**" },
        count(Some(units_to_reach(alpha, tests))),
        needed.join(" | ")
    )
}

/// The rows of the comparison for one metric column, stratum by stratum.
type RowsOf<'a> = &'a dyn Fn(&str) -> Vec<Row>;

/// The design file of a comparison: `rows_of(metric)` gives each metric's stratum rows (the
/// executable pairs); `units` the pooled units, where the comparison pools.
pub(super) fn text(title: &str, (metrics, rows_of): (&[Metric], RowsOf), units: Option<&Units>) -> String {
    let alpha = 1.0 - LEVEL;
    let mut md = format!("# What {title} can show\n\n");
    let _ = writeln!(
        md,
        "Each family's smallest p is what its largest comparison gives when every unit points one way \
         (exact signed-rank or sign test: 2 · 2⁻ⁿ), multiplied by the family's size (Holm's smallest \
         step). Units needed: to reach p < {alpha:.2} at all, and to show a standardised effect d (the mean \
         of the unit effects over their standard deviation) with probability {POWER:.1} after the \
         correction — the normal approximation divided by the signed-rank test's efficiency 3/π, planned \
         for the family's Bonferroni worst case. Within a stratum the units are seeds (pairs); pooled, the \
         units below.\n"
    );
    if let Some(u) = units {
        let _ = writeln!(md, "{}\n", u.reason);
    }
    let header = EFFECTS.iter().map(|d| format!("d = {d}")).collect::<Vec<_>>().join(" | ");
    let _ = writeln!(
        md,
        "| family | tests | units in its largest comparison | smallest p | after Holm | can show at {alpha:.2} | units to reach {alpha:.2} | {header} |"
    );
    let _ = writeln!(md, "|{}", " --- |".repeat(7 + EFFECTS.len()));
    let mut observed = String::new();
    for m in metrics {
        let rows = rows_of(m.column);
        let with_pairs: Vec<&Row> = rows.iter().filter(|r| !r.pairs.is_empty()).collect();
        let most = with_pairs.iter().map(|r| r.pairs.len()).max().unwrap_or(0);
        let _ = writeln!(md, "{}", level_row(&format!("`{}`, stratum by stratum", m.column), with_pairs.len(), most));
        let Some(u) = units else { continue };
        let contrast: fn(f64, f64) -> f64 = match m.contrast {
            Contrast::MedianDifference => |v, b| v - b,
            Contrast::MedianRatio => log_ratio,
        };
        let mut values: Vec<&str> = Vec::new();
        for r in &rows {
            if !values.contains(&r.value.as_str()) {
                values.push(&r.value);
            }
        }
        let mut most_units = 0;
        for v in &values {
            let pairs: Vec<(String, f64, f64)> = rows
                .iter()
                .filter(|r| r.value == *v)
                .flat_map(|r| {
                    let unit = u.of.get(&r.stratum).cloned().unwrap_or_else(|| r.stratum.clone());
                    r.pairs.iter().map(move |&(b, x)| (unit.clone(), x, b))
                })
                .collect();
            let effects: Vec<f64> =
                unit_effects(&pairs, contrast).into_iter().map(|(_, e)| e).filter(|e| e.is_finite()).collect();
            most_units = most_units.max(effects.len());
            let d = standardised(&effects);
            let _ = writeln!(
                observed,
                "| `{}` | {v} | {} | {} | {} |",
                m.column,
                effects.len(),
                d.map_or("–".into(), |d| format!("{d:+.2}")),
                count(d.and_then(|d| units_for_effect(d.abs(), alpha, POWER, values.len())))
            );
        }
        let _ = writeln!(md, "{}", level_row(&format!("`{}`, pooled", m.column), values.len(), most_units));
    }
    if !observed.is_empty() {
        let plural = units.map_or("units", |u| u.kind.names().1);
        let _ = writeln!(
            md,
            "\nThe effects this study observed, pooled (each unit's effect: the median of its pairs' differences, \
             of their log-ratios for time), and the {plural} a study needs to show an effect of that size:\n"
        );
        let _ = writeln!(
            md,
            "| metric | value | {plural} | observed d | {plural} needed |\n| --- | --- | --- | --- | --- |"
        );
        md.push_str(&observed);
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_standardised_effect_is_the_mean_over_the_standard_deviation() {
        assert_eq!(standardised(&[1.0]), None);
        assert_eq!(standardised(&[1.0, 1.0]), None);
        // Mean 2, sample standard deviation 1.
        assert!((standardised(&[1.0, 2.0, 3.0]).unwrap() - 2.0).abs() < 1e-12);
    }

    #[test]
    fn a_level_row_says_when_a_family_cannot_show_anything() {
        // Ten seeds in each of 126 tests: 2⁻⁹ raw, 0.246 after Holm, 13 seeds to reach 0.05.
        let row = level_row("x", 126, 10);
        assert!(row.starts_with("| x | 126 | 10 | 0.0020 | 0.2461 | **no** | 13 |"), "{row}");
        let row = level_row("x", 1, 8);
        assert!(row.starts_with("| x | 1 | 8 | 0.0078 | 0.0078 | yes | 6 | 206 | 33 | 13 | 6 |"), "{row}");
    }
}
