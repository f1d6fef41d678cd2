//! Validated parameters of the thesis GA (003 Tables 4.1–4.3, thesis-ga §14). Built by the
//! experiment loader, which checks every range; the algorithm trusts them.

use super::crossover::{ChildMode, ShortGenomes};
use super::individual::{EvaluationMode, InitParams};
use crate::ga::control::AdaptiveConstants;
use crate::ga::parents::{DrawParams, ParentDraw};

/// Selection scheme and its parameters (003 §3.4, thesis-ga §10).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Selection {
    /// Elite families, architecture (b).
    Elite,
    /// Architecture (a): parents drawn by a scheme of the registry ([`crate::ga::parents`]):
    /// the tournament of size `TS`, the proportionate wheel, the rank wheel of pressure `SP`, or
    /// any scheme added there.
    Draw(ParentDraw),
    /// NSGA-II over 003's two objectives (`cov_final`, `t_final`) with the swept obstacle
    /// cells as the constraint: crowded binary tournaments for mating, `Pop_min` survivors of
    /// parents and offspring by front and crowding distance (003 §5.3's combined selection).
    Nsga2,
}

impl Selection {
    /// Architecture (a) drawing its parents by the registered scheme `name` with `params`.
    pub fn drawn(name: &str, params: DrawParams) -> Option<Self> {
        ParentDraw::named(name, params).map(Selection::Draw)
    }

    /// Architecture (a) with the tournament of size `TS` = `size` (003 §2.2.1.1).
    pub fn tournament(size: usize) -> Self {
        Self::registered("tournament", DrawParams { tournament_size: size, pressure: 0.0, best_parents: 0 })
    }

    /// Architecture (a) with the proportionate wheel (003 §2.2.1.2).
    pub fn prws() -> Self {
        Self::registered("prws", DrawParams { tournament_size: 0, pressure: 0.0, best_parents: 0 })
    }

    /// Architecture (a) with the rank wheel at pressure `SP` = `pressure` (003 §2.2.1.3).
    pub fn rrws(pressure: f64) -> Self {
        Self::registered("rrws", DrawParams { tournament_size: 0, pressure, best_parents: 0 })
    }

    fn registered(name: &str, params: DrawParams) -> Self {
        Self::drawn(name, params).expect("a scheme of the registry")
    }

    /// The parent draw of architecture (a), or `None` for Elite's families (architecture (b))
    /// and NSGA-II (its crowded tournaments).
    pub fn draw(&self) -> Option<ParentDraw> {
        match self {
            Selection::Elite | Selection::Nsga2 => None,
            Selection::Draw(d) => Some(*d),
        }
    }

    /// Short name used in files (`elite`, `nsga2`, or the drawing scheme's: `tournament`, …).
    pub fn name(&self) -> &'static str {
        match self {
            Selection::Elite => "elite",
            Selection::Draw(d) => d.scheme.name(),
            Selection::Nsga2 => "nsga2",
        }
    }
}

/// Parameter control (003 §2.2.3.1, §3.5.2; thesis-ga §12).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Control {
    /// Fixed parameters.
    None,
    /// Linear ramp of `SP` (RRWS) or `TS` (tournament) from `min` to `max` (eq. 3.25).
    Ramp {
        /// `SP_min` / `TS_min`.
        min: f64,
        /// `SP_max` / `TS_max`.
        max: f64,
    },
    /// `P_c` and `P_mA` from diversity and fitness (eqs. 2.3–2.6).
    Adaptive(AdaptiveConstants),
    /// `P_mA` and `P_c` on the Mühlenbein schedule (eqs. 2.1–2.2).
    Muhlenbein,
}

/// Default upper bound of `AC_dist` for fresh actions, in metres.
///
/// 003 Sec. 3.3.1 gives the range [0, 50] "metres" (R2 keeps it literally). On the
/// 11 m maps that clamps nearly every initial viewpoint onto the map edge. Measured over a
/// slice of Table 4.3 (192 configurations × 5 seeds, `results/init-dist/`), 3 m gives the
/// highest coverage and fitness in every selection scheme: f higher than with 50 m in 155 of
/// the 192 paired configurations (mean +0.066) and than with 10 m (= 50 cells) in 119
/// (+0.016). So 3 m is the default; `init_dist_max = 50.0` restores the literal reading.
pub const INIT_DIST_MAX_M: f64 = 3.0;

/// All parameters of the thesis GA.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThesisParams {
    /// Selection scheme (and architecture).
    pub selection: Selection,
    /// `Pop_min`.
    pub pop_min: usize,
    /// `Init_I` (for Elite overwritten by `Pop_min`).
    pub init_individuals: usize,
    /// `Init_AC` and the distance bound of fresh actions.
    pub init: InitParams,
    /// Longest allowed genome (300 in the thesis).
    pub max_genome_len: usize,
    /// `P_c`.
    pub p_c: f64,
    /// `C_len`.
    pub c_len: f64,
    /// `C_child`.
    pub c_child: ChildMode,
    /// Crossover of genomes too short for eqs. 3.21–3.22.
    pub short_genomes: ShortGenomes,
    /// `P_mA`.
    pub p_ma: f64,
    /// `P_mI`.
    pub p_mi: f64,
    /// `keep` (architecture a).
    pub keep: usize,
    /// `select`: pairs per iteration (architecture a).
    pub select: usize,
    /// Parameter control.
    pub control: Control,
    /// How children are evaluated (identical results either way).
    pub evaluation: EvaluationMode,
    /// Whether a seeded run bounds its plans by its seed plans (`thesis.seed_bound`).
    pub seed_bound: SeedBound,
}

/// What a seeded NSGA-II or Elite run asks of its plans beyond 003's obstacle rule
/// (`thesis.seed_bound`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SeedBound {
    /// Nothing (the default): the seeds are initial members like any other.
    #[default]
    None,
    /// A plan that falls short of every seed plan on `cov_final` or `t_final` violates a
    /// constraint by its smallest shortfall, summed over the two objectives. NSGA-II adds it to
    /// the obstacle cells of its constrained domination (a whole cell weighs more than any
    /// shortfall); Elite families and the reported best put every plan that meets it before
    /// every plan that does not ([`super::architecture::bounded_fitness`]). The seeds meet
    /// it, and (with `P_mI` = 0 under Elite, whose re-initialisation can replace any member)
    /// some member that meets it survives every generation, so the plan the run reports is at
    /// least as good as a seed on both objectives.
    Dominate,
}

impl SeedBound {
    /// Whether this is the default (no bound).
    pub fn is_none(&self) -> bool {
        matches!(self, SeedBound::None)
    }
}

impl ThesisParams {
    /// The thesis's fixed settings (Table 4.2, Sec. 4.1.1) with Elite selection and the
    /// operator values of Table A.1 row (e) (`C_len` 0.1, `C_child` 2, `P_mA` 0.01, `P_mI` 0).
    ///
    /// Initial moves are drawn up to [`INIT_DIST_MAX_M`] metres, not the 50 m of a literal
    /// reading of Sec. 3.3.1 (R2): see that constant.
    pub fn thesis_elite() -> Self {
        Self {
            selection: Selection::Elite,
            pop_min: 100,
            init_individuals: 100,
            init: InitParams { actions: 50, dist_max: INIT_DIST_MAX_M },
            max_genome_len: 300,
            p_c: 0.8,
            c_len: 0.1,
            short_genomes: ShortGenomes::Clamp,
            c_child: ChildMode::Both,
            p_ma: 0.01,
            p_mi: 0.0,
            keep: 0,
            select: 0,
            control: Control::None,
            evaluation: EvaluationMode::Incremental,
            seed_bound: SeedBound::None,
        }
    }

    /// Size of the initial population: `Pop_min` for Elite (and NSGA-II), `Init_I` otherwise
    /// (Sec. 4.1.1).
    pub fn initial_size(&self) -> usize {
        match self.selection {
            Selection::Elite | Selection::Nsga2 => self.pop_min,
            Selection::Draw(_) => self.init_individuals,
        }
    }
}

/// The changing-environment retrain (003 §3.5.3, thesis-ga §13, R25).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Retrain {
    /// The region is marked as covered after this many iterations.
    pub at_iteration: u32,
    /// `[x0, y0, x1, y1]` in metres, half-open.
    pub region: [f64; 4],
}
