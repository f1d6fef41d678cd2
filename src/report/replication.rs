//! The report parts that replicate the source papers and the committed studies: 003's claims
//! and tables (`claims`, `thesis_report`, `seed_to_seed`), the ablation of the planners
//! (`ablation` and its figures), the fleets' report (`fleet_report`) and the plans against
//! reference plans (`plans`). The generic study analysis (sections, comparisons, measures,
//! statistics) stays in [`super`].

pub mod ablation;
pub mod ablation_figures;
mod ablation_plots;
pub mod claims;
pub mod fleet_report;
pub mod plans;
pub mod seed_to_seed;
pub mod thesis_report;
