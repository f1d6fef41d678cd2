//! The controls a cell-order search has to beat to earn its place, built from the same
//! decomposition, routes and completion as the search, with no search at all:
//!
//! - the no-search control (`solver = "nearest"`): at each lane direction alone, the
//!   nearest-neighbour tour of the cells (each cell at that direction, entered at its nearest
//!   corner), completed as the search's plans are;
//! - the classical control (`solver = "boustrophedon"`): one boustrophedon over the whole
//!   reachable map at each lane direction, with the search's own completion rather than the
//!   patterns' greedy one, so that a comparison measures the order and not the completion.
//!
//! Each control hands one plan per direction to the common scorer, which keeps the fastest
//! (to the coverage goal where there is one, else among the plans within [`COVERAGE_TIE`] of
//! the best coverage). Neither reads the seed.

use super::Prepared;
use super::config::Completion;
use super::search;
use super::tour::Tour;
use crate::coverage::curve::CoverageCurve;
use crate::geom::Point;
use crate::planner::Scenario;

/// Without a coverage goal, plans whose reachable coverage lies this close to the best one's
/// count as covering as much (a few cells on a real map), and the fastest of them is kept.
pub const COVERAGE_TIE: f64 = 0.005;

/// The nearest-neighbour tour at each of `directions` alone (a cell with no sweep at it takes
/// any of its own): the no-search control's tours, in the order of `directions`.
pub fn direction_tours(prepared: &Prepared, directions: &[f64]) -> Vec<Tour> {
    let cells = &prepared.sweeps.cells;
    directions
        .iter()
        .map(|&d| search::nearest_neighbour_among(&prepared.instance, |k, c| cells[k][c].direction_deg == d))
        .collect()
}

/// The classical control's plan at one lane direction.
#[derive(Clone, Debug)]
pub struct Lanes {
    /// The lane direction in degrees.
    pub direction_deg: f64,
    /// The path from the start station to the end station.
    pub path: Vec<Point>,
    /// Targets the route could not reach and skipped.
    pub skipped: usize,
}

/// A boustrophedon over the whole reachable map of `prepared` at each of `directions`, its
/// lanes joined across gaps of up to `merge_gap_m` as the searches' are
/// ([`super::merged_lanes`]), from the start station, completed as `completion` says and
/// driven to the end station.
pub fn boustrophedon_plans(
    prepared: &Prepared,
    scenario: &Scenario,
    directions: &[f64],
    (completion, merge_gap_m): (Completion, f64),
) -> Result<Vec<Lanes>, String> {
    use crate::patterns::boustrophedon::{decompose, lane_pieces, plan, sweep_cells_with};
    let robot = &scenario.robot;
    let clear = &prepared.clear;
    let join = super::merged_lanes::LaneJoin::new(clear, merge_gap_m, robot.width);
    directions
        .iter()
        .map(|&d| {
            let route = if merge_gap_m > 0.0 {
                let cells = decompose(&join.joined(lane_pieces(clear, robot.width, d)));
                if cells.is_empty() {
                    return Err(format!("boustrophedon at {d}°: no lane of a robot {} m wide fits", robot.width));
                }
                sweep_cells_with(clear, &cells, scenario.start, true)
            } else {
                plan(clear, robot.width, d, scenario.start).map_err(|e| format!("boustrophedon at {d}°: {e}"))?
            };
            let (path, skipped) = prepared.complete(route, robot, scenario.end, completion);
            Ok(Lanes { direction_deg: d, path, skipped })
        })
        .collect()
}

/// The index of the fastest plan (by its curve's last time) among those whose final coverage
/// lies within [`COVERAGE_TIE`] of the best; the first of equals.
pub fn fastest_at_best_coverage(curves: &[CoverageCurve]) -> usize {
    let last = |c: &CoverageCurve| c.points().last().copied().unwrap_or((0.0, 0.0));
    let best = curves.iter().map(|c| last(c).1).fold(f64::NEG_INFINITY, f64::max);
    let mut chosen: Option<usize> = None;
    for (i, c) in curves.iter().enumerate() {
        let (t, cov) = last(c);
        if cov >= best - COVERAGE_TIE && chosen.is_none_or(|j| t < last(&curves[j]).0) {
            chosen = Some(i);
        }
    }
    chosen.unwrap_or(0)
}
