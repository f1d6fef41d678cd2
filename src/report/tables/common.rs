//! The per-group tables of a study that runs any planner other than the thesis GA, on the
//! common scorer's measures: mission time in seconds (`time_s`) and the share of the reachable
//! cells a plan covers (`cov_final_reach`). 003's `t_final` and `f` are one GA's own measures
//! (its time efficiency and its weighted fitness) and do not rank plans of different planners,
//! so these tables leave them to `runs.csv` and `configurations.csv`.
//!
//! The best plan of a set is picked by [`best_by_coverage_then_time`].

use super::groups::{GroupTables, mean_ci_cell};
use crate::report::analysis::best::{COVERAGE, TIME, best_by_coverage_then_time, rule_in_words};
use crate::report::figures::planners_pareto::{PlanPoint, non_dominated};
use crate::stats::mean_ci95;
use std::fmt::Write as _;

/// A mean and its 95 % CI half-width.
type MeanCi = (f64, f64);

impl GroupTables<'_> {
    /// The columns that name a run's configuration: `planner` where the study runs several
    /// (no swept parameter names it), then the swept parameters.
    fn named_columns(&self) -> Vec<String> {
        let planners: std::collections::BTreeSet<String> =
            (0..self.t.rows.len()).map(|r| self.get(r, "planner")).collect();
        let planner =
            (planners.len() > 1 && !self.params.iter().any(|p| p == "planner")).then(|| "planner".to_string());
        planner.into_iter().chain(self.params.iter().cloned()).collect()
    }

    /// The means with 95 % intervals of coverage and time over `rows`.
    fn common_means(&self, rows: &[usize]) -> (MeanCi, MeanCi) {
        let of = |c: &str| mean_ci95(&rows.iter().map(|&r| self.num(r, c)).collect::<Vec<_>>());
        (of(COVERAGE), of(TIME))
    }

    /// Appends the tables on the common scorer's measures to `md`.
    pub(crate) fn write_common(&self, md: &mut String) {
        self.common_best_runs(md);
        self.common_best_configurations(md);
        self.common_fronts(md);
        self.common_per_group(md);
        self.common_top_configurations(md);
        super::effects::section(md, self.t, self.params);
    }

    /// The best run of each group.
    fn common_best_runs(&self, md: &mut String) {
        let params = &self.named_columns();
        let _ = writeln!(md, "## Best run per group ({})\n", rule_in_words());
        let _ = writeln!(md, "| group | run | {} | {COVERAGE} | {TIME} |", params.join(" | "));
        let _ = writeln!(md, "|---|---|{}---|---|", "---|".repeat(params.len()));
        for (label, r) in self.best {
            let vals: Vec<String> = params.iter().map(|p| self.get(*r, p)).collect();
            let _ = writeln!(
                md,
                "| {label} | {} | {} | {:.4} | {:.1} |",
                self.get(*r, "run_id"),
                vals.join(" | "),
                self.num(*r, COVERAGE),
                self.num(*r, TIME)
            );
        }
    }

    /// The best configuration of each group over its seeds, by its means.
    fn common_best_configurations(&self, md: &mut String) {
        let params = &self.named_columns();
        let _ = writeln!(md, "\n## Best configuration per group over seeds (by the means: {})\n", rule_in_words());
        let _ = writeln!(
            md,
            "| group | {} | n | {COVERAGE} mean ± 95 % CI | {TIME} mean ± 95 % CI |\n|---|{}---|---|---|",
            params.join(" | "),
            "---|".repeat(params.len())
        );
        for g in self.groups {
            let members: std::collections::HashSet<usize> = g.rows.iter().copied().collect();
            let configs: Vec<usize> =
                (0..self.configs.len()).filter(|&i| members.contains(&self.configs[i].1[0])).collect();
            let best = best_by_coverage_then_time(&configs, |i| {
                let (c, t) = self.common_means(&self.configs[i].1);
                (c.0, t.0)
            });
            if let Some(i) = best {
                let rows = &self.configs[i].1;
                let vals: Vec<String> = params.iter().map(|p| self.get(rows[0], p)).collect();
                let (c, t) = self.common_means(rows);
                let _ = writeln!(
                    md,
                    "| {} | {} | {} | {} | {} |",
                    g.label,
                    vals.join(" | "),
                    rows.len(),
                    mean_ci_cell(c),
                    time_cell(t)
                );
            }
        }
    }

    /// Each group's plans no other of its executable plans dominates, and the run durations.
    fn common_fronts(&self, md: &mut String) {
        let _ = writeln!(
            md,
            "\n## Non-dominated executable plans ({TIME} lower, {COVERAGE} higher) and run durations per group\n"
        );
        let _ = writeln!(md, "| group | runs | executable | non-dominated | wall s mean | min | max |");
        let _ = writeln!(md, "|---|---|---|---|---|---|---|");
        for g in self.groups {
            let points: Vec<PlanPoint> = g
                .rows
                .iter()
                .map(|&r| PlanPoint {
                    group: 0,
                    time_s: self.num(r, TIME),
                    coverage: self.num(r, COVERAGE),
                    executable: self.get(r, "executable") != "false",
                })
                .collect();
            let executable = points.iter().filter(|p| p.executable).count();
            let (mean, lo, hi) = self.wall_times(&g.rows);
            let _ = writeln!(
                md,
                "| {} | {} | {executable} | {} | {mean:.3} | {lo:.3} | {hi:.3} |",
                g.label,
                g.rows.len(),
                non_dominated(&points).len()
            );
        }
    }

    /// Each group's means with 95 % intervals over its executable runs and over all.
    fn common_per_group(&self, md: &mut String) {
        let _ = writeln!(md, "\n## Per group: mean ± 95 % CI over its runs\n");
        let _ = writeln!(
            md,
            "Executable: runs whose best plan a robot can drive (`executable = true` in runs.csv: the robot's body \
             touches no occupied, unknown or off-map cell along the path). {COVERAGE} and {TIME} are over the \
             executable runs; `{COVERAGE} (all)` over every run.\n"
        );
        let _ = writeln!(
            md,
            "| group | runs | executable | {COVERAGE} | {TIME} | {COVERAGE} (all) |\n|---|---|---|---|---|---|"
        );
        for g in self.groups {
            let drivable: Vec<usize> =
                g.rows.iter().copied().filter(|&r| self.get(r, "executable") == "true").collect();
            let (c, t) = self.common_means(&drivable);
            let (all, _) = self.common_means(&g.rows);
            let _ = writeln!(
                md,
                "| {} | {} | {}/{} | {} | {} | {} |",
                g.label,
                g.rows.len(),
                drivable.len(),
                g.rows.len(),
                mean_ci_cell(c),
                time_cell(t),
                mean_ci_cell(all)
            );
        }
    }
}

impl GroupTables<'_> {
    /// The 20 configurations with the highest mean coverage, the faster first among equals.
    fn common_top_configurations(&self, md: &mut String) {
        let params = &self.named_columns();
        let mut ranked: Vec<(usize, MeanCi, MeanCi)> = (0..self.configs.len())
            .map(|i| {
                let (c, t) = self.common_means(&self.configs[i].1);
                (i, c, t)
            })
            .collect();
        ranked.sort_by(|a, b| b.1.0.total_cmp(&a.1.0).then(a.2.0.total_cmp(&b.2.0)).then(a.0.cmp(&b.0)));
        let _ = writeln!(
            md,
            "\n## Across seeds: the 20 configurations with the highest mean {COVERAGE} (all in configurations.csv)\n"
        );
        let _ = writeln!(
            md,
            "| {} | n | {COVERAGE} mean ± 95 % CI | {TIME} mean ± 95 % CI |\n|{}---|---|---|",
            params.join(" | "),
            "---|".repeat(params.len())
        );
        for (i, c, t) in ranked.into_iter().take(20) {
            let rows = &self.configs[i].1;
            let vals: Vec<String> = params.iter().map(|p| self.get(rows[0], p)).collect();
            let _ = writeln!(md, "| {} | {} | {} | {} |", vals.join(" | "), rows.len(), mean_ci_cell(c), time_cell(t));
        }
    }
}

/// A table cell of a mean time and its 95 % CI half-width in seconds: "–" without runs,
/// "(1 run)" where one run gives no interval.
fn time_cell((mean, half): (f64, f64)) -> String {
    match (mean.is_finite(), half.is_finite()) {
        (false, _) => "–".to_string(),
        (true, false) => format!("{mean:.1} s (1 run)"),
        (true, true) => format!("{mean:.1} ± {half:.1} s"),
    }
}
