//! The waypoint-graph maximin planner of 000 behind the common [`Planner`] interface: builds
//! the world (raster, waypoints, graph, traversal views), runs the maximin GA within the
//! budget, reports the organism chosen by [`reported`](super::run::reported) with its constraint violations, and
//! draws its own figures (paths with loop closures, camera coverage, Pareto snapshots,
//! population objectives).

use super::config::WaypointConfig;
use super::evaluate::{LoopClosureRule, add_views, laplacian_zero_eigenvalues, required_coverage};
use super::figures::{CoverageFigure, GraphFigure, ObjectivesFigure, PathsFigure, SnapshotsFigure};
use super::precompute::Union;
use super::run::{Organism, WaypointOutcome, WaypointStats, run};
use super::world::World;
use crate::coverage::{CoverageGrid, SweepScratch};
use crate::ga::observer::{GenerationRecord, Observer, Observers};
use crate::geom::Point;
use crate::planner::{Budget, Planner, PlannerError, RunOutcome, Scenario};
use std::path::Path;
use std::time::Instant;

/// What the figures need after a run.
struct Artifacts {
    world: World,
    outcome: WaypointOutcome,
}

/// An organism's paths in metres.
fn paths_m(world: &World, o: &Organism) -> Vec<Vec<Point>> {
    o.rows
        .iter()
        .map(|r| {
            r.iter()
                .map(|&i| {
                    let (x, y) = world.map.to_world(world.graph.points[i as usize]);
                    Point::new(x, y)
                })
                .collect()
        })
        .collect()
}

/// The constraints an organism violates at generation `g`, in words.
fn violations(cfg: &WaypointConfig, o: &Organism, g: u32) -> Vec<String> {
    let p = &cfg.ga.objectives;
    let mut out = Vec::new();
    for (k, row) in o.eval.closures.iter().enumerate() {
        if row[k] < p.lc_min {
            out.push(format!(
                "agent {k} has {} self loop closures (counted per {}), fewer than lc_min = {}",
                row[k],
                p.lc_rule.name(),
                p.lc_min
            ));
        }
    }
    if !o.eval.connected() {
        out.push(format!("the agents' loop-closure graph has {} components, not 1", o.eval.components));
    }
    let c_req = required_coverage(p, g);
    if o.eval.coverage < c_req {
        out.push(format!("coverage C = {:.4} is below the required {:.4}", o.eval.coverage, c_req));
    }
    out
}

/// Share of the wall band below which the set-up warns that the graph cannot see part of it.
const REACHABLE_WARNING: f64 = 0.99;

/// What the user should know about the world: waypoints the start cannot reach, and wall band
/// that no traversal sees (which caps `C_walls`, and may make the coverage constraint
/// unreachable).
fn setup_warnings(cfg: &WaypointConfig, world: &World) -> Vec<String> {
    let mut out = Vec::new();
    if world.dropped > 0 {
        out.push(format!(
            "{} waypoints lie where the start cannot reach them through the graph and were dropped",
            world.dropped
        ));
    }
    if world.reachable_walls < REACHABLE_WARNING {
        let c_end = cfg.ga.objectives.c_end;
        let alpha = cfg.ga.objectives.alpha_cov;
        let mut w = format!(
            "the waypoint graph sees only {:.1} % of the wall band (reachable_wall_fraction {:.4}; waypoints.png shows where)",
            100.0 * world.reachable_walls,
            world.reachable_walls
        );
        if alpha + (1.0 - alpha) * world.reachable_walls < c_end {
            w.push_str(&format!(": the coverage constraint C_end = {c_end} cannot be met"));
        }
        out.push(w);
    }
    out
}

/// The history record of one generation: the best organism's coverage swept on the map
/// (`best_coverage`, `best_coverage_reach`) and 000's objectives of the population.
fn generation_record(
    s: &WaypointStats,
    b: &Organism,
    evaluations: u64,
    best_coverage: f64,
    best_coverage_reach: f64,
) -> GenerationRecord {
    GenerationRecord {
        iteration: s.generation,
        evaluations,
        best_fitness: b.eval.coverage,
        mean_fitness: s.mean_coverage,
        best_coverage,
        best_coverage_reach: Some(best_coverage_reach),
        feasible: Some(s.feasible),
        diversity: None,
        robots: Vec::new(),
        extras: vec![
            ("best_walls", b.eval.walls),
            ("best_open", b.eval.open),
            ("best_flight_time", b.eval.flight_time),
            ("c_required", s.c_required),
            ("mean_coverage", s.mean_coverage),
            ("min_coverage", s.min_coverage),
            ("max_coverage", s.max_coverage),
            ("mean_open", s.mean_open),
            ("mean_walls", s.mean_walls),
            ("mean_flight_time", s.mean_flight_time),
            ("min_flight_time", s.min_flight_time),
            ("mean_f1", s.mean_f1),
            ("mean_f2", s.mean_f2),
            ("mean_length", s.mean_length),
            ("mean_self_closures", s.mean_self_closures),
        ],
    }
}

impl WaypointConfig {
    /// `summary.json`'s details of the best organism: 000's objectives, the team's loop
    /// closures and connectivity, and the waypoint graph the run planned on.
    fn details(
        &self,
        scenario: &Scenario,
        world: &World,
        best: &Organism,
        outcome: &WaypointOutcome,
        precompute_s: f64,
    ) -> serde_json::Map<String, serde_json::Value> {
        let e = &best.eval;
        let adjacent: Vec<Vec<bool>> = e
            .closures
            .iter()
            .enumerate()
            .map(|(i, r)| r.iter().enumerate().map(|(j, &c)| i != j && c >= 1).collect())
            .collect();
        let counts = |rule: LoopClosureRule| -> Vec<usize> {
            best.rows.iter().map(|r| rule.count(r, r, true, self.ga.objectives.lc_separation)).collect()
        };
        crate::planner::details(serde_json::json!({
            "wall_coverage": e.walls,
            "open_coverage": e.open,
            "coverage": e.coverage,
            "flight_time": e.flight_time,
            "flight_time_s": e.flight_time * self.world.scale / scenario.robot.speed,
            "loop_closures_ok": e.loops_ok(self.ga.objectives.lc_min),
            "connected": e.connected(),
            "closures": e.closures,
            "laplacian_zero_eigenvalues": laplacian_zero_eigenvalues(&adjacent, 1e-9),
            "agents": best.rows.len(),
            "path_lengths": best.rows.iter().map(Vec::len).collect::<Vec<_>>(),
            "generations": outcome.generations,
            "lc_rule": self.ga.objectives.lc_rule.name(),
            "self_closures_per_run": counts(LoopClosureRule::Run),
            "self_closures_per_edge": counts(LoopClosureRule::Edge),
            "waypoints": world.graph.points.len(),
            "edges": world.graph.edge_count(),
            "waypoints_dropped": world.dropped,
            "gap_waypoints_added": world.gap_fills,
            "passage_waypoints_added": world.passage_fills,
            "reachable_wall_fraction": world.reachable_walls,
            "grid_step_m": self.world.geometry.grid_step,
            "safety_buffer_m": self.world.geometry.buffer,
            "wall_band_m": self.world.geometry.wall_band,
            "initial_feasible": outcome.initial_feasible,
            "precompute_s": precompute_s,
        }))
    }
}

impl Planner for WaypointConfig {
    fn name(&self) -> &'static str {
        "waypoint"
    }

    fn run(
        &self,
        scenario: &Scenario,
        seed: u64,
        budget: &Budget,
        observers: &mut [&mut dyn Observer],
    ) -> Result<RunOutcome, PlannerError> {
        let started = Instant::now();
        let cutoff = crate::planner::executor::SetupCutoff::of_budget(budget, started);
        let world = World::build_within(&scenario.map, &self.world, self.ga.agents, &cutoff).map_err(|e| match e {
            crate::waypoint::world::WorldError::Interrupted => PlannerError::Interrupted,
            e => PlannerError::Input(format!("waypoint planner on map `{}`: {e}", scenario.map.name())),
        })?;
        let precompute_s = started.elapsed().as_secs_f64();
        // The wall clock counts the precompute too: the GA gets what is left of it.
        let budget =
            &Budget { wall_clock: budget.wall_clock.map(|d| d.saturating_sub(started.elapsed())), ..budget.clone() };
        let grid = CoverageGrid::new(&scenario.map);
        let mut scratch = SweepScratch::new(&grid);
        let reach = scenario.reach();
        let mut to_record = |s: &WaypointStats, b: &Organism, evaluations| {
            let counts = scratch.sweep_all(&grid, &paths_m(&world, b), scenario.robot.width);
            generation_record(
                s,
                b,
                evaluations,
                counts.unique() as f64 / grid.area_cells().max(1) as f64,
                crate::coverage::score::reach_coverage(&reach, &scratch),
            )
        };
        let outcome = run(&world, &self.ga, seed, budget, &mut Observers::new(observers), &mut to_record)?;
        let best = &outcome.population[outcome.best];
        let e = &best.eval;
        let viol = violations(self, best, outcome.generations);
        let warnings = setup_warnings(self, &world);
        let details = self.details(scenario, &world, best, &outcome, precompute_s);
        // Every agent starts and ends at the stations, as every other planner's plan does.
        let plan = {
            let legs = crate::planner::legs::StationLegs::new(&scenario.map, scenario.robot.width, scenario.start);
            paths_m(&world, best).iter().map(|p| legs.around(p, scenario.end)).collect()
        };
        let objectives = vec![
            ("coverage", e.coverage),
            ("wall_coverage", e.walls),
            ("open_coverage", e.open),
            ("flight_time", e.flight_time),
        ];
        let (evaluations, generations, stop) = (outcome.evaluations, outcome.generations, outcome.stop);
        Ok(RunOutcome::new(plan, stop)
            .with_objectives(objectives)
            .with_violations(viol)
            .with_warnings(warnings)
            .with_effort(evaluations, generations)
            .with_wall_s(started.elapsed().as_secs_f64())
            .with_details(details)
            .with_history(crate::planner::History::Generations)
            .with_artifacts(Box::new(Artifacts { world, outcome })))
    }

    fn write_figures(
        &self,
        scenario: &Scenario,
        outcome: &RunOutcome,
        dir: &Path,
    ) -> Result<(), crate::plot::PlotError> {
        let Some(a) = outcome.artifacts.downcast_ref::<Artifacts>() else { return Ok(()) };
        let (world, out) = (&a.world, &a.outcome);
        let best = &out.population[out.best];
        let e = &best.eval;
        let to_m = |id: u32| world.map.to_world(world.graph.points[id as usize]);
        let paths: Vec<Vec<(f64, f64)>> = best.rows.iter().map(|r| r.iter().map(|&i| to_m(i)).collect()).collect();
        let (self_cl, shared_cl) = closure_edges(&best.rows, self.ga.objectives.lc_separation);
        let seg = |(a, b): (u32, u32)| (to_m(a), to_m(b));
        let unknown = super::figures::unknown_pixels(&world.map, &scenario.map);
        let title = format!(
            "{} agent(s) on {}: walls {:.1} %, open {:.1} %",
            best.rows.len(),
            scenario.map.name(),
            100.0 * e.walls,
            100.0 * e.open
        );
        crate::plot::save(
            &PathsFigure {
                map: &world.map,
                paths,
                self_closures: self_cl.into_iter().map(seg).collect(),
                shared_closures: shared_cl.into_iter().map(seg).collect(),
                unknown: unknown.clone(),
                title: title.clone(),
            },
            &dir.join("paths"),
        )?;
        let reach = world.traversals.all_views();
        let band = world.map.band(world.band_px);
        let g = &world.graph;
        let edges = (0..g.points.len())
            .flat_map(|i| g.adj[i].iter().filter(move |&&j| (j as usize) > i).map(move |&j| (i as u32, j)))
            .map(|(i, j)| (to_m(i), to_m(j)))
            .collect();
        crate::plot::save(
            &GraphFigure {
                map: &world.map,
                points: (0..g.points.len() as u32).map(to_m).collect(),
                edges,
                starts: world.starts.iter().map(|&s| to_m(s)).collect(),
                band_seen: (0..world.map.occluded.len()).map(|i| reach.contains(i)).collect(),
                band: band.clone(),
                unknown: unknown.clone(),
                title: format!(
                    "{} waypoints on {}: {:.1} % of the wall band seen from the graph",
                    g.points.len(),
                    scenario.map.name(),
                    100.0 * world.reachable_walls
                ),
            },
            &dir.join("waypoints"),
        )?;
        let mut u = Union::new(world.traversals.words);
        for r in &best.rows {
            add_views(r, &world.graph, &world.traversals, &mut u);
        }
        let seen = (0..world.map.occluded.len()).map(|i| u.contains(i)).collect();
        crate::plot::save(&CoverageFigure { map: &world.map, seen, band, unknown, title }, &dir.join("coverage"))?;
        let seconds_per_px = self.world.scale / scenario.robot.speed;
        crate::plot::save(
            &SnapshotsFigure { snapshots: &out.snapshots, seconds_per_px },
            &dir.join("pareto_snapshots"),
        )?;
        crate::plot::save(&ObjectivesFigure { history: &a.outcome.history, seconds_per_px }, &dir.join("objectives"))
    }
}

/// Directed edges as waypoint id pairs.
type EdgeList = Vec<(u32, u32)>;

/// Directed edges that close loops: re-traversals within an agent's path (separated by at
/// least `separation`), and edges shared between agents.
fn closure_edges(rows: &[Vec<u32>], separation: usize) -> (EdgeList, EdgeList) {
    let edges = |r: &Vec<u32>| r.windows(2).map(|w| (w[0], w[1])).collect::<Vec<_>>();
    let mut own = std::collections::BTreeSet::new();
    let mut shared = std::collections::BTreeSet::new();
    for (i, ri) in rows.iter().enumerate() {
        let ei = edges(ri);
        for a in 0..ei.len() {
            if ei.get(a + separation.max(1)..).is_some_and(|rest| rest.contains(&ei[a])) {
                own.insert(ei[a]);
            }
        }
        for rj in &rows[i + 1..] {
            for e in edges(rj) {
                if ei.contains(&e) {
                    shared.insert(e);
                }
            }
        }
    }
    (own.into_iter().collect(), shared.into_iter().collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closure_edges_by_hand() {
        // Agent 0 re-flies 0→1 four steps later; agent 1 shares 2→3 with agent 0.
        let rows = vec![vec![0, 1, 2, 3, 0, 1], vec![5, 2, 3]];
        let (own, shared) = closure_edges(&rows, 4);
        assert_eq!(own, vec![(0, 1)]);
        assert_eq!(shared, vec![(2, 3)]);
        assert!(closure_edges(&rows, 5).0.is_empty());
    }
}
