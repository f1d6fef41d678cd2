//! Running an experiment file with `[[robots]]`: the fleet's negotiation, then its results
//! folder — `config.toml`, `history.csv` (one row per round and robot), `best_path.csv` (with
//! `agent` and `robot` columns), `summary.json` (the fleet metrics and the negotiation's
//! rounds) and `path.png` / `path.svg` (one colour per robot).

use super::config::{FleetMode, FleetRun};
use super::metrics::{FleetScore, FleetScorer};
use super::negotiation::{NegotiationOutcome, negotiate};
use crate::coverage::CoverageGrid;
use crate::planner::PlannerConfig;
use crate::plot::path::PathFigure;
use crate::study::experiment::Experiment;
use std::path::Path;

/// What a fleet run reports (written as `summary.json`).
#[derive(Clone, Debug, serde::Serialize)]
pub struct FleetSummary {
    /// `negotiate`.
    pub mode: FleetMode,
    /// Map name.
    pub map: String,
    /// The run's seed.
    pub seed: u64,
    /// Rounds of exchanges held.
    pub rounds: u32,
    /// Whether the plans settled before the budget ended.
    pub converged: bool,
    /// Evaluations of all robots.
    pub evaluations: u64,
    /// The fleet metrics of the final plans.
    pub fleet: FleetScore,
    /// Wall time in seconds (not part of the deterministic outputs).
    pub wall_s: f64,
}

/// Why a fleet run failed.
#[derive(Debug, thiserror::Error)]
pub enum FleetRunError {
    /// A results file could not be written.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file.
        path: std::path::PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A figure could not be drawn.
    #[error(transparent)]
    Plot(#[from] crate::plot::PlotError),
}

/// Plans `run` for `exp` and writes the results folder `dir`.
pub fn run_fleet(exp: &Experiment, run: &FleetRun, dir: &Path) -> Result<FleetSummary, FleetRunError> {
    let started = std::time::Instant::now();
    let PlannerConfig::Thesis(thesis) = &exp.planner else { unreachable!("fleets are validated to use the thesis GA") };
    let map = &exp.scenario.map;
    let outcome: NegotiationOutcome = match run.mode {
        FleetMode::Negotiate => {
            negotiate(map, &run.fleet, &thesis.params, exp.scenario.projection, exp.seed, &run.negotiation)
        }
    };
    let score = FleetScorer::new(map, &run.fleet).score(&outcome.paths).expect("one path per robot");
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| FleetRunError::Io { path, source }
    };
    std::fs::create_dir_all(dir).map_err(io(dir))?;
    let write = |name: &str, bytes: &[u8]| crate::io::write_atomic(&dir.join(name), bytes).map_err(io(&dir.join(name)));
    write("config.toml", toml::to_string_pretty(&exp.file).expect("experiment files serialise").as_bytes())?;
    let mut history = csv::Writer::from_writer(Vec::new());
    for record in &outcome.history {
        history.serialize(record).expect("records serialise");
    }
    write("history.csv", &history.into_inner().expect("in memory"))?;
    let names: Vec<String> = run.fleet.robots().iter().map(|r| r.name.clone()).collect();
    write("best_path.csv", &crate::io::fleet_path_csv(&outcome.paths, &names))?;
    let summary = FleetSummary {
        mode: run.mode,
        map: map.name().to_string(),
        seed: exp.seed,
        rounds: outcome.rounds,
        converged: outcome.converged,
        evaluations: outcome.evaluations,
        fleet: score,
        wall_s: started.elapsed().as_secs_f64(),
    };
    let json = serde_json::to_string_pretty(&summary).expect("summaries serialise");
    write("summary.json", json.as_bytes())?;
    let grid = CoverageGrid::new(map);
    let figure = PathFigure {
        map,
        grid: &grid,
        paths: outcome.paths.clone(),
        width: exp.scenario.robot.width,
        robots: run.fleet.robots().iter().map(|r| (r.name.clone(), r.footprint.width)).collect(),
        title: format!(
            "{} robots on {} (negotiation): union {:.3}, makespan {:.0} s",
            run.fleet.len(),
            map.name(),
            summary.fleet.union_reach,
            summary.fleet.makespan_s
        ),
    };
    crate::plot::save(&figure, &dir.join("path"))?;
    Ok(summary)
}
