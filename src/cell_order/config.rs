//! `[cell_order]`: the cell-order planner's settings as written, validated once into
//! [`CellOrderConfig`].

use super::search::TourGaParams;
use crate::config::{ConfigError, check_range};
use crate::ga::parents::{DrawParams, Param, ParentDraw, SchemeName};
use crate::planner::Context;
use crate::planner::memory::MemoryEstimate;
use crate::planner::section::{Placement, Section, SectionDecl};
use serde::{Deserialize, Serialize};

/// `[cell_order]` as the cell-order planner's entry declares it: held where a file writes it,
/// and written in full for a run of the cell-order planner.
pub static CELL_ORDER_SECTION: Section<CellOrderSection> = Section::new(
    SectionDecl {
        name: "cell_order",
        readers: "only the cell-order planner (and the thesis GA's cell_order seed plan) reads",
        placement: Placement::BeforeBudget,
        always_held: false,
        type_name: "CellOrderSection",
        tables: &[],
        source: include_str!("config.rs"),
    },
    Some(CellOrderSection::default),
);

/// Which solver orders the cells.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Solver {
    /// The genetic search (optionally memetic).
    Ga,
    /// Held–Karp dynamic programming: the optimum, for maps of a few cells.
    Exact,
    /// Iterated local search ([`super::ils`]): the GTSP reference where Held–Karp cannot run,
    /// a strong search with no population and no crossover.
    Ils,
    /// The no-search control ([`super::controls`]): the nearest-neighbour tour at each of
    /// `directions` alone, completed as `completion` says; the common scorer picks the fastest.
    Nearest,
    /// The classical control ([`super::controls`]): one boustrophedon over the whole reachable
    /// map at each of `directions`, completed as `completion` says (the GA's own completion);
    /// the common scorer picks the fastest.
    Boustrophedon,
}

impl Solver {
    /// Whether this is one of the controls with no search ([`super::controls`]), whose plans
    /// all go to the common scorer.
    pub fn is_control(self) -> bool {
        match self {
            Solver::Nearest | Solver::Boustrophedon => true,
            Solver::Ga | Solver::Ils | Solver::Exact => false,
        }
    }

    /// Whether this solver searches (reads the GA's or the local search's keys and the seed);
    /// the exact solver and the two controls do not.
    pub fn searches(self) -> bool {
        match self {
            Solver::Ga | Solver::Ils => true,
            Solver::Exact | Solver::Nearest | Solver::Boustrophedon => false,
        }
    }
}

/// What the plan does about the cells its sweeps leave uncovered.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Completion {
    /// Boundary chains along the walls near uncovered cells, then the greedy pass
    /// ([`super::boundary`]).
    Boundary,
    /// Each candidate sweep ends with the boundary completion of its own cell
    /// ([`super::cell_completion`]), so that its time is part of the tour's cost; what that
    /// leaves gets the boundary pass after the tour.
    Cells,
    /// The quota heuristic ([`super::quota`]): the boundary chains as pieces, the cheapest per
    /// cell first (approach and turning counted) until the coverage goal is met, the rest after.
    Quota,
    /// The quota heuristic's pieces with a local search ([`super::piece_search`]) deciding
    /// which of them meet the goal, in which order and which way round, by their time with the
    /// transit and turning between them (the quota heuristic itself without a coverage goal).
    QuotaSearch,
    /// The patterns' greedy pass alone (what boustrophedon and spiral do).
    Greedy,
    /// Nothing: the sweeps only.
    None,
}

/// `[cell_order]`: the cell-order planner: a search over the order, lane direction and entry of
/// the boustrophedon cells, and how the strips the lanes leave are covered.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CellOrderSection {
    /// `"ga"`, `"exact"`, `"ils"`, or a control: `"nearest"` or `"boustrophedon"`.
    pub solver: Solver,
    /// Lane directions offered to every cell, in degrees.
    pub directions: Vec<f64>,
    /// Individuals per generation.
    pub population: usize,
    /// Parent selection: the name of a scheme of [`crate::ga::parents::SCHEMES`].
    pub selection: SchemeName,
    /// Tournament size `TS`.
    pub tournament_size: usize,
    /// Selection pressure `SP` of the rank-based wheel (`sp` before).
    pub selection_pressure: f64,
    /// Under `"best"`: how many of the best may be parents (`select` before).
    pub best_parents: usize,
    /// The best carried over unchanged each generation.
    pub keep: usize,
    /// Crossover probability.
    pub p_c: f64,
    /// Probability of an order mutation per child.
    pub p_m: f64,
    /// Per-cell probability of a new sweep choice (default 1 / cells).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub p_choice: Option<f64>,
    /// Local search (best choices, Or-opt, 2-opt) on the best and one random child of every
    /// generation.
    pub memetic: bool,
    /// `"boundary"`, `"cells"`, `"quota"`, `"quota_search"`, `"greedy"` or `"none"`: how the strips the lanes leave
    /// are visited.
    pub completion: Completion,
    /// The share of the reachable coverable cells the plan must cover, in (0, 1]: the GA ranks
    /// tours by when they reach it, the returned plan is the finalist whose common-scorer
    /// coverage curve reaches it first, and it ends there (then drives to the end station).
    /// Unset: tours are ranked by their whole time and the plan covers all it can.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coverage_goal: Option<f64>,
    /// Seed the GA's first population with the nearest-neighbour tour at each single lane
    /// direction of `directions` (the no-search control's tours), kept among the finalists.
    /// Left out of the canonical form while off, so that run ids made before it stay.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub seed_directions: bool,
    /// Put the classical control's plans (one boustrophedon over the whole reachable map per
    /// lane direction, with this completion) among a search's finalists, so that the common
    /// scorer returns whichever plan reaches the coverage goal first and a search is never
    /// slower than the classical control. Needs `coverage_goal`; read by `"ga"` and `"ils"`.
    /// Left out of the canonical form while off, so that run ids made before it stay.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub classical_finalists: bool,
    /// How many of the map's dominant wall orientations
    /// ([`crate::map::orientation::wall_orientations`]) join `directions` as lane directions
    /// (those within 1° of one already there are not added twice); 0 to 8.
    #[serde(skip_serializing_if = "is_zero")]
    pub wall_directions: usize,
    /// Completion driving charged per square metre a sweep leaves in its cell, in metres
    /// (the completion pass drove about 23 m per m² it swept on basement with a 0.6 m robot).
    pub completion_m_per_m2: f64,
    /// The longest gap, in metres, a lane continues across ([`super::merged_lanes`]): where the
    /// obstacles in it are small (each fits in a square of this side: a speck, a pillar; not a
    /// wall) and the robot can drive around them on a detour at most two widths longer than the
    /// gap, the lane goes on around them and the cells on both sides merge into one of longer
    /// lanes. 0 (the default) ends a lane at every obstacle; 0 to 50. Left out of the canonical
    /// form while 0, so that run ids made before it stay.
    #[serde(skip_serializing_if = "is_zero_f64")]
    pub merge_gap_m: f64,
    /// Offer every cell, beside its sweeps with lanes joined across small obstacles, its sweeps
    /// with lanes split at every obstacle, so that a search chooses per cell between the two
    /// layouts (and lane direction and entry, as always); the no-search and classical controls
    /// try each layout for the whole map. Needs `merge_gap_m` > 0. Left out of the canonical
    /// form while off, so that run ids made before it stay.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub offer_split_lanes: bool,
}

impl Default for CellOrderSection {
    fn default() -> Self {
        Self {
            solver: Solver::Ga,
            directions: vec![0.0, 45.0, 90.0, 135.0],
            population: 100,
            selection: SchemeName::parse("tournament").expect("registered"),
            tournament_size: 3,
            selection_pressure: 1.7,
            best_parents: 20,
            keep: 2,
            p_c: 0.9,
            p_m: 0.5,
            p_choice: None,
            memetic: true,
            completion: Completion::Boundary,
            coverage_goal: None,
            seed_directions: false,
            classical_finalists: false,
            wall_directions: 0,
            completion_m_per_m2: 20.0,
            merge_gap_m: 0.0,
            offer_split_lanes: false,
        }
    }
}

/// The validated planner.
#[derive(Clone, Debug, PartialEq)]
pub struct CellOrderConfig {
    /// The solver.
    pub solver: Solver,
    /// Lane directions in degrees.
    pub directions: Vec<f64>,
    /// The GA's parameters.
    pub ga: TourGaParams,
    /// Coverage completion after the tour.
    pub completion: Completion,
    /// The coverage goal, a share of the reachable coverable cells.
    pub coverage_goal: Option<f64>,
    /// Seed the GA with the nearest-neighbour tour at each single direction.
    pub seed_directions: bool,
    /// The classical control's plans among a search's finalists.
    pub classical_finalists: bool,
    /// How many of `directions` were added from the map's walls (the last ones).
    pub wall_directions: usize,
    /// Completion driving charged per square metre a sweep leaves, in metres.
    pub completion_m_per_m2: f64,
    /// How lanes are laid out: the longest gap a lane continues across, in metres, and
    /// whether split sweeps are offered beside joined ones.
    pub layout: super::merged_lanes::LaneLayout,
    /// The robot's width (for the memory estimate).
    pub width: f64,
}

/// Whether a count is zero (a key left out of the canonical form at its default).
fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// Whether a length is zero (a key left out of the canonical form at its default).
fn is_zero_f64(x: &f64) -> bool {
    *x == 0.0
}

/// `directions` and, after them, the `count` dominant wall orientations of `map` that lie more
/// than 1° from each of them.
pub fn with_wall_directions(directions: &[f64], map: &crate::map::GridMap, count: usize) -> Vec<f64> {
    let mut out = directions.to_vec();
    if count == 0 {
        return out;
    }
    for a in crate::map::orientation::wall_orientations(map, count) {
        let near = |d: f64| {
            let gap = (d - a).rem_euclid(180.0);
            gap.min(180.0 - gap) <= 1.0
        };
        if !out.iter().any(|&d| near(d)) {
            out.push(a);
        }
    }
    out
}

/// The `[cell_order]` key that sets a selection parameter.
pub fn param_key(param: Param) -> &'static str {
    match param {
        Param::TournamentSize => "cell_order.tournament_size",
        Param::Pressure => "cell_order.selection_pressure",
        Param::BestParents => "cell_order.best_parents",
    }
}

impl CellOrderSection {
    /// Checks every key against its range.
    pub fn validate(&self, ctx: &Context) -> Result<CellOrderConfig, ConfigError> {
        let o = ctx.origin;
        crate::lanes::check_lane_count(&ctx.scenario.map, ctx.scenario.robot.width)
            .map_err(|e| ctx.error("robot.width", e.to_string()))?;
        if self.directions.is_empty() || self.directions.len() > 36 {
            return Err(ctx.error("cell_order.directions", "needs 1 to 36 lane directions in degrees"));
        }
        for &d in &self.directions {
            check_range(o, "cell_order.directions", d, -360.0, 360.0, "[-360, 360] degrees")?;
        }
        check_range(o, "cell_order.wall_directions", self.wall_directions as f64, 0.0, 8.0, "integers 0..=8")?;
        let directions = with_wall_directions(&self.directions, &ctx.scenario.map, self.wall_directions);
        if directions.len() > 36 {
            return Err(ctx.error(
                "cell_order.wall_directions",
                format!("adds to {} lane directions, more than 36: offer fewer", directions.len()),
            ));
        }
        let count = |key: &str, v: usize, lo: usize, hi: usize| {
            check_range(o, key, v as f64, lo as f64, hi as f64, &format!("integers {lo}..={hi}"))
        };
        count("cell_order.population", self.population, 2, 100_000)?;
        // Each scheme's own key is checked under that scheme only: a default the scheme never
        // reads (`best_parents` = 20 under tournament selection) must not refuse a small population.
        let scheme = self.selection.scheme();
        for &param in scheme.reads() {
            match param {
                Param::TournamentSize => count(param_key(param), self.tournament_size, 1, self.population)?,
                Param::BestParents => count(param_key(param), self.best_parents, 1, self.population)?,
                Param::Pressure => check_range(o, param_key(param), self.selection_pressure, 1.0, 2.0, "[1, 2]")?,
            }
        }
        count("cell_order.keep", self.keep, 0, self.population - 1)?;
        check_range(o, "cell_order.p_c", self.p_c, 0.0, 1.0, "[0, 1]")?;
        check_range(o, "cell_order.p_m", self.p_m, 0.0, 1.0, "[0, 1]")?;
        check_range(o, "cell_order.completion_m_per_m2", self.completion_m_per_m2, 0.0, 1e4, "[0, 10000] m per m²")?;
        let layout = self.lane_layout(ctx)?;
        if let Some(p) = self.p_choice {
            check_range(o, "cell_order.p_choice", p, 0.0, 1.0, "[0, 1]")?;
        }
        self.check_goal(ctx)?;
        if self.solver == Solver::Exact && ctx.checks == crate::planner::Checks::Full {
            check_exact_cells(ctx, &directions, layout)?;
        }
        let params = DrawParams {
            tournament_size: self.tournament_size,
            pressure: self.selection_pressure,
            best_parents: self.best_parents,
        };
        let selection = ParentDraw { scheme, params };
        Ok(CellOrderConfig {
            solver: self.solver,
            directions,
            ga: TourGaParams {
                population: self.population,
                selection,
                keep: self.keep,
                p_c: self.p_c,
                p_m: self.p_m,
                p_choice: self.p_choice,
                memetic: self.memetic,
                goal: self.coverage_goal,
            },
            completion: self.completion,
            coverage_goal: self.coverage_goal,
            seed_directions: self.seed_directions,
            classical_finalists: self.classical_finalists,
            wall_directions: self.wall_directions,
            completion_m_per_m2: self.completion_m_per_m2,
            layout,
            width: ctx.scenario.robot.width,
        })
    }

    /// The lane layouts offered: `merge_gap_m` in range, and split lanes only beside joined ones.
    fn lane_layout(&self, ctx: &Context) -> Result<super::merged_lanes::LaneLayout, ConfigError> {
        check_range(ctx.origin, "cell_order.merge_gap_m", self.merge_gap_m, 0.0, 50.0, "[0, 50] metres")?;
        if self.offer_split_lanes && self.merge_gap_m == 0.0 {
            return Err(ctx.error(
                "cell_order.offer_split_lanes",
                "= true needs cell_order.merge_gap_m > 0 (with 0 every lane is already split at every obstacle)",
            ));
        }
        Ok(super::merged_lanes::LaneLayout { merge_gap_m: self.merge_gap_m, split_too: self.offer_split_lanes })
    }

    /// The coverage goal in (0, 1], and present where `classical_finalists` needs it.
    fn check_goal(&self, ctx: &Context) -> Result<(), ConfigError> {
        if let Some(g) = self.coverage_goal
            && !(g > 0.0 && g <= 1.0)
        {
            return Err(ctx.error(
                "cell_order.coverage_goal",
                format!("= {g} is outside (0, 1] (a share of the reachable cells)"),
            ));
        }
        if self.classical_finalists && self.coverage_goal.is_none() {
            return Err(ctx.error(
                "cell_order.classical_finalists",
                "= true needs cell_order.coverage_goal: a search's plans and the classical control's are compared \
                 by their time to it",
            ));
        }
        Ok(())
    }
}

/// The exact solver's cell limit ([`super::exact::MAX_EXACT_CELLS`]), counted on the
/// decomposition before a run: the cells are known only after it, and a grid must refuse the
/// configuration before it writes anything.
fn check_exact_cells(
    ctx: &Context,
    directions: &[f64],
    layout: super::merged_lanes::LaneLayout,
) -> Result<(), ConfigError> {
    let planning = ctx.scenario.for_planning();
    let (_, _, sweeps) = super::decompose(&planning, directions, layout)
        .map_err(|m| ctx.error("cell_order.solver", format!("cell_order on map `{}`: {m}", ctx.scenario.map.name())))?;
    if sweeps.len() > super::exact::MAX_EXACT_CELLS {
        return Err(ctx.error(
            "cell_order.solver",
            format!(
                "= \"exact\" takes at most {} cells; map `{}` has {} for this robot and start (use \"ga\")",
                super::exact::MAX_EXACT_CELLS,
                ctx.scenario.map.name(),
                sweeps.len()
            ),
        ));
    }
    Ok(())
}

impl CellOrderConfig {
    /// An estimate of a run's own memory on `map`, made before anything is allocated: the
    /// leg-time matrix over candidate sweeps and the transit lengths between their ends (each
    /// `f32`, candidates squared; cells taken as at least two widths square, four entries per
    /// direction and layout offered; the run refuses more than [`super::MAX_CANDIDATES`]
    /// candidates) and one Dijkstra buffer per thread.
    pub fn memory_estimate(&self, map: &crate::map::GridMap, threads: usize) -> MemoryEstimate {
        let free_m2 = map.free_count() as f64 * map.resolution().powi(2);
        let cells = (free_m2 / (4.0 * self.width * self.width)).ceil();
        let layouts = self.layout.control_layouts().len() as f64;
        let candidates = (cells * 4.0 * self.directions.len() as f64 * layouts).min(super::MAX_CANDIDATES as f64);
        let legs = 2.0 * 4.0 * candidates * candidates;
        let dijkstra = 16.0 * (map.rows() * map.cols()) as f64 * threads.max(1) as f64;
        MemoryEstimate {
            bytes: legs + dijkstra,
            key: "cell_order.directions",
            what: format!("leg times and transit lengths between about {candidates:.0} candidate sweeps"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point;
    use crate::map::{CellState, GridMap};

    /// A room whose walls run at 20° and 110°.
    fn turned_room() -> GridMap {
        let (s, c) = 20f64.to_radians().sin_cos();
        let cells = (0..100 * 100)
            .map(|i| {
                let (x, y) = ((i % 100) as f64 - 50.0, (i / 100) as f64 - 50.0);
                let (u, v) = (c * x + s * y, -s * x + c * y);
                if u.abs() < 33.0 && v.abs() < 33.0 { CellState::Free } else { CellState::Occupied }
            })
            .collect();
        GridMap::new("turned", 100, 100, 0.05, Point::origin(), cells).unwrap()
    }

    #[test]
    fn wall_directions_join_the_offered_ones_once() {
        let map = turned_room();
        assert_eq!(with_wall_directions(&[0.0, 90.0], &map, 0), vec![0.0, 90.0]);
        let with = with_wall_directions(&[0.0, 90.0], &map, 2);
        assert_eq!(with.len(), 4, "{with:?}");
        assert!(
            with[2..].iter().any(|a| (a - 20.0).abs() <= 1.5) && with[2..].iter().any(|a| (a - 110.0).abs() <= 1.5)
        );
        // A wall direction within 1° of an offered one is not offered twice.
        let again = with_wall_directions(&with, &map, 2);
        assert_eq!(again, with);
    }
}
