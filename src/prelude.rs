//! What a user of the library, or a planner added from outside it, needs, in one import:
//! `use covga::prelude::*;`.
//!
//! The crate has many public items (every layer's own, for the command line, Python and the
//! tests); these are the few a program that plans, scores, runs or studies coverage works with,
//! each under its own path too. A planner from outside implements [`Planner`] (an iterative one
//! a [`Search`] driven by [`execute`], reporting to the run's [`Observers`]), registers a
//! [`PlannerPlugin`] (a [`PlannerEntry`], as covga's own planners are) whose `validate`
//! checks its section and returns a [`RegisteredPlanner`], and is then selected by `planner = "<name>"` in an experiment file like a built-in planner
//! (`tests/it/plugins.rs`, which imports from here alone). The book's developer guide walks
//! through it.
//!
//! Nothing in the crate imports from here: it stands above every layer and only names what
//! they hold.

// The map and its geometry.
pub use crate::geom::Point;
pub use crate::map::presets::preset;
pub use crate::map::{GridMap, MapError};

// What every planner plans for: the map, the robot's footprint and motion, the stations.
pub use crate::coverage::Footprint;
pub use crate::coverage::fitness::Projection;
pub use crate::planner::{Budget, Context, Plan, Scenario};

// The planner interface and what a run returns.
pub use crate::planner::{History, Planner, PlannerError, RunOutcome, StopReason, details};

// The one executor of iterative searches, its stop rules, and the observers it reports to.
pub use crate::ga::observer::{GenerationRecord, Observer, ObserverMode, Observers, Recorder, RunEvent};
pub use crate::planner::executor::{Finish, Interrupt, Search, StopRule, StopRules, execute};

// Planners from outside: their registration and the checks of their sections.
pub use crate::config::{ConfigError, check_range};
pub use crate::experiment::plugins::{PlannerPlugin, PluginError, register};
pub use crate::experiment::registry::PlannerKind;
pub use crate::planner::entry::{FileSections, PlannerEntry, RegisteredPlanner};
pub use crate::planner::section::{Placement, Section, SectionDecl, SectionSpec};

// Scoring a plan: the common scorer, and `covga eval` as a library call.
pub use crate::coverage::score::{CameraSpec, Score, Scorer};
pub use crate::usecase::eval::{EvalRequest, Evaluation, evaluate};

// Running an experiment into its folder, a grid study, and its report.
pub use crate::report::{ReportError, ReportOptions, write_report, write_report_with};
pub use crate::study::grid::Study;
pub use crate::study::runner::{RunDone, RunnerOptions, StudyError, StudyOutcome, run_study};
pub use crate::usecase::UseCaseError;
pub use crate::usecase::run::{ExperimentText, Prepared, prepare, run_in_folder};
