//! The maximin GA of 000 (§III, waypoint §10–17): initial population from feasible random paths,
//! low-variance parent sampling with fitness pressure γ, row-wise crossover and mutations,
//! penalised objectives with the coverage ramp, maximin fitness over parents ∪ children and
//! elitism. Single and multi-agent (one row per agent).

use super::evaluate::{Evaluation, Evaluator, ObjectiveParams, TurnCosts, required_coverage};
use super::operators::{OperatorParams, crossover, extend_random, mutation_a, mutation_b, repair};
use super::precompute::Union;
use super::world::World;
use crate::ga::maximin::maximin;
use crate::ga::observer::{GenerationRecord, Observers};
use crate::ga::rng::{Purpose, Rng, stream};
use crate::ga::selection::low_variance_sample;
use crate::planner::executor::{Search, StopRules, execute};
use crate::planner::{Budget, PlannerError};
use rand::Rng as _;
use rand::seq::SliceRandom;
use rayon::prelude::*;

/// GA parameters (Table I, waypoint §18–19).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WaypointGaParams {
    /// `N`.
    pub population: usize,
    /// Generations `G`.
    pub generations: u32,
    /// `p_c`.
    pub p_c: f64,
    /// `p_A`.
    pub p_a: f64,
    /// `p_B`.
    pub p_b: f64,
    /// `γ`, fitness pressure.
    pub gamma: f64,
    /// `l_init`.
    pub l_init: usize,
    /// Agents.
    pub agents: usize,
    /// Operators.
    pub ops: OperatorParams,
    /// Objectives and constraints.
    pub objectives: ObjectiveParams,
}

/// One organism: a path per agent and its evaluation.
#[derive(Clone, Debug)]
pub struct Organism {
    /// Waypoint ids per agent.
    pub rows: Vec<Vec<u32>>,
    /// Its evaluation.
    pub eval: Evaluation,
}

/// Per-generation statistics (waypoint §17).
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct WaypointStats {
    /// Generation.
    pub generation: u32,
    /// `C_req`.
    pub c_required: f64,
    /// Mean / min / max of `C`.
    pub mean_coverage: f64,
    /// Minimum `C`.
    pub min_coverage: f64,
    /// Maximum `C`.
    pub max_coverage: f64,
    /// Mean `C_open`.
    pub mean_open: f64,
    /// Mean `C_walls`.
    pub mean_walls: f64,
    /// Mean flight time (px-equivalents).
    pub mean_flight_time: f64,
    /// Minimum flight time.
    pub min_flight_time: f64,
    /// Mean scaled, penalised `f1`.
    pub mean_f1: f64,
    /// Mean scaled, penalised `f2`.
    pub mean_f2: f64,
    /// Organisms meeting every constraint.
    pub feasible: u32,
    /// Mean path length (waypoints per agent).
    pub mean_length: f64,
    /// Mean self loop closures per agent.
    pub mean_self_closures: f64,
}

/// Population `(C, flight time, feasible)` at one generation.
pub type Snapshot = (u32, Vec<(f64, f64, bool)>);

/// The result of a run.
pub struct WaypointOutcome {
    /// Final population.
    pub population: Vec<Organism>,
    /// Index of the reported organism ([`reported`] at the last generation run).
    pub best: usize,
    /// Generations completed.
    pub generations: u32,
    /// Evaluations spent (every organism evaluated, initial attempts included).
    pub evaluations: u64,
    /// Why the run ended.
    pub stop: crate::planner::StopReason,
    /// Population `(C, flight time, feasible)` at generation 0, ~G/3, ~2G/3 and G.
    pub snapshots: Vec<Snapshot>,
    /// Organisms accepted at generation 0 without violating a constraint.
    pub initial_feasible: usize,
    /// Every generation's statistics, the initial population's first.
    pub history: Vec<WaypointStats>,
}

/// Makes the record observers receive from a generation's statistics, its reported organism
/// and the evaluations so far (the planner sweeps the organism's plan on the scenario's grid).
/// Called only for a generation some observer takes.
pub type ToRecord<'a> = dyn FnMut(&WaypointStats, &Organism, u64) -> GenerationRecord + 'a;

/// The organism a run reports at generation `g`: the feasible one with the highest coverage
/// `C` (ties: shorter flight time, then lower index); when none is feasible, the one with the
/// fewest violated constraint types, then the highest coverage. History and summary use this
/// same choice.
pub fn reported(pop: &[Organism], p: &WaypointGaParams, g: u32) -> usize {
    let c_req = required_coverage(&p.objectives, g);
    let key = |o: &Organism| o.eval.violations(&p.objectives, c_req);
    let mut best = 0;
    for i in 1..pop.len() {
        let (a, b) = (&pop[i], &pop[best]);
        let better = key(a).cmp(&key(b)).then(b.eval.coverage.total_cmp(&a.eval.coverage)).then(if key(a) == 0 {
            a.eval.flight_time.total_cmp(&b.eval.flight_time)
        } else {
            std::cmp::Ordering::Equal
        });
        if better == std::cmp::Ordering::Less {
            best = i;
        }
    }
    best
}

fn stats(g: u32, pop: &[Organism], p: &WaypointGaParams) -> WaypointStats {
    let c_req = required_coverage(&p.objectives, g);
    let n = pop.len() as f64;
    let objs: Vec<[f64; 2]> = pop.iter().map(|o| o.eval.objectives(&p.objectives, c_req)).collect();
    let sum = |f: &dyn Fn(&Organism) -> f64| pop.iter().map(f).sum::<f64>() / n;
    WaypointStats {
        generation: g,
        c_required: c_req,
        mean_coverage: sum(&|o| o.eval.coverage),
        min_coverage: pop.iter().map(|o| o.eval.coverage).fold(f64::INFINITY, f64::min),
        max_coverage: pop.iter().map(|o| o.eval.coverage).fold(f64::NEG_INFINITY, f64::max),
        mean_open: sum(&|o| o.eval.open),
        mean_walls: sum(&|o| o.eval.walls),
        mean_flight_time: sum(&|o| o.eval.flight_time),
        min_flight_time: pop.iter().map(|o| o.eval.flight_time).fold(f64::INFINITY, f64::min),
        mean_f1: objs.iter().map(|o| o[0]).sum::<f64>() / n,
        mean_f2: objs.iter().map(|o| o[1]).sum::<f64>() / n,
        feasible: pop.iter().filter(|o| o.eval.violations(&p.objectives, c_req) == 0).count() as u32,
        mean_length: sum(&|o| o.rows.iter().map(Vec::len).sum::<usize>() as f64 / o.rows.len() as f64),
        mean_self_closures: sum(&|o| {
            (0..o.rows.len()).map(|i| o.eval.closures[i][i]).sum::<usize>() as f64 / o.rows.len() as f64
        }),
    }
}

/// Selection weights from maximin values with pressure γ (waypoint §16, W28).
pub fn pressure_weights(fitness: &[f64], gamma: f64) -> Vec<f64> {
    let (lo, hi) = (
        fitness.iter().copied().fold(f64::INFINITY, f64::min),
        fitness.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    );
    let s: Vec<f64> = fitness.iter().map(|&f| if hi > lo { (hi - f) / (hi - lo) } else { 1.0 }).collect();
    let w: Vec<f64> = if gamma >= 1.0 {
        s.iter().map(|&x| if x >= 1.0 { 1.0 } else { 0.0 }).collect()
    } else {
        let e = gamma / (1.0 - gamma);
        s.iter().map(|&x| if e == 0.0 { 1.0 } else { x.powf(e) }).collect()
    };
    let total: f64 = w.iter().sum();
    w.iter().map(|x| x / total).collect()
}

/// Runs the GA on a built world for `p.generations` (or `limits.iterations`, if fewer), within
/// the evaluation, wall-clock and stall limits and the interrupt of `limits` (a stall: no plan
/// better than the best so far, more coverage or as much in less time); each generation's
/// record, made by `to_record`, goes to `observers`. [`PlannerError::Interrupted`] when the
/// interrupt is raised before the initial population is complete (there is no plan yet).
pub fn run(
    world: &World,
    p: &WaypointGaParams,
    seed: u64,
    limits: &Budget,
    observers: &mut Observers,
    to_record: &mut ToRecord<'_>,
) -> Result<WaypointOutcome, PlannerError> {
    let started = std::time::Instant::now();
    let turns = TurnCosts::new(&world.graph, &world.traversals, p.objectives.rho);
    let ev = Evaluator {
        graph: &world.graph,
        traversals: &world.traversals,
        band: &world.band,
        free: world.free,
        band_count: world.band_count,
        params: p.objectives,
        turns: &turns,
    };
    let words = world.traversals.words;
    let g = &world.graph;
    let evaluate_all = |cands: Vec<Vec<Vec<u32>>>| -> Vec<Organism> {
        cands
            .into_par_iter()
            .map_init(|| Union::new(words), |u, rows| Organism { eval: ev.evaluate(&rows, u), rows })
            .collect()
    };
    let interrupted = || limits.interrupt.as_ref().is_some_and(crate::planner::executor::Interrupt::is_raised);
    let (pop, attempt, initial_feasible) =
        initial_population(world, p, seed, &evaluate_all, &interrupted).ok_or(PlannerError::Interrupted)?;
    let first = &pop[reported(&pop, p, 0)].eval;
    let best_seen = (first.coverage, first.flight_time);
    let mut run = Generations {
        p,
        seed,
        graph: g,
        evaluate_all: &evaluate_all,
        rng: stream(seed, Purpose::Main, &[]),
        snap_at: [0, p.generations / 3, 2 * p.generations / 3, p.generations],
        snapshots: Vec::new(),
        pop,
        evaluations: attempt,
        generation: 0,
        best_seen,
        history: Vec::new(),
        to_record,
    };
    run.snapshots.push(snapshot(p, 0, &run.pop));
    // 000's generations, or fewer where the budget's iteration limit says so.
    let rules = StopRules::of_budget(limits, Some(p.generations.min(limits.iterations)), started);
    let finish = execute(&mut run, &rules, observers)?;
    let Generations { pop, mut snapshots, history, .. } = run;
    let generations = finish.iterations;
    if generations > 0 && snapshots.last().is_none_or(|s| s.0 != generations) {
        snapshots.push(snapshot(p, generations, &pop));
    }
    let best = reported(&pop, p, generations);
    Ok(WaypointOutcome {
        population: pop,
        best,
        generations,
        evaluations: finish.evaluations,
        stop: finish.stop,
        snapshots,
        initial_feasible,
        history,
    })
}

/// The initial population (000 §III-A.1, with the constraints of §III-A.4 at their generation-0
/// values): organisms feasible then, in attempt order, topped up with the least-violating
/// rejects; with the attempts made and how many were feasible. Draws batches of `population`
/// until it has them all or has made 200 × `population` attempts (the paper sets no cap; the
/// cap keeps a run finite); `None` when `interrupted` says so between batches.
fn initial_population(
    world: &World,
    p: &WaypointGaParams,
    seed: u64,
    evaluate_all: &dyn Fn(Vec<Vec<Vec<u32>>>) -> Vec<Organism>,
    interrupted: &dyn Fn() -> bool,
) -> Option<(Vec<Organism>, u64, usize)> {
    let g = &world.graph;
    let c0 = required_coverage(&p.objectives, 0);
    let mut accepted: Vec<Organism> = Vec::new();
    let mut rejected: Vec<Organism> = Vec::new();
    let mut attempt = 0u64;
    let cap = 200 * p.population as u64;
    while accepted.len() < p.population && attempt < cap {
        if interrupted() {
            return None;
        }
        let batch = (p.population as u64).min(cap - attempt);
        let cands: Vec<Vec<Vec<u32>>> = (attempt..attempt + batch)
            .map(|k| {
                let mut rng = stream(seed, Purpose::Individual, &[0, k]);
                world
                    .starts
                    .iter()
                    .take(p.agents)
                    .map(|&s| {
                        let mut r = vec![s];
                        extend_random(&mut r, p.l_init, g, &p.ops, &mut rng);
                        r
                    })
                    .collect()
            })
            .collect();
        for o in evaluate_all(cands) {
            if o.eval.violations(&p.objectives, c0) == 0 && accepted.len() < p.population {
                accepted.push(o);
            } else {
                rejected.push(o);
            }
        }
        attempt += batch;
        // Keep only the least-violating rejects (fewest violations, then most coverage).
        rejected.sort_by(|a, b| {
            a.eval
                .violations(&p.objectives, c0)
                .cmp(&b.eval.violations(&p.objectives, c0))
                .then(b.eval.coverage.total_cmp(&a.eval.coverage))
        });
        rejected.truncate(p.population);
    }
    let initial_feasible = accepted.len();
    let mut pop = accepted;
    pop.extend(rejected.into_iter().take(p.population - pop.len()));
    Some((pop, attempt, initial_feasible))
}

/// Each organism's (coverage, flight time, feasible at generation `g`'s constraints).
fn snapshot(p: &WaypointGaParams, g: u32, pop: &[Organism]) -> Snapshot {
    let c_req = required_coverage(&p.objectives, g);
    let of = |o: &Organism| (o.eval.coverage, o.eval.flight_time, o.eval.violations(&p.objectives, c_req) == 0);
    (g, pop.iter().map(of).collect())
}

/// The waypoint GA between generations, as [`execute`] drives it.
struct Generations<'a, 'r> {
    p: &'a WaypointGaParams,
    seed: u64,
    graph: &'a super::graph::Graph,
    evaluate_all: &'a dyn Fn(Vec<Vec<Vec<u32>>>) -> Vec<Organism>,
    rng: Rng,
    /// Generations whose population is kept for the figures (0, a third, two thirds, last).
    snap_at: [u32; 4],
    snapshots: Vec<Snapshot>,
    pop: Vec<Organism>,
    evaluations: u64,
    generation: u32,
    /// The reported plan's best (coverage, flight time) so far: better is more coverage, then
    /// less time.
    best_seen: (f64, f64),
    history: Vec<WaypointStats>,
    to_record: &'r mut ToRecord<'r>,
}

impl Search for Generations<'_, '_> {
    type Error = PlannerError;

    fn progress(&self) -> (u32, u64) {
        (self.generation, self.evaluations)
    }

    fn step(&mut self, _: &mut Observers) -> Result<bool, Self::Error> {
        let (p, seed, g) = (self.p, self.seed, self.graph);
        let gen_ = self.generation + 1;
        let rng = &mut self.rng;
        let c_req = required_coverage(&p.objectives, gen_);
        let objs: Vec<[f64; 2]> = self.pop.iter().map(|o| o.eval.objectives(&p.objectives, c_req)).collect();
        let probs = pressure_weights(&maximin(&objs), p.gamma);
        let mut parents = low_variance_sample(&probs, p.population, rng);
        parents.shuffle(rng);
        let pop_ref = &self.pop;
        let children: Vec<Vec<Vec<u32>>> = parents
            .par_chunks(2)
            .enumerate()
            .flat_map_iter(|(k, pair)| {
                let mut r: Rng = stream(seed, Purpose::Individual, &[u64::from(gen_), k as u64]);
                let (a, b) = (&pop_ref[pair[0]], &pop_ref[*pair.last().expect("pair")]);
                let mut c1 = Vec::with_capacity(a.rows.len());
                let mut c2 = Vec::with_capacity(a.rows.len());
                for row in 0..a.rows.len() {
                    let crossed = if r.random_bool(p.p_c) {
                        crossover(&a.rows[row], &b.rows[row], p.ops.crossover_threshold, &mut r)
                    } else {
                        None
                    };
                    let (x, y) = crossed.unwrap_or_else(|| (a.rows[row].clone(), b.rows[row].clone()));
                    c1.push(x);
                    c2.push(y);
                }
                for c in [&mut c1, &mut c2] {
                    for row in c.iter_mut() {
                        repair(row, g, &p.ops, &mut r);
                        if r.random_bool(p.p_a) {
                            mutation_a(row, g, &p.ops, &mut r);
                        }
                        if r.random_bool(p.p_b) {
                            mutation_b(row, g, &p.ops, &mut r);
                        }
                        repair(row, g, &p.ops, &mut r);
                    }
                }
                [c1, c2]
            })
            .collect();
        let mut pool = std::mem::take(&mut self.pop);
        self.evaluations += children.len() as u64;
        pool.extend((self.evaluate_all)(children));
        let objs: Vec<[f64; 2]> = pool.iter().map(|o| o.eval.objectives(&p.objectives, c_req)).collect();
        let fit = maximin(&objs);
        let ties: Vec<u64> = (0..pool.len()).map(|_| rng.random()).collect();
        let mut order: Vec<usize> = (0..pool.len()).collect();
        order.sort_by(|&x, &y| fit[x].total_cmp(&fit[y]).then(ties[x].cmp(&ties[y])));
        let mut slots: Vec<Option<Organism>> = pool.into_iter().map(Some).collect();
        self.pop = order.iter().take(p.population).map(|&i| slots[i].take().expect("kept once")).collect();
        self.generation = gen_;
        if self.snap_at[1..].contains(&gen_) && self.snapshots.last().is_none_or(|s| s.0 != gen_) {
            self.snapshots.push(snapshot(p, gen_, &self.pop));
        }
        let b = &self.pop[reported(&self.pop, p, gen_)].eval;
        let (coverage, time) = self.best_seen;
        let improved = b.coverage > coverage || (b.coverage == coverage && b.flight_time < time);
        if improved {
            self.best_seen = (b.coverage, b.flight_time);
        }
        Ok(improved)
    }

    fn report(&mut self, observers: &mut Observers) -> Result<(), Self::Error> {
        let (p, g) = (self.p, self.generation);
        let now = stats(g, &self.pop, p);
        if observers.wants(g) {
            let best = &self.pop[reported(&self.pop, p, g)];
            observers.generation(&(self.to_record)(&now, best, self.evaluations))?;
        }
        self.history.push(now);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pressure_limits() {
        let f = [-2.0, -1.0, 0.0, 1.0];
        let uniform = pressure_weights(&f, 0.0);
        assert!(uniform.iter().all(|&p| (p - 0.25).abs() < 1e-12));
        let prop = pressure_weights(&f, 0.5);
        assert!((prop[0] - 1.0 / 2.0).abs() < 1e-12 && prop[3] == 0.0);
        let greedy = pressure_weights(&f, 1.0);
        assert_eq!(greedy, vec![1.0, 0.0, 0.0, 0.0]);
    }
}
