//! Statistics across runs, in one place for every report and for Python: descriptive
//! statistics, rank tests of independent samples ([`rank_sum`], [`kruskal`]) and of samples
//! paired by seed ([`paired`]), effect sizes with bootstrap intervals ([`effect`]), and the
//! correction of a family of tests ([`family`]), what a design can show before it is run and
//! its units of analysis ([`design`]), and the analysis of variance of a grid's factors
//! ([`anova`]). Each test says how its p-value was found
//! ([`Method`]); each effect names its direction.
//!
//! Two-sided tests throughout. Rank tests use mid-ranks for ties; their exact distributions
//! ([`exact`]) are conditional on the ties, so small samples with ties get exact p-values too.

pub mod anova;
pub mod describe;
pub mod design;
pub mod effect;
pub mod exact;
pub mod family;
pub mod kruskal;
pub mod margin;
pub mod paired;
pub mod rank_sum;

pub use describe::{mean_ci95, mean_min_max, median, quartiles, ranks, spearman};
pub use effect::{Contrast, Interval, a12_magnitude, bootstrap_ci, vargha_delaney_a12};
pub use family::{Family, holm};
pub use kruskal::{KruskalWallis, kruskal_wallis};
pub use paired::{SignedRank, sign_test, sign_test_paired, wilcoxon_signed_rank};
pub use rank_sum::{MannWhitney, RankSum, mann_whitney, mann_whitney_u};

/// How a test's p-value was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// From the exact null distribution (counted, see [`exact`]).
    Exact,
    /// From the normal approximation of the statistic.
    Normal,
}

impl Method {
    /// The word for tables: `exact` or `normal`.
    pub fn name(self) -> &'static str {
        match self {
            Method::Exact => "exact",
            Method::Normal => "normal",
        }
    }
}
