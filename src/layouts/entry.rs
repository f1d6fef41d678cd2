//! The lane control's entry in the registry of planners: `planner = "layouts"` and its section
//! `[layouts]`, written in full whether the file sets it or not.

use super::config::{LAYOUTS_SECTION, LayoutsConfig};
use crate::config::ConfigError;
use crate::map::GridMap;
use crate::planner::entry::{FileSections, PlannerEntry, RegisteredPlanner};
use crate::planner::memory::MemoryEstimate;
use crate::planner::section::SectionSpec;
use crate::planner::{Budget, Context};
use std::sync::Arc;

/// The idealised single-direction lane control (`[layouts]`, issue 102 item 1).
pub struct Layouts;

impl PlannerEntry for Layouts {
    fn name(&self) -> &'static str {
        "layouts"
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
        static SECTIONS: &[&dyn SectionSpec] = &[&LAYOUTS_SECTION];
        SECTIONS
    }

    fn written_in_full(&self) -> Option<&'static dyn SectionSpec> {
        Some(&LAYOUTS_SECTION)
    }

    /// It reads every key of `[layouts]`.
    fn why_unread(&self, _file: &dyn FileSections, _key: &str) -> Option<String> {
        None
    }

    fn validate(&self, file: &dyn FileSections, ctx: &Context) -> Result<Arc<dyn RegisteredPlanner>, ConfigError> {
        Ok(Arc::new(LAYOUTS_SECTION.get_or_default(file).validate(ctx)?))
    }
}

impl RegisteredPlanner for LayoutsConfig {
    fn memory_estimate(&self, map: &GridMap, threads: usize) -> MemoryEstimate {
        LayoutsConfig::memory_estimate(self, map, threads)
    }

    fn evaluation_rule(&self) -> &'static str {
        "searches nothing: the finalists it drives are read once each by the common scorer, whatever the limit"
    }

    fn progress_length(&self, budget: &Budget) -> u64 {
        u64::from(budget.iterations)
    }
}
