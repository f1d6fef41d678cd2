//! The thesis GA behind the common [`Planner`] interface: the run loop of [`super::run`] on
//! the scenario, its best individual as the plan, `best_genome.csv` and `population.csv` as
//! extra files, and the history figure of 003 Fig. 4.8 (plus the path before a retrain) as
//! its own figures.

use super::config::ThesisConfig;
use super::individual::Individual;
use super::objective::{CameraObjective, Objective};
use super::run::{ThesisGa, ThesisOutcome};
use super::scenario::ThesisScenario;
use crate::coverage::CoverageGrid;
use crate::coverage::fitness::ThesisScore;
use crate::ga::observer::Observer;
use crate::planner::{Budget, Planner, PlannerError, RunOutcome, Scenario};
use crate::plot::history::HistoryFigure;
use crate::plot::path::PathFigure;
use std::path::Path;

/// `population.csv`: the final population, one row per individual in population order, with
/// both objectives of 003 (eqs. 3.6, 3.10), both projections (eqs. 3.14-3.15), `f_obstacle`
/// (eq. 3.16) and `G_len`: the points of 003's Pareto figures.
pub fn population_csv(population: &[(ThesisScore, usize, u64)]) -> Vec<u8> {
    let mut s = String::from("index,cov_final,t_final,f1,f2,fitness,genome_len,obstacle_cells\n");
    for (i, (sc, len, obj)) in population.iter().enumerate() {
        let (cov, t, f1, f2, f) = (sc.cov_final, sc.t_final, sc.f1, sc.f2, sc.fitness);
        s.push_str(&format!("{i},{cov},{t},{f1},{f2},{f},{len},{obj}\n"));
    }
    s.into_bytes()
}

/// `population_genomes.csv`: the live moves of each member of the final population (S's move
/// and every action, as `best_genome.csv` has them, without the connector and E), one row per
/// move; `member` is the row of `population.csv`.
pub fn population_genomes_csv(population: &[Individual]) -> Vec<u8> {
    let mut s = String::from("member,index,alpha_deg,dist_m\n");
    for (m, ind) in population.iter().enumerate() {
        let live = ind.genome.len().saturating_sub(2);
        for (i, a) in ind.genome[..live].iter().enumerate() {
            s.push_str(&format!("{m},{i},{},{}\n", a.alpha_deg(), a.dist_m()));
        }
    }
    s.into_bytes()
}

/// The final first front of a Pareto run under constrained domination (within the seed
/// plans' `bounds`, when it has them), as `[cov_final, t_final, fitness, genome_len]` rows
/// sorted by `cov_final` (for `summary.json`).
fn final_front(population: &[(ThesisScore, usize, u64)], bounds: &[(f64, f64)]) -> serde_json::Value {
    let points: Vec<(f64, f64)> = population.iter().map(|(s, _, _)| (s.cov_final, s.t_final)).collect();
    let violation: Vec<f64> = population
        .iter()
        .zip(&points)
        .map(|((_, _, obj), &p)| super::architecture::violation(p, *obj, bounds))
        .collect();
    let rank = crate::ga::selection::nsga2::front_ranks(&points, &violation);
    let mut front: Vec<usize> = (0..population.len()).filter(|&i| rank[i] == 0).collect();
    front.sort_by(|&a, &b| points[a].0.total_cmp(&points[b].0).then(a.cmp(&b)));
    front
        .iter()
        .map(|&i| serde_json::json!([points[i].0, points[i].1, population[i].0.fitness, population[i].1]))
        .collect()
}

impl Planner for ThesisConfig {
    fn name(&self) -> &'static str {
        "thesis"
    }

    fn run(
        &self,
        scenario: &Scenario,
        seed: u64,
        budget: &Budget,
        observers: &mut [&mut dyn Observer],
    ) -> Result<RunOutcome, PlannerError> {
        let seeds = self.seeds.iter().map(|g| Individual::with_genome(g.clone())).collect();
        let mut ga = ThesisGa {
            scenario: ThesisScenario::from_common(scenario).with_moves(self.moves).with_camera(match self.objective {
                (Objective::Footprint, _) => None,
                (Objective::Camera, alpha_cov) => Some(CameraObjective::new(
                    &scenario.map,
                    &scenario.camera,
                    alpha_cov,
                    &[scenario.start, scenario.end],
                )),
            }),
            params: self.params,
            seed,
            seeds: (seeds, self.seeded),
        };
        let out = ga.run(budget, self.retrain.as_ref(), observers)?;
        let best = &out.best;
        let sc = best.score;
        let mut details = crate::planner::details(serde_json::json!({
            "cov_final": sc.cov_final,
            "t_final": sc.t_final,
            "fitness": sc.fitness,
            "f1": sc.f1,
            "f2": sc.f2,
            "genome_len": best.len(),
            "metrics": best.path_metrics(&ga.scenario),
        }));
        if !self.moves.is_straight() {
            details.insert("moves".into(), "routed: the plan drives around obstacles between viewpoints".into());
        }
        if matches!(self.params.selection, super::params::Selection::Nsga2) {
            details.insert("front".into(), final_front(&out.final_population, &out.seed_points));
            details
                .insert("front_columns".into(), serde_json::json!(["cov_final", "t_final", "fitness", "genome_len"]));
            details.insert("plan".into(), "the knee of the final front".into());
        }
        if !out.seed_points.is_empty() {
            details.insert("seed_bound".into(), serde_json::json!(out.seed_points));
        }
        if let Some(b) = &out.best_before_retrain {
            details.insert(
                "before_retrain".into(),
                serde_json::json!([b.score.cov_final, b.score.t_final, b.score.fitness]),
            );
        }
        let mut files = vec![
            ("best_genome.csv".into(), best.genome_csv()),
            ("population.csv".into(), population_csv(&out.final_population)),
        ];
        if self.population_genomes {
            files.push(("population_genomes.csv".into(), population_genomes_csv(&out.population)));
        }
        Ok(RunOutcome::new(vec![ga.scenario.driven(&best.points)], out.stop)
            .with_objectives(vec![("cov_final", sc.cov_final), ("t_final", sc.t_final), ("fitness", sc.fitness)])
            .with_violations(crate::coverage::score::obstacle_violations(best.sweep.obj_pix))
            .with_feasible(best.sweep.obj_pix == 0)
            .with_effort(out.evaluations, out.iterations)
            .with_wall_s(out.wall_s)
            .with_details(details)
            .with_files(files)
            .with_history(crate::planner::History::Generations)
            .with_artifacts(Box::new((out, seed))))
    }

    fn write_figures(
        &self,
        scenario: &Scenario,
        outcome: &RunOutcome,
        dir: &Path,
    ) -> Result<(), crate::plot::PlotError> {
        let Some((out, seed)) = outcome.artifacts.downcast_ref::<(ThesisOutcome, u64)>() else { return Ok(()) };
        let map = &scenario.map;
        let title = |ind: &Individual, what: &str| {
            format!(
                "{what} on {}: cov_final {:.3}, t_final {:.3}, G_len {}",
                map.name(),
                ind.score.cov_final,
                ind.score.t_final,
                ind.len()
            )
        };
        let routed = (!self.moves.is_straight()).then(|| ThesisScenario::from_common(scenario).with_moves(self.moves));
        let driven = |ind: &Individual| routed.as_ref().map_or_else(|| ind.points.clone(), |s| s.driven(&ind.points));
        let mut grid = CoverageGrid::new(map);
        if let Some(r) = &self.retrain {
            let [x0, y0, x1, y1] = r.region;
            grid.premark_rect(x0, y0, x1, y1);
            // The best path on the changed map, with the marked region shown.
            let figure = PathFigure {
                map,
                grid: &grid,
                paths: vec![driven(&out.best)],
                width: scenario.robot.width,
                robots: Vec::new(),
                title: title(&out.best, "best path"),
            };
            crate::plot::save(&figure, &dir.join("path"))?;
        }
        if let Some(before) = &out.best_before_retrain {
            let plain = CoverageGrid::new(map);
            let figure = PathFigure {
                map,
                grid: &plain,
                paths: vec![driven(before)],
                width: scenario.robot.width,
                robots: Vec::new(),
                title: title(before, "best before retrain"),
            };
            crate::plot::save(&figure, &dir.join("path_before_retrain"))?;
        }
        let hist = HistoryFigure {
            history: &out.history,
            changes: &out.changes,
            title: format!("{} on {}, seed {}", self.params.selection.name(), map.name(), seed),
        };
        crate::plot::save(&hist, &dir.join("history"))
    }
}
