//! Experiments: the experiment file above every planner. An [`ExperimentFile`] is parsed,
//! validated once into an [`Experiment`] (its scenario, budget and the planner chosen from
//! the one [`registry`]), checked against the memory limit and run by
//! [`output::run_experiment`], which writes the run's folder the same way for every planner,
//! fleets included.

pub mod file;
pub mod fleets;
pub mod ignored;
pub mod keys;
pub mod memory;
pub mod output;
pub mod plugins;
pub mod recommended;
pub mod registry;
pub mod renamed;

pub use file::{Experiment, ExperimentFile};
pub use registry::{PlannerConfig, PlannerKind};
