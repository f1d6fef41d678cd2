//! The cell-order planner: a GA over the combinatorial layer of a boustrophedon decomposition
//! (which cell next, at which lane direction, entered from which corner), the view of
//! Bähnemann et al. (2019) that boustrophedon coverage is a generalised travelling-salesman
//! problem. Cells and their candidate sweeps come from [`sweeps`], wall-free transit costs
//! between sweep ends from [`crate::routing::transit`], the tour problem from [`tour`]; the GA ([`search`],
//! operators in [`operators`], the memetic step in [`local`]), the exact Held–Karp solver
//! ([`exact`]) or the iterated local search of the GTSP reference ([`ils`]) orders them; the
//! controls with no search ([`controls`]) give the plans a search has to beat. The plan drives the chosen sweeps joined by
//! [`crate::map::clearance::Clearance::connect`] routes, then a completion pass (the boundary
//! chains of [`boundary`], or the quota heuristic of [`quota`] that takes the cheapest pieces
//! first up to the coverage goal), then to the end station. Every plan is checked with the body
//! rule and repaired where it touches before it is returned ([`crate::planner::executable`]).

pub mod boundary;
pub mod cell_completion;
pub mod config;
pub mod controls;
pub mod entry;
pub mod exact;
pub mod gtsplib;
pub mod ils;
pub mod local;
pub mod merged_lanes;
pub mod operators;
pub mod piece_search;
mod planner;
pub mod quota;
pub mod rank;
pub mod reads;
pub mod search;
pub mod sweeps;
pub mod tour;

use crate::coverage::CoverageGrid;
use crate::coverage::curve::CoverageCurve;
use crate::coverage::motion::rotation_time;
use crate::ga::observer::{Observer, Observers};
use crate::geom::{Point, Vector};
use crate::lanes::GrowingRoute;
use crate::map::clearance::Clearance;
use crate::map::reach::Reach;
use crate::planner::executor::SetupCutoff;
use crate::planner::{Budget, Planner, PlannerError, RunOutcome, Scenario, StopReason};
use crate::routing::transit::{Transit, distinct};
use config::{CellOrderConfig, Completion, Solver};
use std::time::Instant;
use sweeps::CellSweeps;
use tour::{Candidate, Instance, Tour, UNREACHED_S, leg_time, leg_turn_rad};

pub use planner::{lower_bound_to_goal, time_to_goal};

/// The most candidate sweeps a run accepts (cells × directions × 4 entries): the leg-time
/// matrix and the transit lengths each hold the square of it in `f32`, 3.2 GB at this bound.
pub const MAX_CANDIDATES: usize = 20_000;

/// A map prepared for tours: the reachable clearance, the cells and their sweeps, the tour
/// problem with every leg time.
pub struct Prepared<'m> {
    /// The clearance, restricted to the part reachable from the start.
    pub clear: Clearance<'m>,
    /// Reachable and coverable cells.
    pub reach: Reach,
    /// The cells and their candidate sweeps.
    pub sweeps: CellSweeps,
    /// The tour problem.
    pub instance: Instance,
    /// The share of the reachable coverable cells the plan must cover, where it has a goal
    /// (the quota completion stops choosing pieces there).
    pub coverage_goal: Option<f64>,
}

/// How a map is prepared for tours: the lane directions offered to every cell, the driving
/// charged per square metre a sweep leaves, and the completion (which, for
/// [`Completion::Cells`], becomes part of every candidate sweep).
#[derive(Clone, Copy, Debug)]
pub struct Preparation<'a> {
    /// Lane directions in degrees.
    pub directions: &'a [f64],
    /// Metres of completion driving charged per square metre a sweep leaves in its cell.
    pub completion_m_per_m2: f64,
    /// The plan's completion.
    pub completion: Completion,
    /// The plan's coverage goal, a share of the reachable coverable cells.
    pub coverage_goal: Option<f64>,
    /// How lanes are laid out: joined across gaps of up to a length ([`merged_lanes`]; 0
    /// splits them at every obstacle), and whether split sweeps are offered beside joined ones.
    pub layout: merged_lanes::LaneLayout,
}

impl<'a> Preparation<'a> {
    /// The preparation a `[cell_order]` section asks for.
    pub fn of(section: &'a config::CellOrderSection) -> Self {
        Self {
            directions: &section.directions,
            completion_m_per_m2: section.completion_m_per_m2,
            completion: section.completion,
            coverage_goal: section.coverage_goal,
            layout: merged_lanes::LaneLayout { merge_gap_m: section.merge_gap_m, split_too: section.offer_split_lanes },
        }
    }
}

/// Decomposes the map of `scenario`, builds every candidate sweep at `how.directions` and the
/// leg times between them (wall-free transit at `robot.speed`, turning at `robot.rot_speed`).
/// A sweep's cost is its own time plus the completion it leaves: `how.completion_m_per_m2`
/// metres of driving per square metre of its region it does not sweep.
pub fn prepare<'m>(scenario: &'m Scenario, how: Preparation) -> Result<Prepared<'m>, String> {
    prepare_within(scenario, how, &SetupCutoff::default()).map_err(|e| e.to_string())
}

/// Why a preparation did not finish.
#[derive(Debug, thiserror::Error)]
pub enum PrepareError {
    /// The map and settings cannot be prepared (no room, too many candidate sweeps), or the
    /// wall clock ran out: the message says which.
    #[error("{0}")]
    Input(String),
    /// The run's interrupt was raised.
    #[error("interrupted while preparing the map")]
    Interrupted,
}

/// [`prepare`], given up at `cutoff` (checked after the decomposition and while the transit
/// routes are found, the phases that grow with the map): a run's wall clock and its interrupt
/// cover its preparation.
pub fn prepare_within<'m>(
    scenario: &'m Scenario,
    how: Preparation,
    cutoff: &SetupCutoff,
) -> Result<Prepared<'m>, PrepareError> {
    let s = scenario;
    let (directions, completion_m_per_m2) = (how.directions, how.completion_m_per_m2);
    let begun = Instant::now();
    let stopped = |phase: &str| match cutoff.reached() {
        Some(StopReason::Interrupted) => PrepareError::Interrupted,
        _ => PrepareError::Input(format!(
            "the wall clock (budget.wall_clock_s = {} s) ran out while {phase}, after {:.1} s of preparation: \
             raise budget.wall_clock_s, or offer fewer cell_order.directions",
            cutoff.limit_s(),
            begun.elapsed().as_secs_f64()
        )),
    };
    let (clear, reach, mut sweeps) = decompose(scenario, directions, how.layout).map_err(PrepareError::Input)?;
    if how.completion == Completion::Cells {
        sweeps.complete_in_cells(&clear, s.robot.width, reach.coverable(), s.robot.speed);
    }
    if cutoff.reached().is_some() {
        return Err(stopped("decomposing the map into cells"));
    }
    let count: usize = sweeps.cells.iter().map(Vec::len).sum();
    if count > MAX_CANDIDATES {
        return Err(PrepareError::Input(format!(
            "{} cells with {count} candidate sweeps exceed the limit of {MAX_CANDIDATES}; use fewer \
             cell_order.directions",
            sweeps.len()
        )));
    }
    let flat: Vec<&sweeps::Sweep> = sweeps.cells.iter().flatten().collect();
    let (exits, exit_id) = distinct(&flat.iter().map(|w| w.end()).chain([s.start]).collect::<Vec<_>>());
    let (entries, entry_id) = distinct(&flat.iter().map(|w| w.start()).chain([s.end]).collect::<Vec<_>>());
    let transit = Transit::new_within(&clear, &exits, &entries, &|| cutoff.reached().is_some()).ok_or_else(|| {
        stopped(&format!(
            "finding the wall-free routes between {} sweep ends and {} starts",
            exits.len(),
            entries.len()
        ))
    })?;
    let (speed, rot) = (s.robot.speed, s.robot.rot_speed);
    let reachable = reach.coverable_count().max(1) as f64;
    // Seconds of completion charged for the map cells a sweep leaves (written as it always
    // was, so that tour costs keep their last bits).
    let charge = |missed: usize| completion_m_per_m2 * missed as f64 * s.map.resolution().powi(2) / speed;
    let candidates: Vec<Vec<Candidate>> = sweeps
        .cells
        .iter()
        .zip(&sweeps.region_cells)
        .map(|(cell, &region)| {
            cell.iter()
                .map(|w| Candidate {
                    gain: region.saturating_sub(w.missed_cells) as f64 / reachable,
                    completion_s: charge(w.missed_cells),
                    time_s: w.length_m / speed + rotation_time(w.turn_rad, rot) + charge(w.missed_cells),
                    entry: (w.start(), w.start_heading),
                    exit: (w.end(), w.end_heading),
                })
                .collect()
        })
        .collect();
    let all: Vec<Candidate> = candidates.iter().flatten().copied().collect();
    let n = all.len();
    let mut instance = Instance::new(&candidates, |a, b| {
        let from = a.map_or((s.start, Vector::zeros()), |a| all[a].exit);
        let to = b.map_or((s.end, Vector::zeros()), |b| all[b].entry);
        let metres = transit.metres(exit_id[a.unwrap_or(n)] as usize, entry_id[b.unwrap_or(n)] as usize);
        let turn = if rot > 0.0 { leg_turn_rad(from, to) } else { 0.0 };
        leg_time(metres, turn, speed, rot)
    });
    instance.completion_s_per_share = completion_m_per_m2 * s.map.resolution().powi(2) / speed * reachable;
    Ok(Prepared { clear, reach, sweeps, instance, coverage_goal: how.coverage_goal })
}

/// The reachable clearance of `scenario`, its reach and its cells with their candidate sweeps
/// at `directions`, lanes laid out as `layout` says: the first, cheap part of
/// [`prepare`] (no transit), which validation uses to count the cells.
pub fn decompose<'m>(
    scenario: &'m Scenario,
    directions: &[f64],
    layout: merged_lanes::LaneLayout,
) -> Result<(Clearance<'m>, Reach, CellSweeps), String> {
    let s = scenario;
    let width = s.robot.width;
    let mut clear = Clearance::new(&s.map, width);
    let reach = Reach::new(&clear, &[s.start]);
    if reach.centres().iter().all(|c| !c) {
        return Err(format!("no free area reachable from the start fits a robot {width} m wide"));
    }
    clear.restrict(reach.centres().to_vec());
    let sweeps = CellSweeps::new(&clear, width, directions, reach.coverable(), layout);
    if sweeps.is_empty() {
        return Err(format!("no lane of a robot {width} m wide fits the area reachable from the start"));
    }
    Ok((clear, reach, sweeps))
}

impl Prepared<'_> {
    /// The chosen sweeps of `tour` in order.
    pub fn sweeps_of<'a>(&'a self, tour: &'a Tour) -> impl Iterator<Item = &'a sweeps::Sweep> + 'a {
        tour.order.iter().map(|&k| &self.sweeps.cells[k as usize][tour.choice[k as usize] as usize])
    }

    /// The path of `tour`: from `start` through the chosen sweeps, joined by wall-free routes,
    /// then the strips left uncovered as `completion` says, then to `end`; with the targets it
    /// had to skip.
    pub fn path(
        &self,
        tour: &Tour,
        robot: &crate::coverage::Footprint,
        stations: (Point, Point),
        completion: Completion,
    ) -> (Vec<Point>, usize) {
        let (start, end) = stations;
        let mut route = GrowingRoute::new(start);
        for w in self.sweeps_of(tour) {
            route.drive(&self.clear, &w.points);
        }
        self.complete(route, robot, end, completion)
    }

    /// `route` (a tour's sweeps or a control's lanes) with the strips it leaves uncovered
    /// visited as `completion` says, then driven to `end`; with the targets it had to skip.
    pub fn complete(
        &self,
        mut route: GrowingRoute,
        robot: &crate::coverage::Footprint,
        end: Point,
        completion: Completion,
    ) -> (Vec<Point>, usize) {
        let width = robot.width;
        match completion {
            Completion::None => {}
            Completion::Greedy => crate::lanes::complete::complete(&self.clear, &self.reach, width, &mut route),
            Completion::Quota | Completion::QuotaSearch => {
                let searched = completion == Completion::QuotaSearch;
                quota::complete(&self.clear, &self.reach, robot, (self.coverage_goal, searched), &mut route)
            }
            Completion::Boundary | Completion::Cells => {
                let map = self.clear.map();
                let grid = crate::coverage::CoverageGrid::new(map);
                let mut covered = vec![false; grid.len()];
                for w in route.points().windows(2) {
                    crate::coverage::raster::for_each_swept_cell(grid.raster(), w[0], w[1], width, |i| {
                        covered[i] = true
                    });
                }
                // Every uncovered coverable cell: the plan aims at full coverage of the
                // reachable space; the greedy pass takes what the chains leave.
                let targets: Vec<bool> = covered.iter().zip(self.reach.coverable()).map(|(&c, &k)| k && !c).collect();
                let chains = boundary::chains(&self.clear, &targets);
                for chain in boundary::order(&chains, route.last(), Some(end), robot.speed) {
                    for p in chain {
                        route.go(&self.clear, p);
                    }
                }
                crate::lanes::complete::complete(&self.clear, &self.reach, width, &mut route);
            }
        }
        route.finish(&self.clear, end);
        let skipped = route.skipped();
        // Repaired here, so that the plans a run chooses among are scored as they will be
        // driven; the run checks the one it returns.
        (crate::planner::executable::repaired(&self.clear, width, route.into_points()), skipped)
    }
}

/// The cell-order plan without its GA: the nearest-neighbour tour improved by the memetic
/// step's local search (best choices, Or-opt, 2-opt) until none improves, which is the memetic
/// GA's first individual, driven as [`Prepared::path`] drives a tour with the section's
/// `directions`, `completion_m_per_m2` and `completion`. It reads no random stream, so every
/// run of a configuration gets the same plan; the thesis GA seeds its population with it
/// (`thesis.seed_population = ["cell_order"]`).
pub fn local_optimum_plan(scenario: &Scenario, section: &config::CellOrderSection) -> Result<Vec<Point>, String> {
    local_optimum_plan_within(scenario, section, None)
}

/// [`local_optimum_plan`] whose preparation is refused past `deadline` (see [`prepare_within`]).
pub fn local_optimum_plan_within(
    scenario: &Scenario,
    section: &config::CellOrderSection,
    deadline: Option<(Instant, std::time::Duration)>,
) -> Result<Vec<Point>, String> {
    let planning = scenario.for_planning();
    let cutoff = SetupCutoff { wall_clock: deadline, interrupt: None };
    // The seed is the whole plan: a quota completion takes every piece (the section's
    // coverage goal is not read here).
    let how = Preparation { coverage_goal: None, ..Preparation::of(section) };
    let prepared = prepare_within(&planning, how, &cutoff).map_err(|e| e.to_string())?;
    let mut tour = search::nearest_neighbour(&prepared.instance);
    local::improve(&prepared.instance, &mut tour, search::ROUNDS);
    Ok(prepared.path(&tour, &scenario.robot, (scenario.start, scenario.end), section.completion).0)
}
