//! What a run of the thesis GA needs besides the [`crate::planner::Planner`] interface. Its
//! entry in the registry of planners composes it with the planners whose plans seed it, one
//! layer up (`crate::seeded`).

use super::config::ThesisConfig;
use crate::map::GridMap;
use crate::planner::Budget;
use crate::planner::entry::RegisteredPlanner;
use crate::planner::memory::MemoryEstimate;

impl RegisteredPlanner for ThesisConfig {
    fn memory_estimate(&self, map: &GridMap, threads: usize) -> MemoryEstimate {
        ThesisConfig::memory_estimate(self, map, threads)
    }

    fn evaluation_rule(&self) -> &'static str {
        "stops after the first generation that reaches the limit: fewer than one generation's evaluations past it \
         (its children; every member again after an environment change); the initial population is evaluated whole"
    }

    fn progress_length(&self, budget: &Budget) -> u64 {
        u64::from(budget.iterations)
    }
}
