//! The cell-order planner behind the common [`Planner`] interface: a run prepares the map,
//! solves the tour with the configured solver (or builds a control's plans), chooses the plan
//! the common scorer finds fastest to the coverage goal, and reports it.

use super::*;
use crate::coverage::bound::{TimeBound, free_diameter_m};

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
                let mut to_record = |g: &search::Generation| g.record(lanes.of(prepared, scenario, g.best.0), members);
                let observers = &mut Observers::new(observers);
                let seeds = if self.seed_directions {
                    controls::direction_tours(prepared, &self.directions, self.layout.control_layouts())
                } else {
                    Vec::new()
                };
                let out = match self.solver {
                    Solver::Ils => ils::iterated_local_search(
                        inst,
                        self.ga.goal,
                        &seeds,
                        (seed, started),
                        budget,
                        observers,
                        &mut to_record,
                    )?,
                    Solver::Ga | Solver::Exact | Solver::Nearest | Solver::Boustrophedon => {
                        search::search_from(inst, &self.ga, &seeds, (seed, started), budget, observers, &mut to_record)?
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
            Solver::Nearest => Ok(self.control(
                prepared,
                controls::direction_tours(prepared, &self.directions, self.layout.control_layouts()),
                Vec::new(),
            )),
            Solver::Boustrophedon => {
                let lanes =
                    controls::boustrophedon_plans(prepared, scenario, &self.directions, (self.completion, self.layout))
                        .map_err(|e| {
                            PlannerError::Input(format!("cell_order on map `{}`: {e}", scenario.map.name()))
                        })?;
                Ok(self.control(prepared, Vec::new(), lanes))
            }
            Solver::Exact => exact_tour(prepared, scenario),
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

impl CellOrderConfig {
    /// The tour problem this configuration's runs solve on `scenario`, prepared as a run
    /// prepares it (on the planning raster), as GTSPLIB text named `name` and the CSV of what
    /// each node is ([`super::gtsplib`]). Its objective is the whole tour's time: a coverage
    /// goal, which ends a run's plan early, is not part of the GTSP.
    pub fn gtsplib(&self, scenario: &Scenario, name: &str) -> Result<(String, String), String> {
        let planning = scenario.for_planning();
        let prepared = prepare(&planning, self.preparation())?;
        let inst = &prepared.instance;
        super::gtsplib::check_weights(inst, &scenario.robot)?;
        Ok((super::gtsplib::instance_text(inst, name), super::gtsplib::nodes_csv(inst, &prepared.sweeps)))
    }
}

impl CellOrderConfig {
    /// The plans the common scorer chooses among, each with the targets it skipped: the
    /// classical control's, or the solver's finalists driven (its best alone where a search
    /// has no goal), then with `classical_finalists` the classical control's plans, which start
    /// at the index returned.
    fn candidates(
        &self,
        prepared: &Prepared,
        s: &Scenario,
        solved: &Solved,
    ) -> Result<(Vec<ScoredPlan>, usize), PlannerError> {
        let mut candidates: Vec<ScoredPlan> = match self.solver {
            Solver::Boustrophedon => solved.lanes.iter().map(|l| (l.path.clone(), l.skipped)).collect(),
            Solver::Ga | Solver::Ils | Solver::Exact | Solver::Nearest => {
                let all = self.coverage_goal.is_some() || self.solver == Solver::Nearest;
                let tours = if all { &solved.finalists[..] } else { &solved.finalists[..1] };
                tours.iter().map(|t| prepared.path(t, &s.robot, (s.start, s.end), self.completion)).collect()
            }
        };
        // Validation asks for a goal with `classical_finalists`.
        let classical_from = candidates.len();
        if self.classical_finalists && matches!(self.solver, Solver::Ga | Solver::Ils) {
            let lanes = controls::boustrophedon_plans(prepared, s, &self.directions, (self.completion, self.layout))
                .map_err(|e| PlannerError::Input(format!("cell_order on map `{}`: {e}", s.map.name())))?;
            candidates.extend(lanes.into_iter().map(|l| (l.path, l.skipped)));
        }
        Ok((candidates, classical_from))
    }
}

/// A plan the common scorer may choose, with the targets it skipped.
type ScoredPlan = (Vec<Point>, usize);

/// The plan a run returns, and how it was chosen.
struct Chosen {
    /// Which finalist.
    index: usize,
    /// Its path, ended at the coverage goal where there is one.
    path: Vec<Point>,
    /// Targets its completion had to skip.
    skipped: usize,
    /// With a coverage goal: the goal, the chosen plan's time to it on the common scorer's
    /// curve of the planning raster, and every finalist's.
    goal: Option<(f64, f64, Vec<f64>)>,
}

impl CellOrderConfig {
    /// How a run prepares its map.
    fn preparation(&self) -> Preparation<'_> {
        Preparation {
            directions: &self.directions,
            completion_m_per_m2: self.completion_m_per_m2,
            completion: self.completion,
            coverage_goal: self.coverage_goal,
            layout: self.layout,
        }
    }

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
        let path = crate::lanes::goal::end_at_goal(&prepared.clear, &prepared.reach, grid, &s.robot, path, goal, s.end);
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

/// A lower bound on the time any plan needs to cover the share `goal` of the cells the common
/// scorer counts reachable on `scenario`'s map as given ([`crate::coverage::bound`]: the length
/// bound of their area on its cells, plus the turning any path covering it needs), whatever
/// raster the plan was made on.
pub fn lower_bound_to_goal(scenario: &Scenario, goal: f64) -> TimeBound {
    let (map, robot) = (&scenario.map, &scenario.robot);
    let area = goal * scenario.reach().coverable_count() as f64 * map.resolution().powi(2);
    TimeBound::one_robot(area, (robot.width, robot.speed, robot.rot_speed), map.resolution(), free_diameter_m(map))
}

/// The planner's own fields of `summary.json`.
fn details_of(
    prepared: &Prepared,
    (solved, classical_chosen): (&Solved, bool),
    skipped: usize,
    goal: Option<(f64, f64, Vec<f64>, TimeBound)>,
    directions: Option<&[f64]>,
    control_plan: Option<(f64, Option<bool>)>,
) -> serde_json::Map<String, serde_json::Value> {
    let inst = &prepared.instance;
    // A classical plan chosen over the search's has no tour of the cells.
    let no_tour = Tour { order: Vec::new(), choice: Vec::new() };
    let tour: Vec<serde_json::Value> = prepared
        .sweeps_of(if classical_chosen { &no_tour } else { &solved.tour })
        .zip(&solved.tour.order)
        .map(|(w, k)| {
            let mut item = serde_json::json!({"cell": k, "direction_deg": w.direction_deg, "entry": w.entry});
            if w.split {
                item["split_lanes"] = true.into();
            }
            item
        })
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
    if let Some((d, split)) = control_plan {
        details.insert("control_direction_deg".into(), d.into());
        if let Some(split) = split {
            details.insert("control_split_lanes".into(), split.into());
        }
    }
    if classical_chosen {
        details.insert("classical_chosen".into(), true.into());
    }
    if let Some((goal, time_s, finalists, bound)) = goal {
        details.insert("coverage_goal".into(), goal.into());

        details.insert("lower_bound_to_goal_s".into(), bound.total_s().into());
        details.insert("turning_bound_to_goal_s".into(), bound.turning_s.into());
        // A goal not reached has no time: `null`, not the ranking's penalty.
        let reached = |t: f64| (t < UNREACHED_S).then_some(t);
        details.insert("time_to_goal_s".into(), reached(time_s).into());
        let finalists: Vec<Option<f64>> = finalists.into_iter().map(reached).collect();
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
        // Planned on the refined raster where the map is coarse; scored on the map as given.
        let planning = scenario.for_planning();
        let s = &*planning;
        let cutoff = SetupCutoff::of_budget(budget, started);
        let prepared = prepare_within(s, self.preparation(), &cutoff).map_err(|e| match e {
            PrepareError::Interrupted => PlannerError::Interrupted,
            PrepareError::Input(m) => PlannerError::Input(format!("cell_order on map `{}`: {m}", s.map.name())),
        })?;
        let grid = crate::coverage::CoverageGrid::new(&s.map);
        let mut solved = self.solve(&prepared, s, &grid, (seed, started), budget, observers)?;
        let (candidates, classical_from) = self.candidates(&prepared, s, &solved)?;
        // The common scorer reads every candidate where it chooses among them.
        if self.coverage_goal.is_some() || self.solver.is_control() {
            solved.evaluations += candidates.len() as u64;
        }
        let chosen = self.chosen_plan(&prepared, candidates, s, &grid);
        let classical_chosen = chosen.index >= classical_from;
        let plan_of = |i: usize| controls::control_plan(&self.directions, self.layout.control_layouts(), i);
        let control_plan = match self.solver {
            Solver::Nearest | Solver::Boustrophedon => Some(plan_of(chosen.index)),
            Solver::Ga | Solver::Ils => classical_chosen.then(|| plan_of(chosen.index - classical_from)),
            Solver::Exact => None,
        };
        // Which layout the control plan has, where two were offered.
        let control_plan = control_plan.map(|(d, split)| (d, self.layout.offers_split().then_some(split)));
        if let Some(tour) = solved.finalists.get(chosen.index) {
            solved.tour = tour.clone();
            solved.cost = prepared.instance.cost(&solved.tour, self.coverage_goal);
        }
        let (path, skipped) = (chosen.path, chosen.skipped);
        let path = crate::planner::executable::executable(&prepared.clear, s.robot.width, path)
            .map_err(|e| PlannerError::Input(format!("cell_order on map `{}`: {e}", scenario.map.name())))?;
        if self.solver == Solver::Boustrophedon || classical_chosen {
            // No tour: the cost is the plan's own mission time.
            solved.cost = crate::coverage::curve::segment_end_times(&path, &s.robot).last().copied().unwrap_or(0.0);
        }
        let grid = crate::coverage::CoverageGrid::new(&scenario.map);
        // The goal time is the scored plan's, on the map as given (the same as the planning
        // raster's where the map is planned as it is).
        let goal = chosen.goal.map(|(goal, _, finalists)| {
            let curve = CoverageCurve::of_plan(&grid, &scenario.reach(), std::slice::from_ref(&path), &[s.robot]);
            (goal, time_to_goal(&curve, goal), finalists, lower_bound_to_goal(scenario, goal))
        });
        let metrics = s.robot.measure(&grid, &mut crate::coverage::SweepScratch::new(&grid), &path);
        let sc = crate::coverage::fitness::score(&metrics, &s.robot, scenario.map.resolution(), s.projection);
        let details = details_of(
            &prepared,
            (&solved, classical_chosen),
            skipped,
            goal,
            self.wall_directions_used(),
            control_plan,
        );
        let history = match self.solver {
            Solver::Ga | Solver::Ils => crate::planner::History::Generations,
            Solver::Exact | Solver::Nearest | Solver::Boustrophedon => crate::planner::History::None,
        };
        Ok(RunOutcome::new(vec![path], solved.stop)
            .with_objectives(vec![("cov_final", sc.cov_final), ("t_final", sc.t_final), ("tour_cost_s", solved.cost)])
            .with_effort(solved.evaluations, solved.iterations)
            .with_wall_s(started.elapsed().as_secs_f64())
            .with_details(details)
            .with_history(history))
    }
}

/// The exact solver's tour (Held–Karp over the cells and their choices), its cost the
/// lower bound of the tour model.
fn exact_tour(prepared: &Prepared, scenario: &Scenario) -> Result<Solved, PlannerError> {
    let inst = &prepared.instance;
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
