//! Memory guards: an upper estimate of what a run will allocate, checked against a limit
//! before anything large is allocated. The limit is `--max-memory` when given, else the memory
//! the operating system can still give (`MemAvailable`); a grid multiplies the largest run's
//! estimate by the runs it executes at once.

use super::config::ConfigError;
use super::experiment::Experiment;
use crate::io::human_bytes;
use crate::planner::PlannerConfig;

/// What a run is estimated to need, and the key that drives it (named when it is refused).
#[derive(Clone, Debug, PartialEq)]
pub struct MemoryEstimate {
    /// Bytes, an upper estimate.
    pub bytes: f64,
    /// The experiment-file key that mostly decides the size.
    pub key: &'static str,
    /// What is being allocated, in words (`1000 individuals of up to 200 actions`).
    pub what: String,
}

/// Bytes per map cell every run holds whatever its planner: the map, the reachable set, the
/// scorer's visit counts and camera band.
const COMMON_BYTES_PER_CELL: f64 = 24.0;

/// What any run holds besides its planner and map: the program, the embedded font, the figure
/// buffers (a 1000 × 1200 RGB picture is 3.6 MB) and the output writers. Measured peak RSS of
/// the small shipped experiments is 14–17 MB.
const BASELINE_BYTES: f64 = 32e6;

/// Bytes of a map-sized bit set stored as 64-bit words.
fn bitset_bytes(cells: f64) -> f64 {
    8.0 * (cells / 64.0).ceil()
}

/// The limit runs are checked against: `max_memory` when given, else the memory available now;
/// `None` where neither is known (no check).
pub fn memory_limit(max_memory: Option<u64>) -> Option<u64> {
    max_memory.or_else(crate::io::available_memory)
}

impl Experiment {
    /// An upper estimate of the run's memory when it runs on `threads` threads.
    pub fn memory_estimate(&self, threads: usize) -> MemoryEstimate {
        let map = &self.scenario.map;
        let cells = (map.rows() * map.cols()) as f64;
        let common = COMMON_BYTES_PER_CELL * cells;
        let mut e = match &self.planner {
            PlannerConfig::Thesis(t) => {
                let p = &t.params;
                MemoryEstimate {
                    bytes: crate::thesis::config::memory_estimate(p, map.rows(), map.cols(), threads),
                    key: if p.initial_size() > p.pop_min { "thesis.init_individuals" } else { "thesis.pop_min" },
                    what: format!("{} individuals of up to {} actions", p.initial_size(), p.max_genome_len),
                }
            }
            PlannerConfig::Waypoint(w) => waypoint_estimate(w, map),
            PlannerConfig::Pattern(_) => {
                MemoryEstimate { bytes: 0.0, key: "map.source", what: format!("a pattern on {} cells", cells) }
            }
            PlannerConfig::RandomSearch(r) => MemoryEstimate {
                bytes: r.batch as f64 * (32.0 * r.init.actions as f64 + bitset_bytes(cells)),
                key: "thesis.pop_min",
                what: format!("batches of {} random genomes", r.batch),
            },
        };
        e.bytes += common + BASELINE_BYTES;
        e
    }

    /// Refuses the run (naming the key, the estimate and the limit) when `parallel` runs like it,
    /// each on `threads` threads, would need more than `limit` bytes; returns the estimate
    /// otherwise.
    pub fn check_memory(
        &self,
        origin: &str,
        limit: Option<u64>,
        parallel: usize,
        threads: usize,
    ) -> Result<MemoryEstimate, ConfigError> {
        let e = self.memory_estimate(threads);
        let Some(limit) = limit else { return Ok(e) };
        let parallel = parallel.max(1);
        let total = e.bytes * parallel as f64;
        if total <= limit as f64 {
            return Ok(e);
        }
        let times =
            if parallel > 1 { format!(" × {parallel} runs at once = {}", human_bytes(total)) } else { String::new() };
        Err(ConfigError::new(
            origin,
            e.key,
            format!(
                "would need up to about {} per run ({} on a {} × {} map){times}, more than the memory limit of {} \
                 (the memory available unless --max-memory sets it)",
                human_bytes(e.bytes),
                e.what,
                self.scenario.map.cols(),
                self.scenario.map.rows(),
                human_bytes(limit as f64)
            ),
        ))
    }
}

/// The waypoint planner's world: at most one waypoint per (grid step or anti-crowding
/// distance, the smaller)² of free space, each with
/// at most 16 directed edges (its nearest neighbour per octant, and the reverse of its
/// neighbours' choices: `waypoint::graph`), each edge holding two views stored as the
/// words between their first and last pixel (a view spans at most `2·d_max` rows, a swept edge
/// `max_traverse + width` rows); and the population's paths.
fn waypoint_estimate(w: &crate::waypoint::config::WaypointConfig, map: &crate::map::GridMap) -> MemoryEstimate {
    use crate::waypoint::world::Objective;
    let p = &w.world;
    let px = map.resolution() / p.scale; // work-raster pixels per map cell (per axis)
    let (cols, rows) = (map.cols() as f64 * px, map.rows() as f64 * px);
    let step_px = (p.geometry.grid_step.min(p.geometry.merge) / p.scale).max(1.0);
    let free_px = map.free_count() as f64 * px * px;
    let waypoints = (free_px / (step_px * step_px)).ceil().max(1.0);
    let degree = 16f64.min(waypoints - 1.0).max(1.0);
    let span_rows = match p.objective {
        Objective::Camera => 2.0 * p.d_max / p.scale + 1.0,
        Objective::Footprint { width } => (p.max_traverse + width) / p.scale + 1.0,
    }
    .min(rows);
    let view_bytes = bitset_bytes(span_rows * cols) + 16.0;
    let edges = waypoints * degree;
    let paths = w.ga.population as f64 * 2.0 * w.ga.agents as f64 * 4.0 * (w.ga.l_init as f64 + 64.0);
    MemoryEstimate {
        bytes: edges * 2.0 * (view_bytes + 48.0) + 4.0 * bitset_bytes(cols * rows) + paths,
        key: "waypoint.hallway",
        what: format!("up to {waypoints:.0} waypoints with {edges:.0} edge views"),
    }
}
