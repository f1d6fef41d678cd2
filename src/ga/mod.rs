//! What every GA shares: seeded random streams ([`rng`]), selection operators ([`selection`])
//! and the parent-selection schemes built on them ([`parents`], one registry),
//! parameter-control schedules ([`control`]) and per-generation statistics with their
//! observers ([`observer`]).

pub mod control;
pub mod maximin;
pub mod observer;
pub mod parents;
pub mod pareto;
pub mod rng;
pub mod selection;
