//! The waypoint planner's entry in the registry of planners: `planner = "waypoint"` and its
//! section `[waypoint]`.

use super::config::{WAYPOINT_SECTION, WaypointConfig};
use crate::config::ConfigError;
use crate::map::GridMap;
use crate::planner::entry::{FileSections, PlannerEntry, RegisteredPlanner};
use crate::planner::memory::MemoryEstimate;
use crate::planner::section::SectionSpec;
use crate::planner::{Budget, Context};
use std::sync::Arc;

/// The waypoint-graph maximin planner of 000 (`[waypoint]`).
pub struct Waypoint;

impl PlannerEntry for Waypoint {
    fn name(&self) -> &'static str {
        "waypoint"
    }

    fn sections(&self) -> &'static [&'static dyn SectionSpec] {
        static SECTIONS: &[&dyn SectionSpec] = &[&WAYPOINT_SECTION];
        SECTIONS
    }

    fn why_unread(&self, file: &dyn FileSections, key: &str) -> Option<String> {
        WAYPOINT_SECTION.get_or_default(file).why_unread(key)
    }

    fn validate(&self, file: &dyn FileSections, ctx: &Context) -> Result<Arc<dyn RegisteredPlanner>, ConfigError> {
        Ok(Arc::new(WAYPOINT_SECTION.get_or_default(file).validate(ctx)?))
    }
}

impl RegisteredPlanner for WaypointConfig {
    fn memory_estimate(&self, map: &GridMap, _threads: usize) -> MemoryEstimate {
        WaypointConfig::memory_estimate(self, map)
    }

    fn evaluation_rule(&self) -> &'static str {
        "stops after the first generation that reaches the limit: fewer than one generation's children past it; the \
         initial population is evaluated whole"
    }

    /// Its generations.
    fn progress_length(&self, _budget: &Budget) -> u64 {
        self.ga.generations as u64
    }
}
