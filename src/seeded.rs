//! The thesis GA composed with the planners whose plans seed it: its entry in the registry of
//! planners (`planner = "thesis"`, its section `[thesis]` with `[retrain]`) and the seed plans
//! of `thesis.seed_population`, made by the patterns (`[pattern]`) and the cell-order planner
//! (`[cell_order]`), and the weight of its camera objective, `waypoint.alpha_cov`. The thesis
//! GA names the plans it asks for ([`SeedPlanner`]); this layer above the planners makes them,
//! so that no planner imports another.

use crate::cell_order::config::{CELL_ORDER_SECTION, CellOrderSection};
use crate::config::ConfigError;
use crate::geom::Point;
use crate::patterns::planner::{PATTERN_SECTION, PatternKind, PatternSection};
use crate::patterns::{Pattern, plan};
use crate::planner::entry::{FileSections, PlannerEntry, RegisteredPlanner, section};
use crate::planner::section::SectionSpec;
use crate::planner::sections::OutputSection;
use crate::planner::{Context, Scenario};
use crate::thesis::config::{RETRAIN_SECTION, THESIS_SECTION, ThesisConfig};
use crate::thesis::seeding::{SeedPlan, SeedPlanner};
use crate::waypoint::config::WAYPOINT_SECTION;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The thesis GA of 003 (`[thesis]`), its seed plans made by the patterns and the cell-order
/// planner.
pub struct Thesis;

impl PlannerEntry for Thesis {
    fn name(&self) -> &'static str {
        "thesis"
    }

    fn reads_output(&self, key: &str) -> bool {
        key == "output.population_genomes" || key == "output.diversity_every"
    }

    fn sections(&self) -> &'static [&'static dyn SectionSpec] {
        static SECTIONS: &[&dyn SectionSpec] = &[&THESIS_SECTION, &RETRAIN_SECTION];
        SECTIONS
    }

    /// Its own sections, and those of the plans that seed it and of its camera objective.
    fn sections_read(&self, file: &dyn FileSections) -> Vec<&'static str> {
        THESIS_SECTION.get_or_default(file).sections_read()
    }

    fn why_unread(&self, file: &dyn FileSections, key: &str) -> Option<String> {
        THESIS_SECTION.get_or_default(file).why_unread(key)
    }

    fn validate(&self, file: &dyn FileSections, ctx: &Context) -> Result<Arc<dyn RegisteredPlanner>, ConfigError> {
        let seeds = Seeds {
            pattern: PATTERN_SECTION.get_or_default(file),
            cell_order: CELL_ORDER_SECTION.get_or_default(file),
        };
        let alpha_cov = WAYPOINT_SECTION.get_or_default(file).alpha_cov;
        let retrain = RETRAIN_SECTION.get(file);
        let thesis = THESIS_SECTION.get_or_default(file).validate(retrain, &seeds, alpha_cov, ctx)?;
        let population_genomes =
            section::<OutputSection>(file, "output").and_then(|o| o.population_genomes).unwrap_or(false);
        Ok(Arc::new(ThesisConfig { population_genomes, ..thesis }))
    }
}

/// The seed plans with the file's `[pattern]` and `[cell_order]` (the latter's defaults when
/// the file has none).
pub struct Seeds {
    /// `[pattern]`: the boustrophedon's and spiral's settings.
    pub pattern: PatternSection,
    /// `[cell_order]`: the cell-order plan's settings.
    pub cell_order: CellOrderSection,
}

impl SeedPlanner for Seeds {
    fn check(&self, plan: SeedPlan, ctx: &Context) -> Result<(), ConfigError> {
        match plan {
            SeedPlan::CellOrder => self.cell_order.validate(ctx).map(|_| ()),
            SeedPlan::Boustrophedon => self.pattern.validate(PatternKind::Boustrophedon, ctx).map(|_| ()),
            SeedPlan::Spiral => self.pattern.validate(PatternKind::Spiral, ctx).map(|_| ()),
        }
    }

    fn plan(&self, seed: SeedPlan, s: &Scenario, deadline: Option<(Instant, Duration)>) -> Result<Vec<Point>, String> {
        let pattern_plan = |kind| {
            plan(&s.map, kind, s.robot.width, s.start, s.end, self.pattern.complete)
                .map(|planned| planned.points)
                .map_err(|e| e.to_string())
        };
        match seed {
            SeedPlan::Boustrophedon => pattern_plan(Pattern::Boustrophedon { angle_deg: self.pattern.angle_deg }),
            SeedPlan::Spiral => pattern_plan(Pattern::Spiral),
            SeedPlan::CellOrder => crate::cell_order::local_optimum_plan_within(s, &self.cell_order, deadline),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::Footprint;
    use crate::coverage::fitness::{Projection, score};
    use crate::coverage::{CoverageGrid, SweepScratch};
    use crate::map::presets::preset;
    use crate::thesis::genome::{Action, decode};
    use crate::thesis::individual::{Base, EvalScratch, EvaluationMode, Individual};
    use crate::thesis::scenario::ThesisScenario;
    use crate::thesis::seeding::genome_of_path;

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
}
