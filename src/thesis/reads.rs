//! Which keys of the planner sections the thesis GA reads with its settings: its own section
//! less what its selection scheme does not use, `[retrain]`, and the sections of the plans
//! that seed its population and of its camera objective. The warnings about keys nothing
//! reads follow from this (`experiment::ignored`).

use super::config::{SelectionName, ThesisSection};
use super::seeding::SeedPlan;
use crate::planner::sections::within;

/// The `[thesis]` keys Elite's families and NSGA-II do not read (003 §3.4: Elite keeps the
/// `Pop_min` best of parents and children; architecture (a) draws `Select` pairs of parents).
const UNREAD_BY_ELITE_AND_NSGA2: [&str; 5] =
    ["thesis.init_individuals", "thesis.keep", "thesis.select", "thesis.tournament_size", "thesis.selection_pressure"];

/// The `[cell_order]` keys the `cell_order` seed plan reads (it runs no GA).
const READ_BY_CELL_ORDER_SEED: [&str; 3] =
    ["cell_order.directions", "cell_order.completion", "cell_order.completion_m_per_m2"];

/// Whether the thesis GA under `s` does not read `key` of `[thesis]`.
fn unread_by_selection(s: SelectionName, key: &str) -> bool {
    match s {
        SelectionName::Elite | SelectionName::Nsga2 => UNREAD_BY_ELITE_AND_NSGA2.contains(&key),
        SelectionName::Draw(name) => crate::ga::parents::unread_by_scheme(name.as_str(), key, super::config::param_key),
    }
}

impl ThesisSection {
    /// The planner sections the thesis GA with these settings reads: its own (`[thesis]`,
    /// `[retrain]`), `[pattern]` and `[cell_order]` where they make its seed plans,
    /// `[waypoint]` where its camera objective weighs by `alpha_cov`.
    pub fn sections_read(&self) -> Vec<&'static str> {
        let plans = self.seed_population.plans();
        let mut reads = vec!["thesis", "retrain"];
        if plans.iter().any(|p| matches!(p, SeedPlan::Boustrophedon | SeedPlan::Spiral)) {
            reads.push("pattern");
        }
        if plans.contains(&SeedPlan::CellOrder) {
            reads.push("cell_order");
        }
        if self.objective == super::objective::Objective::Camera {
            reads.push("waypoint");
        }
        reads
    }

    /// Why the thesis GA with these settings does not read `key`, a dotted key of a planner
    /// section it reads ([`Self::sections_read`]), or `None` when it reads it.
    pub fn why_unread(&self, key: &str) -> Option<String> {
        if within(key, "cell_order") && key != "cell_order" && !READ_BY_CELL_ORDER_SEED.iter().any(|k| within(key, k)) {
            return Some(format!(
                "the thesis GA's cell_order seed plan reads only {}",
                READ_BY_CELL_ORDER_SEED.join(", ")
            ));
        }
        if within(key, "waypoint") && key != "waypoint" && key != "waypoint.alpha_cov" {
            return Some("the thesis GA's camera objective reads only waypoint.alpha_cov of [waypoint]".into());
        }
        if key == "thesis.seed_share" && self.seed_population.is_empty() {
            return Some("thesis.seed_population names no pattern to seed with".into());
        }
        unread_by_selection(self.selection, key)
            .then(|| format!("thesis.selection = \"{}\" does not use it", self.selection.name()))
    }
}
