//! The cell-order planner: a GA over the combinatorial layer of a boustrophedon decomposition
//! (which cell next, at which lane direction, entered from which corner), the view of
//! Bähnemann et al. (2019) that boustrophedon coverage is a generalised travelling-salesman
//! problem. Cells and their candidate sweeps come from [`sweeps`], wall-free transit costs
//! between sweep ends from [`transit`], the tour problem from [`tour`]; the GA ([`search`],
//! operators in [`operators`], the memetic step in [`local`]), the exact Held–Karp solver
//! ([`exact`]) or the iterated local search of the GTSP reference ([`ils`]) orders them; the
//! controls with no search ([`controls`]) give the plans a search has to beat. The plan drives the chosen sweeps joined by
//! [`crate::map::clearance::Clearance::connect`] routes, then the patterns' completion pass,
//! then to the end station: executable by construction.

pub mod boundary;
pub mod cell_completion;
pub mod config;
pub mod controls;
pub mod exact;
pub mod ils;
pub mod local;
pub mod operators;
pub mod rank;
pub mod reads;
pub mod search;
pub mod sweeps;
pub mod tour;

use crate::coverage::CoverageGrid;
use crate::coverage::curve::CoverageCurve;
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
use tour::{Candidate, Instance, Tour, UNREACHED_S, leg_time, leg_turn_rad};

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

/// How a map is prepared for tours: the lane directions offered to every cell, the driving
/// charged per square metre a sweep leaves, and the completion (which, for
/// [`Completion::Cells`], becomes part of every candidate sweep).
#[derive(Clone, Copy, Debug)]
pub struct Preparation<'a> {
    /// Lane directions in degrees.
    pub directions: &'a [f64],
    /// Metres of completion driving charged per square metre a sweep leaves in its cell.
    pub completion_m_per_m2: f64,
    /// The plan's completion.
    pub completion: Completion,
}

impl<'a> Preparation<'a> {
    /// The preparation a `[cell_order]` section asks for.
    pub fn of(section: &'a config::CellOrderSection) -> Self {
        Self {
            directions: &section.directions,
            completion_m_per_m2: section.completion_m_per_m2,
            completion: section.completion,
        }
    }
}

/// Decomposes the map of `scenario`, builds every candidate sweep at `how.directions` and the
/// leg times between them (wall-free transit at `robot.speed`, turning at `robot.rot_speed`).
/// A sweep's cost is its own time plus the completion it leaves: `how.completion_m_per_m2`
/// metres of driving per square metre of its region it does not sweep.
pub fn prepare<'m>(scenario: &'m Scenario, how: Preparation) -> Result<Prepared<'m>, String> {
    prepare_within(scenario, how, None)
}

/// [`prepare`], refused once `deadline` has passed (checked after the decomposition and
/// while the transit lengths are computed, the phases that grow with the map): a run's wall
/// clock covers its preparation.
pub fn prepare_within<'m>(
    scenario: &'m Scenario,
    how: Preparation,
    deadline: Option<(Instant, std::time::Duration)>,
) -> Result<Prepared<'m>, String> {
    let s = scenario;
    let (directions, completion_m_per_m2) = (how.directions, how.completion_m_per_m2);
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
    let (clear, reach, mut sweeps) = decompose(scenario, directions)?;
    if how.completion == Completion::Cells {
        sweeps.complete_in_cells(&clear, s.robot.width, reach.coverable(), s.robot.speed);
    }
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
    let reachable = reach.coverable_count().max(1) as f64;
    // Seconds of completion charged for the map cells a sweep leaves (written as it always
    // was, so that tour costs keep their last bits).
    let charge = |missed: usize| completion_m_per_m2 * missed as f64 * s.map.resolution().powi(2) / speed;
    let candidates: Vec<Vec<Candidate>> = sweeps
        .cells
        .iter()
        .zip(&sweeps.region_cells)
        .map(|(cell, &region)| {
            cell.iter()
                .map(|w| Candidate {
                    gain: region.saturating_sub(w.missed_cells) as f64 / reachable,
                    completion_s: charge(w.missed_cells),
                    time_s: w.length_m / speed + rotation_time(w.turn_rad, rot) + charge(w.missed_cells),
                    entry: (w.start(), w.start_heading),
                    exit: (w.end(), w.end_heading),
                })
                .collect()
        })
        .collect();
    let all: Vec<Candidate> = candidates.iter().flatten().copied().collect();
    let n = all.len();
    let mut instance = Instance::new(&candidates, |a, b| {
        let from = a.map_or((s.start, Vector::zeros()), |a| all[a].exit);
        let to = b.map_or((s.end, Vector::zeros()), |b| all[b].entry);
        let metres = transit.metres(exit_id[a.unwrap_or(n)] as usize, entry_id[b.unwrap_or(n)] as usize);
        let turn = if rot > 0.0 { leg_turn_rad(from, to) } else { 0.0 };
        leg_time(metres, turn, speed, rot)
    });
    instance.completion_s_per_share = completion_m_per_m2 * s.map.resolution().powi(2) / speed * reachable;
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
        let mut route = Route::new(start);
        for w in self.sweeps_of(tour) {
            route.drive(&self.clear, &w.points);
        }
        self.complete(route, robot, end, completion)
    }

    /// `route` (a tour's sweeps or a control's lanes) with the strips it leaves uncovered
    /// visited as `completion` says, then driven to `end`; with the targets it had to skip.
    pub fn complete(
        &self,
        mut route: Route,
        robot: &crate::coverage::Footprint,
        end: Point,
        completion: Completion,
    ) -> (Vec<Point>, usize) {
        let width = robot.width;
        match completion {
            Completion::None => {}
            Completion::Greedy => crate::patterns::complete::complete(&self.clear, &self.reach, width, &mut route),
            Completion::Boundary | Completion::Cells => {
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
                for chain in boundary::order(&chains, route.last(), Some(end), robot.speed) {
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
    let prepared = prepare_within(scenario, Preparation::of(section), deadline)?;
    let mut tour = search::nearest_neighbour(&prepared.instance);
    local::improve(&prepared.instance, &mut tour, search::ROUNDS);
    Ok(prepared.path(&tour, &scenario.robot, (scenario.start, scenario.end), section.completion).0)
}

/// The history record of a search's generation (or kick): its best tour's time and lane
/// coverage (`(over all free cells, over the reachable ones)`), with `members` feasible.
fn generation_record(g: &search::Generation, (best_coverage, reach): (f64, f64), members: u32) -> GenerationRecord {
    GenerationRecord {
        iteration: g.iteration,
        evaluations: g.evaluations,
        best_fitness: g.fitness.0,
        mean_fitness: g.fitness.1,
        best_coverage,
        best_coverage_reach: Some(reach),
        feasible: Some(members),
        diversity: None,
        extras: vec![("best_time_s", g.best.1), ("mean_time_s", g.mean_time_s)],
        robots: Vec::new(),
    }
}

/// A solved tour and what it cost to find.
struct Solved {
    tour: Tour,
    /// The tours the common scorer chooses among when the plan has a coverage goal, the
    /// solver's best first.
    finalists: Vec<Tour>,
    cost: f64,
    evaluations: u64,
    iterations: u32,
    stop: StopReason,
    nearest: f64,
    exact: Option<f64>,
    /// The boustrophedon control's plans, one per lane direction (a tour solver has none: its
    /// plans are its finalists driven).
    lanes: Vec<controls::Lanes>,
}

/// The lane coverage of a search's best tour (its sweeps without transit, over all free and
/// over the reachable cells) for the history, swept again only when the best tour changes.
struct LaneCoverage<'g> {
    grid: &'g crate::coverage::CoverageGrid,
    scratch: crate::coverage::SweepScratch,
    last: Option<(Tour, (f64, f64))>,
}

impl<'g> LaneCoverage<'g> {
    fn new(grid: &'g crate::coverage::CoverageGrid) -> Self {
        Self { grid, scratch: crate::coverage::SweepScratch::new(grid), last: None }
    }

    fn of(&mut self, prepared: &Prepared, scenario: &Scenario, tour: &Tour) -> (f64, f64) {
        if let Some((t, c)) = &self.last
            && t == tour
        {
            return *c;
        }
        let paths: Vec<Vec<Point>> = prepared.sweeps_of(tour).map(|w| w.points.clone()).collect();
        let swept = self.scratch.sweep_all(self.grid, &paths, scenario.robot.width).unique();
        let c = (
            swept as f64 / self.grid.area_cells().max(1) as f64,
            crate::coverage::score::reach_coverage(&prepared.reach, &self.scratch),
        );
        self.last = Some((tour.clone(), c));
        c
    }
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
            Solver::Ga | Solver::Ils => {
                let mut lanes = LaneCoverage::new(grid);
                // Every tour is driven on wall-free routes: all members are feasible.
                let members = match self.solver {
                    Solver::Ils => 1,
                    Solver::Ga | Solver::Exact | Solver::Nearest | Solver::Boustrophedon => self.ga.population as u32,
                };
                let report = |g: &search::Generation| {
                    let record = generation_record(g, lanes.of(prepared, scenario, g.best.0), members);
                    observers.iter_mut().try_for_each(|o| o.generation(&record))
                };
                let seeds = if self.seed_directions {
                    controls::direction_tours(prepared, &self.directions)
                } else {
                    Vec::new()
                };
                let out = match self.solver {
                    Solver::Ils => {
                        ils::iterated_local_search(inst, self.ga.goal, &seeds, (seed, started), budget, report)?
                    }
                    Solver::Ga | Solver::Exact | Solver::Nearest | Solver::Boustrophedon => {
                        search::search_from(inst, &self.ga, &seeds, (seed, started), budget, report)?
                    }
                };
                let (tour, cost) = out.best;
                Ok(Solved {
                    tour,
                    finalists: out.finalists,
                    cost,
                    evaluations: out.evaluations,
                    iterations: out.iterations,
                    stop: out.stop,
                    nearest: out.nearest_time_s,
                    exact: None,
                    lanes: Vec::new(),
                })
            }
            Solver::Nearest => {
                Ok(self.control(prepared, controls::direction_tours(prepared, &self.directions), Vec::new()))
            }
            Solver::Boustrophedon => {
                let lanes = controls::boustrophedon_plans(prepared, scenario, &self.directions, self.completion)
                    .map_err(|e| PlannerError::Input(format!("cell_order on map `{}`: {e}", scenario.map.name())))?;
                Ok(self.control(prepared, Vec::new(), lanes))
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
                    finalists: vec![tour.clone()],
                    tour,
                    cost,
                    evaluations: states,
                    iterations: 0,
                    stop: StopReason::Completed,
                    nearest: inst.time(&search::nearest_neighbour(inst)),
                    exact: Some(cost),
                    lanes: Vec::new(),
                })
            }
        }
    }

    /// A control's result, before the common scorer chooses: the no-search control's `tours`
    /// (one per direction, the first standing for the solver's best), or the classical
    /// control's `lanes` and no tour.
    fn control(&self, prepared: &Prepared, tours: Vec<Tour>, lanes: Vec<controls::Lanes>) -> Solved {
        let inst = &prepared.instance;
        Solved {
            tour: tours.first().cloned().unwrap_or(Tour { order: Vec::new(), choice: Vec::new() }),
            cost: tours.first().map_or(0.0, |t| inst.cost(t, self.coverage_goal)),
            finalists: tours,
            evaluations: 0,
            iterations: 0,
            stop: StopReason::Completed,
            nearest: inst.time(&search::nearest_neighbour(inst)),
            exact: None,
            lanes,
        }
    }
}

/// The plan a run returns, and how it was chosen.
struct Chosen {
    /// Which finalist.
    index: usize,
    /// Its path, ended at the coverage goal where there is one.
    path: Vec<Point>,
    /// Targets its completion had to skip.
    skipped: usize,
    /// With a coverage goal: the goal, the chosen plan's time to it on the common scorer's
    /// curve, and every finalist's.
    goal: Option<(f64, f64, Vec<f64>)>,
}

impl CellOrderConfig {
    /// Every lane direction offered, where some came from the map's walls (for the summary).
    fn wall_directions_used(&self) -> Option<&[f64]> {
        (self.wall_directions > 0).then_some(self.directions.as_slice())
    }

    /// The plan a run returns among `candidates` (the solver's finalists driven, its best
    /// first, or a control's plans): with a coverage goal, the one whose common-scorer coverage
    /// curve reaches it first (not the tour cost's estimate), ended where it does and driven to
    /// the end station; without one, a searching solver's best, or for a control the fastest of
    /// the plans within [`controls::COVERAGE_TIE`] of the best coverage.
    fn chosen_plan(
        &self,
        prepared: &Prepared,
        candidates: Vec<(Vec<Point>, usize)>,
        s: &Scenario,
        grid: &CoverageGrid,
    ) -> Chosen {
        let curve =
            |path: &Vec<Point>| CoverageCurve::of_plan(grid, &prepared.reach, std::slice::from_ref(path), &[s.robot]);
        let Some(goal) = self.coverage_goal else {
            let index = match self.solver {
                Solver::Ga | Solver::Ils | Solver::Exact => 0,
                Solver::Nearest | Solver::Boustrophedon => {
                    controls::fastest_at_best_coverage(&candidates.iter().map(|(p, _)| curve(p)).collect::<Vec<_>>())
                }
            };
            let (path, skipped) = candidates.into_iter().nth(index).expect("a solver hands over one plan at least");
            return Chosen { index, path, skipped, goal: None };
        };
        let times: Vec<f64> = candidates.iter().map(|(p, _)| time_to_goal(&curve(p), goal)).collect();
        // The first of the fastest: a searching solver's best wins a tie.
        let index = (0..times.len()).fold(0, |best, i| if times[i] < times[best] { i } else { best });
        let (path, skipped) = candidates.into_iter().nth(index).expect("a solver hands over one plan at least");
        let path = end_at_goal(&prepared.clear, &prepared.reach, grid, &s.robot, path, goal, s.end);
        Chosen { index, path, skipped, goal: Some((goal, times[index], times)) }
    }
}

/// The common scorer's time to the coverage `goal` on a plan's `curve`; a plan that never
/// reaches it costs [`UNREACHED_S`] per unit of shortfall plus [`UNREACHED_S`] plus its whole
/// time, behind every plan that does (as [`Instance::time_to_goal`] ranks tours).
pub fn time_to_goal(curve: &CoverageCurve, goal: f64) -> f64 {
    let end = curve.points().last().map_or(0.0, |p| p.0);
    curve.time_to(goal).unwrap_or(UNREACHED_S * (1.0 + goal - curve.coverage_at(end)) + end)
}

/// `path` cut after the segment whose sweep brings the coverage of `reach`'s cells to `goal`
/// (the whole path when none does), then driven to `end` on a wall-free route.
fn end_at_goal(
    clear: &Clearance,
    reach: &Reach,
    grid: &CoverageGrid,
    robot: &crate::coverage::Footprint,
    mut path: Vec<Point>,
    goal: f64,
    end: Point,
) -> Vec<Point> {
    let needed = (goal * reach.coverable_count() as f64 - 1e-9).ceil().max(0.0) as usize;
    let mut covered = vec![false; grid.len()];
    let mut count = 0usize;
    let mut cut = None;
    for (j, w) in path.windows(2).enumerate() {
        crate::coverage::raster::for_each_swept_cell(grid.raster(), w[0], w[1], robot.width, |i| {
            if !covered[i] && reach.is_coverable(i) {
                covered[i] = true;
                count += 1;
            }
        });
        if count >= needed {
            cut = Some(j + 2);
            break;
        }
    }
    let Some(keep) = cut else { return path };
    path.truncate(keep);
    let mut route = Route::new(*path.last().expect("kept two points"));
    route.finish(clear, end);
    path.extend_from_slice(&route.points()[1..]);
    path
}

/// The planner's own fields of `summary.json`.
fn details_of(
    prepared: &Prepared,
    solved: &Solved,
    skipped: usize,
    goal: Option<(f64, f64, Vec<f64>)>,
    directions: Option<&[f64]>,
    control_direction: Option<f64>,
) -> serde_json::Map<String, serde_json::Value> {
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
    if let Some(d) = directions {
        details.insert("directions_deg".into(), d.into());
    }
    if let Some(d) = control_direction {
        details.insert("control_direction_deg".into(), d.into());
    }
    if let Some((goal, time_s, finalists)) = goal {
        details.insert("coverage_goal".into(), goal.into());
        details.insert("time_to_goal_s".into(), time_s.into());
        details.insert("finalists_time_to_goal_s".into(), finalists.into());
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
        let how = Preparation {
            directions: &self.directions,
            completion_m_per_m2: self.completion_m_per_m2,
            completion: self.completion,
        };
        let prepared = prepare_within(s, how, deadline)
            .map_err(|e| PlannerError::Input(format!("cell_order on map `{}`: {e}", s.map.name())))?;
        let grid = crate::coverage::CoverageGrid::new(&s.map);
        let mut solved = self.solve(&prepared, s, &grid, (seed, started), budget, observers)?;
        let candidates: Vec<(Vec<Point>, usize)> = match self.solver {
            Solver::Boustrophedon => solved.lanes.iter().map(|l| (l.path.clone(), l.skipped)).collect(),
            Solver::Ga | Solver::Ils | Solver::Exact | Solver::Nearest => {
                // Without a goal a searching solver returns its best: only that one is driven.
                let all = self.coverage_goal.is_some() || self.solver == Solver::Nearest;
                let tours = if all { &solved.finalists[..] } else { &solved.finalists[..1] };
                tours.iter().map(|t| prepared.path(t, &s.robot, (s.start, s.end), self.completion)).collect()
            }
        };
        // The common scorer reads every candidate where it chooses among them.
        if self.coverage_goal.is_some() || self.solver.is_control() {
            solved.evaluations += candidates.len() as u64;
        }
        let chosen = self.chosen_plan(&prepared, candidates, s, &grid);
        let control_direction = match self.solver {
            Solver::Nearest | Solver::Boustrophedon => Some(self.directions[chosen.index]),
            Solver::Ga | Solver::Ils | Solver::Exact => None,
        };
        if let Some(tour) = solved.finalists.get(chosen.index) {
            solved.tour = tour.clone();
            solved.cost = prepared.instance.cost(&solved.tour, self.coverage_goal);
        }
        let (path, skipped) = (chosen.path, chosen.skipped);
        if self.solver == Solver::Boustrophedon {
            // No tour: the cost is the plan's own mission time.
            solved.cost = crate::coverage::curve::segment_end_times(&path, &s.robot).last().copied().unwrap_or(0.0);
        }
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
            details: details_of(
                &prepared,
                &solved,
                skipped,
                chosen.goal,
                self.wall_directions_used(),
                control_direction,
            ),
            files: Vec::new(),
            history: match self.solver {
                Solver::Ga | Solver::Ils => crate::planner::History::Generations,
                Solver::Exact | Solver::Nearest | Solver::Boustrophedon => crate::planner::History::None,
            },
            agents: Vec::new(),
            artifacts: Box::new(()),
        })
    }
}
