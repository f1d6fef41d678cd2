//! One interface for every planner, and the one place where planners are registered.
//!
//! A planner gets a [`Scenario`] (map, robot, stations, camera), a seed and a [`Budget`], hands
//! per-generation records to observers and returns a [`RunOutcome`]: the plan (one path per
//! agent), its own objectives, whether the plan meets the planner's constraints, and the effort
//! spent. Studies compare planners only through the common scorer
//! ([`crate::coverage::score::Scorer`]), never through these objectives.
//!
//! Why a trait plus one registry enum: each planner keeps its typed, validated parameters and
//! its state inside its own module and implements [`Planner`]; everything downstream (run
//! loop, output files, study runner, estimates) sees only `&dyn Planner`. The registry
//! ([`PlannerKind`] for the names in the experiment file and [`PlannerConfig`] for the
//! validated parameters) is a closed enum, so the compiler checks every `match` on it when a
//! planner is added. A new planner touches its own module and this file (plus, if it has
//! parameters of its own, one section field of the experiment file).

use crate::coverage::Footprint;
use crate::coverage::score::CameraSpec;
use crate::ga::observer::Observer;
use crate::geom::Point;
use crate::map::GridMap;
use crate::study::config::ConfigError;
use crate::study::experiment::ExperimentFile;
use crate::thesis::fitness::Projection;
use std::any::Any;
use std::path::Path;

pub use crate::thesis::params::Budget;

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

/// A plan: one path per agent, points in metres.
pub type Plan = Vec<Vec<Point>>;

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
}

/// The result of one run of any planner.
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
    /// Whatever the planner needs later to draw its own figures.
    pub artifacts: Box<dyn Any + Send>,
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
}

/// A coverage planner.
pub trait Planner: Send + Sync {
    /// The name used in experiment files and `runs.csv`.
    fn name(&self) -> &'static str;
    /// Whether the plan depends on the seed (deterministic planners run once per
    /// configuration in studies).
    fn deterministic(&self) -> bool {
        false
    }
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

/// Planner names as written in experiment files (`planner = "…"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum PlannerKind {
    /// The action-encoded GA of 003 (`[thesis]`).
    #[default]
    Thesis,
    /// The waypoint-graph maximin planner of 000 (`[waypoint]`).
    Waypoint,
    /// Boustrophedon lanes (`[pattern]`).
    Boustrophedon,
    /// Inward spiral (`[pattern]`).
    Spiral,
    /// Budget-matched random action genomes (the thesis's initial-population draw).
    RandomSearch,
}

impl PlannerKind {
    /// The name as written in experiment files.
    pub fn name(self) -> &'static str {
        match self {
            PlannerKind::Thesis => "thesis",
            PlannerKind::Waypoint => "waypoint",
            PlannerKind::Boustrophedon => "boustrophedon",
            PlannerKind::Spiral => "spiral",
            PlannerKind::RandomSearch => "random_search",
        }
    }

    /// Whether the planner ignores the seed.
    pub fn is_deterministic(self) -> bool {
        matches!(self, PlannerKind::Boustrophedon | PlannerKind::Spiral)
    }
}

/// The validated parameters of the chosen planner.
#[derive(Clone, Debug)]
pub enum PlannerConfig {
    /// The thesis GA.
    Thesis(crate::thesis::config::ThesisConfig),
    /// The waypoint planner.
    Waypoint(crate::waypoint::config::WaypointConfig),
    /// Boustrophedon or spiral.
    Pattern(crate::patterns::planner::PatternConfig),
    /// Random search.
    RandomSearch(crate::patterns::random_search::RandomSearch),
}

impl PlannerConfig {
    /// Validates the section of the file's planner; `origin` names the file in messages.
    pub fn from_file(file: &ExperimentFile, origin: &str, scenario: &Scenario) -> Result<Self, ConfigError> {
        Ok(match file.planner {
            PlannerKind::Thesis => {
                PlannerConfig::Thesis(crate::thesis::config::ThesisConfig::from_file(file, origin, scenario)?)
            }
            PlannerKind::Waypoint => {
                PlannerConfig::Waypoint(crate::waypoint::config::WaypointConfig::from_file(file, origin, scenario)?)
            }
            PlannerKind::Boustrophedon | PlannerKind::Spiral => {
                PlannerConfig::Pattern(crate::patterns::planner::PatternConfig::from_file(file, origin)?)
            }
            PlannerKind::RandomSearch => {
                PlannerConfig::RandomSearch(crate::patterns::random_search::RandomSearch::from_file(file, origin)?)
            }
        })
    }

    /// The planner.
    pub fn planner(&self) -> &dyn Planner {
        match self {
            PlannerConfig::Thesis(p) => p,
            PlannerConfig::Waypoint(p) => p,
            PlannerConfig::Pattern(p) => p,
            PlannerConfig::RandomSearch(p) => p,
        }
    }
}
