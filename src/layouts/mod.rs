//! The idealised single-direction lane control (`planner = "layouts"`, issue 102 item 1): a
//! plan any search over lane layouts has to beat, made with no search. Straight lanes run
//! through the cell centres where the robot fits (the scorer's clearance rule) and that the
//! start reaches, at the best of a few directions, spacings and offsets of the first lane
//! ([`lanes`]); each lane piece is trimmed to where it sweeps new cells, and short leftovers
//! are dropped. The pieces are driven in the greedy nearest order by wall-free grid distance,
//! each entered at its nearer end ([`order`]), joined by the project's wall-free routes, then
//! the shared completion covers what the lanes leave and the plan ends at its coverage goal
//! and drives back to its station ([`crate::lanes`]). The common scorer's time to the goal
//! chooses among the layouts with the best estimates. Boustrophedon coverage as in Choset
//! (2000); the single-direction baseline against which Bähnemann et al. (2019) measure their
//! sweep search.

pub mod config;
pub mod entry;
pub mod fill;
pub mod lanes;
pub mod order;
pub mod planner;

/// An open room of `w × h` cells of 0.05 m inside a wall ring, for the tests.
#[cfg(test)]
pub(crate) fn room(w: usize, h: usize) -> crate::map::GridMap {
    use crate::map::CellState;
    let cells = (0..w * h)
        .map(|i| {
            let (r, c) = (i / w, i % w);
            let wall = r == 0 || c == 0 || r == h - 1 || c == w - 1;
            if wall { CellState::Occupied } else { CellState::Free }
        })
        .collect();
    crate::map::GridMap::new("room", w, h, 0.05, crate::geom::Point::origin(), cells).expect("a free cell")
}
