//! The patterns' entries in the registry of planners: `planner = "boustrophedon"` and
//! `planner = "spiral"`, both set by `[pattern]`.

use super::planner::{PATTERN_SECTION, PatternConfig, PatternKind};
use crate::config::ConfigError;
use crate::map::GridMap;
use crate::planner::entry::{FileSections, PlannerEntry, RegisteredPlanner};
use crate::planner::memory::MemoryEstimate;
use crate::planner::section::SectionSpec;
use crate::planner::{Budget, Context};
use std::sync::Arc;

/// A pattern planner (`[pattern]`): boustrophedon lanes or the inward spiral.
pub struct Pattern(pub PatternKind);

impl PlannerEntry for Pattern {
    fn name(&self) -> &'static str {
        match self.0 {
            PatternKind::Boustrophedon => "boustrophedon",
            PatternKind::Spiral => "spiral",
        }
    }
    fn is_deterministic(&self) -> bool {
        true
    }
    fn plans_once(&self) -> bool {
        true
    }
    fn plans_on_refined_raster(&self) -> bool {
        true
    }
    fn sections(&self) -> &'static [&'static dyn SectionSpec] {
        static SECTIONS: &[&dyn SectionSpec] = &[&PATTERN_SECTION];
        SECTIONS
    }
    /// Every key of `[pattern]` is read.
    fn why_unread(&self, _file: &dyn FileSections, _key: &str) -> Option<String> {
        None
    }
    fn validate(&self, file: &dyn FileSections, ctx: &Context) -> Result<Arc<dyn RegisteredPlanner>, ConfigError> {
        Ok(Arc::new(PATTERN_SECTION.get_or_default(file).validate(self.0, ctx)?))
    }
}

impl RegisteredPlanner for PatternConfig {
    fn memory_estimate(&self, map: &GridMap, _threads: usize) -> MemoryEstimate {
        PatternConfig::memory_estimate(self, map)
    }
    fn evaluation_rule(&self) -> &'static str {
        "plans once: one evaluation, whatever the limit"
    }
    fn progress_length(&self, budget: &Budget) -> u64 {
        u64::from(budget.iterations)
    }
}
