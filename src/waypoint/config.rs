//! The `[waypoint]` section of an experiment file (000 Table I as reconciled, waypoint §18–19) and
//! its validation into the waypoint planner's typed parameters.

use crate::config::{ConfigError, check_range, check_unit};
use crate::coverage::score::CameraSpec;
use crate::geom::Point;
use crate::map::GridMap;
use crate::planner::Context;
use crate::planner::memory::{MemoryEstimate, bitset_bytes};
use crate::planner::section::{Placement, Section, SectionDecl};
use serde::{Deserialize, Serialize};

/// `[waypoint]` as the waypoint planner's entry declares it.
pub static WAYPOINT_SECTION: Section<WaypointSection> = Section::new(
    SectionDecl {
        name: "waypoint",
        readers: "only the waypoint planner (and the thesis GA's camera objective, alpha_cov) reads",
        placement: Placement::BeforeBudget,
        always_held: true,
        type_name: "WaypointSection",
        tables: &[],
        source: include_str!("config.rs"),
    },
    Some(WaypointSection::default),
);

/// `[waypoint]`: 000 Table I as reconciled (waypoint §18–19); metres, degrees. The camera and its
/// raster are the common scorer's (`[scorer.camera]`), which the planner's camera objective
/// measures.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WaypointSection {
    /// UAV width (m).
    pub uav_width: f64,
    /// Narrowest accessible hallway `h_min` (m): sets the waypoint grid step and, by default,
    /// the safety buffer (000 §II-B.2).
    pub hallway: f64,
    /// Waypoint grid step: `half_hallway` (000 §II-B.2, default) or `hallway` (the authors'
    /// driver: `floor(h_min / s)` px).
    pub grid_step: super::geometry::GridStep,
    /// Safety buffer (m): waypoints are nudged at least this far from walls, and the wall term
    /// `C_walls` of eq. 2 scores this band. Default `h_min / 2` (the authors' driver; 000 asks
    /// only that it exceed half the UAV width, which is checked).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub safety_buffer: Option<f64>,
    /// Anti-crowding distance (m): waypoints closer than this are merged. Default: the grid
    /// step (000 §II-B.2).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub merge_distance: Option<f64>,
    /// Width of the wall band scored by `C_walls` (m). Default: the safety buffer (000 eq. 2).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wall_band: Option<f64>,
    /// `waypoint_set = "near_wall"` keeps waypoints at most this far from a wall (m). Default
    /// 2.5 × the safety buffer (the authors' driver; 000 does not say how near).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub near_wall: Option<f64>,
    /// Maximum traverse distance of an edge (m).
    pub max_traverse: f64,
    /// `sections` (000 eq. 1, default) or `fan` (the authors' code's polygon view).
    pub view_shape: crate::coverage::camera::ViewShape,
    /// `full` or `near_wall`.
    pub waypoint_set: super::world::WaypointSet,
    /// `camera` (000) or `footprint`: what the coverage objective measures; the footprint is
    /// the experiment's robot width swept along each edge.
    pub objective: super::world::ObjectiveKind,
    /// Number of agents.
    pub agents: usize,
    /// Per-agent entry positions (m); empty = all start at `stations.start`.
    pub starts: Vec<[f64; 2]>,
    /// `N`: organisms per generation (000 Table I).
    pub population: usize,
    /// Generations `G` (W29).
    pub generations: u32,
    /// `p_c`: crossover probability (000 Table I).
    pub p_c: f64,
    /// `p_A`: probability of mutation A, the tail regrown (000 Table I).
    pub p_a: f64,
    /// `p_B`: probability of mutation B, the shortcut search (000 Table I).
    pub p_b: f64,
    /// `γ`: fitness pressure of the parent sampling (000 §III-A.6, W28).
    pub gamma: f64,
    /// `l_init`: initial path length in waypoints (W15).
    pub l_init: usize,
    /// `l_min`: shortest path in waypoints (000 Table I).
    pub l_min: usize,
    /// `l_max`: longest path in waypoints (000 Table I).
    pub l_max: usize,
    /// `T_x`: the largest difference of the crossover waypoint's positions in the two parents
    /// (000 Table I, W17).
    pub crossover_threshold: usize,
    /// `n_B`: shortcut tries per mutation B (000 Table I).
    pub b_instances: usize,
    /// `D`: mutation B's search distance in waypoints (000 Table I).
    pub b_distance: usize,
    /// `p_acc`: probability of taking a shortcut found (000 Table I).
    pub b_accept: f64,
    /// `M`: path memory in waypoints, not revisited while a path grows (000 Table I).
    pub memory: usize,
    /// `λ`: log-scale turning weight of the forward bias (000 Table I, W14).
    pub lambda: f64,
    /// `ρ`: turning cost factor of the flight time (000 eq. 3).
    pub rho: f64,
    /// `α_cov`: weight of open space against walls in the coverage (000 eq. 2, W11).
    pub alpha_cov: f64,
    /// `C_start`: coverage required at generation 0 (000 Table I, W22).
    pub c_start: f64,
    /// `C_end`: coverage required after the ramp (000 Table I, W22).
    pub c_end: f64,
    /// `G_age`: generations of the coverage ramp (000 Table I, W22).
    pub aging: u32,
    /// `T_sep`: the least separation along the path of a self loop closure, in waypoints (000
    /// Table I, W23).
    pub lc_separation: usize,
    /// Minimum self loop closures (Table I: 2).
    pub lc_min: usize,
    /// What counts as one loop closure: `run` (a run of consecutive re-flown edges, W23,
    /// default) or `edge` (every distinct re-flown edge, the authors' driver).
    pub lc_rule: super::evaluate::LoopClosureRule,
    /// Penalty per violated constraint type (scaled units).
    pub penalty: f64,
}

impl Default for WaypointSection {
    fn default() -> Self {
        Self {
            uav_width: 0.5,
            hallway: 1.5,
            grid_step: super::geometry::GridStep::HalfHallway,
            safety_buffer: None,
            merge_distance: None,
            wall_band: None,
            near_wall: None,
            max_traverse: 4.0,
            view_shape: crate::coverage::camera::ViewShape::Sections,
            waypoint_set: super::world::WaypointSet::Full,
            objective: super::world::ObjectiveKind::Camera,
            agents: 1,
            starts: Vec::new(),
            population: 100,
            generations: 1000,
            p_c: 0.7,
            p_a: 0.3,
            p_b: 0.3,
            gamma: 0.5,
            l_init: 150,
            l_min: 75,
            l_max: 250,
            crossover_threshold: 70,
            b_instances: 20,
            b_distance: 5,
            b_accept: 0.8,
            memory: 10,
            lambda: 0.7,
            rho: 8.0,
            alpha_cov: 0.1,
            c_start: 0.3,
            c_end: 0.8,
            aging: 60,
            lc_separation: 30,
            lc_min: 2,
            lc_rule: super::evaluate::LoopClosureRule::Run,
            penalty: 1000.0,
        }
    }
}

/// The longest path `waypoint.l_max` allows: 400 times 000's 250, far beyond any map here,
/// and a bound on the work of one generation.
pub const MAX_PATH_WAYPOINTS: usize = 100_000;
/// The most shortcut tries of one mutation B (`waypoint.b_instances`): 500 times 000's 20.
pub const MAX_B_INSTANCES: usize = 10_000;

/// The validated waypoint planner: world geometry and GA parameters.
#[derive(Clone, Debug)]
pub struct WaypointConfig {
    /// Geometry.
    pub world: super::world::WorldParams,
    /// GA.
    pub ga: super::run::WaypointGaParams,
}

impl WaypointSection {
    /// Why the waypoint planner with these settings does not read `key` (a dotted key or a
    /// section of the planner sections), or `None` when it reads it.
    pub fn why_unread(&self, key: &str) -> Option<String> {
        if key == "waypoint.alpha_cov" && self.objective == super::world::ObjectiveKind::Footprint {
            return Some(
                "waypoint.objective = \"footprint\" measures the swept area; only the camera objective blends walls and open floor by alpha_cov".into(),
            );
        }
        (key == "waypoint.near_wall" && self.waypoint_set == super::world::WaypointSet::Full)
            .then(|| "waypoint.waypoint_set = \"full\" keeps every waypoint; only \"near_wall\" reads it".into())
    }

    /// Validates this section against the scenario's map and start.
    pub fn validate(&self, ctx: &Context) -> Result<WaypointConfig, ConfigError> {
        let scenario = ctx.scenario;
        let mut c = validate(self, ctx.origin, &scenario.map, scenario.start, &scenario.camera)?;
        if self.objective == super::world::ObjectiveKind::Footprint {
            c.world.objective = super::world::WaypointObjective::Footprint { width: scenario.robot.width };
        }
        Ok(c)
    }
}

impl WaypointConfig {
    /// An upper estimate of the planner's memory on `map`: at most one waypoint per (grid step
    /// or anti-crowding distance, the smaller)² of free space, each with at most 16 directed
    /// edges (its nearest neighbour per octant, and the reverse of its neighbours' choices:
    /// `waypoint::graph`), each edge holding two views stored as the words between their first
    /// and last pixel (a view spans at most `2·d_max` rows, a swept edge `max_traverse + width`
    /// rows); and the population's paths.
    pub fn memory_estimate(&self, map: &GridMap) -> MemoryEstimate {
        use super::world::WaypointObjective;
        let w = self;
        let p = &w.world;
        let px = map.resolution() / p.scale; // work-raster pixels per map cell (per axis)
        let (cols, rows) = (map.cols() as f64 * px, map.rows() as f64 * px);
        let step_px = (p.geometry.grid_step.min(p.geometry.merge) / p.scale).max(1.0);
        let free_px = map.free_count() as f64 * px * px;
        let waypoints = (free_px / (step_px * step_px)).ceil().max(1.0);
        let degree = 16f64.min(waypoints - 1.0).max(1.0);
        let span_rows = match p.objective {
            WaypointObjective::Camera => 2.0 * p.d_max / p.scale + 1.0,
            WaypointObjective::Footprint { width } => (p.max_traverse + width) / p.scale + 1.0,
        }
        .min(rows);
        let view_bytes = bitset_bytes(span_rows * cols) + 16.0;
        let edges = waypoints * degree;
        // Paths grow up to l_max waypoints (mutation A extends them to a length in [len, l_max]).
        let paths = w.ga.population as f64 * 2.0 * w.ga.agents as f64 * 4.0 * (w.ga.ops.l_max as f64 + 64.0);
        let views = edges * 2.0 * (view_bytes + 48.0) + 4.0 * bitset_bytes(cols * rows);
        let (key, what) = if paths > views {
            ("waypoint.l_max", format!("{} paths of up to {} waypoints per agent", 2 * w.ga.population, w.ga.ops.l_max))
        } else {
            ("waypoint.hallway", format!("up to {waypoints:.0} waypoints with {edges:.0} edge views"))
        };
        MemoryEstimate { bytes: views + paths, key, what }
    }
}

/// Range checks of `[waypoint]` and the conversion into planner parameters, with the common
/// scorer's camera (`[scorer.camera]`, checked with the scenario): the planner's camera
/// objective (000 eq. 1) is that camera's coverage, on its raster.
fn validate(
    w: &WaypointSection,
    origin: &str,
    map: &GridMap,
    start: Point,
    camera: &CameraSpec,
) -> Result<WaypointConfig, ConfigError> {
    check_range(origin, "waypoint.uav_width", w.uav_width, 1e-4, 100.0, "[1e-4, 100] metres")?;
    let geometry = super::geometry::Geometry::resolve(w, camera.scale, origin, map)?;
    check_team(w, origin, map)?;
    check_ga(w, origin)?;
    check_view_and_weights(w, origin, map, camera)?;
    let starts: Vec<(f64, f64)> =
        if w.starts.is_empty() { vec![(start.x, start.y)] } else { w.starts.iter().map(|s| (s[0], s[1])).collect() };
    Ok(config_of(w, geometry, starts, camera))
}

/// The moves and the team: `max_traverse`, `agents` and their `starts` (free stations).
fn check_team(w: &WaypointSection, origin: &str, map: &GridMap) -> Result<(), ConfigError> {
    let err = |key: &str, msg: String| ConfigError::new(origin, key, msg);
    check_range(origin, "waypoint.max_traverse", w.max_traverse, 1e-4, 1e6, "[1e-4, 1e6] metres")?;
    if w.agents == 0 || w.agents > 64 {
        return Err(err("waypoint.agents", format!("= {} is out of range [1, 64]", w.agents)));
    }
    if !(w.starts.is_empty() || w.starts.len() == 1 || w.starts.len() == w.agents) {
        return Err(err(
            "waypoint.starts",
            format!("has {} entries: give none, one shared, or one per agent ({})", w.starts.len(), w.agents),
        ));
    }
    for (k, s) in w.starts.iter().enumerate() {
        map.check_station(Point::new(s[0], s[1]), &format!("start of agent {k}"))
            .map_err(|m| err("waypoint.starts", m))?;
    }
    Ok(())
}

/// The GA's probabilities, population, path lengths and shortcut tries.
fn check_ga(w: &WaypointSection, origin: &str) -> Result<(), ConfigError> {
    let err = |key: &str, msg: String| ConfigError::new(origin, key, msg);
    for (key, v) in [
        ("waypoint.p_c", w.p_c),
        ("waypoint.p_a", w.p_a),
        ("waypoint.p_b", w.p_b),
        ("waypoint.gamma", w.gamma),
        ("waypoint.b_accept", w.b_accept),
        ("waypoint.alpha_cov", w.alpha_cov),
        ("waypoint.c_start", w.c_start),
        ("waypoint.c_end", w.c_end),
    ] {
        check_unit(origin, key, v)?;
    }
    if w.population < 2 || w.population > 1_000_000 {
        return Err(err("waypoint.population", format!("= {} is out of range [2, 1000000]", w.population)));
    }
    if !(2 <= w.l_min && w.l_min <= w.l_init && w.l_init <= w.l_max) {
        return Err(err(
            if w.l_min < 2 { "waypoint.l_min" } else { "waypoint.l_init" },
            format!("needs 2 <= l_min ({}) <= l_init ({}) <= l_max ({})", w.l_min, w.l_init, w.l_max),
        ));
    }
    if w.l_max > MAX_PATH_WAYPOINTS {
        return Err(err(
            "waypoint.l_max",
            format!("= {} is out of range [l_init, {MAX_PATH_WAYPOINTS}] waypoints per path", w.l_max),
        ));
    }
    if w.b_instances > MAX_B_INSTANCES {
        return Err(err(
            "waypoint.b_instances",
            format!("= {} is out of range [0, {MAX_B_INSTANCES}] shortcut tries per mutation B", w.b_instances),
        ));
    }
    Ok(())
}

/// The camera's reach for a fan view, and the objective's weights.
fn check_view_and_weights(
    w: &WaypointSection,
    origin: &str,
    map: &GridMap,
    camera: &CameraSpec,
) -> Result<(), ConfigError> {
    let err = |key: &str, msg: String| ConfigError::new(origin, key, msg);
    let diagonal = map.width_m().hypot(map.height_m());
    if w.view_shape == crate::coverage::camera::ViewShape::Fan && camera.d_max > diagonal {
        return Err(err(
            "scorer.camera.d_max",
            format!(
                "= {} m is beyond the map's diagonal of {diagonal:.2} m; a fan view is drawn through its ray ends at d_max, so with view_shape = \"fan\" it must be at most {diagonal:.2} m (with \"sections\" a longer d_max is capped at the map and sees the same)",
                camera.d_max
            ),
        ));
    }
    check_range(origin, "waypoint.lambda", w.lambda, 0.0, 100.0, "[0, 100]")?;
    check_range(origin, "waypoint.rho", w.rho, 0.0, 100.0, "[0, 100]")?;
    check_range(origin, "waypoint.penalty", w.penalty, 0.0, 1e12, "[0, 1e12]")?;
    Ok(())
}

/// The validated planner of a checked section (000's camera world and GA).
fn config_of(
    w: &WaypointSection,
    geometry: super::geometry::Geometry,
    starts: Vec<(f64, f64)>,
    camera: &CameraSpec,
) -> WaypointConfig {
    use super::evaluate::ObjectiveParams;
    use super::operators::OperatorParams;
    WaypointConfig {
        world: super::world::WorldParams {
            scale: camera.scale,
            uav_width: w.uav_width,
            hallway: w.hallway,
            geometry,
            max_traverse: w.max_traverse,
            d_min: camera.d_min,
            d_max: camera.d_max,
            fov_deg: camera.fov_deg,
            sections: camera.sections,
            view_shape: w.view_shape,
            set: w.waypoint_set,
            starts,
            objective: super::world::WaypointObjective::Camera,
        },
        ga: super::run::WaypointGaParams {
            population: w.population,
            generations: w.generations,
            p_c: w.p_c,
            p_a: w.p_a,
            p_b: w.p_b,
            gamma: w.gamma,
            l_init: w.l_init,
            agents: w.agents,
            ops: OperatorParams {
                lambda: w.lambda,
                memory: w.memory,
                l_min: w.l_min,
                l_max: w.l_max,
                crossover_threshold: w.crossover_threshold,
                b_instances: w.b_instances,
                b_distance: w.b_distance,
                b_accept: w.b_accept,
            },
            objectives: ObjectiveParams {
                alpha_cov: w.alpha_cov,
                rho: w.rho,
                scale_coverage: -1.0,
                scale_time: 1e-4,
                c_start: w.c_start,
                c_end: w.c_end,
                aging: w.aging,
                lc_separation: w.lc_separation,
                lc_min: w.lc_min,
                lc_rule: w.lc_rule,
                penalty: w.penalty,
            },
        },
    }
}
