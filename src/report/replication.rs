//! The report parts that replicate the source papers and the committed studies: 003's claims
//! and tables (`claims`, `thesis_report`, `seed_to_seed`), the ablation of the planners
//! (`ablation`: its runs and tests `comparing`, its 2 × 2 of search and objective
//! `search_objective` and its figures `ablation_plots`), the fleets' report (`fleet_report`) and the plans against reference plans
//! (`plans`). They stand on the generic rooms of the report ([`super::analysis`],
//! [`super::tables`], [`super::compare`], [`super::figures`]), and none of those reads from
//! here: only the report's summary (the `sections` of `summary.md`) and its entry points put them in.

pub mod ablation;
mod ablation_plots;
pub mod claims;
mod comparing;
pub mod fleet_report;
pub mod plans;
pub mod search_objective;
pub mod seed_to_seed;
pub mod thesis_report;
