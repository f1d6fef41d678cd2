//! The proportionate roulette wheel (PRWS, 003 §2.2.1.2): `p_i = f_i / Σ f`.

use super::{Draw, DrawParams, Param, ParentScheme};
use crate::ga::selection::{cumulative, proportionate_probabilities, spin};
use rand::RngCore;

/// `selection = "prws"`.
pub struct Prws;

/// Spins of a wheel (running sums of the probabilities), shared with [`super::rrws`].
pub(super) struct Wheel(pub(super) Vec<f64>);

impl Draw for Wheel {
    fn pick(&mut self, rng: &mut dyn RngCore) -> usize {
        spin(&self.0, rng)
    }
}

impl ParentScheme for Prws {
    fn name(&self) -> &'static str {
        "prws"
    }

    fn reads(&self) -> &'static [Param] {
        &[]
    }

    fn prepare<'f>(&self, fitness: &'f [f64], _: &DrawParams) -> Box<dyn Draw + 'f> {
        Box::new(Wheel(cumulative(&proportionate_probabilities(fitness))))
    }
}
