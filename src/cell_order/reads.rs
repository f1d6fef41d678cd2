//! Which keys of the planner sections the cell-order planner reads with its settings: its own
//! section, less the GA's keys under a solver that runs no GA and what the selection scheme does
//! not use. The warnings about keys nothing reads follow from this (`experiment::ignored`).

use super::config::{CellOrderSection, Solver};

/// The `[cell_order]` keys of its GA, which the other solvers do not read.
const GA_KEYS: [&str; 12] = [
    "cell_order.population",
    "cell_order.selection",
    "cell_order.tournament_size",
    "cell_order.selection_pressure",
    "cell_order.best_parents",
    "cell_order.keep",
    "cell_order.p_c",
    "cell_order.p_m",
    "cell_order.p_choice",
    "cell_order.memetic",
    "cell_order.seed_directions",
    "cell_order.classical_finalists",
];

/// The keys of [`GA_KEYS`] the iterated local search reads too: how a search starts and ends.
const SEARCH_KEYS: [&str; 2] = ["cell_order.seed_directions", "cell_order.classical_finalists"];

impl CellOrderSection {
    /// Why the cell-order planner with these settings does not read `key` (a dotted key or a
    /// section of the planner sections), or `None` when it reads it.
    pub fn why_unread(&self, key: &str) -> Option<String> {
        let ga_key = GA_KEYS.contains(&key);
        match self.solver {
            Solver::Exact => ga_key.then(|| {
                "cell_order.solver = \"exact\" runs no GA (Held–Karp reads only the directions and completion)".into()
            }),
            Solver::Ils => (ga_key && !SEARCH_KEYS.contains(&key)).then(|| {
                "cell_order.solver = \"ils\" runs no GA (iterated local search reads the directions, completion, \
                 coverage_goal, seed_directions and classical_finalists)"
                    .into()
            }),
            Solver::Nearest | Solver::Boustrophedon => ga_key.then(|| {
                format!(
                    "cell_order.solver = \"{}\" is a control with no search (it reads the directions, completion and coverage_goal)",
                    if self.solver == Solver::Nearest { "nearest" } else { "boustrophedon" }
                )
            }),
            Solver::Ga => crate::ga::parents::unread_by_scheme(self.selection.as_str(), key, |p| {
                Some(super::config::param_key(p))
            })
            .then(|| format!("cell_order.selection = \"{}\" does not use it", self.selection.as_str())),
        }
    }
}
