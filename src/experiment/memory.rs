//! Memory guards: an upper estimate of what a run will allocate, checked against a limit
//! before anything large is allocated. The limit is `--max-memory` when given, else the least
//! of the memory available, the control group's limit and the resource limits
//! ([`crate::io::memory`]); a grid multiplies the largest run's estimate by the runs it
//! executes at once.

use super::file::Experiment;
use crate::config::ConfigError;
use crate::io::human_bytes;
pub use crate::planner::memory::MemoryEstimate;

/// Bytes per map cell every run holds whatever its planner: the map, the reachable set, the
/// scorer's visit counts and camera band.
const COMMON_BYTES_PER_CELL: f64 = 24.0;

/// What any run holds besides its planner and map: the program, the embedded font, the figure
/// buffers (a 1000 × 1200 RGB picture is 3.6 MB) and the output writers. Measured peak RSS of
/// the small shipped experiments is 14–17 MB.
const BASELINE_BYTES: f64 = 32e6;

pub use crate::io::memory::{MemoryLimit, memory_limit};

impl Experiment {
    /// An upper estimate of the run's memory when it runs on `threads` threads.
    pub fn memory_estimate(&self, threads: usize) -> MemoryEstimate {
        let map = &self.scenario.map;
        let cells = (map.rows() * map.cols()) as f64;
        let common = COMMON_BYTES_PER_CELL * cells;
        let mut e = self.planner.memory_estimate(map, threads);
        e.bytes += common + BASELINE_BYTES;
        let width = self.scenario.robot.width;
        let (cols, rows) = crate::map::refine::planning_size(map, width);
        if self.file.planner.plans_on_refined_raster() && (cols, rows) != (map.cols() as u64, map.rows() as u64) {
            // A narrow robot on coarse cells: planned on the map split k × k (`map::refine`).
            e.bytes += crate::map::refine::PLANNING_BYTES_PER_CELL * cols as f64 * rows as f64;
            e.key = "robot.width";
            e.what = format!("{}, planned on {cols} × {rows} cells for a robot {width} m wide", e.what);
        }
        e
    }

    /// Refuses the run (naming the key, the estimate and the limit) when `parallel` runs like it,
    /// each on `threads` threads, would need more than `limit` bytes; returns the estimate
    /// otherwise.
    pub fn check_memory(
        &self,
        origin: &str,
        limit: Option<&MemoryLimit>,
        parallel: usize,
        threads: usize,
    ) -> Result<MemoryEstimate, ConfigError> {
        let e = self.memory_estimate(threads);
        let Some(limit) = limit else { return Ok(e) };
        let parallel = parallel.max(1);
        let total = e.bytes * parallel as f64;
        if total <= limit.bytes as f64 {
            return Ok(e);
        }
        let times =
            if parallel > 1 { format!(" × {parallel} runs at once = {}", human_bytes(total)) } else { String::new() };
        Err(ConfigError::new(
            origin,
            e.key,
            format!(
                "would need up to about {} per run ({} on a {} × {} map){times}, more than the memory limit of {} \
                 ({}; --max-memory sets another)",
                human_bytes(e.bytes),
                e.what,
                self.scenario.map.cols(),
                self.scenario.map.rows(),
                human_bytes(limit.bytes as f64),
                limit.bound
            ),
        ))
    }
}
