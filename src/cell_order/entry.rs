//! The cell-order planner's entry in the registry of planners: `planner = "cell_order"` and
//! its section `[cell_order]`, written in full whether the file sets it or not.

use super::config::{CELL_ORDER_SECTION, CellOrderConfig, Solver};
use crate::config::ConfigError;
use crate::map::GridMap;
use crate::planner::entry::{FileSections, PlannerEntry, RegisteredPlanner};
use crate::planner::memory::MemoryEstimate;
use crate::planner::section::SectionSpec;
use crate::planner::{Budget, Context};
use std::sync::Arc;

/// The GA over boustrophedon cells' order, direction and entry (`[cell_order]`).
pub struct CellOrder;

impl PlannerEntry for CellOrder {
    fn name(&self) -> &'static str {
        "cell_order"
    }

    fn sections(&self) -> &'static [&'static dyn SectionSpec] {
        static SECTIONS: &[&dyn SectionSpec] = &[&CELL_ORDER_SECTION];
        SECTIONS
    }

    /// A solver that does not search (the exact solver and the controls) ignores the seed.
    fn ignores_seed(&self, file: &dyn FileSections) -> bool {
        CELL_ORDER_SECTION.get(file).is_some_and(|c| !c.solver.searches())
    }

    fn plans_on_refined_raster(&self) -> bool {
        true
    }

    fn written_in_full(&self) -> Option<&'static dyn SectionSpec> {
        Some(&CELL_ORDER_SECTION)
    }

    fn why_unread(&self, file: &dyn FileSections, key: &str) -> Option<String> {
        CELL_ORDER_SECTION.get_or_default(file).why_unread(key)
    }

    fn validate(&self, file: &dyn FileSections, ctx: &Context) -> Result<Arc<dyn RegisteredPlanner>, ConfigError> {
        Ok(Arc::new(CELL_ORDER_SECTION.get_or_default(file).validate(ctx)?))
    }
}

impl RegisteredPlanner for CellOrderConfig {
    fn memory_estimate(&self, map: &GridMap, threads: usize) -> MemoryEstimate {
        CellOrderConfig::memory_estimate(self, map, threads)
    }

    fn evaluation_rule(&self) -> &'static str {
        match self.solver {
            Solver::Ga | Solver::Ils => {
                "stops after the first generation (or kick) that reaches the limit: fewer than one generation's \
                 evaluations past it, the initial population evaluated whole; the common scorer then reads each \
                 finalist once (with a coverage goal), counted on top"
            }
            Solver::Exact | Solver::Nearest | Solver::Boustrophedon => {
                "searches nothing: the tours it builds and the plans the common scorer reads, whatever the limit"
            }
        }
    }

    fn progress_length(&self, budget: &Budget) -> u64 {
        u64::from(budget.iterations)
    }
}
