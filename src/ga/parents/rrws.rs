//! The rank-based roulette wheel (RRWS, 003 §2.2.1.3) at selection pressure `SP`.

use super::prws::Wheel;
use super::{Draw, DrawParams, Param, ParentScheme};
use crate::ga::selection::{cumulative, rank_probabilities};

/// `selection = "rrws"`.
pub struct Rrws;

impl ParentScheme for Rrws {
    fn name(&self) -> &'static str {
        "rrws"
    }

    fn reads(&self) -> &'static [Param] {
        &[Param::Pressure]
    }

    fn ramped(&self) -> Option<Param> {
        Some(Param::Pressure)
    }

    fn prepare<'f>(&self, fitness: &'f [f64], params: &DrawParams) -> Box<dyn Draw + 'f> {
        Box::new(Wheel(cumulative(&rank_probabilities(fitness, params.pressure))))
    }
}
