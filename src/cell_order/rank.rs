//! How well a tour's cost ranks plans as the common scorer does: plans sampled around the
//! tours the search meets (the nearest-neighbour tour and its local optimum, mutated a little
//! or a lot, now and then shuffled), each costed by the tour problem and driven into a path
//! whose coverage curve gives the scorer's time to the coverage goal. Spearman's ρ between the
//! two says whether ranking by the tour's cost is ranking by the time the study reports.

use super::config::Completion;
use super::local::improve;
use super::operators::{choice_mutation, mutate_order};
use super::search::nearest_neighbour;
use super::{Prepared, search};
use crate::coverage::CoverageGrid;
use crate::coverage::curve::CoverageCurve;
use crate::ga::rng::{Purpose, stream};
use crate::planner::Scenario;
use rand::seq::SliceRandom;

/// Sampled plans, each with its cost as the search ranks it, with the cost the search used
/// before coverage goals (the whole tour's time with the completion charge), and with the
/// common scorer's time to the goal.
#[derive(Clone, Debug, PartialEq)]
pub struct RankSample {
    /// [`super::tour::Instance::cost`] with the goal.
    pub surrogate: Vec<f64>,
    /// [`super::tour::Instance::time`]: the whole tour with its completion charge.
    pub tour_time: Vec<f64>,
    /// The common scorer's time to the goal on the plan's coverage curve
    /// ([`super::time_to_goal`]).
    pub scorer: Vec<f64>,
}

impl RankSample {
    /// Spearman's ρ of the surrogate and the scorer's time (`None`: a constant sample).
    pub fn rho(&self) -> Option<f64> {
        crate::stats::describe::spearman(&self.surrogate, &self.scorer)
    }

    /// Spearman's ρ of the whole tour's time and the scorer's time.
    pub fn rho_tour_time(&self) -> Option<f64> {
        crate::stats::describe::spearman(&self.tour_time, &self.scorer)
    }
}

/// `count` plans of `prepared` sampled from `seed`, driven with `completion` and measured
/// against the coverage `goal`.
pub fn sample(
    prepared: &Prepared,
    scenario: &Scenario,
    completion: Completion,
    goal: f64,
    count: usize,
    seed: u64,
) -> RankSample {
    let inst = &prepared.instance;
    let s = scenario;
    let grid = CoverageGrid::new(&s.map);
    let mut rng = stream(seed, Purpose::Main, &[]);
    let nearest = nearest_neighbour(inst);
    let mut optimum = nearest.clone();
    improve(inst, &mut optimum, search::ROUNDS);
    let counts: Vec<usize> = (0..inst.cells()).map(|k| inst.choices(k)).collect();
    let mut out = RankSample { surrogate: Vec::new(), tour_time: Vec::new(), scorer: Vec::new() };
    for i in 0..count {
        let mut tour = if i % 2 == 0 { optimum.clone() } else { nearest.clone() };
        for _ in 0..i % 7 {
            mutate_order(&mut tour.order, &mut rng);
        }
        choice_mutation(&mut tour.choice, &counts, 0.05 * (i % 5) as f64, &mut rng);
        if i % 11 == 10 {
            tour.order.shuffle(&mut rng);
        }
        let (path, _) = prepared.path(&tour, &s.robot, (s.start, s.end), completion);
        let curve = CoverageCurve::of_plan(&grid, &prepared.reach, std::slice::from_ref(&path), &[s.robot]);
        out.scorer.push(super::time_to_goal(&curve, goal));
        out.surrogate.push(inst.cost(&tour, Some(goal)));
        out.tour_time.push(inst.time(&tour));
    }
    out
}
