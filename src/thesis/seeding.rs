//! Seeded populations (`thesis.seed_population`): a pattern's plan written as an action genome
//! (003 §3.2: each leg of the plan one action, its last leg the connector to E), so that a share
//! of the initial population starts from the pattern and the GA can only improve on it under
//! an elitist selection. 003 §5.3 names better starting points among its future work.

use super::genome::{Action, MIN_GENOME_LEN};
use crate::cell_order::config::CellOrderSection;
use crate::cell_order::local_optimum_plan_within;
use crate::geom::{Point, polar_deg};
use crate::patterns::planner::PatternSection;
use crate::patterns::{Pattern, plan};
use crate::planner::Scenario;
use serde::{Deserialize, Serialize};

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
    /// by local search ([`crate::cell_order::local_optimum_plan`]).
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

/// The settings the seed plans are made with: the file's `[pattern]` and `[cell_order]` (the
/// latter's defaults when the file has none).
#[derive(Clone, Copy, Debug)]
pub struct SeedSettings<'a> {
    /// `[pattern]`: the boustrophedon's and spiral's settings.
    pub pattern: &'a PatternSection,
    /// `[cell_order]`: the cell-order plan's settings.
    pub cell_order: &'a CellOrderSection,
}

/// The genome of each pattern's plan on the scenario, or why it cannot seed: the pattern
/// cannot be planned, its genome exceeds `max_genome_len` (named with the length needed), or
/// the cell-order plan's preparation runs past `deadline` (the run's wall clock and its limit).
pub fn seed_genomes(
    plans: SeedPlans,
    settings: SeedSettings,
    scenario: &Scenario,
    max_genome_len: usize,
    deadline: Option<(std::time::Instant, std::time::Duration)>,
) -> Result<Vec<(SeedPlan, Vec<Action>)>, String> {
    let s = scenario;
    let pattern = settings.pattern;
    plans
        .plans()
        .into_iter()
        .map(|p| {
            let in_map = |e: String| format!("the {} seed on map `{}`: {e}", p.name(), s.map.name());
            let pattern_plan = |kind| {
                plan(&s.map, kind, s.robot.width, s.start, s.end, pattern.complete)
                    .map(|planned| planned.points)
                    .map_err(|e| in_map(e.to_string()))
            };
            let points = match p {
                SeedPlan::Boustrophedon => pattern_plan(Pattern::Boustrophedon { angle_deg: pattern.angle_deg })?,
                SeedPlan::Spiral => pattern_plan(Pattern::Spiral)?,
                SeedPlan::CellOrder => local_optimum_plan_within(s, settings.cell_order, deadline).map_err(in_map)?,
            };
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
    use crate::coverage::Footprint;
    use crate::coverage::fitness::{Projection, score};
    use crate::coverage::{CoverageGrid, SweepScratch};
    use crate::map::presets::preset;
    use crate::thesis::genome::decode;
    use crate::thesis::individual::{Base, EvalScratch, EvaluationMode, Individual};
    use crate::thesis::scenario::ThesisScenario;

    /// The genome evaluated by the thesis GA on `scenario`, and the plan `points` scored by the
    /// common scorer with the scenario's robot.
    fn genome_and_plan_scores(
        genome: Vec<Action>,
        scenario: &ThesisScenario,
        points: &[Point],
    ) -> (Individual, crate::coverage::fitness::ThesisScore) {
        let mut ind = Individual::with_genome(genome);
        crate::thesis::individual::evaluate(
            &mut ind,
            scenario,
            Base::None,
            EvaluationMode::Full,
            &mut EvalScratch::default(),
        );
        let (map, robot) = (&scenario.map, scenario.robot);
        let grid = CoverageGrid::new(map);
        let metrics = robot.measure(&grid, &mut SweepScratch::new(&grid), points);
        (ind, score(&metrics, &robot, map.resolution(), Projection::F2))
    }

    #[test]
    fn a_pattern_genome_decodes_to_the_pattern_and_scores_as_it() {
        let map = preset("thesis-2").unwrap();
        let robot = Footprint { width: 0.6, speed: 0.2, rot_speed: 0.5 };
        let start = Point::new(1.3, 1.3);
        let planned = plan(&map, Pattern::Boustrophedon { angle_deg: 0.0 }, 0.6, start, start, true).unwrap();
        let mut genome = genome_of_path(&planned.points);
        assert_eq!(genome.len(), planned.points.len());
        let scenario = ThesisScenario::new(map.clone(), robot, start, start, Projection::F2);
        let mut points = Vec::new();
        decode(&mut genome, &scenario.frame, &mut points);
        assert_eq!(points.len(), planned.points.len());
        for (a, b) in points.iter().zip(&planned.points) {
            assert!((*a - *b).norm() < 1e-9, "{a:?} vs {b:?}");
        }
        let (ind, expected) = genome_and_plan_scores(genome, &scenario, &planned.points);
        assert_eq!(ind.sweep.obj_pix, 0);
        // Equal coverage; the sweep counts behind t_final may differ by a few cells: lanes lie
        // on cell centres, and the viewpoint lattice (2^-36 m, see `genome::snap`) can move a
        // lane's edge across a centre that lies exactly on it.
        assert!((ind.score.cov_final - expected.cov_final).abs() < 1e-12);
        assert!((ind.score.fitness / expected.fitness - 1.0).abs() < 1e-3, "{:?} vs {expected:?}", ind.score);
    }

    /// Under routed moves the seed genome must drive the pattern itself: the boustrophedon puts
    /// lane ends at the clearance limit and decoding moves them by rounding errors, which the
    /// router's standing test tolerates (`routes::STAND_SLACK_M`) instead of moving those
    /// viewpoints to cell centres centimetres away.
    #[test]
    fn a_pattern_genome_under_routed_moves_drives_the_pattern() {
        use crate::routing::routes::Router;
        use crate::thesis::scenario::Moves;
        for (name, start) in [("thesis-2", Point::new(1.3, 1.3)), ("office", Point::new(2.0, 2.0))] {
            let map = preset(name).unwrap();
            let robot = Footprint { width: 0.6, speed: 0.2, rot_speed: 0.0 };
            let planned = plan(&map, Pattern::Boustrophedon { angle_deg: 0.0 }, 0.6, start, start, true).unwrap();
            let mut genome = genome_of_path(&planned.points);
            let scenario =
                ThesisScenario::new(map.clone(), robot, start, start, Projection::F2).with_moves(Moves::Routed);
            let mut points = Vec::new();
            decode(&mut genome, &scenario.frame, &mut points);
            let router = Router::new(&map, 0.6, &[start, start]);
            let moved = points.iter().filter(|&&p| router.position(p) != p).count();
            assert_eq!(moved, 0, "{name}: {moved} of {} seed viewpoints moved", points.len());
            let (ind, expected) = genome_and_plan_scores(genome, &scenario, &planned.points);
            assert_eq!(ind.sweep.obj_pix, 0, "{name}");
            assert!(
                (ind.score.cov_final - expected.cov_final).abs() < 1e-12,
                "{name}: {:?} vs {expected:?}",
                ind.score
            );
        }
    }

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
