//! Running a waypoint-planner experiment and writing its results folder: `config.toml`,
//! `history.csv`, `best_path.csv` (with an agent column), `summary.json`, and the figures
//! `paths`, `coverage`, `pareto_snapshots` and `objectives` (PNG + SVG).

use super::experiment::Experiment;
use super::output::OutputError;
use crate::plot::waypoint::{CoverageFigure, ObjectivesFigure, PathsFigure, SnapshotsFigure};
use crate::waypoint::evaluate::add_views;
use crate::waypoint::precompute::Union;
use crate::waypoint::run::{WaypointStats, run};
use crate::waypoint::world::World;
use std::io::Write;
use std::path::Path;
use std::time::Instant;

/// What a finished waypoint run reports (`summary.json`).
#[derive(serde::Serialize)]
pub struct WaypointSummary {
    /// `C_walls` of the selected organism.
    pub wall_coverage: f64,
    /// `C_open` of the selected organism.
    pub open_coverage: f64,
    /// `C` (eq. 2).
    pub coverage: f64,
    /// Total flight time (px-equivalents of the working raster).
    pub flight_time: f64,
    /// Every agent has at least the minimum number of self loop closures.
    pub loop_closures_ok: bool,
    /// The agents' loop-closure graph is connected (one zero Laplacian eigenvalue).
    pub connected: bool,
    /// The loop-closure matrix (eq. 5).
    pub closures: Vec<Vec<usize>>,
    /// Zero eigenvalues (|λ| < 1e-9) of the agents' Laplacian `L = D − A` (000 eq. 7).
    pub laplacian_zero_eigenvalues: usize,
    /// Agents.
    pub agents: usize,
    /// Waypoints per agent path.
    pub path_lengths: Vec<usize>,
    /// The seed.
    pub seed: u64,
    /// Generations run.
    pub generations: u32,
    /// Waypoints and undirected edges of the graph.
    pub waypoints: usize,
    /// Undirected edges.
    pub edges: usize,
    /// Organisms feasible at generation 0 (of the population size).
    pub initial_feasible: usize,
    /// The plan scored by the thesis footprint model (for the ablation).
    pub footprint: crate::coverage::PathMetrics,
    /// Seconds spent precomputing (map, waypoints, graph, views).
    pub precompute_s: f64,
    /// Wall time in seconds.
    pub wall_s: f64,
}

/// Runs a waypoint experiment into `dir`.
pub fn run_waypoint(
    exp: &Experiment,
    dir: &Path,
    on_generation: &mut dyn FnMut(&WaypointStats),
) -> Result<WaypointSummary, OutputError> {
    let io = |source| OutputError::Io { path: dir.to_path_buf(), source };
    let plan = exp.waypoint.as_ref().expect("validated waypoint experiment");
    std::fs::create_dir_all(dir).map_err(io)?;
    crate::io::write_atomic(
        &dir.join("config.toml"),
        toml::to_string_pretty(&exp.file).expect("serialises").as_bytes(),
    )
    .map_err(io)?;
    let started = Instant::now();
    let world = World::build(&exp.map, &plan.world, plan.ga.agents)
        .map_err(|e| OutputError::Io { path: dir.to_path_buf(), source: std::io::Error::other(e.to_string()) })?;
    let precompute_s = started.elapsed().as_secs_f64();
    let tmp = dir.join(".history.csv.partial");
    let mut hist = std::io::BufWriter::new(std::fs::File::create(&tmp).map_err(io)?);
    writeln!(hist, "generation,c_required,mean_coverage,min_coverage,max_coverage,mean_open,mean_walls,mean_flight_time,min_flight_time,mean_f1,mean_f2,feasible,mean_length,mean_self_closures").map_err(io)?;
    let mut history = Vec::new();
    let mut write_err = None;
    let outcome = run(&world, &plan.ga, exp.file.seed, &mut |s: &WaypointStats| {
        if let Err(e) = writeln!(
            hist,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            s.generation,
            s.c_required,
            s.mean_coverage,
            s.min_coverage,
            s.max_coverage,
            s.mean_open,
            s.mean_walls,
            s.mean_flight_time,
            s.min_flight_time,
            s.mean_f1,
            s.mean_f2,
            s.feasible,
            s.mean_length,
            s.mean_self_closures
        ) {
            write_err.get_or_insert(e);
        }
        history.push(*s);
        on_generation(s);
    });
    if let Some(e) = write_err {
        return Err(io(e));
    }
    hist.flush().map_err(io)?;
    hist.get_ref().sync_all().map_err(io)?;
    std::fs::rename(&tmp, dir.join("history.csv")).map_err(io)?;
    let best = &outcome.population[outcome.best];
    let to_m = |id: u32| world.map.to_world(world.graph.points[id as usize]);
    let paths_m: Vec<Vec<(f64, f64)>> = best.rows.iter().map(|r| r.iter().map(|&i| to_m(i)).collect()).collect();
    let pts: Vec<Vec<crate::geom::Point>> =
        paths_m.iter().map(|p| p.iter().map(|&(x, y)| crate::geom::Point::new(x, y)).collect()).collect();
    crate::io::write_atomic(&dir.join("best_path.csv"), &crate::io::path_csv(&pts)).map_err(io)?;
    let grid = crate::coverage::CoverageGrid::new(&exp.map);
    let footprint = exp.robot.measure_plan(&grid, &mut crate::coverage::SweepScratch::new(&grid), &pts);
    let e = &best.eval;
    let summary = WaypointSummary {
        wall_coverage: e.walls,
        open_coverage: e.open,
        coverage: e.coverage,
        flight_time: e.flight_time,
        loop_closures_ok: e.loops_ok(plan.ga.objectives.lc_min),
        connected: e.connected(),
        closures: e.closures.clone(),
        laplacian_zero_eigenvalues: crate::waypoint::evaluate::laplacian_zero_eigenvalues(
            &e.closures
                .iter()
                .enumerate()
                .map(|(i, r)| r.iter().enumerate().map(|(j, &c)| i != j && c >= 1).collect())
                .collect::<Vec<Vec<bool>>>(),
            1e-9,
        ),
        agents: best.rows.len(),
        path_lengths: best.rows.iter().map(Vec::len).collect(),
        seed: exp.file.seed,
        generations: plan.ga.generations,
        waypoints: world.graph.points.len(),
        edges: world.graph.edge_count(),
        initial_feasible: outcome.initial_feasible,
        footprint,
        precompute_s,
        wall_s: started.elapsed().as_secs_f64(),
    };
    crate::io::write_atomic(
        &dir.join("summary.json"),
        serde_json::to_string_pretty(&summary).expect("serialises").as_bytes(),
    )
    .map_err(io)?;
    // Figures.
    let (self_cl, shared_cl) = closure_edges(&best.rows, plan.ga.objectives.lc_separation);
    let seg = |(a, b): (u32, u32)| (to_m(a), to_m(b));
    let title = format!(
        "{} agent(s) on {}: walls {:.1} %, open {:.1} %",
        best.rows.len(),
        exp.map.name(),
        100.0 * e.walls,
        100.0 * e.open
    );
    crate::plot::save(
        &PathsFigure {
            map: &world.map,
            paths: paths_m,
            self_closures: self_cl.into_iter().map(seg).collect(),
            shared_closures: shared_cl.into_iter().map(seg).collect(),
            title: title.clone(),
        },
        &dir.join("paths"),
    )?;
    let mut u = Union::new(world.traversals.words);
    for r in &best.rows {
        add_views(r, &world.graph, &world.traversals, &mut u);
    }
    let seen = (0..world.map.occluded.len()).map(|i| u.contains(i)).collect();
    crate::plot::save(
        &CoverageFigure { map: &world.map, seen, band: world.map.band(world.buffer), title },
        &dir.join("coverage"),
    )?;
    crate::plot::save(&SnapshotsFigure { snapshots: &outcome.snapshots }, &dir.join("pareto_snapshots"))?;
    crate::plot::save(&ObjectivesFigure { history: &history }, &dir.join("objectives"))?;
    Ok(summary)
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
