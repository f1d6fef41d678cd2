//! The thesis GA's entry in the registry of planners: `planner = "thesis"`, its section
//! `[thesis]` with `[retrain]`, the sections of the plans that seed it and of its camera
//! objective, and what a run of it writes beyond every planner's files.

use super::config::{RetrainSection, ThesisConfig, ThesisSection};
use crate::config::ConfigError;
use crate::map::GridMap;
use crate::planner::entry::{FileSections, PlannerEntry, RegisteredPlanner, section, section_or_default};
use crate::planner::memory::MemoryEstimate;
use crate::planner::sections::OutputSection;
use crate::planner::{Budget, Context};
use std::sync::Arc;

/// The thesis GA of 003 (`[thesis]`).
pub struct Thesis;

impl PlannerEntry for Thesis {
    fn name(&self) -> &'static str {
        "thesis"
    }

    fn reads_output(&self, key: &str) -> bool {
        key == "output.population_genomes" || key == "output.diversity_every"
    }

    fn why_unread(&self, file: &dyn FileSections, key: &str) -> Option<String> {
        section_or_default::<ThesisSection>(file, "thesis").why_unread(key)
    }

    fn validate(&self, file: &dyn FileSections, ctx: &Context) -> Result<Arc<dyn RegisteredPlanner>, ConfigError> {
        let pattern = section_or_default(file, "pattern");
        let cell_order = section_or_default(file, "cell_order");
        let settings = super::seeding::SeedSettings { pattern: &pattern, cell_order: &cell_order };
        let alpha_cov = section_or_default::<crate::waypoint::config::WaypointSection>(file, "waypoint").alpha_cov;
        let retrain = section::<RetrainSection>(file, "retrain");
        let thesis = section_or_default::<ThesisSection>(file, "thesis").validate(retrain, settings, alpha_cov, ctx)?;
        let population_genomes =
            section::<OutputSection>(file, "output").and_then(|o| o.population_genomes).unwrap_or(false);
        Ok(Arc::new(ThesisConfig { population_genomes, ..thesis }))
    }
}

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
