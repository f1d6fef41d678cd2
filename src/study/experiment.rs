//! Experiment files (TOML): one seeded run of a planner on a map with a robot. Parsed with
//! unknown keys rejected, then validated once into typed, range-checked values (003 Table 4.1
//! ranges, spec §14.2).

use super::config::{ConfigError, check_range, check_unit};
use crate::coverage::Footprint;
use crate::ga::control::AdaptiveConstants;
use crate::geom::Point;
use crate::map::GridMap;
use crate::thesis::crossover::ChildMode;
use crate::thesis::fitness::Projection;
use crate::thesis::individual::InitParams;
use crate::thesis::params::{Budget, Control, Retrain, Selection, ThesisParams};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// The file as written (all sections optional; defaults are the thesis's settings).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ExperimentFile {
    /// The run's seed.
    pub seed: u64,
    /// Which planner runs (`thesis`).
    pub planner: PlannerKind,
    /// The map.
    pub map: MapSection,
    /// The robot.
    pub robot: RobotSection,
    /// Start and end stations.
    pub stations: StationsSection,
    /// Thesis GA parameters.
    pub thesis: ThesisSection,
    /// Waypoint planner parameters (used when `planner = "waypoint"`).
    pub waypoint: WaypointSection,
    /// When to stop.
    pub budget: BudgetSection,
    /// Optional changing-environment retrain.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub retrain: Option<RetrainSection>,
    /// Where results go.
    pub output: OutputSection,
}

/// Planner kinds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum PlannerKind {
    /// The action-encoded GA of 003.
    #[default]
    Thesis,
    /// The waypoint-graph maximin planner of 000.
    Waypoint,
}

/// `[waypoint]`: 000 Table I as reconciled (spec §18–19); metres, degrees.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WaypointSection {
    /// Pixel scale `s` (m/px).
    pub scale: f64,
    /// UAV width (m).
    pub uav_width: f64,
    /// Narrowest accessible hallway (m).
    pub hallway: f64,
    /// Maximum traverse distance of an edge (m).
    pub max_traverse: f64,
    /// Camera `d_min` (m).
    pub d_min: f64,
    /// Camera `d_max` (m).
    pub d_max: f64,
    /// Camera field of view (degrees).
    pub fov_deg: f64,
    /// Coverage sections `m`.
    pub sections: usize,
    /// `full` or `near_wall`.
    pub waypoint_set: crate::waypoint::world::WaypointSet,
    /// Number of agents.
    pub agents: usize,
    /// Per-agent entry positions (m); empty = all start at `stations.start`.
    pub starts: Vec<[f64; 2]>,
    /// `N`.
    pub population: usize,
    /// Generations.
    pub generations: u32,
    /// `p_c`.
    pub p_c: f64,
    /// `p_A`.
    pub p_a: f64,
    /// `p_B`.
    pub p_b: f64,
    /// `γ`.
    pub gamma: f64,
    /// `l_init`.
    pub l_init: usize,
    /// `l_min`.
    pub l_min: usize,
    /// `l_max`.
    pub l_max: usize,
    /// `T_x`.
    pub crossover_threshold: usize,
    /// `n_B`.
    pub b_instances: usize,
    /// `D`.
    pub b_distance: usize,
    /// `p_acc`.
    pub b_accept: f64,
    /// `M`.
    pub memory: usize,
    /// `λ`.
    pub lambda: f64,
    /// `ρ`.
    pub rho: f64,
    /// `α_cov`.
    pub alpha_cov: f64,
    /// `C_start`.
    pub c_start: f64,
    /// `C_end`.
    pub c_end: f64,
    /// `G_age`.
    pub aging: u32,
    /// `T_sep`.
    pub lc_separation: usize,
    /// Minimum self loop closures.
    pub lc_min: usize,
    /// Penalty per violated constraint type (scaled units).
    pub penalty: f64,
}

impl Default for WaypointSection {
    fn default() -> Self {
        Self {
            scale: 0.15,
            uav_width: 0.5,
            hallway: 1.5,
            max_traverse: 4.0,
            d_min: 0.2,
            d_max: 7.0,
            fov_deg: 69.4,
            sections: 15,
            waypoint_set: crate::waypoint::world::WaypointSet::Full,
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
            penalty: 1000.0,
        }
    }
}

/// A validated waypoint plan: world geometry and GA parameters.
#[derive(Clone, Debug)]
pub struct WaypointPlan {
    /// Geometry.
    pub world: crate::waypoint::world::WorldParams,
    /// GA.
    pub ga: crate::waypoint::run::GaParams,
}

/// `[map]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MapSection {
    /// Preset name, ROS YAML or image path (relative paths from the experiment file's folder).
    pub source: String,
    /// Metres per pixel for a bare image.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub resolution: Option<f64>,
}

/// `[robot]` (003 Table 4.2).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RobotSection {
    /// `R_width` in metres.
    pub width: f64,
    /// `R_speed` in m/s.
    pub speed: f64,
    /// `R_rot` in rad/s (0 = no rotation cost).
    pub rot_speed: f64,
}

/// `[stations]` (spec R3).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct StationsSection {
    /// `S_pos` in metres.
    pub start: [f64; 2],
    /// `E_pos` in metres (default: the start).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub end: Option<[f64; 2]>,
}

/// `[thesis]`: the parameters of 003 Tables 4.1–4.3.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ThesisSection {
    /// `f1` or `f2`.
    pub projection: Projection,
    /// `elite`, `tournament`, `prws` or `rrws`.
    pub selection: SelectionName,
    /// `Pop_min`.
    pub pop_min: usize,
    /// `Init_I`.
    pub init_individuals: usize,
    /// `Init_AC`.
    pub init_actions: usize,
    /// Upper bound of initial `AC_dist` in metres (R2).
    pub init_dist_max: f64,
    /// Longest genome.
    pub max_genome_len: usize,
    /// `P_c`.
    pub p_c: f64,
    /// `C_len`.
    pub c_len: f64,
    /// `C_child` (0 changing, 1 preserving, 2 both).
    pub c_child: u8,
    /// `P_mA`.
    pub p_ma: f64,
    /// `P_mI`.
    pub p_mi: f64,
    /// `keep` (tournament, PRWS, RRWS).
    pub keep: usize,
    /// `select` (tournament, PRWS, RRWS).
    pub select: usize,
    /// `TS` (tournament).
    pub tournament_size: usize,
    /// `SP` (RRWS).
    pub selection_pressure: f64,
    /// Parameter control.
    pub control: ControlSection,
}

/// Selection scheme names.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SelectionName {
    /// Elite families.
    Elite,
    /// Tournament ("Turn").
    Tournament,
    /// Proportionate roulette wheel.
    Prws,
    /// Rank-based roulette wheel.
    Rrws,
}

/// `[thesis.control]`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum ControlSection {
    /// Fixed parameters.
    None,
    /// eq. 3.25 ramp of SP (RRWS) or TS (tournament).
    Ramp {
        /// Start value.
        min: f64,
        /// End value.
        max: f64,
    },
    /// eqs. 2.3–2.6.
    Adaptive {
        /// `K_1`.
        #[serde(default = "k1")]
        k1: f64,
        /// `K_2`.
        #[serde(default = "k2")]
        k2: f64,
        /// `K`.
        #[serde(default = "k")]
        k: f64,
    },
    /// eqs. 2.1–2.2.
    Muhlenbein,
}

fn k1() -> f64 {
    AdaptiveConstants::default().k1
}
fn k2() -> f64 {
    AdaptiveConstants::default().k2
}
fn k() -> f64 {
    AdaptiveConstants::default().k
}

/// `[budget]`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BudgetSection {
    /// `Iter_max` (total, including iterations after a retrain switch).
    pub iterations: u32,
    /// Wall-clock limit in seconds (0 = none).
    pub wall_clock_s: f64,
    /// Stop after this many iterations without a better best (0 = never).
    pub stall_iterations: u32,
}

/// `[retrain]` (spec §13).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RetrainSection {
    /// Iterations before the switch.
    pub at_iteration: u32,
    /// `[x0, y0, x1, y1]` in metres, marked as covered (default: the 5 m corner of R25).
    #[serde(default = "retrain_region")]
    pub region: [f64; 4],
}

fn retrain_region() -> [f64; 4] {
    [5.0, 5.0, 10.0, 10.0]
}

/// `[output]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub struct OutputSection {
    /// Results folder (default `out/<file stem>`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dir: Option<PathBuf>,
}

impl Default for ExperimentFile {
    fn default() -> Self {
        Self {
            seed: 1,
            planner: PlannerKind::Thesis,
            map: MapSection::default(),
            robot: RobotSection::default(),
            stations: StationsSection::default(),
            thesis: ThesisSection::default(),
            waypoint: WaypointSection::default(),
            budget: BudgetSection::default(),
            retrain: None,
            output: OutputSection::default(),
        }
    }
}
impl Default for MapSection {
    fn default() -> Self {
        Self { source: "thesis-1".into(), resolution: None }
    }
}
impl Default for RobotSection {
    fn default() -> Self {
        let f = Footprint::default();
        Self { width: f.width, speed: f.speed, rot_speed: f.rot_speed }
    }
}
impl Default for StationsSection {
    fn default() -> Self {
        Self { start: [1.3, 1.3], end: None }
    }
}
impl Default for ThesisSection {
    fn default() -> Self {
        let p = ThesisParams::thesis_elite();
        Self {
            projection: Projection::F2,
            selection: SelectionName::Elite,
            pop_min: p.pop_min,
            init_individuals: p.init_individuals,
            init_actions: p.init.actions,
            init_dist_max: p.init.dist_max,
            max_genome_len: p.max_genome_len,
            p_c: p.p_c,
            c_len: p.c_len,
            c_child: p.c_child.index(),
            p_ma: p.p_ma,
            p_mi: p.p_mi,
            keep: 10,
            select: 20,
            tournament_size: 3,
            selection_pressure: 2.0,
            control: ControlSection::None,
        }
    }
}
impl Default for BudgetSection {
    fn default() -> Self {
        Self { iterations: 2000, wall_clock_s: 0.0, stall_iterations: 0 }
    }
}

/// Loads a map from `(source, resolution)`.
pub type MapLoader<'a> = dyn Fn(&str, Option<f64>) -> Result<GridMap, crate::map::MapError> + 'a;

/// A validated experiment, ready to run.
#[derive(Clone, Debug)]
pub struct Experiment {
    /// The file with every default filled in (written as `config.toml`).
    pub file: ExperimentFile,
    /// The map.
    pub map: GridMap,
    /// The robot.
    pub robot: Footprint,
    /// `S_pos`.
    pub start: Point,
    /// `E_pos`.
    pub end: Point,
    /// `f1` / `f2`.
    pub projection: Projection,
    /// GA parameters.
    pub params: ThesisParams,
    /// Stop conditions.
    pub budget: Budget,
    /// Retrain, if any.
    pub retrain: Option<Retrain>,
    /// The waypoint planner's setup when `planner = "waypoint"`.
    pub waypoint: Option<WaypointPlan>,
    /// Results folder.
    pub output_dir: PathBuf,
}

impl ExperimentFile {
    /// Parses TOML text; `origin` names the file in messages.
    pub fn parse(text: &str, origin: &str) -> Result<Self, ConfigError> {
        toml::from_str(text).map_err(|e| ConfigError::from_toml(origin, text, &e))
    }

    /// Reads and parses a file.
    pub fn read(path: &Path) -> Result<Self, ConfigError> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| ConfigError::new(path.display(), "", format!("cannot read experiment file: {e}")))?;
        Self::parse(&text, &path.display().to_string())
    }

    /// Validates every value and loads the map. `base` resolves relative map paths; `origin`
    /// names the file in messages; `stem` names the default output folder.
    pub fn validate(self, origin: &str, base: &Path, stem: &str) -> Result<Experiment, ConfigError> {
        self.validate_with(origin, base, stem, &|src: &str, res: Option<f64>| crate::map::ros::load_map(src, res))
    }

    /// [`Self::validate`] with a map loader (studies share one cache of loaded maps).
    pub fn validate_with(
        mut self,
        origin: &str,
        base: &Path,
        stem: &str,
        load: &MapLoader<'_>,
    ) -> Result<Experiment, ConfigError> {
        let err = |key: &str, msg: String| ConfigError::new(origin, key, msg);
        if self.seed > i64::MAX as u64 {
            return Err(err(
                "seed",
                format!("= {} is out of range [0, {}] (TOML integers are signed 64-bit)", self.seed, i64::MAX),
            ));
        }
        let r = self.robot;
        check_range(origin, "robot.width", r.width, 1e-6, f64::MAX, "> 0 metres")?;
        check_range(origin, "robot.speed", r.speed, 1e-9, f64::MAX, "> 0 m/s")?;
        check_range(
            origin,
            "robot.rot_speed",
            r.rot_speed,
            0.0,
            f64::MAX,
            ">= 0 rad/s (0 disables the rotation cost)",
        )?;
        let t = self.thesis;
        for (key, v) in
            [("thesis.p_c", t.p_c), ("thesis.c_len", t.c_len), ("thesis.p_ma", t.p_ma), ("thesis.p_mi", t.p_mi)]
        {
            check_unit(origin, key, v)?;
        }
        let count = |key: &str, v: usize, lo: usize, hi: usize| {
            if v < lo || v > hi { Err(err(key, format!("= {v} is out of range [{lo}, {hi}]"))) } else { Ok(()) }
        };
        count("thesis.pop_min", t.pop_min, 1, 1_000_000)?;
        count("thesis.init_actions", t.init_actions, 1, 100_000)?;
        count("thesis.max_genome_len", t.max_genome_len, t.init_actions + 2, 1_000_000)?;
        check_range(origin, "thesis.init_dist_max", t.init_dist_max, 1e-9, 1e6, "> 0 metres")?;
        let child = ChildMode::from_index(t.c_child)
            .ok_or_else(|| err("thesis.c_child", format!("= {} is out of range {{0, 1, 2}}", t.c_child)))?;
        let selection = match t.selection {
            SelectionName::Elite => Selection::Elite,
            SelectionName::Tournament => {
                count("thesis.tournament_size", t.tournament_size, 1, t.pop_min)?;
                Selection::Tournament { size: t.tournament_size }
            }
            SelectionName::Prws => Selection::Prws,
            SelectionName::Rrws => {
                check_range(origin, "thesis.selection_pressure", t.selection_pressure, 1.0, 2.0, "[1, 2]")?;
                Selection::Rrws { pressure: t.selection_pressure }
            }
        };
        if selection != Selection::Elite {
            count("thesis.init_individuals", t.init_individuals, t.pop_min, 10_000_000)?;
            count("thesis.keep", t.keep, 0, t.pop_min)?;
            count("thesis.select", t.select, 1, t.pop_min)?;
        }
        let control = match t.control {
            ControlSection::None => Control::None,
            ControlSection::Ramp { min, max } => {
                let (lo, hi, what) = match selection {
                    Selection::Rrws { .. } => (1.0, 2.0, "[1, 2] (SP of RRWS)"),
                    Selection::Tournament { .. } => (1.0, t.pop_min as f64, "[1, pop_min] (TS of the tournament)"),
                    _ => {
                        return Err(err(
                            "thesis.control.kind",
                            "= \"ramp\" needs selection \"rrws\" or \"tournament\"".into(),
                        ));
                    }
                };
                check_range(origin, "thesis.control.min", min, lo, hi, what)?;
                check_range(origin, "thesis.control.max", max, lo, hi, what)?;
                Control::Ramp { min, max }
            }
            ControlSection::Adaptive { k1, k2, k } => {
                for (key, v) in [("thesis.control.k1", k1), ("thesis.control.k2", k2), ("thesis.control.k", k)] {
                    check_unit(origin, key, v)?;
                }
                Control::Adaptive(AdaptiveConstants { k1, k2, k })
            }
            ControlSection::Muhlenbein => Control::Muhlenbein,
        };
        let b = self.budget;
        check_range(origin, "budget.wall_clock_s", b.wall_clock_s, 0.0, 1e9, ">= 0 seconds (0 = no limit)")?;
        let retrain = match self.retrain {
            None => None,
            Some(rt) => {
                if rt.at_iteration >= b.iterations {
                    return Err(err(
                        "retrain.at_iteration",
                        format!("= {} must be below budget.iterations = {}", rt.at_iteration, b.iterations),
                    ));
                }
                let [x0, y0, x1, y1] = rt.region;
                if !rt.region.iter().all(|v| v.is_finite()) || x0 >= x1 || y0 >= y1 {
                    return Err(err(
                        "retrain.region",
                        format!("= {:?} must be [x0, y0, x1, y1] with x0 < x1 and y0 < y1", rt.region),
                    ));
                }
                Some(Retrain { at_iteration: rt.at_iteration, region: rt.region })
            }
        };
        // The map, relative to the experiment file; presets by name.
        let source =
            if crate::map::presets::preset(&self.map.source).is_some() || Path::new(&self.map.source).is_absolute() {
                self.map.source.clone()
            } else {
                base.join(&self.map.source).display().to_string()
            };
        if let Some(res) = self.map.resolution {
            check_range(origin, "map.resolution", res, 1e-9, 1e6, "> 0 metres per pixel")?;
        }
        let map = load(&source, self.map.resolution).map_err(|e| err("map.source", e.to_string()))?;
        let start = Point::new(self.stations.start[0], self.stations.start[1]);
        let end = self.stations.end.map_or(start, |e| Point::new(e[0], e[1]));
        map.check_station(start, "start").map_err(|m| err("stations.start", m))?;
        map.check_station(end, "end").map_err(|m| err("stations.end", m))?;
        let params = ThesisParams {
            selection,
            pop_min: t.pop_min,
            init_individuals: t.init_individuals,
            init: InitParams { actions: t.init_actions, dist_max: t.init_dist_max },
            max_genome_len: t.max_genome_len,
            p_c: t.p_c,
            c_len: t.c_len,
            c_child: child,
            p_ma: t.p_ma,
            p_mi: t.p_mi,
            keep: t.keep,
            select: t.select,
            control,
        };
        let budget = Budget {
            iterations: b.iterations,
            wall_clock: (b.wall_clock_s > 0.0).then(|| Duration::from_secs_f64(b.wall_clock_s)),
            stall_iterations: (b.stall_iterations > 0).then_some(b.stall_iterations),
        };
        let waypoint = match self.planner {
            PlannerKind::Thesis => None,
            PlannerKind::Waypoint => Some(validate_waypoint(&self.waypoint, origin, &map, start)?),
        };
        let output_dir = self.output.dir.clone().unwrap_or_else(|| PathBuf::from("out").join(stem));
        self.stations.end = Some([end.x, end.y]);
        Ok(Experiment {
            robot: Footprint { width: r.width, speed: r.speed, rot_speed: r.rot_speed },
            projection: t.projection,
            file: self,
            map,
            start,
            end,
            params,
            budget,
            retrain,
            waypoint,
            output_dir,
        })
    }
}

/// Range checks of `[waypoint]` and the conversion into planner parameters.
fn validate_waypoint(
    w: &WaypointSection,
    origin: &str,
    map: &GridMap,
    start: Point,
) -> Result<WaypointPlan, ConfigError> {
    let err = |key: &str, msg: String| ConfigError::new(origin, key, msg);
    check_range(origin, "waypoint.scale", w.scale, 1e-4, 10.0, "(0, 10] metres per pixel")?;
    check_range(origin, "waypoint.uav_width", w.uav_width, 1e-4, 100.0, "> 0 metres")?;
    if !(w.hallway.is_finite() && w.hallway >= 2.0 * w.scale && w.hallway >= map.resolution()) {
        return Err(err(
            "waypoint.hallway",
            format!(
                "= {} m is below the cell size: the narrowest hallway must be at least 2 x scale = {} m and the map resolution {} m",
                w.hallway,
                2.0 * w.scale,
                map.resolution()
            ),
        ));
    }
    check_range(origin, "waypoint.max_traverse", w.max_traverse, 1e-4, 1e6, "> 0 metres")?;
    check_range(origin, "waypoint.d_min", w.d_min, 0.0, 1e6, ">= 0 metres")?;
    if !(w.d_max.is_finite() && w.d_max > w.d_min) {
        return Err(err(
            "waypoint.d_max",
            format!("= {} must exceed d_min = {} (camera depth range)", w.d_max, w.d_min),
        ));
    }
    if !(w.fov_deg > 0.0 && w.fov_deg <= 360.0) {
        return Err(err("waypoint.fov_deg", format!("= {} is out of range (0, 360] degrees", w.fov_deg)));
    }
    if w.sections == 0 {
        return Err(err("waypoint.sections", "= 0 is out of range: at least 1".into()));
    }
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
    if w.population < 2 {
        return Err(err("waypoint.population", format!("= {} is out of range: at least 2", w.population)));
    }
    if !(2 <= w.l_min && w.l_min <= w.l_init && w.l_init <= w.l_max) {
        return Err(err(
            "waypoint.l_init",
            format!("needs 2 <= l_min ({}) <= l_init ({}) <= l_max ({})", w.l_min, w.l_init, w.l_max),
        ));
    }
    check_range(origin, "waypoint.lambda", w.lambda, 0.0, 100.0, "[0, 100]")?;
    check_range(origin, "waypoint.rho", w.rho, 0.0, 100.0, "[0, 100]")?;
    check_range(origin, "waypoint.penalty", w.penalty, 0.0, 1e12, ">= 0")?;
    let starts: Vec<(f64, f64)> =
        if w.starts.is_empty() { vec![(start.x, start.y)] } else { w.starts.iter().map(|s| (s[0], s[1])).collect() };
    use crate::waypoint::evaluate::ObjectiveParams;
    use crate::waypoint::operators::OperatorParams;
    Ok(WaypointPlan {
        world: crate::waypoint::world::WorldParams {
            scale: w.scale,
            uav_width: w.uav_width,
            hallway: w.hallway,
            max_traverse: w.max_traverse,
            d_min: w.d_min,
            d_max: w.d_max,
            fov_deg: w.fov_deg,
            sections: w.sections,
            set: w.waypoint_set,
            starts,
        },
        ga: crate::waypoint::run::GaParams {
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
                penalty: w.penalty,
            },
        },
    })
}
