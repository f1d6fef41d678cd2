//! Experiment files, their validation and running one experiment with all its outputs.

pub mod config;
pub mod experiment;
pub mod output;
