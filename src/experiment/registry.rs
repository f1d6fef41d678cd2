//! The one registry of planners: [`PLANNERS`], the list of covga's own planners (one line
//! each, every planner's entry in its own module; the thesis GA's in [`crate::seeded`], which
//! composes it with the planners whose plans seed it), and the planners registered from outside
//! ([`super::plugins::register`]), all the same [`PlannerEntry`]. An experiment file names one
//! (`planner = "…"`) as a [`PlannerKind`]; the entry says which keys it reads, whether it
//! ignores the seed, and validates its settings into the [`PlannerConfig`] a run runs, which
//! gives its memory estimate, evaluation rule and progress length. Nothing outside a planner's
//! folder matches on planners: a new planner is its folder and its line in [`PLANNERS`].

use super::file::ExperimentFile;
use crate::config::ConfigError;
use crate::planner::entry::{PlannerEntry, RegisteredPlanner};
use crate::planner::memory::MemoryEstimate;
use crate::planner::section::SectionSpec;
use crate::planner::{Budget, Context, Planner};
use std::any::Any;
use std::sync::Arc;

/// covga's own planners, in the order studies list them: the registration point, where a new
/// planner's entry adds its line. Planners from outside follow them in the order registered.
pub const PLANNERS: &[&dyn PlannerEntry] = &[
    &crate::seeded::Thesis,
    &crate::waypoint::entry::Waypoint,
    &crate::random_search::RandomSearchEntry,
    &crate::patterns::entry::Pattern(crate::patterns::planner::PatternKind::Boustrophedon),
    &crate::patterns::entry::Pattern(crate::patterns::planner::PatternKind::Spiral),
    &crate::cell_order::entry::CellOrder,
    &crate::layouts::entry::Layouts,
];

/// A planner as an experiment file names it (`planner = "…"`): an entry of the registry.
#[derive(Clone, Copy)]
pub struct PlannerKind(&'static dyn PlannerEntry);

impl Default for PlannerKind {
    /// The thesis GA, the first of [`PLANNERS`].
    fn default() -> Self {
        PlannerKind(PLANNERS[0])
    }
}

impl PartialEq for PlannerKind {
    /// The same planner (names are unique in the registry).
    fn eq(&self, other: &Self) -> bool {
        self.name() == other.name()
    }
}

impl Eq for PlannerKind {}

impl std::hash::Hash for PlannerKind {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.name().hash(state);
    }
}

impl std::fmt::Debug for PlannerKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "PlannerKind({:?})", self.name())
    }
}

impl serde::Serialize for PlannerKind {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> serde::Deserialize<'de> for PlannerKind {
    /// A registered planner's name; the message of an unknown name lists them all.
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        PlannerKind::named(&name).ok_or_else(|| {
            let known: Vec<String> = PlannerKind::all().iter().map(|k| format!("`{}`", k.name())).collect();
            serde::de::Error::custom(format!("unknown variant `{name}`, expected one of {}", known.join(", ")))
        })
    }
}

impl PlannerKind {
    /// covga's own planners ([`PLANNERS`]), in the order studies list them.
    pub fn built_in() -> impl Iterator<Item = PlannerKind> {
        PLANNERS.iter().map(|&e| PlannerKind(e))
    }

    /// Every planner: covga's own, then those registered from outside.
    pub fn all() -> Vec<PlannerKind> {
        let registered = super::plugins::registered().into_iter().map(PlannerKind);
        PlannerKind::built_in().chain(registered).collect()
    }

    /// The planner of this name, built in or registered.
    pub fn named(name: &str) -> Option<PlannerKind> {
        PlannerKind::built_in().find(|k| k.name() == name).or_else(|| super::plugins::find(name).map(PlannerKind))
    }

    /// The planner's entry.
    pub fn entry(self) -> &'static dyn PlannerEntry {
        self.0
    }

    /// The name as written in experiment files.
    pub fn name(self) -> &'static str {
        self.0.name()
    }

    /// Whether the planner ignores the seed whatever its settings.
    pub fn is_deterministic(self) -> bool {
        self.0.is_deterministic()
    }

    /// Whether the planner plans on the raster of [`crate::map::refine::planning_map`] (the
    /// patterns and the cell-order planner), which a narrow robot on coarse cells refines.
    pub fn plans_on_refined_raster(self) -> bool {
        self.0.plans_on_refined_raster()
    }

    /// Why this planner, with `file`'s settings, does not read `key` (a dotted key or a
    /// section of the planner sections), or `None` when it reads it: each planner's entry says
    /// which of those keys it reads, and the tables `[plugins.<name>]` belong to the planners
    /// registered under those names.
    pub fn why_unread(self, file: &ExperimentFile, key: &str) -> Option<String> {
        if key == "plugins" || key.starts_with("plugins.") {
            return super::plugins::why_unread(self.name(), self.0.plugin_keys(), key);
        }
        let name = key.split('.').next().unwrap_or(key);
        if let Some(section) = planner_section(name)
            && !self.0.sections_read(file).contains(&name)
        {
            return Some(format!("{} [{name}]; planner = \"{}\"", section.readers(), self.name()));
        }
        self.0.why_unread(file, key)
    }
}

/// Every planner section: those the registered planners declare
/// ([`PlannerEntry::sections`]), each once, in the order of the planners (covga's own, then
/// those registered from outside). The experiment file holds, checks and writes these.
pub fn planner_sections() -> Vec<&'static dyn SectionSpec> {
    let mut out: Vec<&'static dyn SectionSpec> = Vec::new();
    for kind in PlannerKind::all() {
        for &section in kind.entry().sections() {
            if !out.iter().any(|s| s.name() == section.name()) {
                out.push(section);
            }
        }
    }
    out
}

/// The planner section `[name]`, if a registered planner declares one.
pub fn planner_section(name: &str) -> Option<&'static dyn SectionSpec> {
    PlannerKind::all().into_iter().flat_map(|k| k.entry().sections().iter().copied()).find(|s| s.name() == name)
}

/// The validated planner of a run: the chosen planner's, or a fleet of it.
#[derive(Clone, Debug)]
pub struct PlannerConfig(Arc<dyn RegisteredPlanner>);

impl PlannerConfig {
    /// Validates the section of the file's planner, and its fleet when the file has
    /// `[[robots]]`.
    pub fn from_file(file: &ExperimentFile, ctx: &Context) -> Result<Self, ConfigError> {
        if file.robots.is_empty() {
            let single = file.planner.entry().validate(file, ctx)?;
            if file.fleet.is_some() {
                return Err(ctx.error("fleet", "is set but there are no [[robots]] to plan for"));
            }
            return Ok(PlannerConfig(single));
        }
        Ok(PlannerConfig(Arc::new(super::fleets::validate(file, ctx)?)))
    }

    /// The planner.
    pub fn planner(&self) -> &dyn Planner {
        self.0.as_ref()
    }

    /// The validated planner as its own type, when it is a `T`.
    pub fn downcast_ref<T: Any>(&self) -> Option<&T> {
        let any: &dyn Any = self.0.as_ref();
        any.downcast_ref::<T>()
    }

    /// How far past `budget.evaluations` the planner can go, in words (README, `summary.json`'s
    /// `evaluation_budget`): every search stops at the first iteration boundary at or past the
    /// limit, so it overshoots by less than one iteration's evaluations.
    pub fn evaluation_rule(&self) -> &'static str {
        self.0.evaluation_rule()
    }

    /// An upper estimate of the planner's own memory on `map` with `threads` evaluation
    /// threads (what every run holds besides is added by the experiment).
    pub fn memory_estimate(&self, map: &crate::map::GridMap, threads: usize) -> MemoryEstimate {
        self.0.memory_estimate(map, threads)
    }

    /// The length of a run's progress, in the units its generation records count: the
    /// waypoint planner's generations, the GAs' iterations, nothing for planners that plan in
    /// one step or report rounds of their own.
    pub fn progress_length(&self, budget: &Budget) -> u64 {
        self.0.progress_length(budget)
    }
}

impl ExperimentFile {
    /// Whether the plan ignores the seed: a deterministic planner, one whose settings do not
    /// search (the cell-order planner's exact solver and controls), or a fleet whose mode plans
    /// in one step (area division). Grid studies run such a configuration once.
    pub fn is_deterministic(&self) -> bool {
        if self.robots.is_empty() {
            self.planner.entry().ignores_seed(self)
        } else {
            self.fleet.as_ref().map_or(crate::fleet::config::FleetMode::default(), |f| f.mode).is_deterministic()
        }
    }
}
