//! The GTSP reference above the exact solver's size: iterated local search (Lourenço, Martin
//! & Stützle, "Iterated Local Search", 2003) over the same tours as the GA. The start is the
//! nearest-neighbour tour (and the seed tours) brought to a local optimum of the memetic step's
//! neighbourhoods ([`super::local`]: the exact best choices for an order — the cluster
//! optimisation of GTSP heuristics — Or-opt and 2-opt); then each iteration kicks the incumbent
//! with a double bridge (the order's segments `A B C D` become `A C B D`, a move no sequence of
//! 2-opt and Or-opt moves undoes cheaply), descends to a local optimum again, and keeps the
//! result when it is no slower than the incumbent. No population, no crossover: a strong
//! search that owes nothing to evolution, against which the GA has to earn its place.

use super::local::improve_within;
use super::search::{FINALISTS, Generation, ROUNDS, Searched, ToRecord, finalists, nearest_neighbour, reads_left};
use super::tour::{Instance, Tour};
use crate::ga::observer::Observers;
use crate::ga::rng::{Purpose, stream};
use crate::planner::Budget;
use crate::planner::executor::{Search, StopRules, execute};
use rand::Rng;
use std::time::Instant;

/// The double bridge: `order = A B C D` with cuts `0 ≤ i < j < k ≤ n` becomes `A C B D` (`A`
/// or `D` may be empty: the tour is a path from the start to the end station, so its first
/// and last cells may move too).
pub fn double_bridge(order: &[u32], i: usize, j: usize, k: usize) -> Vec<u32> {
    assert!(i < j && j < k && k <= order.len(), "cuts {i} < {j} < {k} <= {}", order.len());
    [&order[..i], &order[j..k], &order[i..j], &order[k..]].concat()
}

/// Three random cuts for [`double_bridge`] (`n` ≥ 2): `i` in `0..n-1`, `j` and `k` after it.
fn bridge_cuts(n: usize, rng: &mut impl Rng) -> (usize, usize, usize) {
    let i = rng.random_range(0..n - 1);
    let j = rng.random_range(i + 1..n);
    let k = rng.random_range(j + 1..=n);
    (i, j, k)
}

/// Runs iterated local search on `inst` from `seed` within `budget` (an iteration is one kick
/// and its descent; evaluations count each kicked tour once and the descents by the legs they
/// read, as the GA's memetic step is charged), ranking tours by [`Instance::cost`] with
/// `goal`; every iteration's record (made by `to_record`, a generation of one) goes to
/// `observers`. The search starts from the
/// best of the nearest-neighbour tour and `seeds`, each brought to a local optimum, and hands
/// over the best tour and the fastest other distinct local optima it met, then the seeds.
pub fn iterated_local_search(
    inst: &Instance,
    goal: Option<f64>,
    seeds: &[Tour],
    (seed, started): (u64, Instant),
    budget: &Budget,
    observers: &mut Observers,
    to_record: &mut ToRecord<'_>,
) -> std::io::Result<Searched> {
    let legs_per_tour = (inst.cells() + 1) as f64;
    let nearest = nearest_neighbour(inst);
    let nearest_time_s = inst.cost(&nearest, goal);
    let mut kicks = Kicks {
        inst,
        goal,
        rng: stream(seed, Purpose::Main, &[]),
        legs_per_tour,
        scale: nearest_time_s.max(f64::MIN_POSITIVE),
        current: (Tour::default(), f64::INFINITY),
        best: (Tour::default(), f64::INFINITY),
        optima: Vec::new(),
        charged: 0.0,
        budget_evaluations: budget.evaluations,
        iteration: 0,
        stuck: 0,
        to_record,
    };
    let mut start: Option<(Tour, f64)> = None;
    for tour in std::iter::once(nearest).chain(seeds.iter().cloned()) {
        let found = kicks.descend(tour);
        if start.as_ref().is_none_or(|s| found.1 < s.1 - 1e-9) {
            start = Some(found);
        }
    }
    let start = start.expect("the nearest-neighbour tour at least");
    (kicks.current, kicks.best) = (start.clone(), start);
    let finish = execute(&mut kicks, &StopRules::of_budget(budget, None, started), observers)?;
    let finalists = finalists(&kicks.best.0, &kicks.optima);
    Ok(Searched::ended(kicks.best, finalists, seeds, finish, nearest_time_s))
}

/// Iterated local search between iterations, as [`execute`] drives it.
struct Kicks<'a, 'r> {
    inst: &'a Instance,
    goal: Option<f64>,
    rng: crate::ga::rng::Rng,
    legs_per_tour: f64,
    /// The nearest-neighbour tour's cost: fitness is `scale / cost`, as the GA reports it.
    scale: f64,
    /// The tour the next kick starts from.
    current: (Tour, f64),
    /// The best tour so far (replaced only by one faster by more than 1e-9 s).
    best: (Tour, f64),
    /// The fastest distinct local optima met, fastest first, [`FINALISTS`] at most.
    optima: Vec<(Tour, f64)>,
    /// Evaluations charged, descents by the legs they read.
    charged: f64,
    budget_evaluations: Option<u64>,
    iteration: u32,
    /// Kicks in a row that found nothing faster than the incumbent.
    stuck: usize,
    to_record: &'r mut ToRecord<'r>,
}

/// Kicks without a faster tour after which each kick adds one more double bridge.
pub const KICK_GROWTH: usize = 8;

impl Kicks<'_, '_> {
    /// `tour` brought to a local optimum within what is left of the evaluation budget, charged
    /// and remembered among the optima; with its cost.
    fn descend(&mut self, mut tour: Tour) -> (Tour, f64) {
        self.charged += 1.0;
        let left = reads_left(self.budget_evaluations, self.charged, self.legs_per_tour);
        if left > 0 {
            self.charged += improve_within(self.inst, &mut tour, ROUNDS, left) as f64 / self.legs_per_tour;
        }
        let cost = self.inst.cost(&tour, self.goal);
        if !self.optima.iter().any(|(t, _)| *t == tour) {
            let at = self.optima.partition_point(|(_, c)| *c <= cost);
            if at < FINALISTS {
                self.optima.insert(at, (tour.clone(), cost));
                self.optima.truncate(FINALISTS);
            }
        }
        (tour, cost)
    }
}

impl Search for Kicks<'_, '_> {
    type Error = std::io::Error;

    fn progress(&self) -> (u32, u64) {
        (self.iteration, self.charged.ceil() as u64)
    }

    fn step(&mut self, _: &mut Observers) -> std::io::Result<bool> {
        self.iteration += 1;
        let n = self.inst.cells();
        let mut kicked = self.current.0.clone();
        // One bridge, one more for every KICK_GROWTH kicks in a row that found nothing faster:
        // a search stuck in a deep basin kicks harder until it leaves it.
        let bridges = if n >= 2 { 1 + self.stuck / KICK_GROWTH } else { 0 };
        for _ in 0..bridges {
            let (i, j, k) = bridge_cuts(n, &mut self.rng);
            kicked.order = double_bridge(&kicked.order, i, j, k);
        }
        let found = self.descend(kicked);
        self.stuck = if found.1 < self.current.1 - 1e-9 { 0 } else { self.stuck + 1 };
        // No slower than the incumbent: equal tours let the search drift across plateaus.
        if found.1 <= self.current.1 + 1e-9 {
            self.current = found;
        }
        let improved = self.current.1 < self.best.1 - 1e-9;
        if improved {
            self.best = self.current.clone();
        }
        Ok(improved)
    }

    fn report(&mut self, observers: &mut Observers) -> std::io::Result<()> {
        if !observers.wants(self.iteration) {
            return Ok(());
        }
        let record = (self.to_record)(&Generation {
            iteration: self.iteration,
            evaluations: self.charged.ceil() as u64,
            best: (&self.best.0, self.best.1),
            mean_time_s: self.current.1,
            fitness: (self.scale / self.best.1, self.scale / self.current.1),
        });
        observers.generation(&record)
    }
}

#[cfg(test)]
mod tests {
    use super::super::exact::held_karp;
    use super::super::tour::tests::line;
    use super::super::tour::{Candidate, Instance};
    use super::*;
    use crate::geom::{Point, Vector};
    use rand::SeedableRng;

    #[test]
    fn the_double_bridge_swaps_the_middle_segments() {
        let order: Vec<u32> = (0..8).collect();
        assert_eq!(double_bridge(&order, 2, 5, 7), vec![0, 1, 5, 6, 2, 3, 4, 7]);
        assert_eq!(double_bridge(&order, 1, 2, 3), vec![0, 2, 1, 3, 4, 5, 6, 7]);
        assert_eq!(double_bridge(&order, 0, 3, 8), vec![3, 4, 5, 6, 7, 0, 1, 2], "first and last move too");
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        for n in 2..12 {
            for _ in 0..50 {
                let (i, j, k) = bridge_cuts(n, &mut rng);
                assert!(i < j && j < k && k <= n, "{n}: {i} {j} {k}");
            }
        }
    }

    /// `n` cells scattered over a 40 m square, each with four candidate sweeps (two
    /// directions, two entries), legs the straight distance at 1 m/s plus a turning charge:
    /// a generalised TSP with no structure for the search to exploit.
    fn scattered(n: usize, seed: u64) -> Instance {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let z = Vector::zeros();
        let cells: Vec<Vec<Candidate>> = (0..n)
            .map(|_| {
                let c = Point::new(rng.random_range(0.0..40.0), rng.random_range(0.0..40.0));
                let (w, h) = (rng.random_range(1.0..4.0), rng.random_range(1.0..4.0));
                let corners = [c, c + Vector::new(w, 0.0), c + Vector::new(w, h), c + Vector::new(0.0, h)];
                (0..4)
                    .map(|k| Candidate {
                        time_s: 10.0 + k as f64,
                        entry: (corners[k], z),
                        exit: (corners[(k + 2) % 4], z),
                        gain: 1.0 / n as f64,
                        completion_s: 0.0,
                    })
                    .collect()
            })
            .collect();
        let flat: Vec<Candidate> = cells.iter().flatten().copied().collect();
        let station = Point::new(0.0, 0.0);
        Instance::new(&cells, |a, b| {
            let p = a.map_or(station, |a| flat[a].exit.0);
            let q = b.map_or(station, |b| flat[b].entry.0);
            (q - p).norm() + 0.5
        })
    }

    fn run(inst: &Instance, seed: u64, evaluations: u64) -> Searched {
        let budget = Budget { evaluations: Some(evaluations), ..Budget::iterations(1_000_000) };
        let mut none = Observers::none();
        iterated_local_search(inst, None, &[], (seed, Instant::now()), &budget, &mut none, &mut |g| {
            g.record((0.0, 0.0), 1)
        })
        .unwrap()
    }

    #[test]
    fn it_finds_the_optimum_of_small_instances_and_never_returns_worse_than_nearest_neighbour() {
        // (cells, instance seed): Held–Karp's optimum is reached within 50 000 evaluations (the study's budget).
        for (n, s) in [(5, 1), (7, 2), (8, 3), (9, 4), (10, 5), (10, 6), (11, 7), (12, 8)] {
            let inst = scattered(n, s);
            let (_, optimum) = held_karp(&inst).unwrap();
            let out = run(&inst, 11, 50_000);
            assert!((inst.time(&out.best.0) - out.best.1).abs() < 1e-9, "the tour has the cost it claims");
            assert!(out.best.1 <= optimum * (1.0 + 1e-9), "n = {n}, seed {s}: {} against {optimum}", out.best.1);
            assert!(out.best.1 <= out.nearest_time_s);
            // A kick's tour, and a descent cut at its last candidate move (4 + 2n leg reads).
            assert!(out.evaluations <= 50_000 + 4, "the budget: {}", out.evaluations);
        }
        let inst = line(6);
        assert!((run(&inst, 1, 500).best.1 - held_karp(&inst).unwrap().1).abs() < 1e-9);
    }

    #[test]
    fn the_same_seed_gives_the_same_search_and_kicks_improve_on_the_first_descent() {
        let inst = scattered(40, 9);
        let (a, b) = (run(&inst, 5, 20_000), run(&inst, 5, 20_000));
        assert_eq!((&a.best, a.evaluations, a.iterations), (&b.best, b.evaluations, b.iterations));
        let mut records = Vec::new();
        let budget = Budget { evaluations: Some(20_000), ..Budget::iterations(1_000_000) };
        let out = super::super::search::tests::watching(|observers, to_record| {
            iterated_local_search(&inst, None, &[], (5, Instant::now()), &budget, observers, &mut |g| {
                records.push((g.iteration, g.best.1));
                to_record(g)
            })
        });
        assert_eq!(records.len() as u32, out.iterations + 1, "one record per kick and one for the start");
        assert!(records.windows(2).all(|w| w[1].1 <= w[0].1), "the best never gets worse");
        assert!(out.best.1 < records[0].1 - 1e-9, "the kicks find a better tour than the first local optimum");
        assert!(out.finalists.len() > 1 && out.finalists[0] == out.best.0);
    }
}
