//! The layer every planner is built on: one interface for every planner and what it plans for.
//!
//! A planner gets a [`Scenario`] (map, robot, stations, camera), a seed and a [`Budget`], hands
//! per-generation records to observers and returns a [`RunOutcome`]: the plan (one path per
//! agent), the robots that fly it, its own objectives, whether the plan meets the planner's
//! constraints, and the effort spent. Studies compare planners only through the common scorer
//! ([`crate::coverage::score::Scorer`]), never through these objectives.
//!
//! Why a trait here and the registry above the planners: each planner keeps its typed,
//! validated parameters, its section's validation ([`Context`]) and its state inside its own
//! module and implements [`Planner`]; everything downstream (the run loop, output files, study
//! runner) sees only `&dyn Planner`. How a planner registers ([`entry`]) is written here,
//! and each planner's module holds its entry; the list of them lives one layer up, in the
//! registry of the experiment layer, so that this layer depends on no planner.

pub mod entry;
pub mod executable;
pub mod executor;
pub mod legs;
pub mod memory;
pub mod section;
pub mod sections;

use crate::config::ConfigError;
use crate::coverage::Footprint;
use crate::coverage::fitness::Projection;
use crate::coverage::score::CameraSpec;
use crate::ga::observer::Observer;
use crate::geom::Point;
use crate::map::GridMap;
use std::any::Any;
use std::path::Path;
use std::time::Duration;

/// What every planner plans for: the map, the robot, the stations and the camera.
#[derive(Clone, Debug)]
pub struct Scenario {
    /// The map.
    pub map: GridMap,
    /// The robot's footprint and motion (003 Table 4.2).
    pub robot: Footprint,
    /// Start station `S_pos`.
    pub start: Point,
    /// End station `E_pos`.
    pub end: Point,
    /// Projection of the thesis fitness (`f1` or `f2`), used by the scorer's `f` too.
    pub projection: Projection,
    /// The camera of 000 for the scorer's camera model.
    pub camera: CameraSpec,
}

impl Scenario {
    /// The cells the common scorer counts as reachable for a plan of this scenario's robot
    /// that starts at its start station (`cov_final_reach`'s denominator).
    pub fn reach(&self) -> crate::map::reach::Reach {
        crate::map::reach::Reach::new(
            &crate::map::clearance::Clearance::new(&self.map, self.robot.width),
            &[self.start],
        )
    }

    /// The scenario a routing planner (patterns, cell order) plans on: this one, or where the
    /// map's cells are coarser than half the robot's width or close a passage the scorer counts
    /// open, the same with the map's cells split ([`crate::map::refine`],
    /// [`crate::map::passages`]). Its plans are plans on this scenario's map.
    pub fn for_planning(&self) -> std::borrow::Cow<'_, Scenario> {
        match crate::map::passages::planning_map_from(&self.map, self.robot.width, self.start) {
            std::borrow::Cow::Borrowed(_) => std::borrow::Cow::Borrowed(self),
            std::borrow::Cow::Owned(map) => std::borrow::Cow::Owned(Scenario { map, ..self.clone() }),
        }
    }
}

/// A plan: one path per agent, points in metres.
pub type Plan = Vec<Vec<Point>>;

/// One robot of a plan that names its robots (a fleet): who flies each path, at which width
/// and speed, between which stations.
#[derive(Clone, Debug, PartialEq)]
pub struct Agent {
    /// Name used in messages, files and legends.
    pub name: String,
    /// Width, speed and rotation speed (003 Table 4.2's `R_width`, `R_speed`, `R_rot`).
    pub footprint: Footprint,
    /// Start station `S_pos` (m).
    pub start: Point,
    /// End station `E_pos` (m).
    pub end: Point,
}

impl Agent {
    /// The robot's sweep rate `R_width · R_speed` in m²/s.
    pub fn sweep_rate(&self) -> f64 {
        self.footprint.width * self.footprint.speed
    }
}

/// When a run stops (any planner: iterations are generations for the GAs). The executor reads
/// it as stop rules ([`executor::StopRules::of_budget`]), the same for every planner.
#[derive(Clone, Debug, PartialEq)]
pub struct Budget {
    /// `Iter_max`.
    pub iterations: u32,
    /// Optional limit on fitness evaluations (equal budgets across planners).
    pub evaluations: Option<u64>,
    /// Optional wall-clock limit (the thesis used 20 minutes).
    pub wall_clock: Option<Duration>,
    /// Optional stall limit: stop after this many iterations without a better best.
    pub stall_iterations: Option<u32>,
    /// Optional flag that ends the run at its next iteration when raised (Ctrl-C, a notebook).
    pub interrupt: Option<executor::Interrupt>,
}

impl Budget {
    /// No limit but `iterations`.
    pub fn iterations(iterations: u32) -> Self {
        Self { iterations, evaluations: None, wall_clock: None, stall_iterations: None, interrupt: None }
    }
}

/// What a planner's section is validated against: the file it came from (named in messages),
/// the scenario and the budget. Each planner validates its own section with it
/// (`XSection::validate(&self, &Context)`), never the whole experiment file.
#[derive(Clone, Copy, Debug)]
pub struct Context<'a> {
    /// The file (or a description of the source), named in every message.
    pub origin: &'a str,
    /// Map, robot, stations and camera.
    pub scenario: &'a Scenario,
    /// Stop conditions.
    pub budget: &'a Budget,
    /// Whether checks that plan (seed plans, cell counts) run too.
    pub checks: Checks,
}

/// How deep a configuration is checked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Checks {
    /// Every check, those that plan included (a pattern seed's plan, the exact solver's cell
    /// count): what a run needs before it starts.
    Full,
    /// Keys, ranges, map and stations only; nothing is planned (a grid's `--dry-run`, which
    /// must answer at once). The configuration is not runnable: a run validates it again.
    KeysOnly,
}

impl Context<'_> {
    /// A configuration error at `key` of this file.
    pub fn error(&self, key: &str, message: impl Into<String>) -> ConfigError {
        ConfigError::new(self.origin, key, message)
    }
}

/// Why a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    /// The iteration (generation) limit.
    Iterations,
    /// The evaluation budget.
    Evaluations,
    /// The wall-clock limit.
    WallClock,
    /// No better best for the stall limit.
    Stall,
    /// A deterministic planner finished its plan.
    Completed,
    /// A fleet's negotiated plans settled within the tolerance.
    Settled,
    /// The caller raised the run's interrupt flag ([`executor::Interrupt`]).
    Interrupted,
}

/// The result of one run of any planner. Made with [`RunOutcome::new`] and its `with_*`
/// setters (a planner outside the crate cannot write the struct literal), so that a field added
/// later, with its default, breaks no planner.
#[non_exhaustive]
pub struct RunOutcome {
    /// The reported plan.
    pub plan: Plan,
    /// The planner's own objectives of that plan, by name.
    pub objectives: Vec<(&'static str, f64)>,
    /// Whether the plan meets the planner's constraints.
    pub feasible: bool,
    /// The constraints it violates, in words (empty when feasible).
    pub violations: Vec<String>,
    /// What the user should know about the run's set-up (e.g. space the planner cannot reach).
    pub warnings: Vec<String>,
    /// Fitness evaluations spent.
    pub evaluations: u64,
    /// Iterations (generations) completed.
    pub iterations: u32,
    /// Why the run ended.
    pub stop: StopReason,
    /// Wall time in seconds (not part of the deterministic outputs).
    pub wall_s: f64,
    /// Planner-specific summary fields (flattened into `summary.json`).
    pub details: serde_json::Map<String, serde_json::Value>,
    /// Planner-specific result files: name and bytes.
    pub files: Vec<(String, Vec<u8>)>,
    /// The run's history when the planner records it itself (a negotiation's rounds, say)
    /// instead of through generation records, or records none.
    pub history: History,
    /// The robots that fly the plan, one per path, when the experiment names them (a fleet);
    /// empty when every path is flown by the scenario's robot.
    pub agents: Vec<Agent>,
    /// Whatever the planner needs later to draw its own figures.
    pub artifacts: Box<dyn Any + Send>,
}

impl RunOutcome {
    /// A run that returns `plan` and ended for `stop`: feasible, no objectives, warnings,
    /// details or files, no evaluations or iterations counted, no history, flown by the
    /// scenario's robot. The `with_*` setters fill in the rest.
    pub fn new(plan: Plan, stop: StopReason) -> Self {
        Self {
            plan,
            objectives: Vec::new(),
            feasible: true,
            violations: Vec::new(),
            warnings: Vec::new(),
            evaluations: 0,
            iterations: 0,
            stop,
            wall_s: 0.0,
            details: serde_json::Map::new(),
            files: Vec::new(),
            history: History::None,
            agents: Vec::new(),
            artifacts: Box::new(()),
        }
    }

    /// The planner's own objectives of the plan, by name.
    pub fn with_objectives(mut self, objectives: Vec<(&'static str, f64)>) -> Self {
        self.objectives = objectives;
        self
    }

    /// The constraints the plan violates, in words; the plan is feasible when there are none.
    pub fn with_violations(mut self, violations: Vec<String>) -> Self {
        self.feasible = violations.is_empty();
        self.violations = violations;
        self
    }

    /// The plan's feasibility as the planner judges it, where it is not the absence of
    /// violations in words.
    pub fn with_feasible(mut self, feasible: bool) -> Self {
        self.feasible = feasible;
        self
    }

    /// What the user should know about the run's set-up.
    pub fn with_warnings(mut self, warnings: Vec<String>) -> Self {
        self.warnings = warnings;
        self
    }

    /// Fitness evaluations spent and iterations (generations) completed.
    pub fn with_effort(mut self, evaluations: u64, iterations: u32) -> Self {
        self.evaluations = evaluations;
        self.iterations = iterations;
        self
    }

    /// The run's wall time in seconds.
    pub fn with_wall_s(mut self, wall_s: f64) -> Self {
        self.wall_s = wall_s;
        self
    }

    /// Planner-specific summary fields.
    pub fn with_details(mut self, details: serde_json::Map<String, serde_json::Value>) -> Self {
        self.details = details;
        self
    }

    /// Planner-specific result files: name and bytes.
    pub fn with_files(mut self, files: Vec<(String, Vec<u8>)>) -> Self {
        self.files = files;
        self
    }

    /// Where the run's history comes from.
    pub fn with_history(mut self, history: History) -> Self {
        self.history = history;
        self
    }

    /// The robots that fly the plan, one per path.
    pub fn with_agents(mut self, agents: Vec<Agent>) -> Self {
        self.agents = agents;
        self
    }

    /// Whatever the planner needs later to draw its own figures.
    pub fn with_artifacts(mut self, artifacts: Box<dyn Any + Send>) -> Self {
        self.artifacts = artifacts;
        self
    }
}

/// Where a run's `history.csv` comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum History {
    /// The generation records handed to the observers (every GA).
    Generations,
    /// The planner's own CSV bytes.
    Own(Vec<u8>),
    /// No history (a planner that plans in one step without generations).
    None,
}

/// The fields of a JSON object literal as `details` of a [`RunOutcome`].
pub fn details(value: serde_json::Value) -> serde_json::Map<String, serde_json::Value> {
    match value {
        serde_json::Value::Object(map) => map,
        _ => serde_json::Map::new(),
    }
}

/// A planner could not run.
#[derive(Debug, thiserror::Error)]
pub enum PlannerError {
    /// The configuration cannot be planned on this map (the user's input).
    #[error("{0}")]
    Input(String),
    /// An observer failed to write.
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// The run's interrupt was raised before the planner had a plan (during its set-up).
    #[error("interrupted before the first plan")]
    Interrupted,
}

/// A coverage planner.
pub trait Planner: Send + Sync {
    /// The name used in experiment files and `runs.csv`.
    fn name(&self) -> &'static str;
    /// Plans within `budget`, handing every generation's record to `observers`.
    fn run(
        &self,
        scenario: &Scenario,
        seed: u64,
        budget: &Budget,
        observers: &mut [&mut dyn Observer],
    ) -> Result<RunOutcome, PlannerError>;
    /// Draws the planner's own figures into `dir` (the common path figure is drawn for every
    /// planner by the output writer).
    fn write_figures(
        &self,
        _scenario: &Scenario,
        _outcome: &RunOutcome,
        _dir: &Path,
    ) -> Result<(), crate::plot::PlotError> {
        Ok(())
    }
}
