//! Stochastic universal sampling (Baker 1987, "Reducing bias and inefficiency in the selection
//! algorithm"): the proportionate wheel of PRWS (003 §2.2.1.2) read by equally spaced pointers
//! with one random offset, the low-variance sampler 000 §III-A.6 uses, so that over a batch of
//! `n` draws member `i` is picked `⌊n·p_i⌋` or `⌈n·p_i⌉` times, never by luck more or less.
//! Draws come in batches of one per member, shuffled so that pairs mate at random; a GA that
//! draws more starts the next batch.

use super::{Draw, DrawParams, Param, ParentScheme};
use crate::ga::selection::{low_variance_sample, proportionate_probabilities};
use rand::RngCore;
use rand::seq::SliceRandom;

/// `selection = "sus"`.
pub struct Sus;

struct Draws {
    probs: Vec<f64>,
    batch: Vec<usize>,
}

impl Draw for Draws {
    fn pick(&mut self, rng: &mut dyn RngCore) -> usize {
        if self.batch.is_empty() {
            self.batch = low_variance_sample(&self.probs, self.probs.len(), rng);
            self.batch.shuffle(rng);
        }
        self.batch.pop().expect("a batch of one draw per member")
    }
}

impl ParentScheme for Sus {
    fn name(&self) -> &'static str {
        "sus"
    }

    fn reads(&self) -> &'static [Param] {
        &[]
    }

    fn prepare<'f>(&self, fitness: &'f [f64], _: &DrawParams) -> Box<dyn Draw + 'f> {
        Box::new(Draws { probs: proportionate_probabilities(fitness), batch: Vec::new() })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ga::rng::{Purpose, stream};

    /// Each batch of `n` draws picks member `i` `⌊n·p_i⌋` or `⌈n·p_i⌉` times.
    #[test]
    fn a_batch_picks_each_member_its_share_rounded() {
        let fitness = [0.05, 0.3, 0.15, 0.4, 0.1, 0.0, 0.2];
        let probs = proportionate_probabilities(&fitness);
        let n = fitness.len();
        let mut draw = Sus.prepare(&fitness, &DrawParams { tournament_size: 0, pressure: 0.0, best_parents: 0 });
        let mut rng = stream(12, Purpose::Main, &[]);
        for batch in 0..300 {
            let mut counts = vec![0usize; n];
            for _ in 0..n {
                counts[draw.pick(&mut rng)] += 1;
            }
            for (i, p) in probs.iter().enumerate() {
                let share = n as f64 * p;
                let c = counts[i] as f64;
                assert!(c >= share.floor() && c <= share.ceil(), "batch {batch}, member {i}: {c} vs {share}");
            }
        }
    }
}
