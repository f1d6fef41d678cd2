//! Tournament selection ("Turn", 003 §2.2.1.1): the fittest of `TS` distinct contestants.

use super::{Draw, DrawParams, Param, ParentScheme};
use crate::ga::selection::tournament;
use rand::RngCore;

/// `selection = "tournament"`.
pub struct Tournament;

struct Draws<'f> {
    fitness: &'f [f64],
    size: usize,
}

impl Draw for Draws<'_> {
    fn pick(&mut self, rng: &mut dyn RngCore) -> usize {
        tournament(self.fitness, self.size, rng)
    }
}

impl ParentScheme for Tournament {
    fn name(&self) -> &'static str {
        "tournament"
    }

    fn reads(&self) -> &'static [Param] {
        &[Param::TournamentSize]
    }

    fn ramped(&self) -> Option<Param> {
        Some(Param::TournamentSize)
    }

    fn prepare<'f>(&self, fitness: &'f [f64], params: &DrawParams) -> Box<dyn Draw + 'f> {
        Box::new(Draws { fitness, size: params.tournament_size })
    }
}
