//! A fleet behind the common [`Planner`] interface: the robots of `[[robots]]` planned as
//! `[fleet] mode` says — the centralised fleet GA (with `robots_history.csv` per generation and
//! robot), the decentralised negotiation (its rounds as `history.csv`), area division, or the
//! waypoint planner's teams. The outcome names its robots ([`RunOutcome::agents`]), so the run's
//! output scores and draws each robot at its own width.

use super::Fleet;
use super::config::{FleetMethod, FleetMode};
use super::details::{FleetDetails, Negotiation};
use super::metrics::FleetScorer;
use crate::coverage::score::obstacle_violations;
use crate::ga::observer::{GenerationRecord, Observer};
use crate::planner::entry::RegisteredPlanner;
use crate::planner::memory::MemoryEstimate;
use crate::planner::{Budget, History, Planner, PlannerError, RunOutcome, Scenario, StopReason};
use std::time::Instant;

/// A validated fleet and how it is planned.
#[derive(Clone, Debug)]
pub struct FleetPlanner {
    /// The robots.
    pub fleet: Fleet,
    /// The fleet's label in study tables, if any.
    pub name: Option<String>,
    /// How the robots are planned.
    pub method: FleetMethod,
}

/// `robots_history.csv` of the centralised GA: per generation and robot of the best crew, its
/// genome length, distinct swept cells and time as the fitness reads it.
struct RobotHistory {
    names: Vec<String>,
    out: csv::Writer<Vec<u8>>,
}

impl RobotHistory {
    fn new(fleet: &Fleet) -> Self {
        let mut out = csv::Writer::from_writer(Vec::new());
        out.write_record(["iteration", "robot", "genome_len", "swept_cells", "t_actual_s"]).expect("in memory");
        Self { names: fleet.robots().iter().map(|r| r.name.clone()).collect(), out }
    }
    fn finish(self) -> Vec<u8> {
        self.out.into_inner().expect("in memory")
    }
}

impl Observer for RobotHistory {
    fn generation(&mut self, record: &GenerationRecord) -> std::io::Result<()> {
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

/// A fleet's plan and what its method reports besides the fleet metrics.
struct FleetPlan {
    paths: Vec<Vec<crate::geom::Point>>,
    evaluations: u64,
    iterations: u32,
    stop: StopReason,
    details: serde_json::Value,
    violations: Vec<String>,
    history: History,
    files: Vec<(String, Vec<u8>)>,
}

impl FleetPlanner {
    /// The centralised fleet GA: one genome per robot in every member.
    fn central(
        &self,
        s: &Scenario,
        params: &crate::thesis::params::ThesisParams,
        seed: u64,
        budget: &Budget,
        observers: &mut [&mut dyn Observer],
    ) -> Result<FleetPlan, PlannerError> {
        let mut robots = RobotHistory::new(&self.fleet);
        let mut all: Vec<&mut dyn Observer> = observers.iter_mut().map(|o| &mut **o as &mut dyn Observer).collect();
        all.push(&mut robots);
        let mut ga = crate::thesis::run::Ga::<super::central::Crew> {
            scenario: super::central::FleetWorld::new(&s.map, &self.fleet, s.projection),
            params: *params,
            seed,
            seeds: (Vec::new(), 0),
        };
        let out = ga.run(budget, None, &mut all)?;
        let best = &out.best;
        Ok(FleetPlan {
            paths: best.paths(),
            evaluations: out.evaluations,
            iterations: out.iterations,
            stop: out.stop,
            details: serde_json::json!({
                "fitness": best.score.fitness,
                "genome_len": best.robots.iter().map(|r| r.len()).collect::<Vec<_>>(),
            }),
            violations: Vec::new(),
            history: History::Generations,
            files: vec![("robots_history.csv".into(), robots.finish())],
        })
    }

    /// The decentralised negotiation; its rounds are the run's history.
    fn negotiate(
        &self,
        s: &Scenario,
        params: &crate::thesis::params::ThesisParams,
        negotiation: &super::negotiation::NegotiationParams,
        seed: u64,
        budget: &Budget,
    ) -> Result<FleetPlan, PlannerError> {
        let out = super::negotiation::negotiate(&s.map, &self.fleet, params, s.projection, seed, negotiation, budget)
            .ok_or(PlannerError::Interrupted)?;
        let mut history = csv::Writer::from_writer(Vec::new());
        for record in &out.history {
            history.serialize(record).expect("records serialise");
        }
        let iterations = out.history.iter().map(|r| r.iteration).max().unwrap_or(0);
        let changes: Vec<f64> = out.history.iter().map(|r| r.change).collect();
        Ok(FleetPlan {
            paths: out.paths,
            evaluations: out.evaluations,
            iterations,
            stop: out.stop,
            details: serde_json::to_value(Negotiation {
                rounds: out.rounds,
                converged: out.converged,
                last_round_change: changes
                    .chunks(self.fleet.len())
                    .last()
                    .map(|c| c.iter().copied().fold(0.0, f64::max)),
            })
            .expect("a negotiation serialises"),
            violations: Vec::new(),
            history: History::Own(history.into_inner().expect("in memory")),
            files: Vec::new(),
        })
    }
}

impl RegisteredPlanner for FleetPlanner {
    /// An upper estimate of a run's memory on `map` with `threads` evaluation threads: the
    /// thesis GA's population once per robot for the centralised GA (a member holds a genome and
    /// visit map per robot) and for the negotiation (one GA per robot); the waypoint team's
    /// world; nothing worth counting for area division.
    fn memory_estimate(&self, map: &crate::map::GridMap, threads: usize) -> MemoryEstimate {
        let robots = self.fleet.len() as f64;
        match &self.method {
            FleetMethod::Central(params) | FleetMethod::Negotiate(params, _) => {
                let thesis = crate::thesis::config::ThesisConfig {
                    params: *params,
                    retrain: None,
                    seeds: Vec::new(),
                    seeded: 0,
                    moves: crate::thesis::scenario::Moves::Straight,
                    objective: (crate::thesis::objective::Objective::Footprint, 0.0),
                    population_genomes: false,
                };
                let e = thesis.memory_estimate(map, threads);
                MemoryEstimate { bytes: e.bytes * robots, what: format!("{} for each of {robots} robots", e.what), ..e }
            }
            FleetMethod::Divide { .. } => MemoryEstimate {
                bytes: 0.0,
                key: "robots",
                what: format!("{robots} regions on {} cells", map.rows() * map.cols()),
            },
            FleetMethod::Waypoint(w) => w.memory_estimate(map),
        }
    }

    fn evaluation_rule(&self) -> &'static str {
        match self.method.mode() {
            FleetMode::Negotiate => {
                "each robot's GA has an equal share of the limit and stops after the first generation that reaches \
                 its share: fewer than one generation per robot past it"
            }
            FleetMode::Central => {
                "stops after the first generation that reaches the limit: fewer than one generation's evaluations \
                 past it"
            }
            FleetMode::Waypoint => {
                "stops after the first generation that reaches the limit: fewer than one generation's children past it"
            }
            FleetMode::Divide => "plans once: no evaluation, whatever the limit",
        }
    }

    /// The central GA's iterations, the waypoint team's generations, nothing for the methods
    /// that report rounds of their own or plan in one step.
    fn progress_length(&self, budget: &Budget) -> u64 {
        match &self.method {
            FleetMethod::Central(_) => u64::from(budget.iterations),
            FleetMethod::Waypoint(w) => w.ga.generations as u64,
            FleetMethod::Negotiate(..) | FleetMethod::Divide { .. } => 0,
        }
    }
}

impl Planner for FleetPlanner {
    fn name(&self) -> &'static str {
        self.method.mode().planner_name()
    }

    fn run(
        &self,
        scenario: &Scenario,
        seed: u64,
        budget: &Budget,
        observers: &mut [&mut dyn Observer],
    ) -> Result<RunOutcome, PlannerError> {
        let started = Instant::now();
        let map = &scenario.map;
        let plan = match &self.method {
            FleetMethod::Central(params) => self.central(scenario, params, seed, budget, observers)?,
            FleetMethod::Negotiate(params, negotiation) => {
                self.negotiate(scenario, params, negotiation, seed, budget)?
            }
            FleetMethod::Waypoint(waypoint) => {
                let out = waypoint.run(scenario, seed, budget, observers)?;
                FleetPlan {
                    paths: out.plan,
                    evaluations: out.evaluations,
                    iterations: out.iterations,
                    stop: out.stop,
                    details: serde_json::Value::Object(out.details),
                    violations: out.violations,
                    history: History::Generations,
                    files: Vec::new(),
                }
            }
            FleetMethod::Divide { angle_deg } => {
                let (paths, division) = super::division::plan(map, &self.fleet, *angle_deg)
                    .map_err(|e| PlannerError::Input(e.to_string()))?;
                FleetPlan {
                    paths,
                    evaluations: 0,
                    iterations: 0,
                    stop: StopReason::Completed,
                    details: serde_json::json!({
                        "region_cells": division.sizes,
                        "region_targets": division.targets,
                        "detached_cells": division.detached,
                        "angle_deg": angle_deg,
                    }),
                    violations: Vec::new(),
                    history: History::None,
                    files: Vec::new(),
                }
            }
        };
        let score = FleetScorer::new(map, &self.fleet).score(&plan.paths).expect("one path per robot");
        let mut details = crate::planner::details(plan.details);
        details.insert("mode".into(), serde_json::to_value(self.method.mode()).expect("modes serialise"));
        FleetDetails { fleet_name: self.name.clone(), negotiation: None }.write_into(&mut details);
        let mut violations = plan.violations;
        violations.extend(obstacle_violations(score.obstacle_cells));
        Ok(RunOutcome::new(plan.paths, plan.stop)
            .with_objectives(vec![
                ("union_reach", score.union_reach),
                ("makespan_s", score.makespan_s),
                ("cov_final", score.cov_final),
                ("t_final", score.t_final),
            ])
            .with_violations(violations)
            .with_effort(plan.evaluations, plan.iterations)
            .with_wall_s(started.elapsed().as_secs_f64())
            .with_details(details)
            .with_files(plan.files)
            .with_history(plan.history)
            .with_agents(self.fleet.robots().to_vec()))
    }
}
