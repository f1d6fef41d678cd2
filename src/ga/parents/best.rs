//! Parents drawn uniformly from the `best_parents` best: the draw of 003's Elite families (§3.4,
//! architecture (b)) for a GA that mates pairs one at a time (the cell-order GA's `"best"`,
//! called `"elite"` before). The thesis GA's own `"elite"` is its architecture (b), which makes
//! families, not draws: the two names now say two things.

use super::{Draw, DrawParams, Param, ParentScheme};
use crate::ga::selection::best_k;
use rand::{Rng, RngCore};

/// `selection = "best"` of a GA that draws its parents.
pub struct Best;

struct Draws(Vec<usize>);

impl Draw for Draws {
    fn pick(&mut self, rng: &mut dyn RngCore) -> usize {
        self.0[rng.random_range(0..self.0.len())]
    }
}

impl ParentScheme for Best {
    fn name(&self) -> &'static str {
        "best"
    }

    fn reads(&self) -> &'static [Param] {
        &[Param::BestParents]
    }

    fn prepare<'f>(&self, fitness: &'f [f64], params: &DrawParams) -> Box<dyn Draw + 'f> {
        Box::new(Draws(best_k(fitness, params.best_parents.clamp(1, fitness.len()))))
    }
}
