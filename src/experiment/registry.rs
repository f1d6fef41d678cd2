//! The one registry of planners: the names an experiment file may give `planner = "…"`, and
//! for each its validated parameters, whether it ignores the seed, which sections it reads
//! ([`super::ignored`]) and its memory estimate. Every `match` on [`PlannerKind`] and
//! [`PlannerConfig`] is exhaustive, so adding a planner to covga is: its own module, a variant
//! here (the compiler then lists every arm to fill) and, if it has parameters of its own, one
//! section field of the experiment file. A planner from outside the crate needs none of that:
//! it registers itself ([`super::plugins::register`]) and is the [`PlannerKind::Plugin`] variant.

use super::file::ExperimentFile;
use super::plugins::{PlannerPlugin, PluginPlanner};
use crate::cell_order::config::CellOrderConfig;
use crate::config::ConfigError;
use crate::fleet::config::Team;
use crate::fleet::planner::FleetPlanner;
use crate::patterns::planner::{PatternConfig, PatternKind};
use crate::planner::memory::MemoryEstimate;
use crate::planner::{Context, Planner};
use crate::random_search::RandomSearch;
use crate::thesis::config::ThesisConfig;
use crate::waypoint::config::WaypointConfig;
use std::sync::Arc;

/// Planner names as written in experiment files (`planner = "…"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum PlannerKind {
    /// The action-encoded GA of 003 (`[thesis]`).
    #[default]
    Thesis,
    /// The waypoint-graph maximin planner of 000 (`[waypoint]`).
    Waypoint,
    /// Boustrophedon lanes (`[pattern]`).
    Boustrophedon,
    /// Inward spiral (`[pattern]`).
    Spiral,
    /// Budget-matched random action genomes (the thesis's initial-population draw).
    RandomSearch,
    /// The GA over boustrophedon cells' order, direction and entry (`[cell_order]`).
    CellOrder,
    /// A planner added from outside the crate ([`super::plugins`], `[plugins.<name>]`).
    Plugin(&'static PlannerPlugin),
}

impl PlannerKind {
    /// Whether the planner plans on the raster of [`crate::map::refine::planning_map`] (the
    /// patterns and the cell-order planner), which a narrow robot on coarse cells refines.
    pub fn plans_on_refined_raster(self) -> bool {
        matches!(self, PlannerKind::Boustrophedon | PlannerKind::Spiral | PlannerKind::CellOrder)
    }
}

impl PartialEq for PlannerPlugin {
    /// The same registration (names are unique among them).
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

impl Eq for PlannerPlugin {}

impl std::hash::Hash for PlannerPlugin {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.name.hash(state);
    }
}

impl serde::Serialize for PlannerKind {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> serde::Deserialize<'de> for PlannerKind {
    /// A built-in planner's name or a registered plugin's; the message of an unknown name
    /// lists them all.
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        PlannerKind::named(&name).ok_or_else(|| {
            let known: Vec<String> = PlannerKind::all().iter().map(|k| format!("`{}`", k.name())).collect();
            serde::de::Error::custom(format!("unknown variant `{name}`, expected one of {}", known.join(", ")))
        })
    }
}

impl PlannerKind {
    /// Every planner, in the order studies list them.
    pub const ALL: [PlannerKind; 6] = [
        PlannerKind::Thesis,
        PlannerKind::Waypoint,
        PlannerKind::RandomSearch,
        PlannerKind::Boustrophedon,
        PlannerKind::Spiral,
        PlannerKind::CellOrder,
    ];

    /// The built-in planners, then the registered plugins.
    pub fn all() -> Vec<PlannerKind> {
        let plugins = super::plugins::registered().into_iter().map(PlannerKind::Plugin);
        PlannerKind::ALL.into_iter().chain(plugins).collect()
    }

    /// The planner of this name, built in or registered.
    pub fn named(name: &str) -> Option<PlannerKind> {
        PlannerKind::ALL
            .into_iter()
            .find(|k| k.name() == name)
            .or_else(|| super::plugins::find(name).map(PlannerKind::Plugin))
    }

    /// The name as written in experiment files.
    pub fn name(self) -> &'static str {
        match self {
            PlannerKind::Plugin(p) => p.name,
            PlannerKind::Thesis => "thesis",
            PlannerKind::Waypoint => "waypoint",
            PlannerKind::Boustrophedon => "boustrophedon",
            PlannerKind::Spiral => "spiral",
            PlannerKind::RandomSearch => "random_search",
            PlannerKind::CellOrder => "cell_order",
        }
    }

    /// Whether the planner ignores the seed (a grid runs such a configuration once).
    pub fn is_deterministic(self) -> bool {
        match self {
            PlannerKind::Boustrophedon | PlannerKind::Spiral => true,
            PlannerKind::Thesis | PlannerKind::Waypoint | PlannerKind::RandomSearch | PlannerKind::CellOrder => false,
            PlannerKind::Plugin(p) => p.deterministic,
        }
    }

    /// Why this planner, with `file`'s settings, does not read `key` (a dotted key or a
    /// section of the planner sections), or `None` when it reads it: each planner's module
    /// says which of those keys it reads.
    pub fn why_unread(self, file: &ExperimentFile, key: &str) -> Option<String> {
        let plugin = match self {
            PlannerKind::Plugin(p) => Some(p),
            _ => None,
        };
        if key == "plugins" || key.starts_with("plugins.") {
            return super::plugins::why_unread(plugin, key);
        }
        match self {
            PlannerKind::Plugin(p) => crate::planner::sections::unread_section(key, p.name, &[]),
            PlannerKind::Thesis => file.thesis.why_unread(key),
            PlannerKind::Waypoint => file.waypoint.why_unread(key),
            PlannerKind::Boustrophedon | PlannerKind::Spiral => crate::patterns::planner::why_unread(self.name(), key),
            PlannerKind::RandomSearch => crate::random_search::why_unread(key),
            PlannerKind::CellOrder => file.cell_order.clone().unwrap_or_default().why_unread(key),
        }
    }
}

/// The validated parameters of the chosen planner.
#[derive(Clone, Debug)]
pub enum PlannerConfig {
    /// The thesis GA.
    Thesis(ThesisConfig),
    /// The waypoint planner.
    Waypoint(Box<WaypointConfig>),
    /// Boustrophedon or spiral.
    Pattern(PatternConfig),
    /// Random search.
    RandomSearch(RandomSearch),
    /// The cell-order GA (or its exact solver).
    CellOrder(CellOrderConfig),
    /// A fleet of `[[robots]]`, planned as `[fleet] mode` says by the file's planner.
    Fleet(Box<FleetPlanner>),
    /// A planner added from outside the crate.
    Plugin(Arc<dyn PluginPlanner>),
}

impl PlannerConfig {
    /// Validates the section of the file's planner, and its fleet when the file has
    /// `[[robots]]`.
    pub fn from_file(file: &ExperimentFile, ctx: &Context) -> Result<Self, ConfigError> {
        let single = match file.planner {
            PlannerKind::Thesis => {
                let default_cell_order = crate::cell_order::config::CellOrderSection::default();
                let settings = crate::thesis::seeding::SeedSettings {
                    pattern: &file.pattern,
                    cell_order: file.cell_order.as_ref().unwrap_or(&default_cell_order),
                };
                let thesis = file.thesis.validate(file.retrain.as_ref(), settings, file.waypoint.alpha_cov, ctx)?;
                let population_genomes = file.output.population_genomes.unwrap_or(false);
                PlannerConfig::Thesis(crate::thesis::config::ThesisConfig { population_genomes, ..thesis })
            }
            PlannerKind::Waypoint => {
                // A fleet's waypoint team plans one agent per robot: the section as validated,
                // not as written.
                let team = crate::fleet::config::waypoint_team(
                    &file.waypoint,
                    &file.robots,
                    file.fleet.as_ref(),
                    file.stations.start,
                    ctx.origin,
                )?;
                PlannerConfig::Waypoint(Box::new(team.validate(ctx)?))
            }
            PlannerKind::Boustrophedon => {
                PlannerConfig::Pattern(file.pattern.validate(PatternKind::Boustrophedon, ctx)?)
            }
            PlannerKind::Spiral => PlannerConfig::Pattern(file.pattern.validate(PatternKind::Spiral, ctx)?),
            PlannerKind::RandomSearch => PlannerConfig::RandomSearch(RandomSearch::validate(&file.thesis, ctx)?),
            PlannerKind::CellOrder => {
                PlannerConfig::CellOrder(file.cell_order.clone().unwrap_or_default().validate(ctx)?)
            }
            PlannerKind::Plugin(p) => {
                PlannerConfig::Plugin((p.validate)(file.plugins.get(p.name).unwrap_or(&toml::Table::new()), ctx)?)
            }
        };
        if file.robots.is_empty() {
            if file.fleet.is_some() {
                return Err(ctx.error("fleet", "is set but there are no [[robots]] to plan for"));
            }
            return Ok(single);
        }
        let section = file.fleet.clone().unwrap_or_default();
        let team = match single {
            PlannerConfig::Thesis(t) if !t.seeds.is_empty() => {
                return Err(ctx.error(
                    "thesis.seed_population",
                    "seeds the GA of one robot; a fleet's GAs start from random genomes (leave it out)",
                ));
            }
            PlannerConfig::Thesis(t) if !t.moves.is_straight() => {
                return Err(ctx.error(
                    "thesis.moves",
                    "= \"routed\" is built for the GA of one robot; a fleet's GAs drive straight moves (leave it out)",
                ));
            }
            PlannerConfig::Thesis(t) if t.objective.0 == crate::thesis::objective::Objective::Camera => {
                return Err(ctx.error(
                    "thesis.objective",
                    "= \"camera\" is built for the GA of one robot; a fleet's GAs optimise the footprint (leave it out)",
                ));
            }
            PlannerConfig::Thesis(t) => Team::Thesis(t.params),
            PlannerConfig::Waypoint(w) => Team::Waypoint(w),
            PlannerConfig::Pattern(_)
            | PlannerConfig::RandomSearch(_)
            | PlannerConfig::CellOrder(_)
            | PlannerConfig::Fleet(_)
            | PlannerConfig::Plugin(_) => {
                return Err(crate::fleet::config::wrong_planner(ctx.origin, file.planner.name(), section.mode));
            }
        };
        let fleet = section.validate(&file.robots, file.stations.start, file.retrain.is_some(), team, ctx)?;
        Ok(PlannerConfig::Fleet(Box::new(fleet)))
    }

    /// The planner.
    pub fn planner(&self) -> &dyn Planner {
        match self {
            PlannerConfig::Thesis(p) => p,
            PlannerConfig::Waypoint(p) => p.as_ref(),
            PlannerConfig::Pattern(p) => p,
            PlannerConfig::RandomSearch(p) => p,
            PlannerConfig::CellOrder(p) => p,
            PlannerConfig::Fleet(p) => p.as_ref(),
            PlannerConfig::Plugin(p) => p.as_ref(),
        }
    }

    /// How far past `budget.evaluations` the planner can go, in words (README, `summary.json`'s
    /// `evaluation_budget`): every search stops at the first iteration boundary at or past the
    /// limit, so it overshoots by less than one iteration's evaluations.
    pub fn evaluation_rule(&self) -> &'static str {
        use crate::cell_order::config::Solver;
        use crate::fleet::config::FleetMode;
        match self {
            PlannerConfig::Thesis(_) => {
                "stops after the first generation that reaches the limit: fewer than one generation's evaluations \
                 past it (its children; every member again after an environment change); the initial population is \
                 evaluated whole"
            }
            PlannerConfig::Waypoint(_) => {
                "stops after the first generation that reaches the limit: fewer than one generation's children past \
                 it; the initial population is evaluated whole"
            }
            PlannerConfig::Pattern(_) => "plans once: one evaluation, whatever the limit",
            PlannerConfig::RandomSearch(_) => {
                "stops after the first batch that reaches the limit: fewer than random_search.batch evaluations past it"
            }
            PlannerConfig::CellOrder(c) => match c.solver {
                Solver::Ga | Solver::Ils => {
                    "stops after the first generation (or kick) that reaches the limit: fewer than one generation's \
                     evaluations past it, the initial population evaluated whole; the common scorer then reads each \
                     finalist once (with a coverage goal), counted on top"
                }
                Solver::Exact | Solver::Nearest | Solver::Boustrophedon => {
                    "searches nothing: the tours it builds and the plans the common scorer reads, whatever the limit"
                }
            },
            PlannerConfig::Fleet(f) => match f.method.mode() {
                FleetMode::Negotiate => {
                    "each robot's GA has an equal share of the limit and stops after the first generation that reaches \
                     its share: fewer than one generation per robot past it"
                }
                FleetMode::Central => {
                    "stops after the first generation that reaches the limit: fewer than one generation's evaluations \
                     past it"
                }
                FleetMode::Waypoint => {
                    "stops after the first generation that reaches the limit: fewer than one generation's children past it"
                }
                FleetMode::Divide => "plans once: no evaluation, whatever the limit",
            },
            PlannerConfig::Plugin(p) => p.evaluation_rule(),
        }
    }

    /// An upper estimate of the planner's own memory on `map` with `threads` evaluation
    /// threads (what every run holds besides is added by the experiment).
    pub fn memory_estimate(&self, map: &crate::map::GridMap, threads: usize) -> MemoryEstimate {
        match self {
            PlannerConfig::Thesis(t) => t.memory_estimate(map, threads),
            PlannerConfig::Waypoint(w) => w.memory_estimate(map),
            PlannerConfig::Pattern(p) => p.memory_estimate(map),
            PlannerConfig::RandomSearch(r) => r.memory_estimate(map),
            PlannerConfig::CellOrder(c) => c.memory_estimate(map, threads),
            PlannerConfig::Fleet(f) => f.memory_estimate(map, threads),
            PlannerConfig::Plugin(p) => p.memory_estimate(map, threads),
        }
    }

    /// The length of a run's progress, in the units its generation records count: the
    /// waypoint planner's generations, the GAs' iterations, nothing for planners that plan in
    /// one step or report rounds of their own.
    pub fn progress_length(&self, budget: &crate::planner::Budget) -> u64 {
        use crate::fleet::config::FleetMethod;
        match self {
            PlannerConfig::Thesis(_)
            | PlannerConfig::RandomSearch(_)
            | PlannerConfig::Pattern(_)
            | PlannerConfig::CellOrder(_) => u64::from(budget.iterations),
            PlannerConfig::Waypoint(w) => w.ga.generations as u64,
            PlannerConfig::Fleet(f) => match &f.method {
                FleetMethod::Central(_) => u64::from(budget.iterations),
                FleetMethod::Waypoint(w) => w.ga.generations as u64,
                FleetMethod::Negotiate(..) | FleetMethod::Divide { .. } => 0,
            },
            PlannerConfig::Plugin(p) => p.progress_length(budget),
        }
    }
}

impl ExperimentFile {
    /// Whether the plan ignores the seed: a deterministic planner, a cell-order solver that does
    /// not search (the exact solver and the controls), or a fleet whose mode plans in one step
    /// (area division). Grid studies run such a configuration once.
    pub fn is_deterministic(&self) -> bool {
        if self.robots.is_empty() {
            let settled_cell_order = self.planner == PlannerKind::CellOrder
                && self.cell_order.as_ref().is_some_and(|c| !c.solver.searches());
            self.planner.is_deterministic() || settled_cell_order
        } else {
            self.fleet.as_ref().map_or(crate::fleet::config::FleetMode::default(), |f| f.mode).is_deterministic()
        }
    }
}
