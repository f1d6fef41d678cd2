//! The common scorer: every plan of every planner measured the same way, so that studies
//! compare planners only through these numbers (the ablation is fair by construction).
//!
//! - Footprint model (003 §3.1, Listing 3.1): the robot's swept rectangles on one shared visit
//!   map, `cov_final` (eq. 3.6), `t_final` (eqs. 3.7–3.10), `f` (eqs. 3.14–3.16).
//! - Camera model (000 §II-C.1, eq. 1): 000's forward camera posed every [`CAMERA_STEP_M`]
//!   metres along each path and at its vertices, looking along the path; coverage of the
//!   wall band and of the open space of the working raster.
//! - Motion: length, turns, total turn, time at the robot's speed with rotation (eqs. 3.1–3.3)
//!   per agent, their sum and the makespan (the slowest agent).
//!
//! Coverage is reported over two denominators, named in every field: `_free`, all free cells
//! (the thesis's `A_pix`), and `_reach`, the cells the footprint can sweep from the stations
//! ([`crate::map::reach::Reach`]; for the camera, the free pixels connected to the stations).

use super::views::CameraLayer;
use super::{CoverageGrid, Footprint, SweepScratch, motion};
use crate::coverage::fitness::{Projection, f_obstacle};
use crate::geom::Point;
use crate::map::GridMap;
use crate::map::reach::Reach;

/// Spacing of camera poses along a path in metres.
pub const CAMERA_STEP_M: f64 = 1.0;

/// The most camera poses a scoring of a given path may take (`covga eval --path`, Python's
/// `score`): each costs up to about 9 000 pixel tests with 000's default camera, so this bounds
/// a scoring at about half a minute on one core.
pub const MAX_CAMERA_POSES: u64 = 200_000;

/// Refuses `paths` whose scoring would pose the camera more than [`MAX_CAMERA_POSES`] times,
/// with the count and how far to thin them.
pub fn check_camera_poses(paths: &[Vec<Point>]) -> Result<(), String> {
    let poses = camera_poses(paths);
    if poses <= MAX_CAMERA_POSES {
        return Ok(());
    }
    let points: usize = paths.iter().map(Vec::len).sum();
    Err(format!(
        "scoring its {points} points would pose the camera {poses} times (at both ends of each segment and every {CAMERA_STEP_M} m between); at most {MAX_CAMERA_POSES} poses are scored: thin the path first (e.g. keep one point in {})",
        poses.div_ceil(MAX_CAMERA_POSES).max(2)
    ))
}

/// How many times the common scorer poses the camera along `paths`: at both ends of every
/// segment longer than a nanometre and every [`CAMERA_STEP_M`] between (as `coverage` does),
/// so that callers can bound the work before scoring.
pub fn camera_poses(paths: &[Vec<Point>]) -> u64 {
    paths
        .iter()
        .flat_map(|path| path.windows(2))
        .map(|w| {
            let len = (w[1] - w[0]).norm();
            if len < 1e-9 { 0 } else { (len / CAMERA_STEP_M).ceil() as u64 + 1 }
        })
        .sum()
}

/// 000's camera as the scorer uses it (metres and degrees), with the working raster's scale
/// and the width of the wall band whose coverage is reported.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct CameraSpec {
    /// Pixel scale of the working raster (m/px).
    pub scale: f64,
    /// `d_min` (m).
    pub d_min: f64,
    /// `d_max` (m).
    pub d_max: f64,
    /// `θ_fov` (degrees).
    pub fov_deg: f64,
    /// `m` sections.
    pub sections: usize,
    /// Width of the wall band `B` (m): free pixels this close to an obstacle.
    pub band_m: f64,
}

/// Everything the scorer measures of one plan. Field names say which denominator a coverage
/// uses (`_free` or `_reach`).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct Score {
    /// Paths in the plan.
    pub agents: usize,
    /// Whether a robot can drive the plan: its body (a disc of the robot's width) touches no
    /// occupied or unknown cell and stays on the map at every point of every path, vertices,
    /// turns and end caps included ([`crate::map::body`]; the one executability rule of every
    /// planner's plans).
    pub executable: bool,
    /// `cov_final` over all free cells (003 eq. 3.6 with `A_pix` = free cells).
    pub cov_final_free: f64,
    /// `cov_final` over the cells the footprint can reach.
    pub cov_final_reach: f64,
    /// `t_final` (003 eq. 3.10; it does not depend on the denominator).
    pub t_final: f64,
    /// `f_obstacle` of (t_final, cov_final_free) with the experiment's projection.
    pub f_free: f64,
    /// `f_obstacle` of (t_final, cov_final_reach).
    pub f_reach: f64,
    /// Distinct free cells swept.
    pub unique_cells: u64,
    /// Distinct reachable cells swept.
    pub unique_reach_cells: u64,
    /// `cov_pix`: free-cell sweeps.
    pub cells_swept: u64,
    /// `cross_pix`: sweeps of cells already swept.
    pub crossings: u64,
    /// Distinct occupied or unknown cells the robot's body touches along the plan
    /// ([`crate::map::body::BodyContact::wall_cells`]).
    pub obstacle_cells: u64,
    /// `obj_pix` (003 eq. 3.13): sweeps of obstacle cells by the footprint's rectangles, the
    /// count 003's penalty `f_obstacle` reads (so `f_free` and `f_reach` are 003's).
    pub obstacle_sweeps: u64,
    /// Free cells (`A_pix`).
    pub free_cells: u64,
    /// Cells the footprint can sweep from the stations.
    pub reachable_cells: u64,
    /// Free cells the footprint cannot reach, in pockets.
    pub pocket_cells: u64,
    /// Camera coverage of the wall band, all of it.
    pub cam_walls_free: f64,
    /// Camera coverage of the open (free) space, all of it.
    pub cam_open_free: f64,
    /// Camera coverage of the wall band connected to the stations.
    pub cam_walls_reach: f64,
    /// Camera coverage of the free space connected to the stations.
    pub cam_open_reach: f64,
    /// Total path length in metres.
    pub length_m: f64,
    /// Non-zero turns.
    pub turns: u64,
    /// Total absolute turn in radians.
    pub total_turn_rad: f64,
    /// Sum over agents of length / speed + turn / rotation speed, in seconds.
    pub time_s: f64,
    /// The slowest agent's time in seconds.
    pub makespan_s: f64,
    /// Each agent's path length in metres.
    pub agent_length_m: Vec<f64>,
    /// Each agent's time in seconds.
    pub agent_time_s: Vec<f64>,
}

impl Score {
    /// Why the plan is not executable, in words (for a plan that is not).
    pub fn not_executable_why(&self) -> String {
        if self.obstacle_cells > 0 {
            format!("the robot's body touches {} occupied or unknown cells", self.obstacle_cells)
        } else {
            "the robot's body reaches past the map's edge".to_string()
        }
    }

    /// The scalar metrics as `(column, value)` pairs, in a fixed order (the common columns of
    /// `runs.csv`).
    pub fn columns(&self) -> Vec<(&'static str, String)> {
        vec![
            ("agents", self.agents.to_string()),
            ("executable", self.executable.to_string()),
            ("cov_final_free", self.cov_final_free.to_string()),
            ("cov_final_reach", self.cov_final_reach.to_string()),
            ("t_final", self.t_final.to_string()),
            ("f_free", self.f_free.to_string()),
            ("f_reach", self.f_reach.to_string()),
            ("unique_cells", self.unique_cells.to_string()),
            ("unique_reach_cells", self.unique_reach_cells.to_string()),
            ("cells_swept", self.cells_swept.to_string()),
            ("crossings", self.crossings.to_string()),
            ("obstacle_cells", self.obstacle_cells.to_string()),
            ("obstacle_sweeps", self.obstacle_sweeps.to_string()),
            ("free_cells", self.free_cells.to_string()),
            ("reachable_cells", self.reachable_cells.to_string()),
            ("pocket_cells", self.pocket_cells.to_string()),
            ("cam_walls_free", self.cam_walls_free.to_string()),
            ("cam_open_free", self.cam_open_free.to_string()),
            ("cam_walls_reach", self.cam_walls_reach.to_string()),
            ("cam_open_reach", self.cam_open_reach.to_string()),
            ("length_m", self.length_m.to_string()),
            ("turns", self.turns.to_string()),
            ("total_turn_rad", self.total_turn_rad.to_string()),
            ("time_s", self.time_s.to_string()),
            ("makespan_s", self.makespan_s.to_string()),
        ]
    }
    /// The column names of [`Score::columns`].
    pub fn column_names() -> Vec<&'static str> {
        Score::default().columns().into_iter().map(|(k, _)| k).collect()
    }
}

/// Distinct cells of the last sweep in `scratch` (swept on the grid `reach` was made for)
/// that `reach` counts as coverable: the numerator of the scorer's `cov_final_reach`.
pub fn reached_cells(reach: &Reach, scratch: &SweepScratch) -> u64 {
    scratch.visit_counts().filter(|&(i, _)| reach.is_coverable(i as usize)).count() as u64
}

/// `cov_final` over the cells `reach` counts as coverable, of the last sweep in `scratch`
/// (the scorer's `cov_final_reach`, for per-generation records).
pub fn reach_coverage(reach: &Reach, scratch: &SweepScratch) -> f64 {
    reached_cells(reach, scratch) as f64 / reach.coverable_count().max(1) as f64
}

/// Scores plans on one map for one robot, camera and set of stations.
pub struct Scorer {
    grid: CoverageGrid,
    map: GridMap,
    robot: Footprint,
    resolution: f64,
    projection: Projection,
    reach: Reach,
    camera: CameraLayer,
}

impl Scorer {
    /// Prepares the layers: visit grid, reachable cells from `stations`, camera raster.
    pub fn new(
        map: &GridMap,
        robot: Footprint,
        projection: Projection,
        camera: &CameraSpec,
        stations: &[Point],
    ) -> Self {
        Self::for_widths(map, robot, &[robot.width], projection, camera, stations)
    }

    /// As [`Scorer::new`] for a team whose robots have the widths `widths`: the reachable
    /// cells are those of the narrowest (it can sweep every cell a wider robot can from the
    /// same stations); `robot` gives the speeds of eq. 3.10.
    pub fn for_widths(
        map: &GridMap,
        robot: Footprint,
        widths: &[f64],
        projection: Projection,
        camera: &CameraSpec,
        stations: &[Point],
    ) -> Self {
        let narrowest = widths.iter().copied().fold(robot.width, f64::min);
        let reach = Reach::for_width(map, narrowest, stations);
        Self {
            grid: CoverageGrid::new(map),
            map: map.clone(),
            robot,
            resolution: map.resolution(),
            projection,
            reach,
            camera: CameraLayer::new(map, camera, stations),
        }
    }

    /// The visit grid plans are swept on.
    pub fn grid(&self) -> &CoverageGrid {
        &self.grid
    }

    /// The reachable part of the map.
    pub fn reach(&self) -> &Reach {
        &self.reach
    }

    /// `cov_final` over all free cells only (cheap: one sweep; for per-generation records).
    pub fn footprint_coverage(&self, scratch: &mut SweepScratch, paths: &[Vec<Point>]) -> f64 {
        let counts = scratch.sweep_all(&self.grid, paths, self.robot.width);
        counts.unique() as f64 / self.grid.area_cells().max(1) as f64
    }

    /// The layers behind the plan's coverage, one entry per cell in the map's row-major order
    /// (row 0 at the bottom): how many times the footprints swept each free cell (path `k`
    /// of width `widths[k]`; obstacle cells 0), as `cov_final_free` counts them; which cells
    /// count as coverable for `cov_final_reach` is [`Reach::coverable`] of [`Self::reach`].
    pub fn visits(&self, paths: &[Vec<Point>], widths: &[f64]) -> Vec<u32> {
        let mut scratch = SweepScratch::new(&self.grid);
        let mut shares = vec![super::SweepCounts::default(); paths.len()];
        scratch.sweep_fleet(&self.grid, paths, widths, &mut shares);
        (0..self.grid.len()).map(|i| scratch.visits(i)).collect()
    }

    /// Every metric of a plan (one path per agent), every agent the scorer's robot.
    pub fn score(&self, paths: &[Vec<Point>]) -> Score {
        self.score_agents(paths, &vec![self.robot; paths.len()])
    }

    /// Every metric of a plan whose path `k` is driven by `robots[k]` (its width, speed and
    /// rotation speed): the swept cells, executability and times each at that robot's own.
    pub fn score_agents(&self, paths: &[Vec<Point>], robots: &[Footprint]) -> Score {
        assert_eq!(paths.len(), robots.len(), "one robot per path");
        let mut scratch = SweepScratch::new(&self.grid);
        let widths: Vec<f64> = robots.iter().map(|r| r.width).collect();
        let m = self.robot.measure_fleet(&self.grid, &mut scratch, paths, &widths);
        let unique_reach = reached_cells(&self.reach, &scratch);
        let th = crate::coverage::fitness::score(&m, &self.robot, self.resolution, self.projection);
        let reachable = self.reach.coverable_count() as u64;
        let cov_reach = unique_reach as f64 / reachable.max(1) as f64;
        let f_reach = f_obstacle(self.projection.apply(th.t_final, cov_reach), m.obstacle_cells);
        let (mut lengths, mut times) = (Vec::new(), Vec::new());
        for (p, r) in paths.iter().zip(robots) {
            let len = motion::path_length(p);
            let (turn, _) = motion::turning(p);
            lengths.push(len);
            times.push(r.time_s(len, turn));
        }
        let body = crate::map::body::contact(&self.map, paths, &widths);
        // Pose by pose: for one plan that is faster than segment masks, which help only when
        // segments come again (`benches/camera.rs`).
        let [cam_walls_free, cam_open_free, cam_walls_reach, cam_open_reach] = self.camera.coverage_by_pose(paths);
        Score {
            agents: paths.len(),
            executable: body.is_clear(),
            cov_final_free: th.cov_final,
            cov_final_reach: cov_reach,
            t_final: th.t_final,
            f_free: th.fitness,
            f_reach,
            unique_cells: m.unique_cells,
            unique_reach_cells: unique_reach,
            cells_swept: m.cells_swept,
            crossings: m.crossings,
            obstacle_cells: body.wall_cells,
            obstacle_sweeps: m.obstacle_cells,
            free_cells: m.area_cells,
            reachable_cells: reachable,
            pocket_cells: self.reach.pocket_cells() as u64,
            cam_walls_free,
            cam_open_free,
            cam_walls_reach,
            cam_open_reach,
            length_m: m.length_m,
            turns: m.turns,
            total_turn_rad: m.total_turn_rad,
            time_s: times.iter().sum(),
            makespan_s: times.iter().copied().fold(0.0, f64::max),
            agent_length_m: lengths,
            agent_time_s: times,
        }
    }
}

/// The violation of a plan that sweeps obstacle cells, in words (none when it sweeps none):
/// such a path is not drivable, the thesis's only hard constraint.
pub fn obstacle_violations(obstacle_cells: u64) -> Vec<String> {
    if obstacle_cells == 0 { Vec::new() } else { vec![format!("the path sweeps {obstacle_cells} obstacle cells")] }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::presets::preset;

    fn camera() -> CameraSpec {
        CameraSpec { scale: 0.15, d_min: 0.2, d_max: 7.0, fov_deg: 69.4, sections: 15, band_m: 0.45 }
    }

    #[test]
    fn a_lane_on_map_1_by_hand() {
        // thesis-ga §3.3 case 1: (1.3, 1.3) → (4.3, 1.3) sweeps 45 free cells, no crossing.
        let map = preset("thesis-1").unwrap();
        let robot = Footprint { width: 0.6, speed: 0.2, rot_speed: 0.0 };
        let s = Scorer::new(&map, robot, Projection::F2, &camera(), &[Point::new(1.3, 1.3)]);
        let sc = s.score(&[vec![Point::new(1.3, 1.3), Point::new(4.3, 1.3)]]);
        assert_eq!((sc.unique_cells, sc.cells_swept, sc.crossings, sc.obstacle_cells), (45, 45, 0, 0));
        assert_eq!(sc.free_cells, 2025);
        // Map 1 is a 45 x 45-cell open room: every free cell is reachable by a 0.6 m disc.
        assert_eq!(sc.reachable_cells, 2025);
        assert_eq!(sc.unique_reach_cells, 45);
        assert!((sc.cov_final_free - 45.0 / 2025.0).abs() < 1e-15);
        assert_eq!(sc.cov_final_free, sc.cov_final_reach);
        assert!((sc.length_m - 3.0).abs() < 1e-12 && (sc.time_s - 15.0).abs() < 1e-12);
        assert_eq!(sc.makespan_s, sc.time_s);
        assert!(sc.cam_walls_free > 0.0 && sc.cam_walls_free < 1.0 && sc.cam_open_free > 0.0);
    }

    #[test]
    fn the_visit_layer_holds_the_scores_cells_and_crossings() {
        // A lane there and back over its own cells, and a second agent across it.
        let map = preset("thesis-1").unwrap();
        let robot = Footprint { width: 0.6, speed: 0.2, rot_speed: 0.0 };
        let s = Scorer::new(&map, robot, Projection::F2, &camera(), &[Point::new(1.3, 1.3)]);
        let paths = vec![
            vec![Point::new(1.3, 1.3), Point::new(4.3, 1.3), Point::new(1.3, 1.3)],
            vec![Point::new(2.0, 0.5), Point::new(2.0, 3.0)],
        ];
        let sc = s.score(&paths);
        let visits = s.visits(&paths, &[0.6, 0.6]);
        assert_eq!(visits.len(), map.rows() * map.cols());
        assert_eq!(visits.iter().filter(|&&v| v > 0).count() as u64, sc.unique_cells);
        assert_eq!(visits.iter().map(|&v| u64::from(v)).sum::<u64>(), sc.cells_swept);
        let reached = visits.iter().zip(s.reach().coverable()).filter(|(v, c)| **v > 0 && **c).count();
        assert_eq!(reached as u64, sc.unique_reach_cells);
        // Row 0 is the bottom row (0.2 m cells): the cell centred at (2.1, 1.3) m is swept by the
        // lane both ways and by the second agent; (4.1, 1.3) by the lane both ways.
        let at = |x: f64, y: f64| visits[(y / 0.2) as usize * map.cols() + (x / 0.2) as usize];
        assert_eq!((at(2.1, 1.3), at(4.1, 1.3), at(2.1, 2.5), at(4.1, 3.5)), (3, 2, 1, 0));
    }

    /// Two rooms split by a thick wall: the camera's `_reach` figures count only the room of
    /// the station, whose every seen pixel is reachable, so they are the `_free` figures over a
    /// smaller denominator. (The path keeps 2.5 m from the wall: at close range eq. 1's
    /// sections can fall between the centres of a thin wall's pixels and see past it.)
    #[test]
    fn camera_reach_figures_count_the_station_s_room_only() {
        use crate::map::{CellState, GridMap};
        let (cols, rows) = (100, 40);
        let mut cells = vec![CellState::Free; cols * rows];
        for r in 0..rows {
            for c in 0..cols {
                if r == 0 || c == 0 || r == rows - 1 || c == cols - 1 || (60..66).contains(&c) {
                    cells[r * cols + c] = CellState::Occupied;
                }
            }
        }
        let map = GridMap::new("two-rooms", cols, rows, 0.1, Point::origin(), cells).unwrap();
        let robot = Footprint { width: 0.6, speed: 0.2, rot_speed: 0.0 };
        let s = Scorer::new(&map, robot, Projection::F2, &camera(), &[Point::new(1.0, 1.0)]);
        let counts = s.camera.counts;
        assert!(counts[3] < counts[1] && counts[2] < counts[0], "the far room is not reachable: {counts:?}");
        let sc = s.score(&[vec![Point::new(1.0, 1.0), Point::new(1.0, 3.0), Point::new(3.5, 3.0)]]);
        let hits = |share: f64, of: usize| (share * of as f64).round() as usize;
        let (walls, open) = (hits(sc.cam_walls_free, counts[0]), hits(sc.cam_open_free, counts[1]));
        assert!(walls > 0 && open > walls);
        assert_eq!(hits(sc.cam_walls_reach, counts[2]), walls);
        assert_eq!(hits(sc.cam_open_reach, counts[3]), open);
        assert!(sc.cam_open_reach > sc.cam_open_free);
        // The footprint's own share, cheap form: unique cells over all free cells.
        let mut scratch = SweepScratch::new(s.grid());
        let share = s.footprint_coverage(&mut scratch, &[vec![Point::new(1.0, 1.0), Point::new(1.0, 3.0)]]);
        let lane = s.score(&[vec![Point::new(1.0, 1.0), Point::new(1.0, 3.0)]]);
        assert!(share > 0.0);
        assert_eq!(share, lane.unique_cells as f64 / lane.free_cells as f64);
    }

    /// Time per agent is its length at the robot's speed plus its turns at `R_rot` (eqs.
    /// 3.1–3.3): 5 m at 0.2 m/s and a quarter turn at 0.5 rad/s.
    #[test]
    fn agent_time_adds_the_turns_at_the_rotation_speed() {
        let map = preset("thesis-1").unwrap();
        let robot = Footprint { width: 0.6, speed: 0.2, rot_speed: 0.5 };
        let s = Scorer::new(&map, robot, Projection::F2, &camera(), &[Point::new(1.3, 1.3)]);
        let path = vec![Point::new(1.3, 1.3), Point::new(4.3, 1.3), Point::new(4.3, 3.3)];
        let sc = s.score(&[path]);
        let expected = 25.0 + std::f64::consts::PI;
        assert!((sc.agent_time_s[0] - expected).abs() < 1e-9, "{}", sc.agent_time_s[0]);
        assert_eq!((sc.time_s, sc.makespan_s), (sc.agent_time_s[0], sc.agent_time_s[0]));
    }

    /// The columns of `runs.csv` in their order, each value written as Rust writes it.
    #[test]
    fn score_columns_are_named_and_ordered_with_their_values() {
        let sc = Score { agents: 3, cov_final_free: 0.25, crossings: 17, makespan_s: 12.5, ..Score::default() };
        let cols = sc.columns();
        assert_eq!(cols.len(), 25);
        assert_eq!(cols[0], ("agents", "3".to_string()));
        assert_eq!(cols[1], ("executable", "false".to_string()));
        assert_eq!(cols[2], ("cov_final_free", "0.25".to_string()));
        assert_eq!(cols[10], ("crossings", "17".to_string()));
        assert_eq!(cols[24], ("makespan_s", "12.5".to_string()));
        assert_eq!(Score::column_names(), cols.iter().map(|(k, _)| *k).collect::<Vec<_>>());
        let mut names = Score::column_names();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), 25, "no column twice");
    }

    #[test]
    fn makespan_is_the_slowest_agent_and_agents_share_one_visit_map() {
        let map = preset("thesis-1").unwrap();
        let robot = Footprint { width: 0.6, speed: 0.2, rot_speed: 0.0 };
        let s = Scorer::new(&map, robot, Projection::F2, &camera(), &[Point::new(1.3, 1.3)]);
        let a = vec![Point::new(1.3, 1.3), Point::new(4.3, 1.3)];
        let b = vec![Point::new(1.3, 1.3), Point::new(2.3, 1.3)];
        let sc = s.score(&[a.clone(), b]);
        assert_eq!(sc.agents, 2);
        assert!((sc.makespan_s - 15.0).abs() < 1e-12 && (sc.time_s - 20.0).abs() < 1e-12);
        // The second agent re-sweeps cells of the first: crossings, no new unique cells.
        assert_eq!(sc.unique_cells, 45);
        assert!(sc.crossings > 0);
        assert!((sc.agent_length_m[0] - 3.0).abs() < 1e-12 && (sc.agent_length_m[1] - 1.0).abs() < 1e-12);
    }
}
