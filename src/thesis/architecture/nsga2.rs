//! The NSGA-II generation of the thesis GA (`thesis.selection = "nsga2"`): 003's operators
//! (crossover §3.3.2, mutations §3.3.3, corrections §3.3.4) with Pareto selection over its two
//! objectives, the combination of selection schemes 003 §5.3 leaves to future work.

use super::{Generation, Job, recycle, run_jobs};
use crate::ga::rng::Rng;
use crate::ga::selection::nsga2::{crowded_keys, crowded_tournament, survivors};
use crate::thesis::individual::EvalScratch;
use crate::thesis::member::Member;

/// `(cov_final, t_final)` and the obstacle sweeps of each member.
pub(crate) fn objectives<T: Member>(pop: &[T]) -> (Vec<(f64, f64)>, Vec<f64>) {
    let points = pop.iter().map(|m| (m.score().cov_final, m.score().t_final)).collect();
    let violation = pop.iter().map(|m| m.obstacle_cells() as f64).collect();
    (points, violation)
}

impl<T: Member> Generation<'_, T> {
    /// One NSGA-II generation: `Pop_min` offspring from pairs of crowded binary tournaments
    /// (crossover with `P_c`, else mutated copies of both parents; every new member mutated
    /// with `P_mI` and `P_mA` and corrected), then the `Pop_min` survivors of parents and
    /// offspring by constrained front and crowding distance. `spare` as in
    /// [`Self::step_a`].
    pub fn step_nsga2(
        &self,
        pop: Vec<T>,
        rng: &mut Rng,
        scratches: &mut [EvalScratch],
        spare: &mut Vec<T>,
    ) -> (Vec<T>, u64) {
        let p = self.params;
        let fit: Vec<f64> = pop.iter().map(T::fitness).collect();
        let (points, violation) = objectives(&pop);
        let (rank, crowding) = crowded_keys(&points, &violation);
        let mut jobs: Vec<Job<T>> = Vec::with_capacity(p.pop_min + 4);
        let mut kids = Vec::with_capacity(4);
        while jobs.len() < p.pop_min {
            let p1 = crowded_tournament(&rank, &crowding, rng);
            let p2 = crowded_tournament(&rank, &crowding, rng);
            self.mate(&pop, &fit, (p1, p2), rng, &mut jobs, &mut kids, spare);
        }
        spare.append(&mut kids);
        let evaluations = run_jobs(&mut jobs, &pop, self.scenario, &self.context(), scratches);
        let made = jobs.len();
        let all: Vec<T> = pop.into_iter().chain(jobs.into_iter().map(|j| j.ind)).collect();
        let (points, violation) = objectives(&all);
        let keep = survivors(&points, &violation, p.pop_min);
        let mut all: Vec<Option<T>> = all.into_iter().map(Some).collect();
        let next: Vec<T> = keep.iter().map(|&i| all[i].take().expect("each survivor once")).collect();
        recycle(spare, all.into_iter().flatten(), next.len().max(made));
        (next, evaluations)
    }
}
