//! One colour per group in every figure of a report: each run's series — its `--by` group,
//! with its planner where the study has several ([`super::curves::series_label`]) — numbered in
//! the order the study lists its groups, over every run, executable or not. A figure whose
//! series gather runs otherwise (the planner comparison's variants) colours a series by its
//! first run's number, so that a group keeps its colour across the box plots, the Pareto view,
//! the curves and the convergence figure, whichever of them leaves it out.

use crate::report::analysis::study::Study;
use std::collections::BTreeMap;

/// The report's series in colour order, and each run's place among them by run id.
pub(crate) struct RunColours {
    /// The series' labels (the Pareto view's groups), in colour order.
    pub keys: Vec<String>,
    /// Each run's series, by run id.
    pub of_run: BTreeMap<String, usize>,
}

impl RunColours {
    /// The series of the study's runs.
    pub fn of(s: &Study) -> Self {
        let mut keys: Vec<String> = Vec::new();
        let mut of_run = BTreeMap::new();
        for g in &s.groups {
            for &r in &g.rows {
                let label = super::curves::series_label(&g.label, &s.get(r, "planner"), false);
                let k = keys.iter().position(|l| *l == label).unwrap_or_else(|| {
                    keys.push(label);
                    keys.len() - 1
                });
                of_run.insert(s.get(r, "run_id"), k);
            }
        }
        Self { keys, of_run }
    }

    /// The colour of a series made of `runs` (run ids): its first run's, or `fallback` where
    /// none of them is the report's.
    pub fn of_runs<'a>(&self, runs: impl IntoIterator<Item = &'a str>, fallback: usize) -> usize {
        runs.into_iter().find_map(|id| self.of_run.get(id).copied()).unwrap_or(fallback)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A series gathered otherwise (a planner comparison's variant) takes its first run's
    /// colour that the report knows; one of runs the report does not know, its fallback.
    #[test]
    fn a_series_takes_its_first_known_runs_colour() {
        let colours = RunColours {
            keys: vec!["planner=spiral".into(), "planner=boustrophedon".into()],
            of_run: [("s1".to_string(), 0), ("b1".to_string(), 1), ("b2".to_string(), 1)].into_iter().collect(),
        };
        assert_eq!(colours.of_runs(["b2", "s1"], 7), 1);
        assert_eq!(colours.of_runs(["x", "s1"], 7), 0, "an unknown run is skipped");
        assert_eq!(colours.of_runs(["x"], 7), 7);
        assert_eq!(colours.of_runs([], 3), 3);
    }
}
