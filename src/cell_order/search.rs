//! The genetic search over tours: a generational GA whose parents are drawn by covga's
//! parent-selection schemes ([`crate::ga::parents`]), with the `keep` best carried over unchanged,
//! order crossover and uniform choice crossover, order and choice mutation, and optionally the
//! memetic step ([`super::local::improve`]) on the best child and one random child of every
//! generation. The first
//! individual is the nearest-neighbour tour (the greedy rule today's boustrophedon uses), so
//! the search starts from the baseline's way of ordering cells and can only improve on it.

use super::local::improve_within;
use super::operators::{choice_mutation, cuts, mutate_order, order_crossover, uniform_choices};
use super::tour::{Instance, Tour};
use crate::ga::observer::{GenerationRecord, Observers};
use crate::ga::parents::ParentDraw;
use crate::ga::rng::{Purpose, stream};
use crate::ga::selection::best_k;
use crate::planner::executor::{Search, StopRules, execute};
use crate::planner::{Budget, StopReason};
use rand::Rng;
use rand::seq::SliceRandom;
use std::time::Instant;

/// The GA's parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TourGaParams {
    /// Individuals per generation.
    pub population: usize,
    /// Parent selection: a scheme of the registry ([`crate::ga::parents`]) and its parameters.
    pub selection: ParentDraw,
    /// The best carried over unchanged each generation.
    pub keep: usize,
    /// Crossover probability.
    pub p_c: f64,
    /// Probability that a child's order is mutated (inversion, insertion or swap).
    pub p_m: f64,
    /// Per-cell probability that a child's sweep choice is redrawn (`None`: 1 / cells).
    pub p_choice: Option<f64>,
    /// Local search on the best and one random child of every generation (memetic step).
    pub memetic: bool,
    /// The coverage goal tours are ranked by ([`Instance::cost`]); `None`: their whole time.
    pub goal: Option<f64>,
}

/// One generation as the search reports it.
#[derive(Clone, Debug, PartialEq)]
pub struct Generation<'a> {
    /// Generation number (0: the initial population).
    pub iteration: u32,
    /// Evaluations so far (local search charged by the legs it reads).
    pub evaluations: u64,
    /// The best tour so far and its time.
    pub best: (&'a Tour, f64),
    /// Mean time of the population.
    pub mean_time_s: f64,
    /// Fitness `T_NN / T` of the best and the population mean.
    pub fitness: (f64, f64),
}

impl Generation<'_> {
    /// The record observers receive: with the lane coverage of the best tour (of the free and
    /// of the reachable cells, which the planner sweeps) and the number of members.
    pub fn record(&self, (best_coverage, reach): (f64, f64), members: u32) -> GenerationRecord {
        GenerationRecord {
            iteration: self.iteration,
            evaluations: self.evaluations,
            best_fitness: self.fitness.0,
            mean_fitness: self.fitness.1,
            best_coverage,
            best_coverage_reach: Some(reach),
            feasible: Some(members),
            diversity: None,
            extras: vec![("best_time_s", self.best.1), ("mean_time_s", self.mean_time_s)],
            robots: Vec::new(),
        }
    }
}

/// Makes the record observers receive from a generation (the planner sweeps the best tour's
/// lanes for its coverage). Called only for a generation some observer takes.
pub type ToRecord<'r> = dyn FnMut(&Generation<'_>) -> GenerationRecord + 'r;

/// How a search ended.
#[derive(Clone, Debug, PartialEq)]
pub struct Searched {
    /// The best tour found and its time.
    pub best: (Tour, f64),
    /// Evaluations spent.
    pub evaluations: u64,
    /// Generations completed.
    pub iterations: u32,
    /// Why it stopped.
    pub stop: StopReason,
    /// The nearest-neighbour tour's cost (the fitness scale).
    pub nearest_time_s: f64,
    /// The best tour and the fastest other distinct tours of the last population, best
    /// first, at most [`FINALISTS`], then the seeds not among them: what the planner scores
    /// with the common scorer when it chooses by a coverage goal.
    pub finalists: Vec<Tour>,
}

/// The tours a search hands over for the common scorer's choice.
pub const FINALISTS: usize = 8;

/// The nearest-neighbour tour: from the start, the candidate of an unswept cell with the
/// shortest leg (then the shortest own time), until every cell is swept.
pub fn nearest_neighbour(inst: &Instance) -> Tour {
    nearest_neighbour_among(inst, |_, _| true)
}

/// [`nearest_neighbour`] over the candidates `allowed(cell, choice)` admits (every candidate of
/// a cell it admits none of): the tour of the no-search control at one lane direction.
pub fn nearest_neighbour_among(inst: &Instance, allowed: impl Fn(usize, usize) -> bool) -> Tour {
    let n = inst.cells();
    let open: Vec<bool> = (0..n).map(|k| !(0..inst.choices(k)).any(|c| allowed(k, c))).collect();
    let mut done = vec![false; n];
    let mut tour = Tour { order: Vec::with_capacity(n), choice: vec![0; n] };
    let mut here: Option<usize> = None;
    for _ in 0..n {
        let mut best: Option<(f64, f64, usize, usize)> = None;
        for k in (0..n).filter(|&k| !done[k]) {
            for c in (0..inst.choices(k)).filter(|&c| open[k] || allowed(k, c)) {
                let g = inst.flat(k, c);
                let key = (inst.leg(here, Some(g)), inst.own(g));
                if best.is_none_or(|b| key.0 < b.0 - 1e-12 || (key.0 <= b.0 + 1e-12 && key.1 < b.1 - 1e-12)) {
                    best = Some((key.0, key.1, k, c));
                }
            }
        }
        let (_, _, k, c) = best.expect("an unswept cell remains");
        done[k] = true;
        tour.order.push(k as u32);
        tour.choice[k] = c as u16;
        here = Some(inst.flat(k, c));
    }
    tour
}

/// Runs the GA on `inst` from `seed` within `budget`, handing every generation's record
/// (made by `to_record`) to `observers`; the wall clock counts from `started` (the run's start,
/// so the preparation counts too).
pub fn search(
    inst: &Instance,
    params: &TourGaParams,
    run: (u64, Instant),
    budget: &Budget,
    observers: &mut Observers,
    to_record: &mut ToRecord<'_>,
) -> std::io::Result<Searched> {
    search_from(inst, params, &[], run, budget, observers, to_record)
}

/// [`search`] whose first population holds `seeds` after the nearest-neighbour tour (as many as
/// fit), and whose finalists end with them: a plan the seeds give is among those the common
/// scorer chooses from, so the search returns nothing worse than its seeds on the scorer.
pub fn search_from(
    inst: &Instance,
    params: &TourGaParams,
    seeds: &[Tour],
    (seed, started): (u64, Instant),
    budget: &Budget,
    observers: &mut Observers,
    to_record: &mut ToRecord<'_>,
) -> std::io::Result<Searched> {
    let n = inst.cells();
    let counts: Vec<usize> = (0..n).map(|k| inst.choices(k)).collect();
    let p_choice = params.p_choice.unwrap_or(1.0 / n.max(1) as f64);
    let mut rng = stream(seed, Purpose::Main, &[]);
    let mut charged = 0.0f64;
    let legs_per_tour = (n + 1) as f64;
    let nearest = nearest_neighbour(inst);
    let nearest_time_s = inst.cost(&nearest, params.goal);
    let scale = nearest_time_s.max(f64::MIN_POSITIVE);
    let mut pop: Vec<(Tour, f64)> = Vec::with_capacity(params.population);
    let mut first = nearest;
    if params.memetic {
        let left = reads_left(budget.evaluations, charged, legs_per_tour);
        charged += improve_within(inst, &mut first, ROUNDS, left) as f64 / legs_per_tour;
    }
    let t = inst.cost(&first, params.goal);
    pop.push((first, t));
    for tour in seeds.iter().take(params.population.saturating_sub(1)) {
        pop.push((tour.clone(), inst.cost(tour, params.goal)));
    }
    while pop.len() < params.population {
        let mut order: Vec<u32> = (0..n as u32).collect();
        order.shuffle(&mut rng);
        let choice = counts.iter().map(|&c| rng.random_range(0..c.max(1)) as u16).collect();
        let tour = Tour { order, choice };
        let t = inst.cost(&tour, params.goal);
        pop.push((tour, t));
    }
    charged += params.population as f64;
    let best = best_of(&pop);
    let budget_evaluations = budget.evaluations;
    let mut ga = Generations {
        inst,
        params,
        counts,
        p_choice,
        rng,
        legs_per_tour,
        scale,
        pop,
        best,
        charged,
        budget_evaluations,
        iteration: 0,
        to_record,
    };
    let finish = execute(&mut ga, &StopRules::of_budget(budget, None, started), observers)?;
    let finalists = finalists(&ga.best.0, &ga.pop);
    Ok(Searched::ended(ga.best, finalists, seeds, finish, nearest_time_s))
}

impl Searched {
    /// A search that ended with `best`, its `finalists` (best first), then those of `seeds`
    /// not among them.
    pub(super) fn ended(
        best: (Tour, f64),
        mut finalists: Vec<Tour>,
        seeds: &[Tour],
        finish: crate::planner::executor::Finish,
        nearest_time_s: f64,
    ) -> Self {
        for tour in seeds {
            if !finalists.contains(tour) {
                finalists.push(tour.clone());
            }
        }
        Self {
            finalists,
            best,
            evaluations: finish.evaluations,
            iterations: finish.iterations,
            stop: finish.stop,
            nearest_time_s,
        }
    }
}

/// The cell-order GA between generations, as [`execute`] drives it.
struct Generations<'a, 'r> {
    inst: &'a Instance,
    params: &'a TourGaParams,
    /// Choices per cell.
    counts: Vec<usize>,
    p_choice: f64,
    rng: crate::ga::rng::Rng,
    legs_per_tour: f64,
    /// The nearest-neighbour tour's time: fitness is `scale / T`.
    scale: f64,
    pop: Vec<(Tour, f64)>,
    /// The best tour so far (replaced only by one faster by more than 1e-9 s).
    best: (Tour, f64),
    /// Evaluations charged, local search by the legs it reads.
    charged: f64,
    /// The evaluation budget, which the memetic step keeps to.
    budget_evaluations: Option<u64>,
    iteration: u32,
    to_record: &'r mut ToRecord<'r>,
}

/// Leg reads a memetic step may still spend: what is left of an evaluation `budget` after
/// `charged`, so that a long local search does not run far past it.
pub(super) fn reads_left(budget: Option<u64>, charged: f64, legs_per_tour: f64) -> u64 {
    budget.map_or(u64::MAX, |e| ((e as f64 - charged).max(0.0) * legs_per_tour).ceil() as u64)
}

impl Search for Generations<'_, '_> {
    type Error = std::io::Error;

    fn progress(&self) -> (u32, u64) {
        (self.iteration, self.charged.ceil() as u64)
    }

    fn step(&mut self, _: &mut Observers) -> std::io::Result<bool> {
        let (inst, params, n) = (self.inst, self.params, self.inst.cells());
        self.iteration += 1;
        let fitness: Vec<f64> = self.pop.iter().map(|(_, t)| self.scale / t).collect();
        let rng = &mut self.rng;
        let pop = &self.pop;
        let mut parents = params.selection.prepare(&fitness);
        let mut next: Vec<(Tour, f64)> =
            best_k(&fitness, params.keep.min(pop.len())).into_iter().map(|i| pop[i].clone()).collect();
        let first_child = next.len();
        while next.len() < params.population {
            let (a, b) = (&pop[parents.pick(rng)].0, &pop[parents.pick(rng)].0);
            let mut child = if n > 1 && rng.random::<f64>() < params.p_c {
                let (i, j) = cuts(n, rng);
                Tour {
                    order: order_crossover(&a.order, &b.order, i, j),
                    choice: uniform_choices(&a.choice, &b.choice, rng),
                }
            } else {
                a.clone()
            };
            if rng.random::<f64>() < params.p_m {
                mutate_order(&mut child.order, rng);
            }
            choice_mutation(&mut child.choice, &self.counts, self.p_choice, rng);
            let t = inst.cost(&child, params.goal);
            next.push((child, t));
        }
        self.charged += (params.population - first_child) as f64;
        if params.memetic && first_child < next.len() {
            // The best child, and one drawn at random so that orders whose choices are still
            // poor get their chance too.
            let best_child = first_child + best_index(&next[first_child..]);
            let drawn = self.rng.random_range(first_child..next.len());
            for k in if drawn == best_child { vec![best_child] } else { vec![best_child, drawn] } {
                let left = reads_left(self.budget_evaluations, self.charged, self.legs_per_tour);
                if left == 0 {
                    break;
                }
                self.charged += improve_within(inst, &mut next[k].0, ROUNDS, left) as f64 / self.legs_per_tour;
                next[k].1 = inst.cost(&next[k].0, params.goal);
            }
        }
        self.pop = next;
        let candidate = best_of(&self.pop);
        let improved = candidate.1 < self.best.1 - 1e-9;
        if improved {
            self.best = candidate;
        }
        Ok(improved)
    }

    fn report(&mut self, observers: &mut Observers) -> std::io::Result<()> {
        if !observers.wants(self.iteration) {
            return Ok(());
        }
        let fitness: Vec<f64> = self.pop.iter().map(|(_, t)| self.scale / t).collect();
        let mean_time_s = self.pop.iter().map(|(_, t)| t).sum::<f64>() / self.pop.len() as f64;
        let record = (self.to_record)(&Generation {
            iteration: self.iteration,
            evaluations: self.charged.ceil() as u64,
            best: (&self.best.0, self.best.1),
            mean_time_s,
            fitness: (self.scale / self.best.1, fitness.iter().sum::<f64>() / fitness.len() as f64),
        });
        observers.generation(&record)
    }
}

/// Rounds of local search allowed per memetic step (a bound; it usually stops far earlier).
pub const ROUNDS: usize = 10_000;

/// `best`, then the distinct tours of `pop` other than it, fastest first (the population's
/// order among equals), [`FINALISTS`] in all at most.
pub(super) fn finalists(best: &Tour, pop: &[(Tour, f64)]) -> Vec<Tour> {
    let mut ranked: Vec<&(Tour, f64)> = pop.iter().collect();
    ranked.sort_by(|a, b| a.1.total_cmp(&b.1));
    let mut out = vec![best.clone()];
    for (tour, _) in ranked {
        if out.len() == FINALISTS {
            break;
        }
        if !out.contains(tour) {
            out.push(tour.clone());
        }
    }
    out
}

fn best_index(pop: &[(Tour, f64)]) -> usize {
    (0..pop.len()).fold(0, |b, i| if pop[i].1 < pop[b].1 { i } else { b })
}

fn best_of(pop: &[(Tour, f64)]) -> (Tour, f64) {
    pop[best_index(pop)].clone()
}

#[cfg(test)]
pub(super) mod tests {
    use super::super::tour::tests::line;
    use super::*;

    /// The scheme `name` with `TS` = `size`, `SP` = `pressure`, `select` = `select`.
    fn draw(name: &str, size: usize, pressure: f64, select: usize) -> ParentDraw {
        ParentDraw::named(
            name,
            crate::ga::parents::DrawParams { tournament_size: size, pressure, best_parents: select },
        )
        .unwrap()
    }

    fn params(selection: ParentDraw, memetic: bool) -> TourGaParams {
        TourGaParams { population: 40, selection, keep: 2, p_c: 0.9, p_m: 0.5, p_choice: None, memetic, goal: None }
    }

    /// Runs `search` with an observer that takes every record, so that the record maker it is
    /// handed (which the search wraps to look at each generation) runs once per generation.
    pub(in crate::cell_order) fn watching(
        search: impl FnOnce(&mut Observers, &mut dyn FnMut(&Generation) -> GenerationRecord) -> std::io::Result<Searched>,
    ) -> Searched {
        let mut recorder = crate::ga::observer::Recorder::default();
        let mut list: [&mut dyn crate::ga::observer::Observer; 1] = [&mut recorder];
        let out = search(&mut Observers::new(&mut list), &mut |g| g.record((0.0, 0.0), 1)).unwrap();
        assert_eq!(recorder.history.len() as u32, out.iterations + 1, "a record per generation");
        out
    }

    #[test]
    fn the_ga_sorts_a_shuffled_line_and_never_loses_its_best() {
        let inst = line(8);
        let optimum = super::super::exact::held_karp(&inst).unwrap().1;
        for selection in [
            draw("best", 3, 1.7, 10),
            draw("tournament", 3, 1.7, 20),
            draw("prws", 3, 1.7, 20),
            draw("rrws", 3, 1.8, 20),
        ] {
            let mut last = f64::INFINITY;
            let out = watching(|observers, to_record| {
                search(
                    &inst,
                    &params(selection, false),
                    (7, Instant::now()),
                    &Budget::iterations(300),
                    observers,
                    &mut |g| {
                        assert!(g.best.1 <= last + 1e-12, "the best never gets worse");
                        last = g.best.1;
                        to_record(g)
                    },
                )
            });
            assert!((out.best.1 - optimum).abs() < 1e-9, "{selection:?}: {} vs {optimum}", out.best.1);
            assert!(out.best.1 <= out.nearest_time_s);
        }
    }

    #[test]
    fn same_seed_same_search() {
        let inst = line(9);
        let run = |seed| {
            search(
                &inst,
                &params(draw("tournament", 2, 1.7, 20), true),
                (seed, Instant::now()),
                &Budget::iterations(20),
                &mut Observers::none(),
                &mut |_| unreachable!("no observer takes a record"),
            )
            .unwrap()
        };
        assert_eq!(run(3), run(3));
        let mut evals = 0;
        let budget = Budget { evaluations: Some(500), ..Budget::iterations(1_000_000) };
        let out = watching(|observers, to_record| {
            search(&inst, &params(draw("prws", 3, 1.7, 20), true), (4, Instant::now()), &budget, observers, &mut |g| {
                assert!(g.evaluations >= evals);
                evals = g.evaluations;
                to_record(g)
            })
        });
        assert_eq!(out.stop, StopReason::Evaluations);
        assert!(out.evaluations >= 500 && out.evaluations < 500 + 40 + 200, "{}", out.evaluations);
    }

    #[test]
    fn seeds_join_the_first_population_and_the_finalists() {
        let inst = line(6);
        // Every cell swept right to left only: the control's tour at that one "direction".
        let seed = nearest_neighbour_among(&inst, |_, c| c == 1);
        assert!(seed.choice.iter().all(|&c| c == 1), "{seed:?}");
        assert_eq!(nearest_neighbour_among(&inst, |_, _| true), nearest_neighbour(&inst));
        let p = params(draw("tournament", 3, 1.7, 20), false);
        let (seeds, budget) = (std::slice::from_ref(&seed), Budget::iterations(2));
        let out = search_from(&inst, &p, seeds, (3, Instant::now()), &budget, &mut Observers::none(), &mut |g| {
            g.record((0.0, 0.0), 1)
        })
        .unwrap();
        assert!(out.finalists.contains(&seed), "{:?}", out.finalists);
        assert!(out.best.1 <= inst.time(&seed) + 1e-9, "the best is no worse than a seed");
        assert_eq!(out.finalists[0], out.best.0);
    }

    /// The local search stops once its read budget is spent: over by at most one candidate
    /// move of a pass (`4 + 2n` leg reads), where a whole step on a shuffled tour of many cells
    /// costs many budgets.
    #[test]
    fn local_search_stops_at_its_read_budget() {
        let inst = line(300);
        let mut shuffled = nearest_neighbour(&inst);
        shuffled.order.shuffle(&mut stream(1, Purpose::Main, &[]));
        let whole = super::super::local::improve(&inst, &mut shuffled.clone(), ROUNDS);
        let candidate = 4 + 2 * 300;
        for cap in [1u64, 1000, whole / 20, whole / 5] {
            let capped = super::super::local::improve_within(&inst, &mut shuffled.clone(), ROUNDS, cap);
            assert!(capped <= cap + candidate, "cap {cap}: {capped} reads");
        }
        let least = super::super::local::improve_within(&inst, &mut shuffled.clone(), ROUNDS, 1);
        assert!(4 * least < whole, "one round ({least} reads) against the whole step ({whole})");
    }
}
