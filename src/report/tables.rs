//! The report's tables in markdown (and CSV beside them), each from what [`super::analysis`]
//! computed: the per-group tables of the summary (`groups`, on the common scorer's measures
//! `common`), the Kruskal–Wallis tests of the swept parameters (`effects`) and their
//! analysis of variance ([`anova`], 003 §5.3), any figure the runs record per group
//! (`--measure`, [`measures`]) and what a re-run changed (`--previous`, [`rescore`]).

pub mod anova;
pub(crate) mod common;
pub(crate) mod effects;
pub(crate) mod groups;
pub mod measures;
pub mod rescore;
