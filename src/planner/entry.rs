//! How a planner registers: one [`PlannerEntry`] per planner, the same for the planners of
//! covga (each its own folder's entry, listed once in the experiment layer's registry) and for
//! planners added from outside it. An entry names the planner, says which keys of the
//! experiment file it reads, and validates its settings into a [`RegisteredPlanner`], which
//! runs and says what a run of it needs besides the [`Planner`] interface.
//!
//! The file reaches an entry as [`FileSections`]: its sections by name, each the typed section
//! the file holds, so that this layer depends on no experiment file and each planner reads its
//! own section types.

use super::memory::MemoryEstimate;
use super::section::SectionSpec;
use super::{Budget, Context, Planner};
use crate::config::ConfigError;
use crate::map::GridMap;
use std::any::Any;
use std::sync::Arc;

/// A planner validated for one run, as a run needs it besides the [`Planner`] interface.
/// Each method has a default that holds for a planner that iterates under the budget.
pub trait RegisteredPlanner: Planner + std::fmt::Debug + Any {
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
    /// How far past `budget.evaluations` it can go, in words (README, `summary.json`'s
    /// `evaluation_budget`).
    fn evaluation_rule(&self) -> &'static str {
        "as the planner's own documentation says (a planner added from outside covga)"
    }
    /// The length of a run's progress in the units of its generation records: the budget's
    /// iterations by default.
    fn progress_length(&self, budget: &Budget) -> u64 {
        u64::from(budget.iterations)
    }
}

/// The sections of an experiment file by name (`thesis`, `pattern`, `plugins`, …), each as the
/// typed section the file holds, or `None` where the file has no such section.
pub trait FileSections {
    /// The section `[name]`.
    fn section(&self, name: &str) -> Option<&dyn Any>;
}

/// The section `[name]` of `file` as a `T`, or `None` where the file has none.
///
/// # Panics
/// When the file holds the section as another type than `T`: a section has one type, so this
/// is a mistake in covga's code, not in a file.
pub fn section<'a, T: Any>(file: &'a dyn FileSections, name: &str) -> Option<&'a T> {
    file.section(name).map(|s| {
        s.downcast_ref::<T>()
            .unwrap_or_else(|| panic!("[{name}] is held as another type than {}", std::any::type_name::<T>()))
    })
}

/// The section `[name]` of `file`, or the section's defaults where the file has none.
pub fn section_or_default<T: Any + Clone + Default>(file: &dyn FileSections, name: &str) -> T {
    section::<T>(file, name).cloned().unwrap_or_default()
}

/// A planner as the registry holds it: its name, what it reads of an experiment file and how
/// its settings become a [`RegisteredPlanner`]. Only [`name`](Self::name),
/// [`why_unread`](Self::why_unread) and [`validate`](Self::validate) have no default.
pub trait PlannerEntry: Send + Sync {
    /// The name experiment files give `planner = "…"`.
    fn name(&self) -> &'static str;
    /// Whether it ignores the seed whatever its settings (a grid runs such a configuration
    /// once); false by default.
    fn is_deterministic(&self) -> bool {
        false
    }
    /// Whether, with `file`'s settings, it ignores the seed (a solver that does not search);
    /// [`is_deterministic`](Self::is_deterministic) by default.
    fn ignores_seed(&self, file: &dyn FileSections) -> bool {
        let _ = file;
        self.is_deterministic()
    }
    /// Whether it plans once, in full, and reads no `[budget]` key; false by default.
    fn plans_once(&self) -> bool {
        false
    }
    /// Whether it plans on the raster of [`crate::map::refine::planning_map`], which a narrow
    /// robot on coarse cells refines (checked before it validates); false by default.
    fn plans_on_refined_raster(&self) -> bool {
        false
    }
    /// Whether it reads `key` of `[output]` (the population's genomes, its diversity), which
    /// only some planners write; false by default.
    fn reads_output(&self, key: &str) -> bool {
        let _ = key;
        false
    }
    /// A section of its own that the written `config.toml` shows in full even where the file
    /// leaves it out (every setting of the planner that ran); none by default.
    fn written_in_full(&self) -> Option<&'static dyn SectionSpec> {
        None
    }
    /// The sections of its own it declares (`[cell_order]`, say): the experiment file holds,
    /// checks and writes them from these declarations alone. A section several planners read
    /// is declared by one of them (the thesis GA declares `[thesis]`, which random search
    /// reads too); none by default.
    fn sections(&self) -> &'static [&'static dyn SectionSpec] {
        &[]
    }
    /// The planner sections it reads with `file`'s settings: a key of any other is named as
    /// unread, with who reads it. Its own sections by default.
    fn sections_read(&self, file: &dyn FileSections) -> Vec<&'static str> {
        let _ = file;
        self.sections().iter().map(|s| s.name()).collect()
    }
    /// The keys of its table `[plugins.<name>]`, for a planner added from outside covga;
    /// `None` (by default) for a planner that has no such table.
    fn plugin_keys(&self) -> Option<&'static [&'static str]> {
        None
    }
    /// Why it does not read `key` (a dotted key of a planner section it reads, see
    /// [`sections_read`](Self::sections_read)) with `file`'s settings, or `None` when it reads
    /// it.
    fn why_unread(&self, file: &dyn FileSections, key: &str) -> Option<String>;
    /// Checks its settings in `file` against the run's scenario and budget, and makes the
    /// planner; a refusal names the key and the range.
    fn validate(&self, file: &dyn FileSections, ctx: &Context) -> Result<Arc<dyn RegisteredPlanner>, ConfigError>;
}
