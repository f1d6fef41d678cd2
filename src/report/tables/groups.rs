//! The per-group tables of `covga report`'s summary: best run and best configuration per
//! group (003 Tables A.1/A.2), fronts with hypervolume and run durations (Table 4.4), means
//! with confidence intervals, and the Kruskal–Wallis tests of [`super::effects`].

use crate::ga::pareto::hypervolume_2d;
use crate::report::analysis::design::{PROJECTION, projection_levels, projection_scopes};
use crate::report::analysis::runs::{ConfigRow, Group};
use crate::report::figures::pareto::ParetoFacet;
use crate::stats::{mean_ci95, mean_min_max};
use crate::study::records::RunsTable;
use std::fmt::Write as _;

/// What the tables are made of.
pub(crate) struct GroupTables<'a> {
    /// The runs.
    pub t: &'a RunsTable,
    /// The groups of `--by`.
    pub groups: &'a [Group],
    /// The best run of each group (of each group and projection where f1 and f2 both occur),
    /// with its label.
    pub best: &'a [(String, usize)],
    /// Each group's Pareto facet.
    pub facets: &'a [ParetoFacet],
    /// Configurations over their replicates, best mean f first.
    pub configs: &'a [ConfigRow],
    /// The swept-parameter columns.
    pub params: &'a [String],
    /// Whether the tables give the common scorer's measures (a study that runs any planner
    /// other than the thesis GA, [`super::common`]) instead of 003's.
    pub common: bool,
}

impl GroupTables<'_> {
    /// Appends the tables to `md`.
    pub fn write(&self, md: &mut String) {
        if self.common {
            return self.write_common(md);
        }
        self.best_runs(md);
        self.best_configurations(md);
        self.fronts(md);
        self.per_group(md);
        self.top_configurations(md);
        super::effects::section(md, self.t, self.params);
    }

    /// A number of row `r` (NaN where absent).
    pub(crate) fn num(&self, r: usize, c: &str) -> f64 {
        self.t.num(&self.t.rows[r], c).unwrap_or(f64::NAN)
    }

    /// The mean, least and most wall time of `rows`' runs [s].
    pub(crate) fn wall_times(&self, rows: &[usize]) -> (f64, f64, f64) {
        mean_min_max(&rows.iter().map(|&r| self.num(r, "wall_s")).collect::<Vec<_>>())
    }

    /// A cell of row `r` (empty where absent).
    pub(crate) fn get(&self, r: usize, c: &str) -> String {
        self.t.col(c).map(|i| self.t.rows[r][i].clone()).unwrap_or_default()
    }

    /// A configuration's cells: its parameter values, replicates, means with CIs, mean f.
    fn config_cells(&self, (_, rows, c, tf, f): &ConfigRow) -> String {
        let vals: Vec<String> = self.params.iter().map(|p| self.get(rows[0], p)).collect();
        format!("{} | {} | {} | {} | {:.4} |", vals.join(" | "), rows.len(), mean_ci_cell(*c), mean_ci_cell(*tf), f)
    }

    /// The best run of each group (of each projection where f1 and f2 both occur).
    fn best_runs(&self, md: &mut String) {
        let (groups, best, params) = (self.groups, self.best, self.params);
        let _ = writeln!(md, "## Best configuration per group (highest f over all free cells)\n");
        if best.len() > groups.len() {
            let _ = writeln!(md, "f1 and f2 are different functions: the best run of each projection.\n");
        }
        let _ = writeln!(md, "| group | run | {} | cov_final | t_final | f |", params.join(" | "));
        let _ = writeln!(md, "|---|---|{}---|---|---|", "---|".repeat(params.len()));
        for (label, r) in best {
            let r = *r;
            let vals: Vec<String> = params.iter().map(|p| self.get(r, p)).collect();
            let _ = writeln!(
                md,
                "| {} | {} | {} | {:.6} | {:.6} | {:.6} |",
                label,
                self.get(r, "run_id"),
                vals.join(" | "),
                self.num(r, "cov_final_free"),
                self.num(r, "t_final"),
                self.num(r, "f_free")
            );
        }
    }

    /// The best configuration of each group over its seeds (003 Tables A.1/A.2).
    fn best_configurations(&self, md: &mut String) {
        let (t, groups, params, conf_rows) = (self.t, self.groups, self.params, self.configs);
        let _ = writeln!(
            md,
            "\n## Best configuration per group over seeds (highest mean f; 003 Tables A.1/A.2 with 95 % CIs)\n"
        );
        let _ = writeln!(
            md,
            "| group | {} | n | cov_final mean ± 95 % CI | t_final mean ± 95 % CI | mean f |\n|---|{}---|---|---|---|",
            params.join(" | "),
            "---|".repeat(params.len())
        );
        for g in groups {
            for (suffix, rows) in projection_scopes(t, &g.rows) {
                let members: std::collections::HashSet<usize> = rows.into_iter().collect();
                if let Some(c) = conf_rows.iter().find(|c| members.contains(&c.1[0])) {
                    let _ = writeln!(md, "| {}{suffix} | {}", g.label, self.config_cells(c));
                }
            }
        }
    }

    /// Each group's front of executable runs, its hypervolume and the run durations.
    fn fronts(&self, md: &mut String) {
        let (groups, facets) = (self.groups, self.facets);
        let _ = writeln!(
            md,
            "\n## Fronts of the executable runs, hypervolume (reference point (0, 0)) and run durations per group\n"
        );
        let _ = writeln!(
            md,
            "| group | runs | front size | hypervolume | wall s mean | min | max |\n|---|---|---|---|---|---|---|"
        );
        for (g, f) in groups.iter().zip(facets) {
            let (mean, lo, hi) = self.wall_times(&g.rows);
            let _ = writeln!(
                md,
                "| {} | {} | {} | {:.4} | {:.3} | {:.3} | {:.3} |",
                g.label,
                g.rows.len(),
                f.front.len(),
                hypervolume_2d(&f.points, (0.0, 0.0)),
                mean,
                lo,
                hi
            );
        }
    }

    /// Each group's means with 95 % intervals, over its executable runs and over all.
    fn per_group(&self, md: &mut String) {
        let (t, groups) = (self.t, self.groups);
        let _ = writeln!(md, "\n## Per group: mean ± 95 % CI over its runs\n");
        let _ = writeln!(
            md,
            "Executable: runs whose best plan a robot can drive (`executable = true` in runs.csv: the robot's body touches no occupied, unknown or off-map cell along the path). cov_final, t_final and f are over the executable runs; `cov_final (all)` over every run.\n"
        );
        // f per projection where the study sweeps it (f1 and f2 are different functions).
        let mixed = groups.iter().any(|g| projection_scopes(t, &g.rows).len() > 1);
        let f_levels = projection_levels(t, "f_free").filter(|_| mixed);
        let f_heads = match &f_levels {
            None => "f".to_string(),
            Some(levels) => levels.iter().map(|l| format!("f ({l})")).collect::<Vec<_>>().join(" | "),
        };
        let f_count = f_levels.as_ref().map_or(1, Vec::len);
        let _ = writeln!(
            md,
            "| group | runs | executable | cov_final | t_final | {f_heads} | cov_final (all) |\n|---|---|---|---|---|{}---|",
            "---|".repeat(f_count)
        );
        for g in groups {
            let drivable: Vec<usize> =
                g.rows.iter().copied().filter(|&r| self.get(r, "executable") == "true").collect();
            let ci = |c: &str, rows: &[usize]| mean_ci95(&rows.iter().map(|&r| self.num(r, c)).collect::<Vec<_>>());
            let (c, tf) = (ci("cov_final_free", &drivable), ci("t_final", &drivable));
            let f_cells: Vec<String> = match &f_levels {
                None => vec![ci("f_free", &drivable)],
                Some(levels) => levels
                    .iter()
                    .map(|l| {
                        let rows: Vec<usize> =
                            drivable.iter().copied().filter(|&r| self.get(r, PROJECTION) == *l).collect();
                        ci("f_free", &rows)
                    })
                    .collect(),
            }
            .into_iter()
            .map(mean_ci_cell)
            .collect();
            let all = ci("cov_final_free", &g.rows);
            let _ = writeln!(
                md,
                "| {} | {} | {}/{} | {} | {} | {} | {} |",
                g.label,
                g.rows.len(),
                drivable.len(),
                g.rows.len(),
                mean_ci_cell(c),
                mean_ci_cell(tf),
                f_cells.join(" | "),
                mean_ci_cell(all)
            );
        }
    }

    /// The 20 configurations with the highest mean f (within one projection).
    fn top_configurations(&self, md: &mut String) {
        let (t, params, conf_rows) = (self.t, self.params, self.configs);
        // f1 and f2 are different functions: configurations are ranked by f within one
        // projection only.
        let scopes: Vec<(String, Vec<&ConfigRow>)> = match projection_levels(t, "f_free") {
            None => vec![(String::new(), conf_rows.iter().collect())],
            Some(levels) => levels
                .into_iter()
                .map(|l| {
                    let rows = conf_rows.iter().filter(|c| self.get(c.1[0], PROJECTION) == l).collect();
                    (format!(" with {PROJECTION} = {l}"), rows)
                })
                .collect(),
        };
        for (scope, rows) in scopes {
            let _ = writeln!(
                md,
                "\n## Across seeds: the 20 configurations{scope} with the highest mean f (all in configurations.csv)\n"
            );
            let _ = writeln!(
                md,
                "| {} | n | cov_final mean ± 95 % CI | t_final mean ± 95 % CI | mean f |\n|{}---|---|---|---|",
                params.join(" | "),
                "---|".repeat(params.len())
            );
            for c in rows.into_iter().take(20) {
                let _ = writeln!(md, "| {}", self.config_cells(c));
            }
        }
    }
}

/// A table cell of a mean and its 95 % CI half-width: "–" without runs, the mean alone with
/// "(1 run)" where one run gives no interval.
pub(crate) fn mean_ci_cell((mean, half): (f64, f64)) -> String {
    match (mean.is_finite(), half.is_finite()) {
        (false, _) => "–".to_string(),
        (true, false) => format!("{mean:.4} (1 run)"),
        (true, true) => format!("{mean:.4} ± {half:.4}"),
    }
}
