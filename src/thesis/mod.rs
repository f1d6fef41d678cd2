//! The action-encoded variable-length GA of 003 (§3.2–3.5): genome and decoding, crossover,
//! mutation and corrections, diversity, the two architectures, parameters, the `[thesis]`
//! section's validation and the run loop with retraining, with the evaluator's own kernels (a
//! cache of swept segments, [`segments`]; lane counts for the diversity, [`lanes`]). Its
//! fitness equations are the common scorer's (`crate::coverage::fitness`).

pub mod architecture;
pub mod batch;
pub mod config;
pub mod crossover;
pub mod diversity;
pub mod entry;
pub mod genome;
pub mod individual;
pub mod lanes;
pub mod member;
pub mod mutation;
pub mod objective;
pub mod params;
pub mod planner;
pub mod reads;
pub mod run;
pub mod scenario;
pub mod seeding;
pub mod segments;
