//! Running an experiment file with `[[robots]]` (by `covga run` or in a grid study): the fleet
//! is planned as `[fleet] mode` says, then its results folder is written — `config.toml`,
//! `history.csv` (per generation for the centralised GA, with `robots_history.csv` per
//! generation and robot; per round and robot for the negotiation), `best_path.csv` (with
//! `agent` and `robot` columns), `summary.json` (the common summary with the fleet metrics)
//! and, when asked, `path.png` / `path.svg` (one colour per robot).

use super::config::{FleetMode, FleetRun};
use super::metrics::{FleetScore, FleetScorer};
use crate::coverage::CoverageGrid;
use crate::ga::observer::Observer;
use crate::geom::Point;
use crate::planner::{PlannerConfig, StopReason};
use crate::plot::path::PathFigure;
use crate::study::experiment::Experiment;
use crate::study::output::{HistoryCsv, OutputError, Summary, scorer_of};
use std::path::Path;

/// A fleet's plan and what its planner reports besides the fleet metrics.
struct FleetPlan {
    paths: Vec<Vec<Point>>,
    evaluations: u64,
    iterations: u32,
    stop: StopReason,
    details: serde_json::Value,
    /// The planner's own constraint violations (the waypoint planner's), in words.
    violations: Vec<String>,
}

/// `robots_history.csv` of the centralised GA: per generation and robot of the best crew, its
/// genome length, distinct swept cells and time as the fitness reads it.
struct RobotHistory {
    names: Vec<String>,
    out: csv::Writer<Vec<u8>>,
}

impl RobotHistory {
    fn new(fleet: &super::Fleet) -> Self {
        let mut out = csv::Writer::from_writer(Vec::new());
        out.write_record(["iteration", "robot", "genome_len", "swept_cells", "t_actual_s"]).expect("in memory");
        Self { names: fleet.robots().iter().map(|r| r.name.clone()).collect(), out }
    }
    fn finish(self) -> Vec<u8> {
        self.out.into_inner().expect("in memory")
    }
}

impl Observer for RobotHistory {
    fn generation(&mut self, record: &crate::ga::observer::GenerationRecord) -> std::io::Result<()> {
        for (name, r) in self.names.iter().zip(&record.robots) {
            let row = [
                record.iteration.to_string(),
                name.clone(),
                r.genome_len.to_string(),
                r.swept_cells.to_string(),
                r.t_actual_s.to_string(),
            ];
            self.out.write_record(&row).map_err(std::io::Error::other)?;
        }
        Ok(())
    }
}

fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> OutputError + '_ {
    move |source| OutputError::Io { path: path.to_path_buf(), source }
}

/// Plans `run` for `exp`, writes the results folder `dir` (figures when `figures`) and returns
/// the summary. `extra` observers see the centralised GA's generations.
pub fn run_fleet(
    exp: &Experiment,
    run: &FleetRun,
    dir: &Path,
    figures: bool,
    extra: &mut [&mut dyn Observer],
) -> Result<Summary, OutputError> {
    let started = std::time::Instant::now();
    let thesis = || match &exp.planner {
        PlannerConfig::Thesis(t) => t.params,
        _ => unreachable!("fleets planned by the thesis GA are validated to configure it"),
    };
    let map = &exp.scenario.map;
    let projection = exp.scenario.projection;
    std::fs::create_dir_all(dir).map_err(io_err(dir))?;
    let write = |name: &str, bytes: &[u8]| crate::io::write_atomic(&dir.join(name), bytes).map_err(io_err(dir));
    let plan = match run.mode {
        FleetMode::Central => {
            let mut history = HistoryCsv::create(dir).map_err(io_err(dir))?;
            let mut robots = RobotHistory::new(&run.fleet);
            let mut observers: Vec<&mut dyn Observer> = vec![&mut history, &mut robots];
            observers.extend(extra.iter_mut().map(|o| &mut **o as &mut dyn Observer));
            let mut ga = crate::thesis::run::Ga::<super::central::Crew> {
                scenario: super::central::FleetWorld::new(map, &run.fleet, projection),
                params: thesis(),
                seed: exp.seed,
            };
            let out = ga.run(&exp.budget, None, &mut observers).map_err(io_err(dir))?;
            history.finish().map_err(io_err(dir))?;
            write("robots_history.csv", &robots.finish())?;
            let best = &out.best;
            FleetPlan {
                paths: best.paths(),
                evaluations: out.evaluations,
                iterations: out.iterations,
                stop: out.stop,
                details: serde_json::json!({
                    "fitness": best.score.fitness,
                    "genome_len": best.robots.iter().map(|r| r.len()).collect::<Vec<_>>(),
                }),
                violations: Vec::new(),
            }
        }
        FleetMode::Negotiate => {
            let out = super::negotiation::negotiate(map, &run.fleet, &thesis(), projection, exp.seed, &run.negotiation);
            let mut history = csv::Writer::from_writer(Vec::new());
            for record in &out.history {
                history.serialize(record).expect("records serialise");
            }
            write("history.csv", &history.into_inner().expect("in memory"))?;
            let iterations = out.history.iter().map(|r| r.iteration).max().unwrap_or(0);
            let stop = if out.converged {
                StopReason::Settled
            } else if run.negotiation.evaluations.is_some() && iterations < run.negotiation.iterations {
                StopReason::Evaluations
            } else {
                StopReason::Iterations
            };
            let changes: Vec<f64> = out.history.iter().map(|r| r.change).collect();
            FleetPlan {
                paths: out.paths,
                evaluations: out.evaluations,
                iterations,
                stop,
                details: serde_json::json!({
                    "rounds": out.rounds,
                    "converged": out.converged,
                    "last_round_change": changes.chunks(run.fleet.len()).last().map(|c| c.iter().copied().fold(0.0, f64::max)),
                }),
                violations: Vec::new(),
            }
        }
        FleetMode::Waypoint => {
            let mut history = HistoryCsv::create(dir).map_err(io_err(dir))?;
            let mut observers: Vec<&mut dyn Observer> = vec![&mut history];
            observers.extend(extra.iter_mut().map(|o| &mut **o as &mut dyn Observer));
            let out = match exp.planner.planner().run(&exp.scenario, exp.seed, &exp.budget, &mut observers) {
                Ok(out) => out,
                Err(e) => {
                    history.discard();
                    return Err(match e {
                        crate::planner::PlannerError::Input(m) => OutputError::Planner(m),
                        crate::planner::PlannerError::Io(e) => {
                            OutputError::Io { path: dir.join("history.csv"), source: e }
                        }
                    });
                }
            };
            history.finish().map_err(io_err(dir))?;
            FleetPlan {
                paths: out.plan,
                evaluations: out.evaluations,
                iterations: out.iterations,
                stop: out.stop,
                details: serde_json::Value::Object(out.details),
                violations: out.violations,
            }
        }
        FleetMode::Divide => {
            let (paths, division) = super::division::plan(map, &run.fleet, run.angle_deg)
                .map_err(|e| OutputError::Planner(e.to_string()))?;
            FleetPlan {
                paths,
                evaluations: 0,
                iterations: 0,
                stop: StopReason::Completed,
                details: serde_json::json!({
                    "region_cells": division.sizes,
                    "region_targets": division.targets,
                    "detached_cells": division.detached,
                    "angle_deg": run.angle_deg,
                }),
                violations: Vec::new(),
            }
        }
    };
    let score: FleetScore = FleetScorer::new(map, &run.fleet).score(&plan.paths).expect("one path per robot");
    write("config.toml", toml::to_string_pretty(&exp.file).expect("experiment files serialise").as_bytes())?;
    let names: Vec<String> = run.fleet.robots().iter().map(|r| r.name.clone()).collect();
    write("best_path.csv", &crate::io::fleet_path_csv(&plan.paths, &names))?;
    let mut details = crate::planner::details(plan.details);
    details.insert("mode".into(), serde_json::to_value(run.mode).expect("modes serialise"));
    if let Some(name) = &run.name {
        details.insert("fleet_name".into(), name.clone().into());
    }
    let mut violations = plan.violations;
    violations.extend(crate::thesis::planner::obstacle_violations(score.obstacle_cells));
    let feasible = violations.is_empty();
    let summary = Summary {
        planner: run.mode.planner_name(),
        map: map.name().to_string(),
        seed: exp.seed,
        evaluations: plan.evaluations,
        iterations: plan.iterations,
        stop: plan.stop,
        feasible,
        violations,
        warnings: Vec::new(),
        objectives: [
            ("union_reach", score.union_reach),
            ("makespan_s", score.makespan_s),
            ("cov_final", score.cov_final),
            ("t_final", score.t_final),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect(),
        score: scorer_of(exp, &plan.paths).score(&plan.paths),
        fleet: Some(score),
        details,
        wall_s: started.elapsed().as_secs_f64(),
    };
    write("summary.json", serde_json::to_string_pretty(&summary).expect("summaries serialise").as_bytes())?;
    if figures {
        let grid = CoverageGrid::new(map);
        let f = summary.fleet.as_ref().expect("set above");
        let figure = PathFigure {
            map,
            grid: &grid,
            paths: plan.paths.clone(),
            width: exp.scenario.robot.width,
            robots: run.fleet.robots().iter().map(|r| (r.name.clone(), r.footprint.width)).collect(),
            title: format!(
                "{} robots on {} ({}): union {:.3}, makespan {:.0} s",
                run.fleet.len(),
                map.name(),
                run.mode.planner_name(),
                f.union_reach,
                f.makespan_s
            ),
        };
        crate::plot::save(&figure, &dir.join("path"))?;
    }
    Ok(summary)
}
