//! The best plan of a set on the common scorer's measures: the one covering most, where a plan
//! within [`COVERAGE_TIE`] of that coverage is as good and the fastest of those wins (a planner
//! that covers 0.1 % more in twice the time is not the better one). The study's best runs, the
//! tables' best configurations and the planner comparison's best paths all pick by it.

use crate::cell_order::controls::COVERAGE_TIE;

/// The common scorer's coverage column.
pub const COVERAGE: &str = "cov_final_reach";
/// The common scorer's mission-time column, in seconds.
pub const TIME: &str = "time_s";

/// The best of `items` by coverage and time: the fastest of those within [`COVERAGE_TIE`] of
/// the highest coverage, the first of equals; `None` when no item has a finite coverage and
/// time.
pub fn best_by_coverage_then_time<T: Copy>(items: &[T], measures: impl Fn(T) -> (f64, f64)) -> Option<T> {
    let finite: Vec<(T, f64, f64)> = items
        .iter()
        .map(|&i| {
            let (c, t) = measures(i);
            (i, c, t)
        })
        .filter(|(_, c, t)| c.is_finite() && t.is_finite())
        .collect();
    let top = finite.iter().map(|x| x.1).fold(f64::NEG_INFINITY, f64::max);
    finite
        .iter()
        .filter(|x| x.1 >= top - COVERAGE_TIE)
        .fold(None, |best: Option<&(T, f64, f64)>, x| match best {
            Some(b) if b.2 <= x.2 => Some(b),
            _ => Some(x),
        })
        .map(|x| x.0)
}

/// The rule [`best_by_coverage_then_time`] applies, in words for a table's heading.
pub fn rule_in_words() -> String {
    format!("highest {COVERAGE}; of those within {COVERAGE_TIE} of it, the shortest {TIME}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_best_plan_covers_most_and_of_near_equals_is_fastest() {
        // (coverage, time) per item, and the best.
        type Case<'a> = (&'a [(f64, f64)], Option<usize>);
        let cases: &[Case] = &[
            (&[], None),
            (&[(f64::NAN, 1.0)], None),
            // More coverage beyond the tie wins however slow.
            (&[(0.90, 100.0), (0.95, 900.0)], Some(1)),
            // Within the tie the faster wins, even with a little less coverage.
            (&[(0.950, 900.0), (0.947, 400.0)], Some(1)),
            // Just outside the tie: coverage decides.
            (&[(0.950, 900.0), (0.944, 400.0)], Some(0)),
            // Equal plans: the first.
            (&[(0.9, 5.0), (0.9, 5.0)], Some(0)),
            // A plan without a time is no candidate.
            (&[(0.99, f64::NAN), (0.9, 5.0)], Some(1)),
        ];
        for (items, want) in cases {
            let idx: Vec<usize> = (0..items.len()).collect();
            assert_eq!(best_by_coverage_then_time(&idx, |i| items[i]), *want, "{items:?}");
        }
        assert!(rule_in_words().contains("0.005"));
    }
}
