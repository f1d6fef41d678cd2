//! Planners added from outside the crate. A program that links covga registers its planner
//! once, before it reads an experiment file ([`register`]); from then on `planner = "name"`
//! selects it and it runs, writes, warns and joins grids and reports as covga's own planners
//! do: it is a [`PlannerEntry`] of the one registry ([`super::registry`]), as they are.
//! [`PlannerPlugin`] is the entry of a planner whose settings are one table of its own,
//! `[plugins.<name>]`.

use crate::config::ConfigError;
use crate::planner::Context;
use crate::planner::entry::{FileSections, PlannerEntry, RegisteredPlanner, section};
use std::collections::BTreeMap;
use std::sync::{Arc, RwLock};

/// How a plugin checks its section (empty when the file has none) and makes its planner.
pub type ValidateSection = fn(&toml::Table, &Context) -> Result<Arc<dyn RegisteredPlanner>, ConfigError>;

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
    /// A section it declares is named as a key of the file's own, or as another type's section.
    #[error("the section `[{0}]` is a key of the experiment file or another planner's section of another type")]
    SectionTaken(&'static str),
}

impl PlannerEntry for PlannerPlugin {
    fn name(&self) -> &'static str {
        self.name
    }

    fn is_deterministic(&self) -> bool {
        self.deterministic
    }

    fn plugin_keys(&self) -> Option<&'static [&'static str]> {
        Some(self.keys)
    }

    /// It reads none of the planner sections (its own table is the registry's to answer for).
    fn why_unread(&self, _file: &dyn FileSections, _key: &str) -> Option<String> {
        None
    }

    /// Checks `[plugins.<name>]`, an empty table where the file has none.
    fn validate(&self, file: &dyn FileSections, ctx: &Context) -> Result<Arc<dyn RegisteredPlanner>, ConfigError> {
        let tables = section::<BTreeMap<String, toml::Table>>(file, "plugins");
        (self.validate)(tables.and_then(|t| t.get(self.name)).unwrap_or(&toml::Table::new()), ctx)
    }
}

static PLUGINS: RwLock<Vec<&'static dyn PlannerEntry>> = RwLock::new(Vec::new());

/// Registers `planner` for every experiment file read after it, in any thread: a
/// [`PlannerPlugin`], or any other [`PlannerEntry`].
pub fn register(planner: &'static dyn PlannerEntry) -> Result<(), PluginError> {
    let name = planner.name();
    if !well_formed(name) {
        return Err(PluginError::BadName(name));
    }
    for section in planner.sections() {
        let other = super::registry::planner_section(section.name()).filter(|o| o.type_id() != section.type_id());
        if !well_formed(section.name()) || super::file::is_shared_key(section.name()) || other.is_some() {
            return Err(PluginError::SectionTaken(section.name()));
        }
    }
    let built_in = super::registry::PLANNERS.iter().any(|p| p.name() == name);
    let mut plugins = PLUGINS.write().unwrap_or_else(std::sync::PoisonError::into_inner);
    if built_in || plugins.iter().any(|p| p.name() == name) {
        return Err(PluginError::Taken(name));
    }
    plugins.push(planner);
    Ok(())
}

/// Whether `name` can be written as `planner = "…"` and as a section's name: lower-case
/// letters, digits and `_`, starting with a letter.
fn well_formed(name: &str) -> bool {
    let mut chars = name.chars();
    chars.next().is_some_and(|c| c.is_ascii_lowercase())
        && chars.all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
}

/// The planner registered from outside under `name`.
pub fn find(name: &str) -> Option<&'static dyn PlannerEntry> {
    PLUGINS.read().unwrap_or_else(std::sync::PoisonError::into_inner).iter().copied().find(|p| p.name() == name)
}

/// Every planner registered from outside, in the order of registration.
pub fn registered() -> Vec<&'static dyn PlannerEntry> {
    PLUGINS.read().unwrap_or_else(std::sync::PoisonError::into_inner).clone()
}

/// Why the planner called `planner`, whose table `[plugins.<planner>]` has the keys `keys`
/// (`None` for a planner without one), does not read `key` of the `plugins` table, or `None`
/// when it reads it: each planner reads its own table's listed keys only.
pub fn why_unread(planner: &str, keys: Option<&[&str]>, key: &str) -> Option<String> {
    let rest = if key == "plugins" { "" } else { key.strip_prefix("plugins.")? };
    let (section, inner) = rest.split_once('.').map_or((rest, None), |(s, k)| (s, Some(k)));
    match keys {
        Some(keys) if planner == section || section.is_empty() => {
            let unread = inner.is_some_and(|k| !keys.contains(&k));
            unread.then(|| format!("planner = \"{planner}\" reads {} of [plugins.{planner}]", keys_text(keys)))
        }
        Some(_) | None if section.is_empty() => Some("no planner added from outside covga runs here".to_string()),
        Some(_) | None => Some(format!("only planner = \"{section}\" reads [plugins.{section}]")),
    }
}

/// A table's keys as the warnings list them.
fn keys_text(keys: &[&str]) -> String {
    if keys.is_empty() {
        return "no key".to_string();
    }
    keys.iter().map(|k| format!("`{k}`")).collect::<Vec<_>>().join(", ")
}

/// Refuses a `[plugins.<name>]` section whose planner is not registered, naming the section.
pub fn check_sections(
    sections: &std::collections::BTreeMap<String, toml::Table>,
    origin: &str,
) -> Result<(), ConfigError> {
    match sections.keys().find(|name| find(name).is_none_or(|p| p.plugin_keys().is_none())) {
        Some(name) => Err(ConfigError::new(
            origin,
            &format!("plugins.{name}"),
            format!(
                "names no registered planner (registered: {})",
                match registered().iter().map(|p| format!("`{}`", p.name())).collect::<Vec<_>>().join(", ") {
                    list if list.is_empty() => "none".to_string(),
                    list => list,
                }
            ),
        )),
        None => Ok(()),
    }
}
