//! The forest plot of a pooled time comparison ([`crate::report::figures::forest`]): each
//! compared value's units with their ratios, the pooled median with the bootstrap interval
//! the margin table gives, the units' mean and the margin, from the same pairs.

use super::margin::MARGIN;
use super::pooled::Pooled;
use super::units::Units;
use super::{BOOTSTRAP_SEED, Comparison, LEVEL, Metric, RESAMPLES};
use crate::report::figures::forest::{ForestFigure, ForestPanel, ForestRow};
use crate::stats::design::cluster_bootstrap_ci;

/// The margin as the comparison's text names it.
pub(super) const MARGIN_TEXT: &str = "0.95";

/// A unit's label as a row names it: the floor plan's file stem, other parts by their last key
/// name (`map.source=experiments/maps/basement.yaml, robot.rot_speed=0.52` → `basement,
/// rot_speed=0.52`).
fn short_unit(label: &str) -> String {
    let part = |p: &str| match p.split_once('=') {
        Some(("map.source", v)) => {
            let file = v.rsplit('/').next().unwrap_or(v);
            file.rsplit_once('.').map_or(file, |(stem, _)| stem).to_string()
        }
        Some((k, v)) => format!("{}={v}", k.rsplit('.').next().unwrap_or(k)),
        None => p.to_string(),
    };
    label.split(", ").map(part).collect::<Vec<_>>().join(", ")
}

/// One value's panel: its units' ratios (each the exponential of the median log-ratio of its
/// pairs with positive times) and their pooled statistics; `None` without a unit.
fn panel(p: &Pooled, cmp: &Comparison, m: &Metric) -> Option<ForestPanel> {
    let mut rows = Vec::new();
    for (name, pairs) in p.unit_names.iter().zip(&p.by_unit) {
        let mut ratios: Vec<f64> = pairs.iter().filter(|(b, v)| *b > 0.0 && *v > 0.0).map(|(b, v)| v / b).collect();
        if ratios.is_empty() {
            continue;
        }
        let mut logs: Vec<f64> = ratios.iter().map(|r| r.ln()).collect();
        let ratio = crate::stats::median(&mut logs).exp();
        ratios.sort_by(f64::total_cmp);
        rows.push(ForestRow { name: short_unit(name), ratio, low: ratios[0], high: ratios[ratios.len() - 1] });
    }
    let singletons: Vec<Vec<f64>> = rows.iter().map(|r| vec![r.ratio]).collect();
    let median = cluster_bootstrap_ci(&singletons, crate::stats::median, LEVEL, RESAMPLES, BOOTSTRAP_SEED)?;
    let mean = rows.iter().map(|r| r.ratio).sum::<f64>() / rows.len() as f64;
    let title = format!("{}={} against {}: {}", cmp.key, p.value, cmp.baseline, m.column);
    Some(ForestPanel { title, rows, mean, median, margin: MARGIN })
}

/// The forest plot of the pooled comparisons `pooled` of time metric `m`; `None` where no
/// value has a unit with a ratio.
pub(super) fn figure(pooled: &[Pooled], units: &Units, cmp: &Comparison, m: &Metric) -> Option<ForestFigure> {
    let panels: Vec<ForestPanel> = pooled.iter().filter_map(|p| panel(p, cmp, m)).collect();
    (!panels.is_empty()).then(|| ForestFigure { panels, unit: units.kind.names().0.to_string() })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_unit_is_named_by_its_floor_plan_and_its_other_settings() {
        assert_eq!(short_unit("map.source=experiments/maps/generated/house-1.yaml"), "house-1");
        assert_eq!(short_unit("map.source=basement.yaml, robot.rot_speed=0.52"), "basement, rot_speed=0.52");
    }
}
