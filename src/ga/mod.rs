//! What every GA shares: seeded random streams ([`rng`]), selection schemes ([`selection`]),
//! parameter-control schedules ([`control`]) and per-generation statistics with their
//! observers ([`observer`]).

pub mod control;
pub mod maximin;
pub mod observer;
pub mod pareto;
pub mod rng;
pub mod selection;
