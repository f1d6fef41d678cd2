//! The memory `eval` needs, estimated from the map's size and the robot's width before anything
//! large is allocated, and checked against the limit runs are checked against
//! ([`crate::io::memory`]): `--max-memory` when given, else the least of the memory available,
//! the control group's limit and the resource limits. A narrow robot on coarse cells is planned
//! on a refined raster ([`crate::map::refine`]) whose size grows with the square of the split,
//! and a large map is scored cell by cell: either can ask for gigabytes.

use super::UseCaseError;
use crate::io::human_bytes;
use crate::io::memory::{MemoryLimit, memory_limit};
use crate::map::GridMap;
use crate::map::refine::{PLANNING_BYTES_PER_CELL, check_planning_size, planning_size};

/// Bytes per map cell that reading and scoring hold, an upper estimate: the decoded image, the
/// map and its copy before the obstacles, the clearance and reachable sets, the coverage grid,
/// the scorer's visit counts, camera band and curve, the figure. Measured: the peak resident
/// memory of `eval --path` on all-free maps of 1 and 4 million cells grows by 115 bytes a cell.
const SCORING_BYTES_PER_CELL: f64 = 128.0;

/// What `eval` holds whatever the map: the program, the font, the figure buffers.
const BASELINE_BYTES: f64 = 32e6;

/// An upper estimate of `eval`'s memory on `map` for a robot `width` metres wide, with a
/// pattern planned when `planned`; with what it is, in words.
pub fn estimate(map: &GridMap, width: f64, planned: bool) -> (f64, String) {
    let cells = map.cols() as f64 * map.rows() as f64;
    let mut bytes = BASELINE_BYTES + SCORING_BYTES_PER_CELL * cells;
    let mut what = format!("map `{}` of {} × {} cells", map.name(), map.cols(), map.rows());
    if planned {
        let (cols, rows) = planning_size(map, width);
        bytes += PLANNING_BYTES_PER_CELL * cols as f64 * rows as f64;
        if (cols, rows) != (map.cols() as u64, map.rows() as u64) {
            what.push_str(&format!(
                " planned on {cols} × {rows} cells of {} m for a robot {} m wide",
                crate::io::short_number(map.resolution() * map.cols() as f64 / cols as f64),
                crate::io::short_number(width)
            ));
        }
    }
    (bytes, what)
}

/// Refuses an `eval` of `map` for a robot `width` metres wide (a pattern planned when
/// `planned`) whose planning raster exceeds the cap on cells, or whose estimate exceeds the
/// memory limit (`max_memory` when given), naming the flag to change.
pub fn check(map: &GridMap, width: f64, planned: bool, max_memory: Option<u64>) -> Result<(), UseCaseError> {
    if planned {
        // The lanes' own cap first: it names the narrowest width a pattern is planned for.
        crate::lanes::check_lane_count(map, width).map_err(|e| UseCaseError::Input(format!("--width: {e}")))?;
        check_planning_size(map, width, "--width").map_err(UseCaseError::Input)?;
    }
    let Some(limit) = memory_limit(max_memory) else { return Ok(()) };
    refuse_over(map, width, planned, &limit)
}

/// The refusal of [`check`] against a known `limit`.
fn refuse_over(map: &GridMap, width: f64, planned: bool, limit: &MemoryLimit) -> Result<(), UseCaseError> {
    let (bytes, what) = estimate(map, width, planned);
    if bytes <= limit.bytes as f64 {
        return Ok(());
    }
    let refined = planned && planning_size(map, width) != (map.cols() as u64, map.rows() as u64);
    let change = if refined {
        "give a wider --width (cells coarser than half the width are split to a quarter of it), a map with finer \
         cells, or more memory"
    } else {
        "give a smaller map (crop it, or a coarser resolution), or more memory"
    };
    let flag = if refined { format!("--width = {} m", crate::io::short_number(width)) } else { "--map".to_string() };
    Err(UseCaseError::Input(format!(
        "{flag}: eval would need up to about {} ({what}), more than the memory limit of {} ({}; --max-memory \
         sets another): {change}",
        human_bytes(bytes),
        human_bytes(limit.bytes as f64),
        limit.bound
    )))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::memory::MemoryBound;
    use crate::map::presets::preset;

    fn limit(bytes: u64) -> MemoryLimit {
        MemoryLimit { bytes, bound: MemoryBound::Given }
    }

    #[test]
    fn a_narrow_robot_on_coarse_cells_is_refused_by_its_planning_raster() {
        let m = preset("thesis-1").unwrap();
        // 0.6 m on 0.2 m cells is planned on the map as it is: a few hundred kB.
        assert!(refuse_over(&m, 0.6, true, &limit(1 << 30)).is_ok());
        // 0.004 m splits each cell 200 × 200: 11 000 × 11 000 cells.
        let Err(UseCaseError::Input(m4)) = refuse_over(&m, 0.004, true, &limit(1 << 30)) else { panic!() };
        assert!(m4.starts_with("--width = 0.004 m") && m4.contains("11000 × 11000") && m4.contains("15.5 GB"), "{m4}");
        // Scoring a path alone plans nothing.
        assert!(refuse_over(&m, 0.004, false, &limit(1 << 30)).is_ok());
        // 0.001 m would split each cell 800 × 800, past the cap on cells whatever the memory.
        let Err(UseCaseError::Input(m1)) = check(&m, 0.001, true, Some(u64::MAX)) else { panic!() };
        assert!(m1.contains("--width = 0.001 m") && m1.contains("268435456") && m1.contains("at least"), "{m1}");
    }

    #[test]
    fn a_large_map_is_refused_naming_the_map() {
        let m = preset("thesis-1").unwrap();
        let Err(UseCaseError::Input(msg)) = refuse_over(&m, 0.6, true, &limit(1_000_000)) else { panic!() };
        assert!(msg.starts_with("--map:") && msg.contains("55 × 55") && msg.contains("--max-memory"), "{msg}");
    }
}
