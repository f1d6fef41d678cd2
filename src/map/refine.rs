//! The raster the routing planners plan on: the map itself, or, where its cells are coarse
//! against the robot, the same map with every cell split into `k × k` cells of its state.
//!
//! Why: the patterns and the cell-order planner place the robot's centre at cell centres
//! (connecting moves are A* over them) and test its clearance at samples a fraction of a cell
//! apart. On cells coarser than half the robot's width, a gap the body fits through can hold no
//! cell centre with the clearance (a 1 m gap between pillars on 0.5 m cells: the centres lie
//! 0.25 m from the pillars, a 0.6 m robot needs 0.3 m), so the start's component shrinks to a few
//! cells and a plan "covers" nothing of a reachable map; and the samples lie so far apart that a
//! move can pass a pillar's corner deeper than the body rule allows. Splitting the cells changes
//! no geometry (each new cell lies inside one old cell of the same state), so a plan made on the
//! refined raster is a plan on the map, scored on the map as given.
//!
//! Maps with cells at most half the robot's width are planned as they are (every committed
//! study's map is such a map, and its plans stay what they were), unless a passage the scorer
//! counts open holds no cell centre the robot fits at ([`super::passages`]).

use super::GridMap;
use std::borrow::Cow;

/// The coarsest cell, as a fraction of the robot's width, that is planned on as it is.
pub const MAX_CELL_PER_WIDTH: f64 = 0.5;

/// The cell size, as a fraction of the robot's width, that a coarser map is refined to (at most).
pub const REFINED_CELL_PER_WIDTH: f64 = 0.25;

/// How many times [`refinement`]'s least split it may grow to open passages of whole cells.
pub const MAX_PASSAGE_SPLIT: usize = 2;

/// How many cells each cell of a map of `resolution` metres per cell is split into along each
/// axis for a robot `width` metres wide: 1 where `resolution ≤ width/2`; else the least `k`
/// with `resolution / k ≤ width/4`, raised (up to [`MAX_PASSAGE_SPLIT`] times) until the
/// narrowest passage of whole cells the robot fits through holds a cell centre it fits at.
///
/// Why the second rule: such a passage (a door or a gap between pillars `g` = `n · resolution`
/// wide, the least multiple of the cell above the width) lets the robot's centre through only
/// within `(g − width)/2` of its middle, and its middle is a cell border or a cell centre of the
/// map. A refined raster of cells `ρ` has a centre within `ρ/2` of any line, so `ρ < g − width`
/// keeps the passage open to the planners as it is to the scorer (a 0.9 m robot on 0.5 m cells
/// between pillars 1 m apart: `ρ` = 0.083 m, where 0.167 m closed the passage).
pub fn refinement(resolution: f64, width: f64) -> usize {
    if !(width > 0.0 && resolution.is_finite()) || resolution <= MAX_CELL_PER_WIDTH * width {
        return 1;
    }
    let k = (resolution / (REFINED_CELL_PER_WIDTH * width) - 1e-9).ceil().max(1.0) as usize;
    let passage = ((width / resolution + 1e-9).floor() + 1.0) * resolution;
    // A margin of 1 %: the passage's centre must fit with more than rounding to spare.
    let open = (1.01 * resolution / (passage - width)).ceil().max(1.0) as usize;
    k.max(open.min(MAX_PASSAGE_SPLIT * k))
}

/// `map` with every cell split into `k × k` cells of the same state (the same frame, name and
/// extent; `k = 1` is a copy).
pub fn refined(map: &GridMap, k: usize) -> GridMap {
    let (cols, rows) = (map.cols() * k, map.rows() * k);
    let mut cells = Vec::with_capacity(cols * rows);
    for r in 0..rows {
        for c in 0..cols {
            cells.push(map.state(r / k, c / k));
        }
    }
    GridMap::new(map.name(), cols, rows, map.resolution() / k as f64, map.origin(), cells)
        .expect("a refined map has the free cells of its map and a positive resolution")
        .scored_on(map.scored_resolution())
}

/// Per cell of `map` refined by `k` ([`refined`]), the flag of the cell of `map` it lies in.
pub fn refined_flags(map: &GridMap, flags: &[bool], k: usize) -> Vec<bool> {
    let cols = map.cols() * k;
    (0..map.rows() * k * cols).map(|i| flags[map.index(i / cols / k, i % cols / k)]).collect()
}

/// The raster a routing planner plans on for a robot `width` metres wide: `map` itself where
/// its cells are fine enough, else `map` refined by [`refinement`].
pub fn planning_map(map: &GridMap, width: f64) -> Cow<'_, GridMap> {
    match refinement(map.resolution(), width) {
        1 => Cow::Borrowed(map),
        k => Cow::Owned(refined(map, k)),
    }
}

/// The most cells a planning raster may have: the cap on a map's cells
/// ([`super::ros::MAX_MAP_CELLS`]), so that no width refines a map past what could be loaded.
pub const MAX_PLANNING_CELLS: u64 = super::ros::MAX_MAP_CELLS;

/// Bytes per cell of the raster a pattern is planned on, an upper estimate: the refined map,
/// its clearance, the reachable set, the lanes' and the completion pass's layers. Measured: the
/// peak resident memory of `eval` on thesis-1 for robots 0.05 and 0.03 m wide (refined rasters
/// of 0.8 and 2.2 million cells) grows by 103 bytes a cell.
pub const PLANNING_BYTES_PER_CELL: f64 = 128.0;

/// Columns and rows of the raster [`planning_map`] plans `map` on for a robot `width` metres
/// wide, computed without building it.
pub fn planning_size(map: &GridMap, width: f64) -> (u64, u64) {
    let k = refinement(map.resolution(), width) as u64;
    (map.cols() as u64 * k, map.rows() as u64 * k)
}

/// Refuses a robot `width` metres wide (named `width_name` in the message) for which `map`'s
/// planning raster would have more than [`MAX_PLANNING_CELLS`] cells, naming its size and the
/// least width that stays within the cap; checked before anything is allocated.
pub fn check_planning_size(map: &GridMap, width: f64, width_name: &str) -> Result<(), String> {
    let (cols, rows) = planning_size(map, width);
    let cells = cols as f64 * rows as f64;
    if cells <= MAX_PLANNING_CELLS as f64 {
        return Ok(());
    }
    let k = refinement(map.resolution(), width);
    // The largest split that stays within the cap, and the least width that asks for no more.
    let k_max = ((MAX_PLANNING_CELLS as f64 / (map.cols() * map.rows()) as f64).sqrt().floor()).max(1.0);
    let min_width = ((map.resolution() / (REFINED_CELL_PER_WIDTH * k_max)) * 1e4).ceil() / 1e4;
    let short = crate::io::short_number;
    Err(format!(
        "{width_name} = {} m: the planners split map `{}`'s {} m cells {k} × {k} for so narrow a robot (to cells of \
         at most a quarter of its width), a raster of {cols} × {rows} = {cells:.3e} cells, more than the \
         {MAX_PLANNING_CELLS} a map may have; give {width_name} of at least {} m, or a map with finer cells",
        short(width),
        map.name(),
        short(map.resolution()),
        short(min_width),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point;
    use crate::map::CellState;

    #[test]
    fn refinement_only_where_cells_are_coarser_than_half_the_width() {
        // (resolution, width, k)
        let table = [
            (0.05, 0.6, 1),
            (0.2, 0.4, 1),
            (0.3, 0.6, 1),
            // The 0.62 m passage needs cells under 0.02 m: the split stops at twice the least.
            (0.31, 0.6, 6),
            (0.4, 0.6, 3),
            (0.45, 0.6, 3),
            (0.5, 0.6, 4),
            // Pillars 1 m apart and a 0.9 m robot: cells under 0.1 m (the least split gives 0.167).
            (0.5, 0.9, 6),
            (0.5, 0.3, 7),
            (0.5, f64::NAN, 1),
        ];
        for (res, width, k) in table {
            assert_eq!(refinement(res, width), k, "resolution {res}, width {width}");
        }
    }

    /// A split map's edges are its map's to the bit: `n·(res/k)` differs from `n/k·res` in the
    /// last bit for about one split in five, enough for a plan at the clearance limit off the
    /// split map's edge to leave the map it is scored on.
    #[test]
    fn a_refined_map_has_its_maps_edges_to_the_bit() {
        let mut differ = 0;
        for i in 0..400 {
            let res = 0.1 + 0.5 * (i as f64 * 0.618_033_988_749_895).fract();
            let (cols, rows, k) = (2 + i % 17, 3 + i % 11, 2 + i % 39);
            let m =
                GridMap::new("m", cols, rows, res, Point::new(-1.3, 2.7), vec![CellState::Free; cols * rows]).unwrap();
            let r = refined(&m, k);
            assert_eq!((r.width_m(), r.height_m()), (m.width_m(), m.height_m()), "res {res}, k {k}");
            differ += usize::from((cols * k) as f64 * (res / k as f64) != m.width_m());
        }
        assert!(differ > 20, "the rounding this guards against occurs: {differ} of 400");
    }

    #[test]
    fn a_refined_map_has_the_same_geometry() {
        use CellState::{Free as F, Occupied as O, Unknown as U};
        let m = GridMap::new("m", 3, 2, 0.5, Point::new(1.0, -2.0), vec![F, O, U, F, F, O]).unwrap();
        let r = refined(&m, 3);
        assert_eq!((r.cols(), r.rows(), r.resolution(), r.origin()), (9, 6, 0.5 / 3.0, m.origin()));
        assert_eq!((r.width_m(), r.height_m()), (m.width_m(), m.height_m()));
        for row in 0..r.rows() {
            for col in 0..r.cols() {
                let p = r.cell_centre(row, col);
                let (mr, mc) = m.cell_at(p).unwrap();
                assert_eq!(r.state(row, col), m.state(mr, mc), "cell ({row}, {col})");
            }
        }
        assert_eq!(r.free_count(), 9 * m.free_count());
        let flags = refined_flags(&m, &[true, false, false, false, true, true], 3);
        assert_eq!(flags.iter().filter(|f| **f).count(), 27);
        assert!(flags[r.index(0, 0)] && !flags[r.index(0, 3)] && flags[r.index(5, 8)]);
        assert!(matches!(planning_map(&m, 2.0), Cow::Borrowed(_)));
        assert_eq!(planning_map(&m, 0.6).resolution(), 0.125);
    }
}
