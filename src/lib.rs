#![warn(missing_docs)]
//! covga: coverage path planning with genetic algorithms.
//!
//! The crate implements the action-encoded GA of 003 ([`thesis`]), pattern baselines
//! ([`patterns`]), a common footprint scorer ([`coverage`]) on occupancy grid maps ([`map`]),
//! experiment files and runs ([`study`]), figures ([`plot`]) and the `covga` command line
//! ([`cli`]). Paper references (`003 eq. 3.13`) point into `shared/seeds` of the project's
//! design documents.

pub mod cli;
pub mod coverage;
pub mod fleet;
pub mod fuzz_entry;
pub mod ga;
pub mod geom;
pub mod io;
pub mod map;
pub mod patterns;
pub mod planner;
pub mod plot;
pub mod study;
pub mod thesis;
pub mod waypoint;
