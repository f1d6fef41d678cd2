//! Planners added from outside the crate. A program that links covga registers its planner
//! once, before it reads an experiment file ([`register`]); from then on `planner = "name"`
//! selects it, its settings are the table `[plugins.name]`, and it runs, writes, warns and
//! joins grids and reports as a built-in planner does. The built-in planners stay variants of
//! [`PlannerKind`](super::registry::PlannerKind), so that every `match` on them is exhaustive;
//! a plugin is the one variant that stands for all planners from outside.

use crate::config::ConfigError;
use crate::map::GridMap;
use crate::planner::memory::MemoryEstimate;
use crate::planner::{Budget, Context, Planner};
use std::sync::{Arc, RwLock};

/// A planner from outside the crate, as a run needs it besides the [`Planner`] interface.
/// Each method has a default that holds for a planner that iterates under the budget.
pub trait PluginPlanner: Planner + std::fmt::Debug {
    /// An upper estimate of the planner's own memory on `map` with `threads` evaluation
    /// threads (nothing by default).
    fn memory_estimate(&self, map: &GridMap, threads: usize) -> MemoryEstimate {
        let _ = threads;
        MemoryEstimate {
            bytes: 0.0,
            key: "planner",
            what: format!("{} on {} cells", self.name(), map.rows() * map.cols()),
        }
    }
    /// How far past `budget.evaluations` it can go, in words (`summary.json`'s
    /// `evaluation_budget`).
    fn evaluation_rule(&self) -> &'static str {
        "as the planner's own documentation says (a planner added from outside covga)"
    }
    /// The length of a run's progress in the units of its generation records.
    fn progress_length(&self, budget: &Budget) -> u64 {
        u64::from(budget.iterations)
    }
}

/// How a plugin checks its section (empty when the file has none) and makes its planner.
pub type ValidateSection = fn(&toml::Table, &Context) -> Result<Arc<dyn PluginPlanner>, ConfigError>;

/// What registers a planner: its name, whether it reads the seed, the keys of its section
/// and how the section becomes a planner.
#[derive(Debug)]
pub struct PlannerPlugin {
    /// The name experiment files give `planner = "…"`; its section is `[plugins.<name>]`.
    pub name: &'static str,
    /// Whether it ignores the seed (a grid then runs each configuration once).
    pub deterministic: bool,
    /// The keys of `[plugins.<name>]` it reads: any other key of the section is named in a
    /// warning and refused as a grid axis.
    pub keys: &'static [&'static str],
    /// Checks its section (empty when the file has none) against the run's scenario and
    /// budget, and makes the planner; a refusal names `plugins.<name>.<key>` and the range.
    pub validate: ValidateSection,
}

/// Why a planner could not be registered.
#[derive(Debug, PartialEq, Eq, thiserror::Error)]
pub enum PluginError {
    /// The name is a built-in planner's or another plugin's.
    #[error("a planner named `{0}` is already registered")]
    Taken(&'static str),
    /// The name could not be written as `planner = "…"` and a section name.
    #[error("`{0}` is not a planner name: lower-case letters, digits and `_`, starting with a letter")]
    BadName(&'static str),
}

static PLUGINS: RwLock<Vec<&'static PlannerPlugin>> = RwLock::new(Vec::new());

/// Registers `plugin` for every experiment file read after it, in any thread.
pub fn register(plugin: &'static PlannerPlugin) -> Result<(), PluginError> {
    let name = plugin.name;
    let mut chars = name.chars();
    let well_formed = chars.next().is_some_and(|c| c.is_ascii_lowercase())
        && chars.all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_');
    if !well_formed {
        return Err(PluginError::BadName(name));
    }
    let built_in = super::registry::PlannerKind::ALL.iter().any(|k| k.name() == name);
    let mut plugins = PLUGINS.write().unwrap_or_else(std::sync::PoisonError::into_inner);
    if built_in || plugins.iter().any(|p| p.name == name) {
        return Err(PluginError::Taken(name));
    }
    plugins.push(plugin);
    Ok(())
}

/// The registered plugin named `name`.
pub fn find(name: &str) -> Option<&'static PlannerPlugin> {
    PLUGINS.read().unwrap_or_else(std::sync::PoisonError::into_inner).iter().copied().find(|p| p.name == name)
}

/// Every registered plugin, in the order of registration.
pub fn registered() -> Vec<&'static PlannerPlugin> {
    PLUGINS.read().unwrap_or_else(std::sync::PoisonError::into_inner).clone()
}

/// Why the planner `planner` (a plugin's name, or `None` for a built-in planner) does not read
/// `key` of the `plugins` table, or `None` when it reads it: each plugin reads its own
/// section's listed keys only.
pub fn why_unread(planner: Option<&'static PlannerPlugin>, key: &str) -> Option<String> {
    let rest = if key == "plugins" { "" } else { key.strip_prefix("plugins.")? };
    let (section, inner) = rest.split_once('.').map_or((rest, None), |(s, k)| (s, Some(k)));
    match planner {
        Some(p) if p.name == section || section.is_empty() => {
            let unread = inner.is_some_and(|k| !p.keys.contains(&k));
            unread.then(|| format!("planner = \"{}\" reads {} of [plugins.{}]", p.name, keys_text(p), p.name))
        }
        Some(_) | None if section.is_empty() => Some("no planner added from outside covga runs here".to_string()),
        Some(_) | None => Some(format!("only planner = \"{section}\" reads [plugins.{section}]")),
    }
}

/// A plugin's keys as the warnings list them.
fn keys_text(p: &PlannerPlugin) -> String {
    if p.keys.is_empty() {
        return "no key".to_string();
    }
    p.keys.iter().map(|k| format!("`{k}`")).collect::<Vec<_>>().join(", ")
}

/// Refuses a `[plugins.<name>]` section whose planner is not registered, naming the section.
pub fn check_sections(
    sections: &std::collections::BTreeMap<String, toml::Table>,
    origin: &str,
) -> Result<(), ConfigError> {
    match sections.keys().find(|name| find(name).is_none()) {
        Some(name) => Err(ConfigError::new(
            origin,
            &format!("plugins.{name}"),
            format!(
                "names no registered planner (registered: {})",
                match registered().iter().map(|p| format!("`{}`", p.name)).collect::<Vec<_>>().join(", ") {
                    list if list.is_empty() => "none".to_string(),
                    list => list,
                }
            ),
        )),
        None => Ok(()),
    }
}
