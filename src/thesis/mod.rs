//! The action-encoded variable-length GA of 003 (§3.2–3.5): fitness, genome and decoding,
//! crossover, mutation and corrections, diversity, the two architectures and retraining.

pub mod fitness;
