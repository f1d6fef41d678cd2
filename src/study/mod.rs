//! Experiment files, their validation and running one experiment with all its outputs.

pub mod ablation;
pub mod anova;
pub mod anova_report;
pub mod claims;
pub mod config;
pub mod estimate;
pub mod experiment;
pub mod fleet_report;
pub mod grid;
pub mod ignored;
pub mod memory;
pub mod merge;
pub mod output;
pub mod records;
pub mod report;
mod report_tables;
pub mod runner;
pub mod slurm;
pub mod stats;
pub mod thesis_report;
