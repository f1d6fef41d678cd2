//! One generation of each architecture (003 §3.5.1, Fig. 3.9; thesis-ga §11): (a) keep + selection
//! + crossover + mutation + refill for Tournament / PRWS / RRWS, and (b) Elite families.
//!
//! Decisions that shape the generation (selection, pairing, crossover, cut points) come from
//! the run's main stream in a fixed order. Each new or changed individual is then a job with
//! its own stream (seed, iteration, slot) for mutation and re-initialisation, and jobs are
//! mutated, corrected and evaluated in parallel: the result does not depend on the threads.

use super::individual::EvalScratch;
use super::member::{Member, Op, Origin, Variation};
use super::params::ThesisParams;
use crate::ga::parents::{DrawParams, ParentDraw};
use crate::ga::rng::{Purpose, Rng, from_stream_seed, stream_seed};
use crate::ga::selection::best_k;
use rand::Rng as _;
use rand::seq::SliceRandom;
use rayon::prelude::*;

/// Effective operator probabilities of one generation (after parameter control).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Effective {
    /// `P_c`.
    pub p_c: f64,
    /// `P_mI`.
    pub p_mi: f64,
    /// `P_mA`, fixed or per individual.
    pub p_ma: MutationRate,
    /// `TS` for tournaments.
    pub tournament_size: usize,
    /// `SP` for RRWS.
    pub pressure: f64,
}

/// The action-mutation probability: fixed, or the adaptive `P_m` of eqs. 2.4–2.6 per individual.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MutationRate {
    /// One value for everyone.
    Fixed(f64),
    /// `(P_m^Diversity + K·(f_max − f)/(f_max − f_min)) / 2` for an individual of fitness `f`.
    Adaptive {
        /// `P_m^Diversity` (eq. 2.4).
        diversity_part: f64,
        /// `K`.
        k: f64,
        /// Population minimum fitness.
        f_min: f64,
        /// Population maximum fitness.
        f_max: f64,
    },
}

impl MutationRate {
    /// The probability for an individual of fitness `f`.
    pub fn for_fitness(&self, f: f64) -> f64 {
        match *self {
            MutationRate::Fixed(p) => p,
            MutationRate::Adaptive { diversity_part, k, f_min, f_max } => {
                let c = crate::ga::control::AdaptiveConstants { k1: 0.0, k2: 0.0, k };
                crate::ga::control::adaptive_p_m(
                    diversity_part,
                    crate::ga::control::adaptive_p_m_fitness(f, f_min, f_max, &c),
                )
            }
        }
    }
}

/// What a job's member was made from (an index into the parents), for incremental evaluation.
#[derive(Clone, Copy, Debug)]
enum JobOrigin {
    /// A fresh genome.
    New,
    /// A copy of an evaluated member.
    Copy,
    /// A crossover child of this receiving parent (index into the population).
    Child(usize),
}

/// A job's random stream, made on the worker that runs the job: a generator's state is about
/// 300 bytes, which cost more to move through the job list than to make where it is used.
#[derive(Clone, Copy, Debug)]
struct JobStream {
    /// The stream's seed ([`stream_seed`]).
    seed: u64,
    /// A Bernoulli draw with this probability, made from the stream (and true) before the job
    /// was made: made again, so that the job goes on from where the stream was.
    drawn: Option<f64>,
}

impl JobStream {
    fn new(seed: u64) -> Self {
        Self { seed, drawn: None }
    }

    /// The generator, where the job's first draw comes next.
    fn rng(self) -> Rng {
        let mut rng = from_stream_seed(self.seed);
        if let Some(p) = self.drawn {
            let again = rng.random_bool(p);
            debug_assert!(again, "the draw made before the job was true");
        }
        rng
    }
}

/// A member to be changed and evaluated, with its own random stream.
pub(crate) struct Job<T> {
    ind: T,
    stream: JobStream,
    op: Op,
    origin: JobOrigin,
    evaluations: u64,
}

impl<T: Member> Job<T> {
    /// A member whose genome a re-initialisation will draw, in a recycled member.
    fn fresh(spare: &mut Vec<T>, stream: JobStream, op: Op) -> Self {
        Self { ind: spare.pop().unwrap_or_default(), stream, op, origin: JobOrigin::New, evaluations: 0 }
    }
    /// A seed member (a pattern's genome), evaluated as it is.
    fn seed(ind: T, stream: JobStream) -> Self {
        Self { ind, stream, op: Op::Evaluate, origin: JobOrigin::New, evaluations: 0 }
    }
    /// A crossover child (built by [`Member::cross`] in a recycled member).
    fn child(ind: T, receiver: usize, stream: JobStream, op: Op) -> Self {
        Self { ind, stream, op, origin: JobOrigin::Child(receiver), evaluations: 0 }
    }
    /// A copy of `of`, in a recycled member.
    fn copy(spare: &mut Vec<T>, of: &T, stream: JobStream, op: Op) -> Self {
        let mut ind = spare.pop().unwrap_or_default();
        ind.clone_from(of);
        Self { ind, stream, op, origin: JobOrigin::Copy, evaluations: 0 }
    }
    fn execute(&mut self, pop: &[T], world: &T::World, run: &Variation, scratch: &mut EvalScratch) {
        let origin = match self.origin {
            JobOrigin::New => Origin::New,
            JobOrigin::Copy => Origin::Copy,
            JobOrigin::Child(receiver) => Origin::Child(&pop[receiver]),
        };
        let mut rng = self.stream.rng();
        self.evaluations += self.ind.vary_and_evaluate(self.op, origin, world, run, scratch, &mut rng);
    }
}

/// Members of the initial population evaluated per thread between two looks at the set-up's
/// stop (a few milliseconds each on the thesis maps).
const INITIAL_BLOCK_PER_THREAD: usize = 8;

/// Runs jobs in parallel, one scratch per chunk; `pop` holds the parents the jobs' children
/// were made from. Returns the evaluations spent.
pub(crate) fn run_jobs<T: Member>(
    jobs: &mut [Job<T>],
    pop: &[T],
    world: &T::World,
    context: &Variation,
    scratches: &mut [EvalScratch],
) -> u64 {
    if jobs.is_empty() {
        return 0;
    }
    let chunk = jobs.len().div_ceil(scratches.len());
    jobs.par_chunks_mut(chunk).zip(scratches.par_iter_mut()).for_each(|(jobs, scratch)| {
        for job in jobs {
            job.execute(pop, world, context, scratch);
        }
    });
    jobs.iter().map(|j| j.evaluations).sum()
}

/// What Elite families and the reported best compare members by: `f_obstacle` (003 eq.
/// 3.16); with seed plans' objectives `bounds` (`thesis.seed_bound = "dominate"`), a plan
/// behind every seed on `cov_final` or `t_final` ranks below every plan that is not, as minus
/// its smallest summed shortfall (`f_obstacle` is never negative).
pub fn bounded_fitness<T: Member>(m: &T, bounds: &[(f64, f64)]) -> f64 {
    if bounds.is_empty() {
        return m.fitness();
    }
    let s = m.score();
    let shortfall = violation((s.cov_final, s.t_final), 0, bounds);
    if shortfall > 0.0 { -shortfall } else { m.fitness() }
}

/// The family contest of the Elite scheme (003 §3.4.1): indices of the two fittest members,
/// listed children first so that a child wins a tie with a parent (R20).
/// The first two of the indices sorted stably by descending fitness, found without sorting.
pub fn family_survivors(fitness: &[f64]) -> [usize; 2] {
    debug_assert!(fitness.len() >= 2);
    let better = |x: usize, y: usize| fitness[x].total_cmp(&fitness[y]).is_gt();
    // The earliest of the fittest, then the earliest of the fittest of the others.
    let first = (1..fitness.len()).fold(0, |best, i| if better(i, best) { i } else { best });
    let second = (0..fitness.len())
        .filter(|&i| i != first)
        .reduce(|best, i| if better(i, best) { i } else { best })
        .expect("two members at least");
    [first, second]
}

/// Context of one generation.
pub(crate) struct Generation<'a, T: Member> {
    pub scenario: &'a T::World,
    pub params: &'a ThesisParams,
    pub effective: Effective,
    pub seed: u64,
    pub iteration: u32,
    /// The seed plans' `(cov_final, t_final)` that bound Pareto selection (empty: none).
    pub bounds: &'a [(f64, f64)],
}

impl<T: Member> Generation<'_, T> {
    /// The stream of new member `slot` of this generation.
    fn stream(&self, slot: usize) -> JobStream {
        JobStream::new(stream_seed(self.seed, Purpose::Individual, &[u64::from(self.iteration), slot as u64]))
    }

    fn context(&self) -> Variation {
        Variation { init: self.params.init, mode: self.params.evaluation }
    }

    /// Crosses `pop[a]` and `pop[b]` into `kids`, topped up with members of `spare` first so
    /// that the children reuse their buffers. False when no child could be made.
    fn cross(&self, pop: &[T], (a, b): (usize, usize), rng: &mut Rng, kids: &mut Vec<T>, spare: &mut Vec<T>) -> bool {
        let want = self.params.c_child.children();
        while kids.len() < want {
            kids.push(spare.pop().unwrap_or_default());
        }
        T::cross(&pop[a], &pop[b], self.params, self.scenario, rng, kids)
    }

    /// Initial population of `size` genomes, evaluated (thesis-ga §6): the first `seeded` are
    /// `seeds` in turn, as they are; the others random. Asks `stop` between blocks of members
    /// and gives up (`None`) when it says so: a large initial population on a large map is
    /// seconds of work that an interrupt must not wait for. Each member draws from its own
    /// stream, so the blocks change nothing.
    pub fn initial(
        &self,
        size: usize,
        seeds: &[T],
        seeded: usize,
        scratches: &mut [EvalScratch],
        stop: &dyn Fn() -> bool,
    ) -> Option<(Vec<T>, u64)> {
        let mut jobs: Vec<Job<T>> = (0..size)
            .map(|s| match seeds.get(s % seeds.len().max(1)) {
                Some(seed) if s < seeded => Job::seed(seed.clone(), self.stream(s)),
                _ => Job::fresh(&mut Vec::new(), self.stream(s), Op::Reinit),
            })
            .collect();
        let block = INITIAL_BLOCK_PER_THREAD * scratches.len().max(1);
        let mut evaluations = 0;
        for jobs in jobs.chunks_mut(block) {
            if stop() {
                return None;
            }
            evaluations += run_jobs(jobs, &[], self.scenario, &self.context(), scratches);
        }
        Some((jobs.into_iter().map(|j| j.ind).collect(), evaluations))
    }

    /// Architecture (a) (thesis-ga §11.1): `keep` elite copies, `select` pairs by the scheme,
    /// crossover with `P_c`, mutation of offspring and rest, refill to `Pop_min` (R22).
    /// New members are built in the members of `spare` (their buffers are reused, their
    /// contents overwritten); the members that do not pass on are put there.
    pub fn step_a(
        &self,
        draw: ParentDraw,
        pop: Vec<T>,
        rng: &mut Rng,
        scratches: &mut [EvalScratch],
        spare: &mut Vec<T>,
    ) -> (Vec<T>, u64) {
        let (p, e) = (self.params, self.effective);
        let n = pop.len();
        let fit: Vec<f64> = pop.iter().map(T::fitness).collect();
        let elite = best_k(&fit, p.keep.min(n));
        // The effective `TS` and `SP` of this generation (parameter control may ramp them).
        let params = DrawParams { tournament_size: e.tournament_size, pressure: e.pressure, ..draw.params };
        let mut parents = ParentDraw { params, ..draw }.prepare(&fit);
        let mut pick = |rng: &mut Rng| parents.pick(rng);
        let mut jobs: Vec<Job<T>> = Vec::with_capacity(4 * p.select);
        let mut kids = Vec::with_capacity(4);
        for _ in 0..p.select {
            let p1 = pick(rng);
            let mut p2 = pick(rng);
            for _ in 0..10 {
                if p2 != p1 || n < 2 {
                    break;
                }
                p2 = pick(rng);
            }
            self.mate(&pop, &fit, (p1, p2), rng, &mut jobs, &mut kids, spare);
        }
        spare.append(&mut kids);
        let evaluations = run_jobs(&mut jobs, &pop, self.scenario, &self.context(), scratches);
        let made = jobs.len();
        let mut old: Vec<Option<T>> = pop.into_iter().map(Some).collect();
        let mut next: Vec<T> = elite.iter().map(|&i| old[i].take().expect("distinct elite")).collect();
        next.extend(jobs.into_iter().map(|j| j.ind));
        if next.len() < p.pop_min {
            let rest: Vec<usize> = (0..n).filter(|&i| old[i].is_some()).collect();
            let want = (p.pop_min - next.len()).min(rest.len());
            for k in rand::seq::index::sample(rng, rest.len(), want) {
                next.push(old[rest[k]].take().expect("sampled once"));
            }
        }
        recycle(spare, old.into_iter().flatten(), next.len().max(made));
        (next, evaluations)
    }

    /// Crosses `pop[p1]` and `pop[p2]` with `P_c` into child jobs, or else copies both parents;
    /// every new member is then mutated with `P_mI` and `P_mA` (`fit`: the parents' fitness,
    /// which adaptive control reads). Architecture (a) and NSGA-II make their offspring so.
    #[allow(clippy::too_many_arguments)]
    fn mate(
        &self,
        pop: &[T],
        fit: &[f64],
        (p1, p2): (usize, usize),
        rng: &mut Rng,
        jobs: &mut Vec<Job<T>>,
        kids: &mut Vec<T>,
        spare: &mut Vec<T>,
    ) {
        let e = self.effective;
        let crossing = rng.random_bool(e.p_c.clamp(0.0, 1.0));
        if crossing && self.cross(pop, (p1, p2), rng, kids, spare) {
            for (k, ind) in kids.drain(..).enumerate() {
                let receiver = if k % 2 == 0 { p1 } else { p2 };
                let op = Op::Mutate { p_mi: e.p_mi, p_ma: e.p_ma.for_fitness(fit[receiver]) };
                jobs.push(Job::child(ind, receiver, self.stream(jobs.len()), op));
            }
        } else {
            for q in [p1, p2] {
                let op = Op::Mutate { p_mi: e.p_mi, p_ma: e.p_ma.for_fitness(fit[q]) };
                jobs.push(Job::copy(spare, &pop[q], self.stream(jobs.len()), op));
            }
        }
    }

    /// Architecture (b) (thesis-ga §11.2): random families of two; crossing families keep their two
    /// best of parents and children (ties to children, R20); the others pass on, each
    /// re-initialised with `P_mI`; an odd individual passes unchanged. `spare` as in
    /// [`Self::step_a`].
    pub fn step_b(
        &self,
        pop: Vec<T>,
        rng: &mut Rng,
        scratches: &mut [EvalScratch],
        spare: &mut Vec<T>,
    ) -> (Vec<T>, u64) {
        let e = self.effective;
        let n = pop.len();
        let mut order: Vec<usize> = (0..n).collect();
        order.shuffle(rng);
        // Sized once: growing a vector of jobs moves every job made so far.
        let mut jobs: Vec<Job<T>> = Vec::with_capacity(n / 2 * self.params.c_child.children());
        let mut families = Vec::with_capacity(n / 2);
        let mut kids = Vec::with_capacity(4);
        let mut slot = 0;
        for pair in order.chunks_exact(2) {
            let (a, b) = (pair[0], pair[1]);
            let crossing = rng.random_bool(e.p_c.clamp(0.0, 1.0));
            if crossing && self.cross(&pop, (a, b), rng, &mut kids, spare) {
                let start = jobs.len();
                for (k, ind) in kids.drain(..).enumerate() {
                    let receiver = if k % 2 == 0 { a } else { b };
                    let op = Op::MutateAction { p_ma: e.p_ma.for_fitness(pop[receiver].fitness()) };
                    jobs.push(Job::child(ind, receiver, self.stream(slot), op));
                    slot += 1;
                }
                families.push(Family::Cross { parents: [a, b], kids: start..jobs.len() });
            } else {
                let mut member = |q: usize, jobs: &mut Vec<Job<T>>| {
                    let s = self.stream(slot);
                    slot += 1;
                    let p_mi = e.p_mi.clamp(0.0, 1.0);
                    if s.rng().random_bool(p_mi) {
                        jobs.push(Job::fresh(spare, JobStream { drawn: Some(p_mi), ..s }, Op::Reinit));
                        Err(jobs.len() - 1)
                    } else {
                        Ok(q)
                    }
                };
                let ma = member(a, &mut jobs);
                let mb = member(b, &mut jobs);
                families.push(Family::Apart([ma, mb]));
            }
        }
        spare.append(&mut kids);
        let evaluations = run_jobs(&mut jobs, &pop, self.scenario, &self.context(), scratches);
        let made = jobs.len();
        let mut old: Vec<Option<T>> = pop.into_iter().map(Some).collect();
        let mut new: Vec<Option<T>> = jobs.into_iter().map(|j| Some(j.ind)).collect();
        let mut next = Vec::with_capacity(n);
        if n % 2 == 1 {
            next.push(old[order[n - 1]].take().expect("odd one"));
        }
        self.families_pass_on(families, (&mut old, &mut new), &mut next, spare);
        // Members re-initialised in place of a parent leave the parent behind.
        recycle(spare, old.into_iter().flatten(), next.len().max(made));
        (next, evaluations)
    }

    /// Architecture (b)'s survivors, family by family, onto `next`: the best two of each
    /// crossing family (children first, so that they win ties), and each member of the others
    /// or its re-initialised replacement. What does not pass on goes to `spare`.
    fn families_pass_on(
        &self,
        families: Vec<Family>,
        (old, new): (&mut [Option<T>], &mut [Option<T>]),
        next: &mut Vec<T>,
        spare: &mut Vec<T>,
    ) {
        let (mut cands, mut fitness): (Vec<Option<T>>, Vec<f64>) = (Vec::with_capacity(6), Vec::with_capacity(6));
        for family in families {
            match family {
                Family::Cross { parents, kids } => {
                    // Children first, so that they win ties.
                    cands.clear();
                    cands.extend(kids.map(|k| new[k].take()));
                    cands.extend(parents.iter().map(|&q| old[q].take()));
                    fitness.clear();
                    let key = |c: &Option<T>| c.as_ref().map_or(f64::NEG_INFINITY, |m| bounded_fitness(m, self.bounds));
                    fitness.extend(cands.iter().map(key));
                    for k in family_survivors(&fitness) {
                        next.push(cands[k].take().expect("each member survives once"));
                    }
                    spare.extend(cands.drain(..).flatten());
                }
                Family::Apart(members) => {
                    for m in members {
                        next.push(match m {
                            Ok(q) => old[q].take().expect("member"),
                            Err(k) => new[k].take().expect("re-initialised"),
                        });
                    }
                }
            }
        }
    }
}

/// A pair of architecture (b) (003 §3.5.1, Fig. 3.9b): crossing, with the indices of its parents in the
/// population and of its children among the generation's jobs; or apart, each member kept
/// (`Ok`, its index in the population) or re-initialised (`Err`, its job).
enum Family {
    Cross { parents: [usize; 2], kids: std::ops::Range<usize> },
    Apart([Result<usize, usize>; 2]),
}

/// Puts the members that did not pass on into `spare`, kept to at most `limit` (a population,
/// or a generation's new members if they are more) so that the next generation finds a
/// member to reuse for each it makes, and a large initial population is not held on to.
fn recycle<T>(spare: &mut Vec<T>, dropped: impl Iterator<Item = T>, limit: usize) {
    spare.extend(dropped.take(limit.saturating_sub(spare.len())));
    spare.truncate(limit);
}

mod nsga2;
pub(crate) use nsga2::objectives;
pub use nsga2::violation;
#[cfg(test)]
mod tests;
