//! The NSGA-II generation of the thesis GA (`thesis.selection = "nsga2"`): 003's operators
//! (crossover §3.3.2, mutations §3.3.3, corrections §3.3.4) with Pareto selection over its two
//! objectives, the combination of selection schemes 003 §5.3 leaves to future work.

use super::{Generation, Job, recycle, run_jobs};
use crate::ga::rng::Rng;
use crate::ga::selection::nsga2::{crowded_keys, crowded_tournament, survivors};
use crate::thesis::individual::EvalScratch;
use crate::thesis::member::Member;

/// The constraint violation of a plan with objectives `(cov, t)` and `obstacle_cells` swept:
/// its obstacle sweeps (003's hard constraint), plus, with seed plans' objectives `bounds`
/// (`thesis.seed_bound = "dominate"`), its smallest shortfall behind one of them summed over
/// both objectives (below 2, so one obstacle cell outweighs any shortfall).
pub fn violation((cov, t): (f64, f64), obstacle_cells: u64, bounds: &[(f64, f64)]) -> f64 {
    let shortfall =
        bounds.iter().map(|&(bc, bt)| (bc - cov).max(0.0) + (bt - t).max(0.0)).fold(f64::INFINITY, f64::min);
    obstacle_cells as f64 + if bounds.is_empty() { 0.0 } else { shortfall }
}

/// `(cov_final, t_final)` and the constraint violation ([`violation`]) of each member.
pub(crate) fn objectives<T: Member>(pop: &[T], bounds: &[(f64, f64)]) -> (Vec<(f64, f64)>, Vec<f64>) {
    let points: Vec<(f64, f64)> = pop.iter().map(|m| (m.score().cov_final, m.score().t_final)).collect();
    let violation = pop.iter().zip(&points).map(|(m, &p)| violation(p, m.obstacle_cells(), bounds)).collect();
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
        let (points, violation) = objectives(&pop, self.bounds);
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
        let (points, violation) = objectives(&all, self.bounds);
        let keep = survivors(&points, &violation, p.pop_min);
        let mut all: Vec<Option<T>> = all.into_iter().map(Some).collect();
        let next: Vec<T> = keep.iter().map(|&i| all[i].take().expect("each survivor once")).collect();
        recycle(spare, all.into_iter().flatten(), next.len().max(made));
        (next, evaluations)
    }
}

#[cfg(test)]
mod tests {
    use super::violation;

    /// Obstacle cells count whole; with seed bounds, the smallest summed shortfall behind one
    /// seed is added (0 for a plan at least as good as some seed on both objectives).
    #[test]
    fn the_violation_of_a_plan() {
        let seeds = [(0.9, 0.5), (0.6, 0.8)];
        /// A plan's objectives, its obstacle cells, the seed bounds and the violation wanted.
        type Case<'a> = ((f64, f64), u64, &'a [(f64, f64)], f64);
        let cases: [Case; 7] = [
            ((0.5, 0.5), 0, &[], 0.0),
            ((0.5, 0.5), 3, &[], 3.0),
            ((0.95, 0.55), 0, &seeds, 0.0),
            ((0.6, 0.8), 0, &seeds, 0.0),
            ((0.85, 0.5), 0, &seeds, 0.05),
            ((0.7, 0.6), 0, &seeds, 0.2),
            ((0.85, 0.5), 2, &seeds, 2.05),
        ];
        for (plan, obstacles, bounds, want) in cases {
            let got = violation(plan, obstacles, bounds);
            assert!((got - want).abs() < 1e-12, "{plan:?} {obstacles} {bounds:?}: {got} != {want}");
        }
    }
}
