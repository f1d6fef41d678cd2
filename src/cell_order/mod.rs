//! The cell-order planner: a GA over the combinatorial layer of a boustrophedon decomposition
//! (which cell next, at which lane direction, entered from which corner), the view of
//! Bähnemann et al. (2019) that boustrophedon coverage is a generalised travelling-salesman
//! problem. Cells and their candidate sweeps come from [`sweeps`], wall-free transit costs
//! between sweep ends from [`transit`], the tour problem from [`tour`]; the GA ([`search`],
//! operators in [`operators`], the memetic step in [`local`]) or the exact Held–Karp solver
//! ([`exact`]) orders them. The plan drives the chosen sweeps joined by
//! [`crate::map::clearance::Clearance::connect`] routes, then the patterns' completion pass,
//! then to the end station: executable by construction.

pub mod boundary;
pub mod config;
pub mod exact;
pub mod local;
pub mod operators;
pub mod search;
pub mod sweeps;
pub mod tour;

use crate::coverage::motion::rotation_time;
use crate::coverage::transit::{Transit, distinct};
use crate::ga::observer::{GenerationRecord, Observer};
use crate::geom::{Point, Vector};
use crate::map::clearance::Clearance;
use crate::map::reach::Reach;
use crate::patterns::Route;
use crate::planner::{Budget, Planner, PlannerError, RunOutcome, Scenario, StopReason};
use config::{CellOrderConfig, Completion, Solver};
use std::time::Instant;
use sweeps::CellSweeps;
use tour::{Candidate, Instance, Tour, leg_time, leg_turn_rad};

/// The most candidate sweeps a run accepts (cells × directions × 4 entries): the leg-time
/// matrix and the transit lengths each hold the square of it in `f32`, 3.2 GB at this bound.
pub const MAX_CANDIDATES: usize = 20_000;

/// A map prepared for tours: the reachable clearance, the cells and their sweeps, the tour
/// problem with every leg time.
pub struct Prepared<'m> {
    /// The clearance, restricted to the part reachable from the start.
    pub clear: Clearance<'m>,
    /// Reachable and coverable cells.
    pub reach: Reach,
    /// The cells and their candidate sweeps.
    pub sweeps: CellSweeps,
    /// The tour problem.
    pub instance: Instance,
}

/// Decomposes the map of `scenario`, builds every candidate sweep at `directions` and the leg
/// times between them (wall-free transit at `robot.speed`, turning at `robot.rot_speed`). A
/// sweep's cost is its own time plus the completion it leaves: `completion_m_per_m2` metres
/// of driving per square metre of its region it does not sweep.
pub fn prepare<'m>(
    scenario: &'m Scenario,
    directions: &[f64],
    completion_m_per_m2: f64,
) -> Result<Prepared<'m>, String> {
    prepare_within(scenario, directions, completion_m_per_m2, None)
}

/// [`prepare`], refused once `deadline` has passed (checked after the decomposition and
/// while the transit lengths are computed, the phases that grow with the map): a run's wall
/// clock covers its preparation.
pub fn prepare_within<'m>(
    scenario: &'m Scenario,
    directions: &[f64],
    completion_m_per_m2: f64,
    deadline: Option<(Instant, std::time::Duration)>,
) -> Result<Prepared<'m>, String> {
    let s = scenario;
    let begun = Instant::now();
    let out_of_time = |phase: &str| {
        let limit = deadline.map_or(0.0, |(_, d)| d.as_secs_f64());
        format!(
            "the wall clock (budget.wall_clock_s = {limit} s) ran out while {phase}, after {:.1} s of preparation: \
             raise budget.wall_clock_s, or offer fewer cell_order.directions",
            begun.elapsed().as_secs_f64()
        )
    };
    let past = || deadline.is_some_and(|(d, _)| Instant::now() >= d);
    let (clear, reach, sweeps) = decompose(scenario, directions)?;
    if past() {
        return Err(out_of_time("decomposing the map into cells"));
    }
    let count: usize = sweeps.cells.iter().map(Vec::len).sum();
    if count > MAX_CANDIDATES {
        return Err(format!(
            "{} cells with {count} candidate sweeps exceed the limit of {MAX_CANDIDATES}; use fewer \
             cell_order.directions",
            sweeps.len()
        ));
    }
    let flat: Vec<&sweeps::Sweep> = sweeps.cells.iter().flatten().collect();
    let (exits, exit_id) = distinct(&flat.iter().map(|w| w.end()).chain([s.start]).collect::<Vec<_>>());
    let (entries, entry_id) = distinct(&flat.iter().map(|w| w.start()).chain([s.end]).collect::<Vec<_>>());
    let transit = Transit::new_within(&clear, &exits, &entries, deadline.map(|(d, _)| d)).ok_or_else(|| {
        out_of_time(&format!(
            "finding the wall-free routes between {} sweep ends and {} starts",
            exits.len(),
            entries.len()
        ))
    })?;
    let (speed, rot) = (s.robot.speed, s.robot.rot_speed);
    let candidates: Vec<Vec<Candidate>> = sweeps
        .cells
        .iter()
        .map(|cell| {
            cell.iter()
                .map(|w| Candidate {
                    time_s: w.length_m / speed
                        + rotation_time(w.turn_rad, rot)
                        + completion_m_per_m2 * w.missed_cells as f64 * s.map.resolution().powi(2) / speed,
                    entry: (w.start(), w.start_heading),
                    exit: (w.end(), w.end_heading),
                })
                .collect()
        })
        .collect();
    let all: Vec<Candidate> = candidates.iter().flatten().copied().collect();
    let n = all.len();
    let instance = Instance::new(&candidates, |a, b| {
        let from = a.map_or((s.start, Vector::zeros()), |a| all[a].exit);
        let to = b.map_or((s.end, Vector::zeros()), |b| all[b].entry);
        let metres = transit.metres(exit_id[a.unwrap_or(n)] as usize, entry_id[b.unwrap_or(n)] as usize);
        let turn = if rot > 0.0 { leg_turn_rad(from, to) } else { 0.0 };
        leg_time(metres, turn, speed, rot)
    });
    Ok(Prepared { clear, reach, sweeps, instance })
}

/// The reachable clearance of `scenario`, its reach and its cells with their candidate sweeps
/// at `directions`: the first, cheap part of [`prepare`] (no transit), which validation uses
/// to count the cells.
pub fn decompose<'m>(scenario: &'m Scenario, directions: &[f64]) -> Result<(Clearance<'m>, Reach, CellSweeps), String> {
    let s = scenario;
    let width = s.robot.width;
    let mut clear = Clearance::new(&s.map, width);
    let reach = Reach::new(&clear, &[s.start]);
    if reach.centres().iter().all(|c| !c) {
        return Err(format!("no free area reachable from the start fits a robot {width} m wide"));
    }
    clear.restrict(reach.centres().to_vec());
    let sweeps = CellSweeps::new(&clear, width, directions, reach.coverable());
    if sweeps.is_empty() {
        return Err(format!("no lane of a robot {width} m wide fits the area reachable from the start"));
    }
    Ok((clear, reach, sweeps))
}

impl Prepared<'_> {
    /// The chosen sweeps of `tour` in order.
    pub fn sweeps_of<'a>(&'a self, tour: &'a Tour) -> impl Iterator<Item = &'a sweeps::Sweep> + 'a {
        tour.order.iter().map(|&k| &self.sweeps.cells[k as usize][tour.choice[k as usize] as usize])
    }

    /// The path of `tour`: from `start` through the chosen sweeps, joined by wall-free routes,
    /// then the strips left uncovered as `completion` says, then to `end`; with the targets it
    /// had to skip.
    pub fn path(
        &self,
        tour: &Tour,
        robot: &crate::coverage::Footprint,
        stations: (Point, Point),
        completion: Completion,
    ) -> (Vec<Point>, usize) {
        let (start, end) = stations;
        let width = robot.width;
        let mut route = Route::new(start);
        for w in self.sweeps_of(tour) {
            route.drive(&self.clear, &w.points);
        }
        match completion {
            Completion::None => {}
            Completion::Greedy => crate::patterns::complete::complete(&self.clear, &self.reach, width, &mut route),
            Completion::Boundary => {
                let map = self.clear.map();
                let grid = crate::coverage::CoverageGrid::new(map);
                let mut covered = vec![false; grid.len()];
                for w in route.points().windows(2) {
                    crate::coverage::raster::for_each_swept_cell(grid.raster(), w[0], w[1], width, |i| {
                        covered[i] = true
                    });
                }
                // Every uncovered coverable cell: the plan aims at full coverage of the
                // reachable space; the greedy pass takes what the chains leave.
                let targets: Vec<bool> = covered.iter().zip(self.reach.coverable()).map(|(&c, &k)| k && !c).collect();
                let chains = boundary::chains(&self.clear, &targets);
                for chain in boundary::order(&chains, route.last(), end, robot.speed) {
                    for p in chain {
                        route.go(&self.clear, p);
                    }
                }
                crate::patterns::complete::complete(&self.clear, &self.reach, width, &mut route);
            }
        }
        route.finish(&self.clear, end);
        let skipped = route.skipped();
        (route.into_points(), skipped)
    }
}

/// The cell-order plan without its GA: the nearest-neighbour tour improved by the memetic
/// step's local search (best choices, Or-opt, 2-opt) until none improves, which is the memetic
/// GA's first individual, driven as [`Prepared::path`] drives a tour with the section's
/// `directions`, `completion_m_per_m2` and `completion`. It reads no random stream, so every
/// run of a configuration gets the same plan; the thesis GA seeds its population with it
/// (`thesis.seed_population = ["cell_order"]`).
pub fn local_optimum_plan(scenario: &Scenario, section: &config::CellOrderSection) -> Result<Vec<Point>, String> {
    local_optimum_plan_within(scenario, section, None)
}

/// [`local_optimum_plan`] whose preparation is refused past `deadline` (see [`prepare_within`]).
pub fn local_optimum_plan_within(
    scenario: &Scenario,
    section: &config::CellOrderSection,
    deadline: Option<(Instant, std::time::Duration)>,
) -> Result<Vec<Point>, String> {
    let prepared = prepare_within(scenario, &section.directions, section.completion_m_per_m2, deadline)?;
    let mut tour = search::nearest_neighbour(&prepared.instance);
    local::improve(&prepared.instance, &mut tour, search::ROUNDS);
    Ok(prepared.path(&tour, &scenario.robot, (scenario.start, scenario.end), section.completion).0)
}

/// A solved tour and what it cost to find.
struct Solved {
    tour: Tour,
    cost: f64,
    evaluations: u64,
    iterations: u32,
    stop: StopReason,
    nearest: f64,
    exact: Option<f64>,
}

impl CellOrderConfig {
    /// Orders the cells with the configured solver, handing the GA's generations to
    /// `observers` (with the lane coverage of each generation's best tour, swept on `grid`).
    fn solve(
        &self,
        prepared: &Prepared,
        scenario: &Scenario,
        grid: &crate::coverage::CoverageGrid,
        (seed, started): (u64, Instant),
        budget: &Budget,
        observers: &mut [&mut dyn Observer],
    ) -> Result<Solved, PlannerError> {
        let inst = &prepared.instance;
        match self.solver {
            Solver::Ga => {
                let mut scratch = crate::coverage::SweepScratch::new(grid);
                // Lane coverage of the best tour (its sweeps without transit), recomputed when
                // the best changes.
                let mut lanes: Option<(Tour, (f64, f64))> = None;
                let mut lane_coverage = |tour: &Tour| -> (f64, f64) {
                    if let Some((t, c)) = &lanes
                        && t == tour
                    {
                        return *c;
                    }
                    let paths: Vec<Vec<Point>> = prepared.sweeps_of(tour).map(|w| w.points.clone()).collect();
                    let swept = scratch.sweep_all(grid, &paths, scenario.robot.width).unique();
                    let c = (
                        swept as f64 / grid.area_cells().max(1) as f64,
                        crate::coverage::score::reach_coverage(&prepared.reach, &scratch),
                    );
                    lanes = Some((tour.clone(), c));
                    c
                };
                let out = search::search(inst, &self.ga, (seed, started), budget, |g| {
                    let (best_coverage, best_coverage_reach) = lane_coverage(g.best.0);
                    let record = GenerationRecord {
                        iteration: g.iteration,
                        evaluations: g.evaluations,
                        best_fitness: g.fitness.0,
                        mean_fitness: g.fitness.1,
                        best_coverage,
                        best_coverage_reach: Some(best_coverage_reach),
                        // Every tour is driven on wall-free routes: all members are feasible.
                        feasible: Some(self.ga.population as u32),
                        diversity: None,
                        extras: vec![("best_time_s", g.best.1), ("mean_time_s", g.mean_time_s)],
                        robots: Vec::new(),
                    };
                    observers.iter_mut().try_for_each(|o| o.generation(&record))
                })?;
                let (tour, cost) = out.best;
                Ok(Solved {
                    tour,
                    cost,
                    evaluations: out.evaluations,
                    iterations: out.iterations,
                    stop: out.stop,
                    nearest: out.nearest_time_s,
                    exact: None,
                })
            }
            Solver::Exact => {
                let (tour, cost) = exact::held_karp(inst).ok_or_else(|| {
                    PlannerError::Input(format!(
                        "cell_order on map `{}`: cell_order.solver = \"exact\" takes at most {} cells; this map has {} \
                         (use \"ga\")",
                        scenario.map.name(),
                        exact::MAX_EXACT_CELLS,
                        inst.cells()
                    ))
                })?;
                // The states the dynamic programme fills stand in for evaluations.
                let states = (1u64 << inst.cells()) * (0..inst.cells()).map(|k| inst.choices(k) as u64).sum::<u64>();
                Ok(Solved {
                    tour,
                    cost,
                    evaluations: states,
                    iterations: 0,
                    stop: StopReason::Completed,
                    nearest: inst.time(&search::nearest_neighbour(inst)),
                    exact: Some(cost),
                })
            }
        }
    }
}

/// The planner's own fields of `summary.json`.
fn details_of(prepared: &Prepared, solved: &Solved, skipped: usize) -> serde_json::Map<String, serde_json::Value> {
    let inst = &prepared.instance;
    let tour: Vec<serde_json::Value> = prepared
        .sweeps_of(&solved.tour)
        .zip(&solved.tour.order)
        .map(|(w, k)| serde_json::json!({"cell": k, "direction_deg": w.direction_deg, "entry": w.entry}))
        .collect();
    let mut details = crate::planner::details(serde_json::json!({
        "cells": inst.cells(),
        "candidates": (0..inst.cells()).map(|k| inst.choices(k)).sum::<usize>(),
        "base_direction_deg": prepared.sweeps.base_direction_deg,
        "tour_cost_s": solved.cost,
        "nearest_neighbour_cost_s": solved.nearest,
        "skipped_targets": skipped,
        "pockets": prepared.reach.pocket_count(),
        "tour": tour,
    }));
    if let Some(t) = solved.exact {
        details.insert("exact_cost_s".into(), t.into());
    }
    details
}

impl Planner for CellOrderConfig {
    fn name(&self) -> &'static str {
        "cell_order"
    }

    fn run(
        &self,
        scenario: &Scenario,
        seed: u64,
        budget: &Budget,
        observers: &mut [&mut dyn Observer],
    ) -> Result<RunOutcome, PlannerError> {
        let started = Instant::now();
        let s = scenario;
        let deadline = budget.wall_clock.map(|d| (started + d, d));
        let prepared = prepare_within(s, &self.directions, self.completion_m_per_m2, deadline)
            .map_err(|e| PlannerError::Input(format!("cell_order on map `{}`: {e}", s.map.name())))?;
        let grid = crate::coverage::CoverageGrid::new(&s.map);
        let solved = self.solve(&prepared, s, &grid, (seed, started), budget, observers)?;
        let (path, skipped) = prepared.path(&solved.tour, &s.robot, (s.start, s.end), self.completion);
        let metrics = s.robot.measure(&grid, &mut crate::coverage::SweepScratch::new(&grid), &path);
        let sc = crate::coverage::fitness::score(&metrics, &s.robot, s.map.resolution(), s.projection);
        Ok(RunOutcome {
            plan: vec![path],
            objectives: vec![("cov_final", sc.cov_final), ("t_final", sc.t_final), ("tour_cost_s", solved.cost)],
            feasible: true,
            warnings: Vec::new(),
            violations: Vec::new(),
            evaluations: solved.evaluations,
            iterations: solved.iterations,
            stop: solved.stop,
            wall_s: started.elapsed().as_secs_f64(),
            details: details_of(&prepared, &solved, skipped),
            files: Vec::new(),
            history: match self.solver {
                Solver::Ga => crate::planner::History::Generations,
                Solver::Exact => crate::planner::History::None,
            },
            agents: Vec::new(),
            artifacts: Box::new(()),
        })
    }
}
