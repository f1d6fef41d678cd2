//! The `[thesis]` and `[retrain]` sections of an experiment file and their validation into the
//! thesis GA's typed parameters (003 Tables 4.1–4.3 ranges, thesis-ga §14.2). Library users get the
//! same checks through [`ThesisSection::validate`].

use super::crossover::{ChildMode, ShortGenomes};
use super::genome::Action;
use super::individual::{EvaluationMode, InitParams};
use super::objective::Objective;
use super::params::{Control, Retrain, SeedBound, Selection, ThesisParams};
use super::scenario::Moves;
use super::seeding::{SeedPlanner, SeedPlans, seed_genomes};
use crate::config::{ConfigError, check_range, check_unit};
use crate::ga::control::AdaptiveConstants;
use crate::ga::parents::{DrawParams, Param, ParentDraw, SchemeName};
use crate::planner::memory::MemoryEstimate;
use crate::planner::section::{Placement, Section, SectionDecl};
use crate::planner::{Checks, Context};
use serde::{Deserialize, Serialize};

/// `[thesis]` as the thesis GA's entry declares it (random search reads it too).
pub static THESIS_SECTION: Section<ThesisSection> = Section::new(
    SectionDecl {
        name: "thesis",
        readers: "the thesis GA and random search read",
        placement: Placement::BeforeBudget,
        always_held: true,
        type_name: "ThesisSection",
        tables: &["ControlSection"],
        source: include_str!("config.rs"),
    },
    Some(ThesisSection::default),
);

/// `[retrain]` as the thesis GA's entry declares it: held only where a file writes it.
pub static RETRAIN_SECTION: Section<RetrainSection> = Section::new(
    SectionDecl {
        name: "retrain",
        readers: "only the thesis GA reads",
        placement: Placement::AfterBudget,
        always_held: false,
        type_name: "RetrainSection",
        tables: &[],
        source: include_str!("config.rs"),
    },
    None,
);

/// `[thesis]`: the parameters of 003 Tables 4.1–4.3.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ThesisSection {
    /// `elite`, `nsga2`, or a registered parent draw (`tournament`, `prws`, `rrws`, …).
    pub selection: SelectionName,
    /// `Pop_min`: the population size (003 Table 4.2).
    pub pop_min: usize,
    /// `Init_I`: initial genomes of the tournament and roulette schemes (003 Table 4.2); Elite
    /// starts from `Pop_min`.
    pub init_individuals: usize,
    /// `Init_AC`: free actions of a new genome (003 §3.3.1).
    pub init_actions: usize,
    /// Upper bound of initial `AC_dist` in metres (R2).
    pub init_dist_max: f64,
    /// The longest genome in actions (003 §4.1.1: 300).
    pub max_genome_len: usize,
    /// `P_c`: crossover probability (003 Table 4.2).
    pub p_c: f64,
    /// `C_len`: the largest share of a genome one crossover exchanges (003 eq. 3.20).
    pub c_len: f64,
    /// `C_child`: 0 two locality-changing children, 1 two locality-preserving ones, 2 all four
    /// (003 §3.3.2).
    pub c_child: u8,
    /// `clamp` (default) or `literal`: crossover of genomes too short for the cut-point ranges
    /// of 003 eqs. 3.21–3.22 (see `ShortGenomes`).
    pub short_genomes: ShortGenomes,
    /// `P_mA`: probability of an action mutation (003 §3.3.3).
    pub p_ma: f64,
    /// `P_mI`: probability of re-initialising a genome (003 §3.3.3).
    pub p_mi: f64,
    /// `keep`: the best members copied unchanged each iteration (tournament, PRWS, RRWS; 003
    /// §3.5.1).
    pub keep: usize,
    /// `select`: pairs drawn each iteration (tournament, PRWS, RRWS; 003 §3.4.2).
    pub select: usize,
    /// `TS`: tournament size (003 §3.4.2).
    pub tournament_size: usize,
    /// `SP`: selection pressure of the rank-based roulette wheel (003 §3.4.3).
    pub selection_pressure: f64,
    /// Parameter control.
    pub control: ControlSection,
    /// `incremental` (default) or `full`: how children are evaluated. Both give identical
    /// results; `full` sweeps every path whole and exists to check that.
    pub evaluation: EvaluationMode,
    /// `straight` (default, 003) or `routed`: a move whose straight segment would sweep an
    /// obstacle drives around it on a wall-free route (003 §5.3's future work).
    #[serde(skip_serializing_if = "Moves::is_straight")]
    pub moves: Moves,
    /// Patterns whose plans (with the file's `[pattern]` settings) seed the initial population
    /// as action genomes; none by default (003's random start).
    #[serde(skip_serializing_if = "SeedPlans::is_empty")]
    pub seed_population: SeedPlans,
    /// Share of the initial population that is seeded, in (0, 1] (default 0.1; at least one
    /// member per pattern).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seed_share: Option<f64>,
    /// `none` (default) or `dominate`: with NSGA-II or Elite and a seeded population, plans
    /// that fall short of every seed plan on either objective count as violating a constraint.
    #[serde(skip_serializing_if = "SeedBound::is_none")]
    pub seed_bound: SeedBound,
    /// `footprint` (default, 003 eq. 3.6) or `camera`: what `cov_final` measures; with the
    /// camera, 000's eq. 2 coverage along the driven path, weighted by `waypoint.alpha_cov`
    /// (see [`super::objective`]).
    #[serde(skip_serializing_if = "Objective::is_footprint")]
    pub objective: Objective,
}

/// `thesis.selection` as written: one of the thesis GA's own architectures, or a parent draw
/// of the registry ([`crate::ga::parents`]) for architecture (a).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SelectionName {
    /// Elite families (architecture (b)); the registry's draw from the best is `"best"`.
    Elite,
    /// NSGA-II (Pareto fronts and crowding over `cov_final` and `t_final`).
    Nsga2,
    /// Architecture (a) with a registered parent draw (`tournament`, `prws`, `rrws`, …).
    Draw(SchemeName),
}

impl SelectionName {
    /// The thesis GA's names of its own, which no registered draw can take.
    const OWN: [&'static str; 2] = ["elite", "nsga2"];

    /// The name as written in experiment files.
    pub fn name(self) -> &'static str {
        match self {
            SelectionName::Elite => "elite",
            SelectionName::Nsga2 => "nsga2",
            SelectionName::Draw(d) => d.as_str(),
        }
    }

    /// Which member of the final population a run returns as its plan under this selection:
    /// the knee of the first front under NSGA-II ([`crate::thesis::run::knee_index`]), the
    /// fittest member otherwise (the highest `f`, 003 eq. 3.13).
    pub fn returned_plan(self) -> &'static str {
        match self {
            SelectionName::Nsga2 => "the knee of its final first front",
            SelectionName::Elite | SelectionName::Draw(_) => "its fittest member (highest `f`)",
        }
    }

    /// The name `name` means for the thesis GA, if any.
    pub fn parse(name: &str) -> Option<Self> {
        match name {
            "elite" => Some(SelectionName::Elite),
            "nsga2" => Some(SelectionName::Nsga2),
            _ => SchemeName::parse(name).map(SelectionName::Draw),
        }
    }
}

impl Serialize for SelectionName {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for SelectionName {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        Self::parse(&name).ok_or_else(|| crate::ga::parents::unknown_scheme(&name, &Self::OWN))
    }
}

/// The `[thesis]` key that sets a selection parameter, if the section has one (it has no key
/// for "how many of the best may be parents": its `select` counts the pairs drawn).
pub fn param_key(param: Param) -> Option<&'static str> {
    match param {
        Param::TournamentSize => Some("thesis.tournament_size"),
        Param::Pressure => Some("thesis.selection_pressure"),
        Param::BestParents => None,
    }
}

/// `[thesis.control]`: parameter control of the thesis GA (thesis-ga §12), chosen by `kind`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum ControlSection {
    /// Fixed parameters.
    None,
    /// eq. 3.25 ramp of SP (RRWS) or TS (tournament).
    Ramp {
        /// Start value.
        min: f64,
        /// End value.
        max: f64,
    },
    /// eqs. 2.3–2.6.
    Adaptive {
        /// `K_1`.
        #[serde(default = "k1")]
        k1: f64,
        /// `K_2`.
        #[serde(default = "k2")]
        k2: f64,
        /// `K`.
        #[serde(default = "k")]
        k: f64,
    },
    /// eqs. 2.1–2.2.
    Muhlenbein,
}

fn k1() -> f64 {
    AdaptiveConstants::default().k1
}
fn k2() -> f64 {
    AdaptiveConstants::default().k2
}
fn k() -> f64 {
    AdaptiveConstants::default().k
}

/// `[retrain]`: the changing environment of the thesis GA (thesis-ga §13): after
/// `at_iteration` iterations a region counts as covered by another robot and the run goes on.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RetrainSection {
    /// Iterations before the switch.
    pub at_iteration: u32,
    /// `[x0, y0, x1, y1]` in metres, marked as covered (default: the 5 m corner of R25).
    #[serde(default = "retrain_region")]
    pub region: [f64; 4],
}

fn retrain_region() -> [f64; 4] {
    [5.0, 5.0, 10.0, 10.0]
}

impl Default for ThesisSection {
    fn default() -> Self {
        let p = ThesisParams::thesis_elite();
        Self {
            selection: SelectionName::Elite,
            pop_min: p.pop_min,
            init_individuals: INIT_INDIVIDUALS,
            init_actions: p.init.actions,
            init_dist_max: p.init.dist_max,
            max_genome_len: p.max_genome_len,
            p_c: p.p_c,
            c_len: p.c_len,
            c_child: p.c_child.index(),
            short_genomes: p.short_genomes,
            p_ma: p.p_ma,
            p_mi: p.p_mi,
            keep: 10,
            select: 20,
            tournament_size: 3,
            selection_pressure: 2.0,
            control: ControlSection::None,
            evaluation: EvaluationMode::Incremental,
            moves: Moves::Straight,
            seed_population: SeedPlans::default(),
            seed_share: None,
            seed_bound: SeedBound::None,
            objective: Objective::Footprint,
        }
    }
}
/// The share of the initial population that is seeded when `thesis.seed_population` is set
/// and `thesis.seed_share` is not.
pub const DEFAULT_SEED_SHARE: f64 = 0.1;

/// `Init_I` of 003 Table 4.2 for the non-Elite schemes, the default of
/// `thesis.init_individuals` (Elite starts from `Pop_min` individuals and ignores it).
pub const INIT_INDIVIDUALS: usize = 1000;

/// The validated thesis GA: its parameters and the optional retrain.
#[derive(Clone, Debug, PartialEq)]
pub struct ThesisConfig {
    /// Operator and population parameters.
    pub params: ThesisParams,
    /// The changing-environment retrain, if any.
    pub retrain: Option<Retrain>,
    /// The genomes that seed the initial population, one per pattern (empty: none).
    pub seeds: Vec<Vec<Action>>,
    /// Members of the initial population that are seeds (cycling through `seeds`).
    pub seeded: usize,
    /// How the robot drives from one viewpoint to the next.
    pub moves: Moves,
    /// What `cov_final` measures, with `α_cov` for the camera.
    pub objective: (Objective, f64),
    /// Whether the run writes its final population's genomes (`population_genomes.csv`,
    /// `output.population_genomes`).
    pub population_genomes: bool,
}

impl ThesisSection {
    /// Validates this section and the experiment's `[retrain]` (if any) into the thesis GA.
    /// `seeds` makes the seed plans (with the file's settings of the planners that make them).
    /// `alpha_cov` is `waypoint.alpha_cov`, the weight of the camera objective.
    pub fn validate(
        &self,
        retrain: Option<&RetrainSection>,
        seeds: &dyn SeedPlanner,
        alpha_cov: f64,
        ctx: &Context,
    ) -> Result<ThesisConfig, ConfigError> {
        let (origin, scenario, b) = (ctx.origin, ctx.scenario, ctx.budget);
        let err = |key: &str, msg: String| ConfigError::new(origin, key, msg);
        let params = validate_params(self, origin)?;
        if self.objective == Objective::Camera {
            if retrain.is_some() {
                return Err(err(
                    "thesis.objective",
                    "= \"camera\" cannot be used with [retrain]: the camera objective has no pre-marked region".into(),
                ));
            }
            if !(0.0..=1.0).contains(&alpha_cov) {
                return Err(err("waypoint.alpha_cov", format!("= {alpha_cov} is out of range [0, 1]")));
            }
        }
        let retrain = match retrain.copied() {
            None => None,
            Some(rt) => {
                if rt.at_iteration >= b.iterations {
                    return Err(err(
                        "retrain.at_iteration",
                        format!("= {} must be below budget.iterations = {}", rt.at_iteration, b.iterations),
                    ));
                }
                let [x0, y0, x1, y1] = rt.region;
                if !rt.region.iter().all(|v| v.is_finite()) || x0 >= x1 || y0 >= y1 {
                    return Err(err(
                        "retrain.region",
                        format!("= {:?} must be [x0, y0, x1, y1] with x0 < x1 and y0 < y1", rt.region),
                    ));
                }
                // A region over every free cell would leave A_pix = 0: nothing to cover, and
                // cov_final undefined (eq. 3.10).
                let mut grid = crate::coverage::sweep::CoverageGrid::new(&scenario.map);
                grid.premark_rect(x0, y0, x1, y1);
                if grid.area_cells() == 0 {
                    return Err(err(
                        "retrain.region",
                        format!(
                            "= {:?} covers every free cell of the map: nothing would be left to cover after the change (A_pix = 0)",
                            rt.region
                        ),
                    ));
                }
                Some(Retrain { at_iteration: rt.at_iteration, region: rt.region })
            }
        };
        let (seeds, seeded) = self.seeds(&params, seeds, ctx)?;
        let objective = (self.objective, alpha_cov);
        Ok(ThesisConfig { params, retrain, seeds, seeded, moves: self.moves, objective, population_genomes: false })
    }

    /// The seed genomes and how many initial members are seeds.
    fn seeds(
        &self,
        params: &ThesisParams,
        planner: &dyn SeedPlanner,
        ctx: &Context,
    ) -> Result<(Vec<Vec<Action>>, usize), ConfigError> {
        if !self.seed_bound.is_none() && !matches!(params.selection, Selection::Nsga2 | Selection::Elite) {
            return Err(ctx.error(
                "thesis.seed_bound",
                "= \"dominate\" needs thesis.selection = \"nsga2\" or \"elite\" (it bounds their survivors)",
            ));
        }
        if self.seed_population.is_empty() {
            if self.seed_share.is_some() {
                return Err(ctx.error("thesis.seed_share", "is set but thesis.seed_population names no pattern"));
            }
            if !self.seed_bound.is_none() {
                return Err(ctx.error(
                    "thesis.seed_bound",
                    "= \"dominate\" needs seed plans: thesis.seed_population names no pattern",
                ));
            }
            return Ok((Vec::new(), 0));
        }
        let share = self.seed_share.unwrap_or(DEFAULT_SEED_SHARE);
        if !(share > 0.0 && share <= 1.0) {
            return Err(ctx.error("thesis.seed_share", format!("= {share} is out of range (0, 1]")));
        }
        // The sections the seeds read, with their own range checks under their own keys.
        for plan in self.seed_population.plans() {
            planner.check(plan, ctx)?;
        }
        if !self.seed_bound.is_none() && params.selection == Selection::Elite && params.p_mi > 0.0 {
            return Err(ctx.error(
                "thesis.seed_bound",
                format!(
                    "= \"dominate\" with Elite needs thesis.p_mi = 0 (it is {}): a re-initialisation can replace any member, the seeds too, so the run could end outside the bound",
                    params.p_mi
                ),
            ));
        }
        if ctx.checks == Checks::KeysOnly {
            // A dry run plans no seed: the keys above are checked, the plans when the run starts.
            return Ok((Vec::new(), 0));
        }
        let deadline = ctx.budget.wall_clock.map(|d| (std::time::Instant::now() + d, d));
        let genomes = seed_genomes(self.seed_population, planner, ctx.scenario, params.max_genome_len, deadline)
            .map_err(|m| ctx.error("thesis.seed_population", m))?;
        let size = params.initial_size();
        let seeded = ((share * size as f64).ceil() as usize).max(genomes.len()).min(size);
        Ok((genomes.into_iter().map(|(_, g)| g).collect(), seeded))
    }
}

/// An upper estimate of a run's memory in bytes: twice the initial population (parents and
/// offspring), each individual `32·max_genome_len` bytes of genome and viewpoints plus its
/// bit-sliced visit map: one bit per cell (rows padded to 64 columns) for each bit of the
/// largest possible count, which is below `max_genome_len`; and the segment cache of each of
/// the run's `threads` evaluation threads.
pub fn memory_estimate(params: &ThesisParams, rows: usize, cols: usize, threads: usize) -> f64 {
    let len = params.max_genome_len as f64;
    let planes = f64::from(usize::BITS - params.max_genome_len.leading_zeros());
    let plane_bytes = 8.0 * rows as f64 * cols.div_ceil(64) as f64;
    let per = 32.0 * len + plane_bytes * planes;
    let caches = (super::segments::CACHE_BYTES * threads.max(1)) as f64;
    2.0 * params.initial_size().max(params.pop_min) as f64 * per + caches
}

impl ThesisConfig {
    /// An upper estimate of a run's memory on `map` with `threads` evaluation threads
    /// ([`memory_estimate`]), with the key that drives it.
    pub fn memory_estimate(&self, map: &crate::map::GridMap, threads: usize) -> MemoryEstimate {
        let p = &self.params;
        let routes = match self.moves {
            Moves::Straight => 0.0,
            Moves::Routed => crate::routing::routes::Router::memory_estimate(map.rows() * map.cols(), threads),
        };
        let views = match self.objective.0 {
            Objective::Footprint => 0.0,
            Objective::Camera => (crate::coverage::views::VIEW_CACHE_BYTES * threads.max(1)) as f64,
        };
        MemoryEstimate {
            bytes: memory_estimate(p, map.rows(), map.cols(), threads) + routes + views,
            key: if p.initial_size() > p.pop_min { "thesis.init_individuals" } else { "thesis.pop_min" },
            what: format!("{} individuals of up to {} actions", p.initial_size(), p.max_genome_len),
        }
    }
}

/// Validates a `[thesis]` section into [`ThesisParams`].
pub fn validate_params(t: &ThesisSection, origin: &str) -> Result<ThesisParams, ConfigError> {
    let t = *t;
    for (key, v) in [("thesis.p_c", t.p_c), ("thesis.c_len", t.c_len), ("thesis.p_ma", t.p_ma), ("thesis.p_mi", t.p_mi)]
    {
        check_unit(origin, key, v)?;
    }
    check_count(origin, "thesis.pop_min", t.pop_min, 1, 1_000_000)?;
    check_count(origin, "thesis.init_actions", t.init_actions, 1, 100_000)?;
    check_count(origin, "thesis.max_genome_len", t.max_genome_len, t.init_actions + 2, 1_000_000)?;
    check_range(origin, "thesis.init_dist_max", t.init_dist_max, 1e-9, 1e6, "[1e-9, 1e6] metres")?;
    let child = ChildMode::from_index(t.c_child).ok_or_else(|| {
        ConfigError::new(origin, "thesis.c_child", format!("= {} is out of range {{0, 1, 2}}", t.c_child))
    })?;
    let selection = validate_selection(&t, origin)?;
    if selection.draw().is_some() {
        check_count(origin, "thesis.init_individuals", t.init_individuals, t.pop_min, 10_000_000)?;
        check_count(origin, "thesis.keep", t.keep, 0, t.pop_min)?;
        check_count(origin, "thesis.select", t.select, 1, t.pop_min)?;
    }
    let control = validate_control(&t, &selection, origin)?;
    let params = ThesisParams {
        selection,
        pop_min: t.pop_min,
        init_individuals: t.init_individuals,
        init: InitParams { actions: t.init_actions, dist_max: t.init_dist_max },
        max_genome_len: t.max_genome_len,
        p_c: t.p_c,
        c_len: t.c_len,
        c_child: child,
        short_genomes: t.short_genomes,
        p_ma: t.p_ma,
        p_mi: t.p_mi,
        keep: t.keep,
        select: t.select,
        control,
        evaluation: t.evaluation,
        seed_bound: t.seed_bound,
    };
    Ok(params)
}

/// A count `v` of `key` within `[lo, hi]`.
fn check_count(origin: &str, key: &str, v: usize, lo: usize, hi: usize) -> Result<(), ConfigError> {
    if v < lo || v > hi {
        return Err(ConfigError::new(origin, key, format!("= {v} is out of range [{lo}, {hi}]")));
    }
    Ok(())
}

/// The selection of a `[thesis]` section, each parameter its scheme reads checked.
fn validate_selection(t: &ThesisSection, origin: &str) -> Result<Selection, ConfigError> {
    Ok(match t.selection {
        SelectionName::Elite => Selection::Elite,
        SelectionName::Nsga2 => Selection::Nsga2,
        SelectionName::Draw(name) => {
            let scheme = name.scheme();
            for &param in scheme.reads() {
                match (param, param_key(param)) {
                    (Param::TournamentSize, Some(key)) => check_count(origin, key, t.tournament_size, 1, t.pop_min)?,
                    (Param::Pressure, Some(key)) => check_range(origin, key, t.selection_pressure, 1.0, 2.0, "[1, 2]")?,
                    (_, _) => {
                        return Err(ConfigError::new(
                            origin,
                            "thesis.selection",
                            format!("= \"{}\" reads {param:?}, which [thesis] does not set", name.as_str()),
                        ));
                    }
                }
            }
            let params =
                DrawParams { tournament_size: t.tournament_size, pressure: t.selection_pressure, best_parents: 0 };
            Selection::Draw(ParentDraw { scheme, params })
        }
    })
}

/// The parameter control of a `[thesis]` section (003 §3.5.2), its range that of the
/// parameter it moves.
fn validate_control(t: &ThesisSection, selection: &Selection, origin: &str) -> Result<Control, ConfigError> {
    Ok(match t.control {
        ControlSection::None => Control::None,
        ControlSection::Ramp { min, max } => {
            let (lo, hi, what) = match selection.draw().and_then(|d| d.scheme.ramped()) {
                Some(Param::Pressure) => (1.0, 2.0, "[1, 2] (SP of RRWS)"),
                Some(Param::TournamentSize) => (1.0, t.pop_min as f64, "[1, pop_min] (TS of the tournament)"),
                Some(Param::BestParents) | None => {
                    let ramped: Vec<String> = crate::ga::parents::SCHEMES
                        .iter()
                        .filter(|s| s.ramped().is_some_and(|p| param_key(p).is_some()))
                        .map(|s| format!("\"{}\"", s.name()))
                        .collect();
                    return Err(ConfigError::new(
                        origin,
                        "thesis.control.kind",
                        format!("= \"ramp\" needs selection {}", ramped.join(" or ")),
                    ));
                }
            };
            check_range(origin, "thesis.control.min", min, lo, hi, what)?;
            check_range(origin, "thesis.control.max", max, lo, hi, what)?;
            Control::Ramp { min, max }
        }
        ControlSection::Adaptive { k1, k2, k } => {
            for (key, v) in [("thesis.control.k1", k1), ("thesis.control.k2", k2), ("thesis.control.k", k)] {
                check_unit(origin, key, v)?;
            }
            Control::Adaptive(AdaptiveConstants { k1, k2, k })
        }
        ControlSection::Muhlenbein => Control::Muhlenbein,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// F2 is the default projection (thesis-ga §5) and `C_child` = 2 (both) the default child mode.
    #[test]
    fn the_thesis_defaults() {
        assert_eq!(
            crate::planner::sections::ScorerSection::default().projection,
            crate::coverage::fitness::Projection::F2
        );
        assert_eq!(ThesisSection::default().c_child, 2, "C_child = 2 (both) by default");
    }
}
