//! Seeded populations (`thesis.seed_population`): a pattern's plan written as an action genome
//! (003 §3.2: each leg of the plan one action, its last leg the connector to E), so that a share
//! of the initial population starts from the pattern and the GA can only improve on it under
//! an elitist selection. 003 §5.3 names better starting points among its future work.

use super::genome::{Action, MIN_GENOME_LEN};
use crate::config::ConfigError;
use crate::geom::{Point, polar_deg};
use crate::planner::{Context, Scenario};
use serde::{Deserialize, Serialize};
use std::time::{Duration, Instant};

/// A pattern whose plan can seed the initial population.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SeedPlan {
    /// The boustrophedon of the file's `[pattern]` (its `angle_deg` and `complete`).
    Boustrophedon,
    /// The spiral (with the file's `pattern.complete`).
    Spiral,
    /// The cell-order plan of the file's `[cell_order]` (its `directions`, `completion` and
    /// `completion_m_per_m2`) without its GA: the nearest-neighbour tour of the cells improved
    /// by local search (the cell-order planner's `local_optimum_plan`).
    CellOrder,
}

impl SeedPlan {
    /// The name as written in experiment files.
    pub fn name(self) -> &'static str {
        match self {
            SeedPlan::Boustrophedon => "boustrophedon",
            SeedPlan::Spiral => "spiral",
            SeedPlan::CellOrder => "cell_order",
        }
    }
}

/// `thesis.seed_population`: a set of patterns, written as a list of names.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(try_from = "Vec<SeedPlan>", into = "Vec<SeedPlan>")]
pub struct SeedPlans {
    boustrophedon: bool,
    spiral: bool,
    cell_order: bool,
}

impl TryFrom<Vec<SeedPlan>> for SeedPlans {
    type Error = String;
    fn try_from(list: Vec<SeedPlan>) -> Result<Self, String> {
        let mut set = SeedPlans::default();
        for p in list {
            let slot = match p {
                SeedPlan::Boustrophedon => &mut set.boustrophedon,
                SeedPlan::Spiral => &mut set.spiral,
                SeedPlan::CellOrder => &mut set.cell_order,
            };
            if *slot {
                return Err(format!("`{}` is listed twice", p.name()));
            }
            *slot = true;
        }
        Ok(set)
    }
}

impl From<SeedPlans> for Vec<SeedPlan> {
    fn from(set: SeedPlans) -> Self {
        set.plans()
    }
}

impl SeedPlans {
    /// Whether no pattern seeds the population (the default: 003's random start).
    pub fn is_empty(&self) -> bool {
        self.plans().is_empty()
    }
    /// The patterns, in a fixed order.
    pub fn plans(&self) -> Vec<SeedPlan> {
        [
            (self.boustrophedon, SeedPlan::Boustrophedon),
            (self.spiral, SeedPlan::Spiral),
            (self.cell_order, SeedPlan::CellOrder),
        ]
        .into_iter()
        .filter_map(|(on, p)| on.then_some(p))
        .collect()
    }
}

/// The action genome whose decoded path is `points` (from S, which `points[0]` must be, to E,
/// the last point): one live action per leg but the last, which the connector drives; a path
/// of one leg gets one zero action (thesis-ga §2.1's smallest genome).
pub fn genome_of_path(points: &[Point]) -> Vec<Action> {
    let legs = points.len().saturating_sub(1);
    let mut genome = Vec::with_capacity(legs.max(1) + MIN_GENOME_LEN - 1);
    let mut alpha = 0.0;
    for w in points[..legs.max(1)].windows(2) {
        let (a, d) = polar_deg(w[1] - w[0], alpha);
        genome.push(Action::new(a, d));
        alpha = a;
    }
    if genome.is_empty() {
        genome.push(Action::new(0.0, 0.0));
    }
    genome.push(Action::new(alpha, 0.0));
    genome.push(Action::new(0.0, 0.0));
    genome
}

/// What makes the seed plans: the planners whose plans seed the population, with the file's
/// settings of each. The thesis GA names the plans it asks for; a composition above the
/// planners makes them, so that the thesis GA imports no other planner.
pub trait SeedPlanner {
    /// Checks the settings `plan` is made with, under their own keys and ranges.
    fn check(&self, plan: SeedPlan, ctx: &Context) -> Result<(), ConfigError>;
    /// The plan `plan` on `scenario` (from its start to its end), or why it cannot be made;
    /// the cell-order plan's preparation is refused past `deadline` (the run's wall clock and
    /// its limit).
    fn plan(
        &self,
        plan: SeedPlan,
        scenario: &Scenario,
        deadline: Option<(Instant, Duration)>,
    ) -> Result<Vec<Point>, String>;
}

/// The genome of each pattern's plan on the scenario, or why it cannot seed: the pattern
/// cannot be planned, its genome exceeds `max_genome_len` (named with the length needed), or
/// the cell-order plan's preparation runs past `deadline` (the run's wall clock and its limit).
pub fn seed_genomes(
    plans: SeedPlans,
    planner: &dyn SeedPlanner,
    scenario: &Scenario,
    max_genome_len: usize,
    deadline: Option<(Instant, Duration)>,
) -> Result<Vec<(SeedPlan, Vec<Action>)>, String> {
    let s = scenario;
    plans
        .plans()
        .into_iter()
        .map(|p| {
            let in_map = |e: String| format!("the {} seed on map `{}`: {e}", p.name(), s.map.name());
            let points = planner.plan(p, s, deadline).map_err(in_map)?;
            let genome = genome_of_path(&points);
            if genome.len() > max_genome_len {
                return Err(format!(
                    "the {} seed is a genome of {} genes, more than thesis.max_genome_len = {max_genome_len}; \
                     raise it to at least {}",
                    p.name(),
                    genome.len(),
                    genome.len()
                ));
            }
            Ok((p, genome))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_paths_and_the_set_of_names() {
        let p = Point::new(1.0, 1.0);
        assert_eq!(genome_of_path(&[p, p]).len(), MIN_GENOME_LEN);
        assert_eq!(genome_of_path(&[p, Point::new(2.0, 1.0), p]).len(), 3);
        let set = SeedPlans::try_from(vec![SeedPlan::Spiral, SeedPlan::Boustrophedon]).unwrap();
        assert_eq!(set.plans(), vec![SeedPlan::Boustrophedon, SeedPlan::Spiral]);
        assert!(SeedPlans::try_from(vec![SeedPlan::Spiral, SeedPlan::Spiral]).unwrap_err().contains("twice"));
        assert!(SeedPlans::default().is_empty());
    }
}
