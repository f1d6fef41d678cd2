//! The waypoint planner's entry in the registry of planners: `planner = "waypoint"` and its
//! section `[waypoint]`.

use super::config::{WaypointConfig, WaypointSection};
use crate::config::ConfigError;
use crate::map::GridMap;
use crate::planner::entry::{FileSections, PlannerEntry, RegisteredPlanner, section_or_default};
use crate::planner::memory::MemoryEstimate;
use crate::planner::{Budget, Context};
use std::sync::Arc;

/// The waypoint-graph maximin planner of 000 (`[waypoint]`).
pub struct Waypoint;

impl PlannerEntry for Waypoint {
    fn name(&self) -> &'static str {
        "waypoint"
    }

    fn why_unread(&self, file: &dyn FileSections, key: &str) -> Option<String> {
        section_or_default::<WaypointSection>(file, "waypoint").why_unread(key)
    }

    fn validate(&self, file: &dyn FileSections, ctx: &Context) -> Result<Arc<dyn RegisteredPlanner>, ConfigError> {
        Ok(Arc::new(section_or_default::<WaypointSection>(file, "waypoint").validate(ctx)?))
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
