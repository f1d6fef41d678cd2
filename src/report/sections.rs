//! The sections of a study's `summary.md`, in the order they are written: each a small type
//! behind [`Section`], listed once in [`SECTIONS`]. A new section is a type and a line there.

mod colours;
mod curves;

use crate::coverage::CoverageGrid;
use crate::plot::path::PathFigure;
use crate::report::analysis::ReportError;
use crate::report::analysis::runs::read_history_diversity;
use crate::report::analysis::study::Study;
use crate::report::figures::diversity::{DiversityFigure, DiversityGroup};
use crate::report::figures::pareto::{ParetoFacet, ParetoFigure};
use crate::report::figures::paths::PathsGridFigure;
use crate::report::figures::planners_pareto::{PlanPoint, PlannersPareto};
use crate::report::replication::{ablation, thesis_report};
use crate::report::tables::{anova, groups};
use crate::stats::median;
use std::collections::BTreeSet;
use std::fmt::Write as _;

/// One section of a study report: the figures and files it draws into the report folder and
/// the Markdown it appends to `summary.md`.
pub(super) trait Section: Sync {
    /// Whether the study has what the section reads (a planner comparison, the thesis's tables).
    fn applies(&self, _study: &Study) -> bool {
        true
    }
    /// Draws the section's files and appends its Markdown to `md`.
    fn write(&self, study: &Study, md: &mut String) -> Result<(), ReportError>;
}

/// Every section, in the order of `summary.md`.
pub(super) const SECTIONS: &[&dyn Section] = &[
    &Heading,
    &ParetoFronts,
    &Diversity,
    &BestPaths,
    &curves::CoverageCurves,
    &PlannerComparison,
    &GroupTables,
    &ThesisTables,
    &Anova,
];

/// The title, the notes, the filters and the counts.
struct Heading;

impl Section for Heading {
    fn write(&self, s: &Study, md: &mut String) -> Result<(), ReportError> {
        let replicate = s.t.col("replicate").unwrap_or(0);
        let replicates = s.t.rows.iter().map(|r| r[replicate].clone()).collect::<BTreeSet<_>>().len();
        let _ = writeln!(md, "# Study report: {}\n", s.dir.display());
        if let Some(note) = &s.incomplete {
            let _ = writeln!(md, "{note}\n");
        }
        if !s.selected.is_empty() {
            let _ = writeln!(md, "Runs with {} only.\n", s.selected.join(", "));
        }
        let _ = writeln!(
            md,
            "{} runs, {} configurations, {} replicate(s); grouped by {}.\n",
            s.t.rows.len(),
            s.configs.len(),
            replicates,
            if s.by.is_empty() { "nothing (one group)".to_string() } else { s.by.join(", ") }
        );
        Ok(())
    }
}

/// The Pareto figure: for the thesis GA alone, one panel per group, fronts over the executable
/// plans on 003's measures; with any other planner, one panel per map on the common scorer's
/// mission time and reachable coverage ([`PlannersPareto`]).
struct ParetoFronts;

impl Section for ParetoFronts {
    fn write(&self, s: &Study, md: &mut String) -> Result<(), ReportError> {
        if s.common_measures() {
            crate::plot::save(&planners_pareto(s), &s.out.join("pareto"))?;
            let _ = writeln!(md, "![Mission time against reachable coverage, every plan](pareto.png)\n");
            return Ok(());
        }
        let facets = s
            .facets
            .iter()
            .map(|f| ParetoFacet {
                label: f.label.clone(),
                points: f.points.clone(),
                front: f.front.clone(),
                rows: f.rows.clone(),
                excluded: f.excluded.clone(),
                kinds: f.kinds.clone(),
            })
            .collect();
        let kinds = if s.kinds.len() > 1 { s.kinds.clone() } else { Vec::new() };
        crate::plot::save(&ParetoFigure { facets, shape: s.shape, kinds }, &s.out.join("pareto"))?;
        let _ = writeln!(md, "![Pareto fronts](pareto.png)\n");
        Ok(())
    }
}

/// The Pareto view across planners: per map, each run's plan in its group's series, numbered
/// as every figure of the report numbers them ([`colours::RunColours`]).
fn planners_pareto(s: &Study) -> PlannersPareto {
    let colours = colours::RunColours::of(s);
    let mut panels: Vec<(String, Vec<PlanPoint>)> = Vec::new();
    for g in &s.groups {
        for &r in &g.rows {
            let point = PlanPoint {
                group: colours.of_run[&s.get(r, "run_id")],
                time_s: s.num(r, "time_s"),
                coverage: s.num(r, "cov_final_reach"),
                executable: s.executable(r),
            };
            let map = s.get(r, "map");
            match panels.iter_mut().find(|(m, _)| *m == map) {
                Some((_, points)) => points.push(point),
                None => panels.push((map, vec![point])),
            }
        }
    }
    let names = curves::distinct_parts(&colours.keys);
    PlannersPareto { groups: names, panels }
}

/// The diversity of each group's front runs over the iterations (median and range), where
/// their histories measured it.
struct Diversity;

impl Section for Diversity {
    fn write(&self, s: &Study, md: &mut String) -> Result<(), ReportError> {
        let mut groups = Vec::new();
        let colours = colours::RunColours::of(s);
        for (g, f) in s.groups.iter().zip(&s.facets) {
            let curves: Vec<Vec<(u32, f64)>> = f
                .front
                .iter()
                .filter_map(|&k| {
                    let run = s.get(f.rows[k], "run_id");
                    read_history_diversity(&s.dir.join("runs").join(run).join("history.csv"))
                })
                .collect();
            if curves.is_empty() {
                continue;
            }
            let len = curves.iter().map(Vec::len).min().unwrap_or(0);
            let curve = (0..len)
                .map(|i| {
                    let mut v: Vec<f64> = curves.iter().map(|c| c[i].1).collect();
                    let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
                    let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                    (curves[0][i].0, median(&mut v), lo, hi)
                })
                .collect();
            let ids: Vec<String> = g.rows.iter().map(|&r| s.get(r, "run_id")).collect();
            let colour = colours.of_runs(ids.iter().map(String::as_str), groups.len());
            groups.push(DiversityGroup { label: g.label.clone(), runs: curves.len(), curve, colour });
        }
        if !groups.is_empty() {
            crate::plot::save(&DiversityFigure { groups }, &s.out.join("diversity"))?;
            let _ = writeln!(md, "![Diversity of the front runs](diversity.png)\n");
        }
        Ok(())
    }
}

/// The best run's path of each group, on its map, where the runs' folders hold them.
struct BestPaths;

impl Section for BestPaths {
    fn write(&self, s: &Study, md: &mut String) -> Result<(), ReportError> {
        let planner_col = s.t.header.iter().rposition(|h| h == "planner");
        let by_planner_varies =
            planner_col.is_some_and(|c| s.t.rows.iter().map(|row| row[c].as_str()).collect::<BTreeSet<_>>().len() > 1);
        let mut loaded = Vec::new();
        // Groups whose run folder holds a plan that cannot be drawn here: named, not dropped.
        let mut not_drawn = Vec::new();
        for (group_label, r) in &s.best {
            let r = *r;
            let run_dir = s.dir.join("runs").join(s.get(r, "run_id"));
            let Ok(cfg) = crate::experiment::file::ExperimentFile::read(&run_dir.join("config.toml")) else { continue };
            let Ok(paths) = crate::io::read_path_csv(&run_dir.join("best_path.csv")) else { continue };
            let map = match crate::map::ros::load_map(&cfg.map.source, &cfg.map.bare_image()) {
                Ok(map) => map,
                Err(e) => {
                    not_drawn
                        .push(format!("{group_label} (its map `{}` cannot be read from here: {e})", cfg.map.source));
                    continue;
                }
            };
            let mut grid = CoverageGrid::new(&map);
            if let Some(rt) = crate::thesis::config::RETRAIN_SECTION.get(&cfg) {
                let [x0, y0, x1, y1] = rt.region;
                grid.premark_rect(x0, y0, x1, y1);
            }
            // The planner too, where a study compares several.
            let label = match planner_col.map(|c| s.t.rows[r][c].as_str()) {
                Some(p) if !group_label.contains(p) && by_planner_varies => format!("{group_label}, {p}"),
                _ => group_label.clone(),
            };
            // Across planners the common scorer's measures; for the thesis GA alone 003's, named.
            let title = if s.common_measures() {
                format!(
                    "{}: {:.0} s, {:.1} % of the reachable cells",
                    crate::plot::panel_label(&label),
                    s.num(r, "time_s"),
                    100.0 * s.num(r, "cov_final_reach")
                )
            } else {
                format!(
                    "{}: cov_final {:.3} of the free cells, t_final {:.3}",
                    crate::plot::panel_label(&label),
                    s.num(r, "cov_final_free"),
                    s.num(r, "t_final")
                )
            };
            loaded.push((map, grid, paths, cfg.robot.width, title));
        }
        if !not_drawn.is_empty() {
            let _ = writeln!(md, "The best paths of these groups are not drawn: {}.\n", not_drawn.join("; "));
        }
        if loaded.is_empty() {
            return Ok(());
        }
        let panels = loaded
            .iter()
            .map(|(map, grid, paths, width, title)| PathFigure {
                map,
                grid,
                paths: paths.clone(),
                width: *width,
                robots: Vec::new(),
                title: title.clone(),
            })
            .collect();
        crate::plot::save(&PathsGridFigure { panels }, &s.out.join("best_paths"))?;
        let _ = writeln!(md, "![Best path per group](best_paths.png)\n");
        Ok(())
    }
}

/// The planner comparison of a study that runs several planners ([`ablation`]).
struct PlannerComparison;

impl Section for PlannerComparison {
    fn applies(&self, s: &Study) -> bool {
        ablation::applies(&s.t)
    }
    fn write(&self, s: &Study, md: &mut String) -> Result<(), ReportError> {
        let colours = colours::RunColours::of(s);
        md.push_str(&ablation::compare(s.dir, &s.t, &s.out, &colours.of_run)?.markdown);
        Ok(())
    }
}

/// The tables per group: fronts, best runs, configurations ([`groups`]).
struct GroupTables;

impl Section for GroupTables {
    fn write(&self, s: &Study, md: &mut String) -> Result<(), ReportError> {
        groups::GroupTables {
            t: &s.t,
            groups: &s.groups,
            best: &s.best,
            facets: &s.facets,
            configs: &s.configs,
            params: &s.params,
            common: s.common_measures(),
        }
        .write(md);
        Ok(())
    }
}

/// The thesis's tables and claims, for a study of the thesis GA ([`thesis_report`]).
struct ThesisTables;

impl Section for ThesisTables {
    fn applies(&self, s: &Study) -> bool {
        thesis_report::applies(&s.t)
    }
    fn write(&self, s: &Study, md: &mut String) -> Result<(), ReportError> {
        md.push_str(&thesis_report::sections(&s.t, &s.folders));
        Ok(())
    }
}

/// The ANOVA of the swept parameters ([`anova`]).
struct Anova;

impl Section for Anova {
    fn write(&self, s: &Study, md: &mut String) -> Result<(), ReportError> {
        md.push_str(&anova::section(&s.t, &s.params));
        Ok(())
    }
}
