//! Boustrophedon and spiral behind the common [`Planner`] interface: deterministic, one
//! evaluation, each plan checked with the body rule before it is returned
//! ([`crate::planner::executable`]); pockets the robot cannot reach are reported.

use super::{Pattern, plan};
use crate::config::{ConfigError, check_range};
use crate::ga::observer::{GenerationRecord, Observer};
use crate::planner::memory::MemoryEstimate;
use crate::planner::section::{Placement, Section, SectionDecl};
use crate::planner::{Budget, Context, Planner, PlannerError, RunOutcome, Scenario, StopReason};
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// `[pattern]` as the patterns' entries declare it.
pub static PATTERN_SECTION: Section<PatternSection> = Section::new(
    SectionDecl {
        name: "pattern",
        readers: "only the boustrophedon and spiral patterns (and the thesis GA's seed plans) read",
        placement: Placement::BeforeBudget,
        always_held: true,
        type_name: "PatternSection",
        tables: &[],
        source: include_str!("planner.rs"),
    },
    Some(PatternSection::default),
);

/// `[pattern]`: the boustrophedon and spiral patterns (and the thesis GA's seed plans made from
/// them).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PatternSection {
    /// Lane direction of the boustrophedon in degrees from +x.
    pub angle_deg: f64,
    /// Visit the strips the lanes or rings leave uncovered afterwards (coverage completion).
    pub complete: bool,
}

impl Default for PatternSection {
    fn default() -> Self {
        Self { angle_deg: 0.0, complete: true }
    }
}

/// A validated pattern planner.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatternConfig {
    /// The pattern.
    pub pattern: Pattern,
    /// Coverage completion after the pattern.
    pub complete: bool,
}

impl PatternConfig {
    /// An upper estimate of a run's own memory on `map` beyond what every run holds: none
    /// worth counting (the lanes and the completion pass are small against the map's layers).
    pub fn memory_estimate(&self, map: &crate::map::GridMap) -> MemoryEstimate {
        MemoryEstimate {
            bytes: 0.0,
            key: "map.source",
            what: format!("a pattern on {} cells", (map.rows() * map.cols()) as f64),
        }
    }
}

/// Which pattern an experiment asks for (its `planner = "…"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PatternKind {
    /// Boustrophedon lanes at `pattern.angle_deg`.
    Boustrophedon,
    /// Contour-parallel inward rings.
    Spiral,
}

impl PatternSection {
    /// The pattern `kind` with this section checked.
    pub fn validate(&self, kind: PatternKind, ctx: &Context) -> Result<PatternConfig, ConfigError> {
        let a = self.angle_deg;
        check_range(ctx.origin, "pattern.angle_deg", a, -360.0, 360.0, "[-360, 360] degrees")?;
        super::check_lane_count(&ctx.scenario.map, ctx.scenario.robot.width)
            .map_err(|e| ctx.error("robot.width", e.to_string()))?;
        let pattern = match kind {
            PatternKind::Spiral => Pattern::Spiral,
            PatternKind::Boustrophedon => Pattern::Boustrophedon { angle_deg: a },
        };
        Ok(PatternConfig { pattern, complete: self.complete })
    }
}

impl Planner for PatternConfig {
    fn name(&self) -> &'static str {
        match self.pattern {
            Pattern::Boustrophedon { .. } => "boustrophedon",
            Pattern::Spiral => "spiral",
        }
    }

    fn run(
        &self,
        scenario: &Scenario,
        _seed: u64,
        _budget: &Budget,
        observers: &mut [&mut dyn Observer],
    ) -> Result<RunOutcome, PlannerError> {
        let started = Instant::now();
        let s = scenario;
        let planned = plan(&s.map, self.pattern, s.robot.width, s.start, s.end, self.complete)
            .map_err(|e| PlannerError::Input(format!("{} on map `{}`: {e}", self.name(), s.map.name())))?;
        let grid = crate::coverage::CoverageGrid::new(&s.map);
        let mut scratch = crate::coverage::SweepScratch::new(&grid);
        let metrics = s.robot.measure(&grid, &mut scratch, &planned.points);
        let sc = crate::coverage::fitness::score(&metrics, &s.robot, s.map.resolution(), s.projection);
        let record = GenerationRecord {
            iteration: 0,
            evaluations: 1,
            best_fitness: sc.fitness,
            mean_fitness: sc.fitness,
            best_coverage: sc.cov_final,
            best_coverage_reach: Some(crate::coverage::score::reach_coverage(&s.reach(), &scratch)),
            feasible: Some(1),
            diversity: None,
            robots: Vec::new(),
            extras: Vec::new(),
        };
        for o in observers.iter_mut() {
            o.generation(&record)?;
        }
        let mut details = crate::planner::details(serde_json::json!({
            "pockets": planned.pockets,
            "pocket_area_m2": planned.pocket_area_m2,
            "skipped_targets": planned.skipped_targets,
        }));
        if let Pattern::Boustrophedon { angle_deg } = self.pattern {
            details.insert("angle_deg".into(), angle_deg.into());
        }
        Ok(RunOutcome::new(vec![planned.points], StopReason::Completed)
            .with_objectives(vec![("cov_final", sc.cov_final), ("t_final", sc.t_final), ("fitness", sc.fitness)])
            .with_effort(1, 0)
            .with_wall_s(started.elapsed().as_secs_f64())
            .with_details(details)
            .with_history(crate::planner::History::Generations))
    }
}
