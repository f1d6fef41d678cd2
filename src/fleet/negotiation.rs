//! Decentralised negotiation between the robots of a fleet (beyond 003, built on its retrain,
//! §3.5.3): every robot runs its own thesis GA; every `k` iterations the robots exchange their
//! current best plans, and each marks the cells the others' plans sweep as already covered
//! (the retrain's pre-marks), re-evaluates its population and continues. The rounds end when
//! no robot's plan changes by more than a tolerance, or with the iteration budget.
//!
//! Determinism: each robot's GA has its own seed, derived from the run's seed and the robot's
//! index; the robots step in parallel but exchange only between rounds, in robot order, so the
//! outcome does not depend on the number of threads.

use super::Fleet;
use crate::coverage::fitness::Projection;
use crate::coverage::{CoverageGrid, SweepScratch};
use crate::ga::observer::Observers;
use crate::ga::rng::{Purpose, stream};
use crate::geom::Point;
use crate::map::GridMap;
use crate::planner::executor::{Interrupt, Search, SetupCutoff, StopRule, StopRules, execute};
use crate::planner::{Budget, StopReason};
use crate::thesis::params::ThesisParams;
use crate::thesis::run::{GaState, ThesisGa, best_index};
use crate::thesis::scenario::ThesisScenario;
use rand::RngCore;
use rayon::prelude::*;
use std::time::Instant;

/// How the robots negotiate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NegotiationParams {
    /// Iterations of every robot's GA per round (`k`).
    pub round_iterations: u32,
    /// Iterations of every robot's GA in all (the budget).
    pub iterations: u32,
    /// Evaluations of all robots together (the budget), shared equally: robot `k` of `n` may
    /// spend `E / n`, plus one when `k < E mod n`.
    pub evaluations: Option<u64>,
    /// A plan "changes" when the share of its swept cells that differ from the previous
    /// round's (symmetric difference over union) exceeds this.
    pub tolerance: f64,
}

/// One robot at the end of one round.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct RoundRecord {
    /// Round, from 1.
    pub round: u32,
    /// Robot name.
    pub robot: String,
    /// Iterations of its GA so far.
    pub iteration: u32,
    /// Its evaluations so far.
    pub evaluations: u64,
    /// `f_obstacle` of its best plan against the others' plans of the previous round.
    pub best_fitness: f64,
    /// `cov_final` of that plan (cells the others did not cover, over the cells left to it).
    pub cov_final: f64,
    /// `t_final` of that plan.
    pub t_final: f64,
    /// Share of its best plan's swept cells that changed since the previous round (1 in the
    /// first round).
    pub change: f64,
}

/// The result of a negotiation.
#[derive(Clone, Debug, PartialEq)]
pub struct NegotiationOutcome {
    /// One path per robot (its final best plan), in the fleet's order.
    pub paths: Vec<Vec<Point>>,
    /// Rounds held.
    pub rounds: u32,
    /// Whether the plans settled within the tolerance before the budget ended.
    pub converged: bool,
    /// Evaluations of all robots, re-evaluations after each exchange included.
    pub evaluations: u64,
    /// Per round and robot.
    pub history: Vec<RoundRecord>,
    /// Why it ended.
    pub stop: StopReason,
}

/// The seed of robot `k`'s GA under the run's `seed`: the run's own seed for the first robot
/// (so that a fleet of one is the single-robot run, bit for bit), a derived one for the others.
pub fn robot_seed(seed: u64, k: usize) -> u64 {
    if k == 0 { seed } else { stream(seed, Purpose::Robot, &[k as u64]).next_u64() }
}

/// Cells a plan sweeps with a robot of `width` (one flag per cell).
fn swept(grid: &CoverageGrid, scratch: &mut SweepScratch, points: &[Point], width: f64) -> Vec<bool> {
    scratch.sweep(grid, points, width);
    let mut cells = vec![false; grid.len()];
    for (i, _) in scratch.visit_counts() {
        cells[i as usize] = true;
    }
    cells
}

/// `|a Δ b| / |a ∪ b|` (0 for two empty sets).
pub fn plan_change(a: &[bool], b: &[bool]) -> f64 {
    let (mut diff, mut union) = (0usize, 0usize);
    for (&x, &y) in a.iter().zip(b) {
        diff += usize::from(x != y);
        union += usize::from(x || y);
    }
    if union == 0 { 0.0 } else { diff as f64 / union as f64 }
}

/// Runs the negotiation of `fleet` on `map` with the thesis GA `params` (each robot with its
/// own width, speed and stations), one round per step of [`execute`]. Besides its own ends (the
/// plans settle; every robot's share of the iterations or evaluations is spent) it stops on
/// the interrupt, the wall clock and the stall limit of `limits` (rounds in a row in which the
/// fleet's plans together sweep no more cells than before); the interrupt and the wall clock
/// also end the robots' GAs inside a round, at their next generation. `None` when the interrupt
/// was raised while the robots' initial populations were made (there is no plan yet).
pub fn negotiate(
    map: &GridMap,
    fleet: &Fleet,
    params: &ThesisParams,
    projection: Projection,
    seed: u64,
    np: &NegotiationParams,
    limits: &Budget,
) -> Option<NegotiationOutcome> {
    let started = Instant::now();
    let robots = fleet.robots();
    let gas: Vec<ThesisGa> = robots
        .iter()
        .enumerate()
        .map(|(k, r)| ThesisGa {
            scenario: ThesisScenario::new(map.clone(), r.footprint, r.start, r.end, projection),
            params: *params,
            seed: robot_seed(seed, k),
            seeds: (Vec::new(), 0),
        })
        .collect();
    let cutoff = SetupCutoff::of_budget(limits, started);
    let raised = || cutoff.interrupt.as_ref().is_some_and(Interrupt::is_raised);
    let states: Vec<GaState> = gas.par_iter().map(|ga| ga.init_until(false, &raised)).collect::<Option<_>>()?;
    let grid = CoverageGrid::new(map);
    let scratch = SweepScratch::new(&grid);
    let cells = vec![vec![false; grid.len()]; robots.len()];
    let mut rounds = Rounds {
        fleet,
        np,
        cutoff: &cutoff,
        gas,
        states,
        grid,
        scratch,
        premarked: cells.clone(),
        previous: cells,
        history: Vec::new(),
        rounds: 0,
        converged: false,
        fleet_cells: 0,
    };
    // The robots' iterations and evaluations are shares of the budget that the rounds keep
    // to themselves ([`Search::finished`]); the run's other rules end the rounds here.
    let mut rules = StopRules::default();
    if let Some(flag) = &limits.interrupt {
        rules = rules | StopRule::Interrupted(flag.clone());
    }
    if let Some(stall) = limits.stall_iterations {
        rules = rules | StopRule::Stall(stall);
    }
    if let Some(limit) = limits.wall_clock {
        rules = rules | StopRule::WallClock { limit, since: started };
    }
    let finish = match execute(&mut rounds, &rules, &mut Observers::none()) {
        Ok(finish) => finish,
        Err(never) => match never {},
    };
    let Rounds { states, rounds, converged, history, .. } = rounds;
    let paths = states.iter().map(|s| s.population[best_index(&s.population)].points.clone()).collect();
    let evaluations = states.iter().map(|s| s.evaluations).sum();
    Some(NegotiationOutcome { paths, rounds, converged, evaluations, history, stop: finish.stop })
}

/// A negotiation between rounds, as [`execute`] drives it.
struct Rounds<'a> {
    fleet: &'a Fleet,
    np: &'a NegotiationParams,
    /// The interrupt and the wall clock, read by the robots' GAs inside a round.
    cutoff: &'a SetupCutoff,
    gas: Vec<ThesisGa>,
    states: Vec<GaState>,
    grid: CoverageGrid,
    scratch: SweepScratch,
    /// The cells each robot's best plan swept at the end of the last round.
    previous: Vec<Vec<bool>>,
    /// The cells each robot has pre-marked (what the others' plans swept).
    premarked: Vec<Vec<bool>>,
    history: Vec<RoundRecord>,
    rounds: u32,
    converged: bool,
    /// The most cells the fleet's plans together have swept at the end of a round.
    fleet_cells: usize,
}

impl Rounds<'_> {
    /// Evaluations robot `k` may spend: its share of the budget's.
    fn share(&self, k: usize) -> Option<u64> {
        let n = self.fleet.len() as u64;
        self.np.evaluations.map(|e| e / n + u64::from((k as u64) < e % n))
    }
    /// Whether robot `k`'s GA has iterations and evaluations left.
    fn budget_left(&self, k: usize) -> bool {
        let s = &self.states[k];
        s.iteration < self.np.iterations && self.share(k).is_none_or(|e| s.evaluations < e)
    }
}

impl Search for Rounds<'_> {
    type Error = std::convert::Infallible;

    fn progress(&self) -> (u32, u64) {
        (self.rounds, self.states.iter().map(|s| s.evaluations).sum())
    }

    fn finished(&self) -> Option<StopReason> {
        if self.converged {
            return Some(StopReason::Settled);
        }
        if (0..self.fleet.len()).any(|k| self.budget_left(k)) {
            return None;
        }
        let iterations = self.states.iter().map(|s| s.iteration).max().unwrap_or(0);
        Some(if self.np.evaluations.is_some() && iterations < self.np.iterations {
            StopReason::Evaluations
        } else {
            StopReason::Iterations
        })
    }

    /// One round: after the first, each robot pre-marks what the others' plans swept; then
    /// every robot's GA runs `round_iterations` generations (fewer where its share ends or the
    /// cutoff is reached), and the round's plans are compared with the last round's.
    fn step(&mut self, _: &mut Observers) -> Result<bool, Self::Error> {
        if self.rounds > 0 {
            exchange(&mut self.gas, &mut self.states, &self.previous, &mut self.premarked);
        }
        let (np, cutoff) = (self.np, self.cutoff);
        let share: Vec<Option<u64>> = (0..self.fleet.len()).map(|k| self.share(k)).collect();
        self.gas.par_iter().zip(self.states.par_iter_mut()).enumerate().for_each(|(k, (ga, state))| {
            let mut scratches = ga.new_scratches();
            for _ in 0..np.round_iterations.max(1) {
                let active = state.iteration < np.iterations
                    && share[k].is_none_or(|e| state.evaluations < e)
                    && cutoff.reached().is_none();
                if !active {
                    break;
                }
                let effective = ga.effective(state, state.iteration + 1, np.iterations);
                ga.step(state, effective, &mut scratches, false);
            }
        });
        self.rounds += 1;
        let now = self.record_round();
        let fleet_cells = (0..self.grid.len()).filter(|&i| now.iter().any(|cells| cells[i])).count();
        let improved = fleet_cells > self.fleet_cells;
        self.fleet_cells = self.fleet_cells.max(fleet_cells);
        self.previous = now;
        Ok(improved)
    }

    fn report(&mut self, _: &mut Observers) -> Result<(), Self::Error> {
        Ok(())
    }
}

impl Rounds<'_> {
    /// Records every robot's best plan at the end of a round, with how much it changed since
    /// the last; whether all settled within the tolerance (from the second round). The cells
    /// each plan sweeps.
    fn record_round(&mut self) -> Vec<Vec<bool>> {
        let robots = self.fleet.robots();
        let bests: Vec<usize> = self.states.iter().map(|s| best_index(&s.population)).collect();
        let now: Vec<Vec<bool>> = (0..robots.len())
            .map(|k| {
                let points = &self.states[k].population[bests[k]].points;
                swept(&self.grid, &mut self.scratch, points, robots[k].footprint.width)
            })
            .collect();
        let mut settled = self.rounds >= 2;
        for (k, r) in robots.iter().enumerate() {
            let best = &self.states[k].population[bests[k]];
            let change = if self.rounds == 1 { 1.0 } else { plan_change(&now[k], &self.previous[k]) };
            settled &= change <= self.np.tolerance;
            self.history.push(RoundRecord {
                round: self.rounds,
                robot: r.name.clone(),
                iteration: self.states[k].iteration,
                evaluations: self.states[k].evaluations,
                best_fitness: best.fitness(),
                cov_final: best.score.cov_final,
                t_final: best.score.t_final,
                change,
            });
        }
        self.converged = settled;
        now
    }
}

/// The exchange: every robot pre-marks what the others' plans (`swept`, one flag per cell
/// each) sweep, and re-evaluates its population only when that changed from `premarked`.
fn exchange(gas: &mut [ThesisGa], states: &mut [GaState], swept: &[Vec<bool>], premarked: &mut [Vec<bool>]) {
    let cells = swept.first().map_or(0, Vec::len);
    for (k, (ga, state)) in gas.iter_mut().zip(states.iter_mut()).enumerate() {
        let others: Vec<bool> =
            (0..cells).map(|i| swept.iter().enumerate().any(|(j, cells)| j != k && cells[i])).collect();
        if others != premarked[k] {
            ga.set_premarks(state, &others);
            premarked[k] = others;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fleet::config::FleetFile;
    use crate::fleet::metrics::FleetScorer;
    use crate::map::presets::preset;

    fn params(iterations_pop: usize) -> ThesisParams {
        let section = crate::thesis::config::ThesisSection { pop_min: iterations_pop, ..Default::default() };
        crate::thesis::config::validate_params(&section, "test").unwrap()
    }

    #[test]
    fn a_fleet_of_one_is_the_single_robot_run() {
        let map = preset("thesis-2").unwrap();
        let fleet = FleetFile::parse(
            "[[robots]]\nname = \"solo\"\nwidth = 0.6\nspeed = 0.2\nstart = [1.3, 1.3]\n",
            "f.toml",
            &map,
        )
        .unwrap();
        let p = params(20);
        let np = NegotiationParams { round_iterations: 30, iterations: 150, evaluations: None, tolerance: 0.0 };
        let negotiated = negotiate(&map, &fleet, &p, Projection::F1, 11, &np, &Budget::iterations(u32::MAX)).unwrap();
        let r = &fleet.robots()[0];
        let mut single = ThesisGa {
            scenario: ThesisScenario::new(map.clone(), r.footprint, r.start, r.end, Projection::F1),
            params: p,
            seed: 11,
            seeds: (Vec::new(), 0),
        };
        let budget = crate::planner::Budget::iterations(150);
        let alone = single.run(&budget, None, &mut []).unwrap();
        assert_eq!(negotiated.paths, vec![alone.best.points.clone()]);
        assert_eq!(negotiated.evaluations, alone.evaluations);
        assert_eq!(negotiated.rounds, 5);
    }

    #[test]
    fn plan_change_by_hand() {
        let a = [true, true, false, false];
        let b = [true, false, true, false];
        assert!((plan_change(&a, &b) - 2.0 / 3.0).abs() < 1e-12);
        assert_eq!(plan_change(&a, &a), 0.0);
        assert_eq!(plan_change(&[false], &[false]), 0.0);
    }

    /// A narrow slow robot and a wide fast one, in opposite corners.
    fn two_robots(map: &crate::map::GridMap) -> Fleet {
        FleetFile::parse(
            "[[robots]]\nname = \"a\"\nwidth = 0.4\nspeed = 0.2\nstart = [1.3, 1.3]\n\
             [[robots]]\nname = \"b\"\nwidth = 0.9\nspeed = 0.5\nstart = [9.55, 9.55]\n",
            "f.toml",
            map,
        )
        .unwrap()
    }

    #[test]
    fn negotiation_is_deterministic_on_any_thread_count_and_shares_the_map() {
        let map = preset("thesis-1").unwrap();
        let fleet = two_robots(&map);
        let np = NegotiationParams { round_iterations: 40, iterations: 200, evaluations: None, tolerance: 0.0 };
        let p = params(20);
        let run =
            |threads: usize| {
                rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(|| {
                    negotiate(&map, &fleet, &p, Projection::F1, 7, &np, &Budget::iterations(u32::MAX)).unwrap()
                })
            };
        let (one, two) = (run(1), run(2));
        assert_eq!(one, two, "same plans, history and evaluations with 1 and 2 threads");
        assert_eq!(one.rounds, 5);
        assert_eq!(one.history.len(), 10);
        assert!(one.history.iter().all(|r| r.iteration % 40 == 0));
        // Against the same robots planning alone (one round, no exchange), the negotiated plans
        // overlap less.
        let alone = negotiate(
            &map,
            &fleet,
            &p,
            Projection::F1,
            7,
            &NegotiationParams { round_iterations: 200, ..np },
            &Budget::iterations(u32::MAX),
        )
        .unwrap();
        assert_eq!(alone.rounds, 1);
        let scorer = FleetScorer::new(&map, &fleet);
        let (together, apart) = (scorer.score(&one.paths).unwrap(), scorer.score(&alone.paths).unwrap());
        assert!(
            together.overlap_fraction < apart.overlap_fraction,
            "negotiated {} vs alone {}",
            together.overlap_fraction,
            apart.overlap_fraction
        );
    }

    /// The run's stall limit counts rounds in which the fleet's plans together sweep no more
    /// cells; its wall clock ends the robots' GAs inside a round; the rounds' own ends
    /// (settled, budget spent) name the stop when they come first.
    #[test]
    fn a_negotiation_stops_on_the_runs_stall_limit_and_wall_clock() {
        let map = preset("thesis-2").unwrap();
        let fleet = two_robots(&map);
        // A tolerance below 0 (no file can set one): the plans never settle.
        let np = NegotiationParams { round_iterations: 1, iterations: 400, evaluations: None, tolerance: -1.0 };
        let p = params(20);
        let run = |limits: Budget| negotiate(&map, &fleet, &p, Projection::F1, 7, &np, &limits).unwrap();
        let free = run(Budget::iterations(u32::MAX));
        let stalled = run(Budget { stall_iterations: Some(2), ..Budget::iterations(u32::MAX) });
        assert_eq!(stalled.stop, StopReason::Stall);
        assert!(stalled.rounds < free.rounds, "{} rounds stalled, {} without a limit", stalled.rounds, free.rounds);
        assert_eq!(stalled.history[..], free.history[..stalled.history.len()], "the same rounds until the stall");
        let clocked = run(Budget { wall_clock: Some(std::time::Duration::ZERO), ..Budget::iterations(u32::MAX) });
        assert_eq!((clocked.stop, clocked.rounds), (StopReason::WallClock, 0));
        assert_eq!(clocked.paths.len(), 2, "the initial populations' best plans");
        assert_eq!((free.stop, free.rounds), (StopReason::Iterations, 400));
        let settling = NegotiationParams { tolerance: 0.0, ..np };
        let settled = negotiate(&map, &fleet, &p, Projection::F1, 7, &settling, &Budget::iterations(u32::MAX)).unwrap();
        assert_eq!(settled.stop, StopReason::Settled);
    }
}
