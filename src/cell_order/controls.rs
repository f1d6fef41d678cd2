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
use super::merged_lanes::LaneLayout;
use super::search;
use super::tour::Tour;
use crate::coverage::curve::CoverageCurve;
use crate::geom::Point;
use crate::planner::Scenario;

/// Without a coverage goal, plans whose reachable coverage lies this close to the best one's
/// count as covering as much (a few cells on a real map), and the fastest of them is kept.
pub const COVERAGE_TIE: f64 = 0.005;

/// The nearest-neighbour tour at each of `directions` alone (a cell with no sweep at it takes
/// any of its own) and each of the `layouts` ([`LaneLayout::control_layouts`]: `true` takes a
/// cell's split sweeps where it has them at that direction, its joined ones where not): the
/// no-search control's tours, direction by direction within each layout.
pub fn direction_tours(prepared: &Prepared, directions: &[f64], layouts: &[bool]) -> Vec<Tour> {
    let cells = &prepared.sweeps.cells;
    let has_split = |k: usize, d: f64| cells[k].iter().any(|w| w.split && w.direction_deg == d);
    layouts
        .iter()
        .flat_map(|&split| directions.iter().map(move |&d| (split, d)))
        .map(|(split, d)| {
            search::nearest_neighbour_among(&prepared.instance, |k, c| {
                let w = &cells[k][c];
                w.direction_deg == d && (w.split == split || (split && !has_split(k, d)))
            })
        })
        .collect()
}

/// The lane direction and layout (`true`: split) of the control plan at `index` among the plans
/// [`direction_tours`] or [`boustrophedon_plans`] make for `directions` and `layouts`.
pub fn control_plan(directions: &[f64], layouts: &[bool], index: usize) -> (f64, bool) {
    (directions[index % directions.len()], layouts[index / directions.len()])
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
/// lanes joined across small obstacles as the searches' are ([`super::merged_lanes`]), and
/// where `layout` offers split lanes, then at each direction again with its lanes split at
/// every obstacle ([`control_plan`] names each plan); from the start station, completed as
/// `completion` says and driven to the end station.
pub fn boustrophedon_plans(
    prepared: &Prepared,
    scenario: &Scenario,
    directions: &[f64],
    (completion, layout): (Completion, LaneLayout),
) -> Result<Vec<Lanes>, String> {
    use crate::lanes::boustrophedon::{decompose, lane_pieces, plan, sweep_cells_with};
    let robot = &scenario.robot;
    let clear = &prepared.clear;
    let join = super::merged_lanes::LaneJoin::new(clear, layout.merge_gap_m, robot.width);
    let layouts = layout.control_layouts();
    (0..directions.len() * layouts.len())
        .map(|i| {
            let (d, split) = control_plan(directions, layouts, i);
            let route = if layout.merge_gap_m > 0.0 && !split {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_plans_run_through_the_directions_within_each_layout() {
        let dirs = [0.0, 45.0, 90.0];
        for (layouts, index, want) in [
            (&[false][..], 0, (0.0, false)),
            (&[false][..], 2, (90.0, false)),
            (&[false, true][..], 1, (45.0, false)),
            (&[false, true][..], 3, (0.0, true)),
            (&[false, true][..], 5, (90.0, true)),
        ] {
            assert_eq!(control_plan(&dirs, layouts, index), want, "{layouts:?} {index}");
        }
        assert_eq!(LaneLayout::joined(2.4).control_layouts(), &[false]);
        assert_eq!(LaneLayout { merge_gap_m: 2.4, split_too: true }.control_layouts(), &[false, true]);
        assert_eq!(LaneLayout { merge_gap_m: 0.0, split_too: true }.control_layouts(), &[false], "nothing to split");
    }
}
