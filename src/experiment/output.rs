//! Running one experiment of any planner and writing its results folder: `config.toml`,
//! `history.csv` (streamed: planner-neutral columns, then the planner's extras),
//! `best_path.csv`, the planner's own files, `summary.json` (the run, the planner's objectives
//! and details, and the common [`Score`]), `path.png/.svg` and the planner's own figures.
//! Every file is written to a temporary name and renamed when complete.

use super::file::Experiment;
use crate::coverage::score::{Score, Scorer};
use crate::ga::observer::{GenerationRecord, Observer};
use crate::planner::{Agent, History, PlannerError, RunOutcome, StopReason};
use crate::plot::path::PathFigure;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Failure while running or writing results.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// A results file could not be written.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The planner cannot plan this configuration (the user's input).
    #[error("{0}")]
    Planner(String),
    /// A figure could not be drawn.
    #[error(transparent)]
    Plot(#[from] crate::plot::PlotError),
    /// The run's interrupt flag was raised: it stopped part-way and wrote nothing.
    #[error("the run was interrupted after {iterations} iterations; nothing was written")]
    Interrupted {
        /// Iterations it had completed.
        iterations: u32,
    },
}

fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> OutputError + '_ {
    move |source| OutputError::Io { path: path.to_path_buf(), source }
}

/// Streams `history.csv` row by row into a temporary file, renamed by [`HistoryCsv::finish`];
/// the header comes from the first record (neutral columns, then that planner's extras).
struct HistoryCsv {
    tmp: PathBuf,
    path: PathBuf,
    out: std::io::BufWriter<std::fs::File>,
    header_written: bool,
    diversity_every: u32,
}

impl HistoryCsv {
    /// Opens `<dir>/history.csv` (as a temporary file until finished).
    pub fn create(dir: &Path, diversity_every: u32) -> std::io::Result<Self> {
        let path = dir.join("history.csv");
        let tmp = dir.join(PARTIAL_HISTORY);
        let out = std::io::BufWriter::new(std::fs::File::create(&tmp)?);
        Ok(Self { tmp, path, out, header_written: false, diversity_every })
    }
    /// Removes the temporary file (the run was refused).
    pub fn discard(self) {
        let _ = std::fs::remove_file(&self.tmp);
    }
    /// Flushes, syncs and renames into place.
    pub fn finish(mut self) -> std::io::Result<()> {
        if !self.header_written {
            writeln!(self.out, "{}", GenerationRecord::default().header())?;
        }
        self.out.flush()?;
        self.out.get_ref().sync_all()?;
        std::fs::rename(&self.tmp, &self.path)
    }
}

impl Observer for HistoryCsv {
    fn generation(&mut self, record: &GenerationRecord) -> std::io::Result<()> {
        if !self.header_written {
            writeln!(self.out, "{}", record.header())?;
            self.header_written = true;
        }
        writeln!(self.out, "{}", record.csv_row())
    }
    fn diversity_every(&self) -> Option<u32> {
        Some(self.diversity_every)
    }
}

/// The history's file name while the run goes on (renamed to `history.csv` when it ends).
pub const PARTIAL_HISTORY: &str = ".history.csv.partial";

/// `budget.evaluations` and what the run made of it (`summary.json`'s `evaluation_budget`).
#[derive(Clone, Debug, serde::Serialize)]
pub struct EvaluationBudget {
    /// `budget.evaluations`.
    pub limit: u64,
    /// Evaluations spent past the limit (0 when within it).
    pub past_limit: u64,
    /// How far past the limit the planner can go, in words.
    pub rule: &'static str,
}

/// What a finished run reports (`summary.json`).
#[derive(Clone, Debug, serde::Serialize)]
pub struct Summary {
    /// The planner's name.
    pub planner: &'static str,
    /// The map's name.
    pub map: String,
    /// The seed.
    pub seed: u64,
    /// Fitness evaluations spent.
    pub evaluations: u64,
    /// Where `budget.evaluations` limits the run: the limit and how far past it the planner can go.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub evaluation_budget: Option<EvaluationBudget>,
    /// Iterations (generations) completed.
    pub iterations: u32,
    /// Why the run stopped.
    pub stop: StopReason,
    /// Whether the plan meets the planner's own constraints (the waypoint planner's ramp and
    /// loop closures, the thesis GA's obstacle-free rule, …); whether a robot can drive it at
    /// all is the common scorer's `score.executable`.
    pub planner_feasible: bool,
    /// The planner's constraints it violates, in words.
    pub violations: Vec<String>,
    /// Warnings about the run's set-up, in words.
    pub warnings: Vec<String>,
    /// The planner's own objectives of the plan.
    pub objectives: std::collections::BTreeMap<String, f64>,
    /// The common scorer's metrics of the plan.
    pub score: Score,
    /// The robot and the time model `score.time_s` follows, in words
    /// ([`crate::coverage::motion::time_model`]); for a fleet, each robot's (`per robot: name:
    /// model; …`).
    pub time_model: String,
    /// The plan's time-to-coverage curve in figures: times to 80, 90 and 95 % of the reachable
    /// cells and the area over the curve (the curve itself is `coverage_curve.csv`).
    pub coverage_curve: crate::coverage::curve::CurveSummary,
    /// Fleet metrics of a plan of several agents (the experiment's robot for each; union,
    /// overlap, makespan, balance), as `covga eval --fleet` reports them.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fleet: Option<crate::fleet::metrics::FleetScore>,
    /// Planner-specific fields.
    #[serde(flatten)]
    pub details: serde_json::Map<String, serde_json::Value>,
    /// Wall time in seconds (the only field that differs between identical runs).
    pub wall_s: f64,
}

/// The time model of a plan in words: the experiment's robot, or for a plan that names its
/// robots (a fleet) each robot's own, since each drives at its own speeds.
fn plan_time_model(exp: &Experiment, agents: &[Agent]) -> String {
    if agents.is_empty() {
        return crate::coverage::motion::time_model(&exp.scenario.robot);
    }
    let each: Vec<String> =
        agents.iter().map(|a| format!("{}: {}", a.name, crate::coverage::motion::time_model(&a.footprint))).collect();
    format!("per robot: {}", each.join("; "))
}

/// The common scorer of an experiment: its map, robot, projection and camera, with the
/// stations and every agent's start as the places reachability is measured from; for a plan
/// that names its robots, the narrowest robot's reachable cells.
fn scorer_of(exp: &Experiment, plan: &[Vec<crate::geom::Point>], agents: &[Agent]) -> Scorer {
    let s = &exp.scenario;
    let mut stations = vec![s.start];
    stations.extend(plan.iter().filter_map(|p| p.first().copied()));
    let widths: Vec<f64> = agents.iter().map(|a| a.footprint.width).collect();
    Scorer::for_widths(&s.map, s.robot, &widths, s.projection, &s.camera, &stations)
}

/// The common score of a plan: each named robot at its own width and speeds, any other plan
/// with the experiment's robot on every path.
fn common_score(scorer: &Scorer, plan: &[Vec<crate::geom::Point>], agents: &[Agent]) -> Score {
    if agents.len() == plan.len() && !agents.is_empty() {
        let robots: Vec<_> = agents.iter().map(|a| a.footprint).collect();
        scorer.score_agents(plan, &robots)
    } else {
        scorer.score(plan)
    }
}

/// A planner's `details` with its `time_to_goal_s` read off the common scorer's `curve` on the
/// map as given, wherever the planner states a `coverage_goal`: a planner that plans on a
/// refined raster (or on its own reachable set) estimates the time where it chooses its plan,
/// but the recorded goal time is the scored plan's (`null` where the plan does not reach it).
fn with_goal_time_of(
    mut details: serde_json::Map<String, serde_json::Value>,
    curve: &crate::coverage::curve::CoverageCurve,
) -> serde_json::Map<String, serde_json::Value> {
    if let Some(goal) = details.get("coverage_goal").and_then(serde_json::Value::as_f64) {
        details.insert("time_to_goal_s".into(), curve.time_to(goal).into());
    }
    details
}

/// The time-to-coverage curve of a plan, each agent on its own clock: each named robot at its
/// own width and speeds, any other plan with the experiment's robot on every path.
fn coverage_curve(
    exp: &Experiment,
    scorer: &Scorer,
    plan: &[Vec<crate::geom::Point>],
    agents: &[Agent],
) -> crate::coverage::curve::CoverageCurve {
    let robots: Vec<_> = if agents.len() == plan.len() && !agents.is_empty() {
        agents.iter().map(|a| a.footprint).collect()
    } else {
        vec![exp.scenario.robot; plan.len()]
    };
    crate::coverage::curve::CoverageCurve::of_plan(scorer.grid(), scorer.reach(), plan, &robots)
}

/// The fleet metrics of a plan: for a plan that names its robots (a fleet), each robot at its
/// own width and stations; for any other plan of two agents or more, each agent the
/// experiment's robot starting and ending where its path does.
fn team_score(
    exp: &Experiment,
    plan: &[Vec<crate::geom::Point>],
    agents: &[Agent],
) -> Option<crate::fleet::metrics::FleetScore> {
    let fleet = if agents.is_empty() {
        if plan.len() < 2 || plan.iter().any(Vec::is_empty) {
            return None;
        }
        let stations: Vec<_> = plan.iter().map(|p| (p[0], *p.last().expect("non-empty"))).collect();
        crate::fleet::Fleet::homogeneous(exp.scenario.robot, &stations)?
    } else {
        crate::fleet::Fleet::from_agents(agents.to_vec())?
    };
    crate::fleet::metrics::FleetScorer::new(&exp.scenario.map, &fleet).score(plan).ok()
}

/// The title of a run's path figure: the common score, or the fleet's union and makespan for
/// a plan that names its robots.
fn path_title(planner: &str, map: &str, summary: &Summary, outcome: &RunOutcome) -> String {
    match (&summary.fleet, outcome.agents.is_empty()) {
        (Some(f), false) => format!(
            "{} robots on {map} ({planner}): union {:.3}, makespan {:.0} s",
            outcome.agents.len(),
            f.union_reach,
            f.makespan_s
        ),
        _ => {
            let s = &summary.score;
            format!(
                "{planner} on {map}: cov_final {:.3} (reachable {:.3}), t_final {:.3}",
                s.cov_final_free, s.cov_final_reach, s.t_final
            )
        }
    }
}

/// The planner's run of `exp`, its generations streamed to `history` and to `extra`; a run
/// refused, failed or interrupted leaves nothing behind, not even its partial history.
fn plan(
    exp: &Experiment,
    dir: &Path,
    mut history: HistoryCsv,
    extra: &mut [&mut dyn Observer],
) -> Result<(RunOutcome, HistoryCsv), OutputError> {
    let outcome = {
        let mut observers: Vec<&mut dyn Observer> = vec![&mut history];
        observers.extend(extra.iter_mut().map(|o| &mut **o as &mut dyn Observer));
        exp.planner.planner().run(&exp.scenario, exp.seed, &exp.budget, &mut observers)
    };
    match outcome {
        Ok(o) if o.stop == crate::planner::StopReason::Interrupted => {
            // A run cut short by its caller is not the run the file asks for: nothing of it stays.
            history.discard();
            Err(OutputError::Interrupted { iterations: o.iterations })
        }
        Ok(o) => Ok((o, history)),
        Err(e) => {
            history.discard();
            Err(match e {
                PlannerError::Input(m) => OutputError::Planner(m),
                PlannerError::Interrupted => OutputError::Interrupted { iterations: 0 },
                PlannerError::Io(e) => OutputError::Io { path: dir.join("history.csv"), source: e },
            })
        }
    }
}

/// Runs the experiment, streaming history to `dir`, and writes every result file; `figures`
/// adds the PNG/SVG pictures (studies leave them out: one picture costs more than a run).
pub fn run_experiment(
    exp: &Experiment,
    dir: &Path,
    figures: bool,
    extra: &mut [&mut dyn Observer],
) -> Result<Summary, OutputError> {
    std::fs::create_dir_all(dir).map_err(io_err(dir))?;
    let history = HistoryCsv::create(dir, exp.diversity_every).map_err(io_err(dir))?;
    let planner = exp.planner.planner();
    let (outcome, history) = plan(exp, dir, history, extra)?;
    match &outcome.history {
        History::Generations => history.finish().map_err(io_err(dir))?,
        History::Own(bytes) => {
            history.discard();
            crate::io::write_atomic(&dir.join("history.csv"), bytes).map_err(io_err(dir))?;
        }
        History::None => history.discard(),
    }
    let config = toml::to_string_pretty(&exp.file).expect("experiment files serialise");
    crate::io::write_atomic(&dir.join("config.toml"), config.as_bytes()).map_err(io_err(dir))?;
    let write = |name: &str, bytes: &[u8]| crate::io::write_atomic(&dir.join(name), bytes).map_err(io_err(dir));
    let names: Vec<String> = outcome.agents.iter().map(|a| a.name.clone()).collect();
    if names.is_empty() {
        write("best_path.csv", &crate::io::path_csv(&outcome.plan))?;
    } else {
        write("best_path.csv", &crate::io::fleet_path_csv(&outcome.plan, &names))?;
    }
    for (name, bytes) in &outcome.files {
        write(name, bytes)?;
    }
    let scorer = scorer_of(exp, &outcome.plan, &outcome.agents);
    let score = common_score(&scorer, &outcome.plan, &outcome.agents);
    let fleet = team_score(exp, &outcome.plan, &outcome.agents);
    let curve = coverage_curve(exp, &scorer, &outcome.plan, &outcome.agents);
    write("coverage_curve.csv", &curve.csv())?;
    let summary = Summary {
        planner: planner.name(),
        map: exp.scenario.map.name().to_string(),
        seed: exp.seed,
        evaluations: outcome.evaluations,
        evaluation_budget: exp.budget.evaluations.map(|limit| EvaluationBudget {
            limit,
            past_limit: outcome.evaluations.saturating_sub(limit),
            rule: exp.planner.evaluation_rule(),
        }),
        iterations: outcome.iterations,
        stop: outcome.stop,
        planner_feasible: outcome.feasible,
        violations: outcome.violations.clone(),
        warnings: outcome.warnings.clone(),
        objectives: outcome.objectives.iter().map(|(k, v)| (k.to_string(), *v)).collect(),
        score,
        time_model: plan_time_model(exp, &outcome.agents),
        coverage_curve: curve.summary(),
        fleet,
        details: with_goal_time_of(outcome.details.clone(), &curve),
        wall_s: outcome.wall_s,
    };
    write("summary.json", serde_json::to_string_pretty(&summary).expect("summary serialises").as_bytes())?;
    if figures {
        let figure = PathFigure {
            map: &exp.scenario.map,
            grid: scorer.grid(),
            paths: outcome.plan.clone(),
            width: exp.scenario.robot.width,
            // A team without named robots (000's multi-agent plans) is drawn one colour per
            // agent as well.
            robots: if outcome.agents.is_empty() && outcome.plan.len() > 1 {
                (0..outcome.plan.len()).map(|k| (format!("agent {k}"), exp.scenario.robot.width)).collect()
            } else {
                outcome.agents.iter().map(|a| (a.name.clone(), a.footprint.width)).collect()
            },
            title: path_title(planner.name(), exp.scenario.map.name(), &summary, &outcome),
        };
        crate::plot::save(&figure, &dir.join("path"))?;
        planner.write_figures(&exp.scenario, &outcome, dir)?;
    }
    Ok(summary)
}
