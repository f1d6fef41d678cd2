//! Experiment files (TOML): one seeded run of a planner on a map with a robot. Parsed with
//! unknown keys rejected, then validated once into an [`Experiment`]: the scenario, the chosen
//! planner's typed parameters (each planner's section is converted beside its algorithm:
//! `thesis/config.rs`, `waypoint/config.rs`, `patterns/planner.rs`), the seed, the budget and
//! the output folder. Nothing downstream reads the raw file except to write `config.toml`.

use super::config::{ConfigError, check_range};
use crate::coverage::Footprint;
use crate::geom::Point;
use crate::map::GridMap;
use crate::patterns::planner::PatternSection;
use crate::planner::{Budget, PlannerConfig, PlannerKind, Scenario};
use crate::thesis::config::{RetrainSection, ThesisSection};
use crate::waypoint::config::WaypointSection;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// The file as written (all sections optional; defaults are the thesis's settings).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ExperimentFile {
    /// The run's seed.
    pub seed: u64,
    /// Which planner runs: `thesis`, `waypoint`, `boustrophedon`, `spiral` or `random_search`.
    pub planner: PlannerKind,
    /// The map.
    pub map: MapSection,
    /// The robot.
    pub robot: RobotSection,
    /// Start and end stations.
    pub stations: StationsSection,
    /// Thesis GA parameters (random search draws its genomes with these too).
    pub thesis: ThesisSection,
    /// Waypoint planner parameters; its camera is also the common scorer's camera.
    pub waypoint: WaypointSection,
    /// Pattern planner settings.
    pub pattern: PatternSection,
    /// When to stop.
    pub budget: BudgetSection,
    /// Optional changing-environment retrain (thesis GA).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub retrain: Option<RetrainSection>,
    /// Where results go.
    pub output: OutputSection,
    /// A fleet instead of one robot: `[[robots]]` entries (defaults from `[robot]` and
    /// `[stations]`), planned by the thesis GA as `[fleet]` says.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub robots: Vec<crate::fleet::config::RobotEntry>,
    /// How a fleet is planned.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fleet: Option<crate::fleet::config::FleetSection>,
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

/// `[budget]`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BudgetSection {
    /// `Iter_max` (total, including iterations after a retrain switch); the thesis GA's
    /// iterations (the waypoint planner's generations are `waypoint.generations`).
    pub iterations: u32,
    /// Fitness evaluations (0 = no limit): the equal budget of a planner comparison.
    pub evaluations: u64,
    /// Wall-clock limit in seconds (0 = none).
    pub wall_clock_s: f64,
    /// Stop after this many iterations without a better best (0 = never).
    pub stall_iterations: u32,
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
            pattern: PatternSection::default(),
            budget: BudgetSection::default(),
            retrain: None,
            output: OutputSection::default(),
            robots: Vec::new(),
            fleet: None,
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
impl Default for BudgetSection {
    fn default() -> Self {
        Self { iterations: 2000, evaluations: 0, wall_clock_s: 0.0, stall_iterations: 0 }
    }
}

/// Loads a map from `(source, resolution)`.
pub type MapLoader<'a> = dyn Fn(&str, Option<f64>) -> Result<GridMap, crate::map::MapError> + 'a;

/// A validated experiment, ready to run.
#[derive(Clone, Debug)]
pub struct Experiment {
    /// The file with every default filled in (written as `config.toml`).
    pub file: ExperimentFile,
    /// Map, robot, stations, camera.
    pub scenario: Scenario,
    /// The chosen planner, validated.
    pub planner: PlannerConfig,
    /// The run's seed.
    pub seed: u64,
    /// Stop conditions.
    pub budget: Budget,
    /// Results folder.
    pub output_dir: PathBuf,
    /// The fleet and its negotiation, when the file has `[[robots]]`.
    pub fleet: Option<crate::fleet::config::FleetRun>,
}

impl ExperimentFile {
    /// Whether the plan ignores the seed: a deterministic planner, or a fleet planned by area
    /// division. Grid studies run such a configuration once.
    pub fn is_deterministic(&self) -> bool {
        let divide = self.fleet.as_ref().is_some_and(|f| f.mode == crate::fleet::config::FleetMode::Divide);
        self.planner.is_deterministic() || (!self.robots.is_empty() && divide)
    }

    /// Parses TOML text; `origin` names the file in messages.
    /// A text that sets nothing (empty, or only comments) is refused: it is more often a wrong
    /// or truncated file than a wish for every default, which is said with one key, e.g.
    /// `planner = "thesis"`.
    pub fn parse(text: &str, origin: &str) -> Result<Self, ConfigError> {
        let file = toml::from_str(text).map_err(|e| ConfigError::from_toml(origin, text, &e))?;
        if text.parse::<toml::Table>().is_ok_and(|t| t.is_empty()) {
            return Err(ConfigError::new(
                origin,
                "",
                "sets nothing (the file is empty or only comments); to run every default, say so with one key, \
                 e.g. `planner = \"thesis\"`",
            ));
        }
        Ok(file)
    }

    /// Reads and parses a file.
    pub fn read(path: &Path) -> Result<Self, ConfigError> {
        Self::parse(&Self::read_text(path)?, &path.display().to_string())
    }

    /// The text of an experiment file (for [`Self::parse`] and for checks on what it sets).
    pub fn read_text(path: &Path) -> Result<String, ConfigError> {
        std::fs::read_to_string(path)
            .map_err(|e| ConfigError::new(path.display(), "", format!("cannot read experiment file: {e}")))
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
        let b = self.budget;
        check_range(origin, "budget.wall_clock_s", b.wall_clock_s, 0.0, 1e9, ">= 0 seconds (0 = no limit)")?;
        if b.evaluations > i64::MAX as u64 {
            return Err(err("budget.evaluations", format!("= {} is out of range [0, {}]", b.evaluations, i64::MAX)));
        }
        // The map, relative to the experiment file; presets by name.
        let source =
            if crate::map::presets::preset(&self.map.source).is_some() || Path::new(&self.map.source).is_absolute() {
                self.map.source.clone()
            } else {
                base.join(&self.map.source).display().to_string()
            };
        let bare_image = [".pgm", ".png"].iter().any(|e| self.map.source.to_ascii_lowercase().ends_with(e));
        if bare_image && self.map.resolution.is_none() {
            return Err(err(
                "map.resolution",
                format!(
                    "is missing: the bare image `{}` needs its metres per pixel, e.g. `resolution = 0.05` under [map] (or give a ROS map YAML)",
                    self.map.source
                ),
            ));
        }
        if let Some(res) = self.map.resolution {
            check_range(origin, "map.resolution", res, 1e-9, 1e6, "> 0 metres per pixel")?;
        }
        let map = load(&source, self.map.resolution).map_err(|e| err("map.source", e.to_string()))?;
        let start = Point::new(self.stations.start[0], self.stations.start[1]);
        let end = self.stations.end.map_or(start, |e| Point::new(e[0], e[1]));
        map.check_station(start, "start").map_err(|m| err("stations.start", m))?;
        map.check_station(end, "end").map_err(|m| err("stations.end", m))?;
        let robot = Footprint { width: r.width, speed: r.speed, rot_speed: r.rot_speed };
        robot.check_fits(&map).map_err(|m| err("robot.width", m))?;
        let camera = crate::waypoint::config::camera_spec(&self.waypoint, origin, &map)?;
        let scenario = Scenario { map, robot, start, end, projection: self.thesis.projection, camera };
        crate::fleet::config::waypoint_team(&mut self, origin)?;
        let planner = PlannerConfig::from_file(&self, origin, &scenario)?;
        let budget = Budget {
            iterations: b.iterations,
            evaluations: (b.evaluations > 0).then_some(b.evaluations),
            wall_clock: (b.wall_clock_s > 0.0).then(|| Duration::from_secs_f64(b.wall_clock_s)),
            stall_iterations: (b.stall_iterations > 0).then_some(b.stall_iterations),
        };
        let output_dir = self.output.dir.clone().unwrap_or_else(|| PathBuf::from("out").join(stem));
        let fleet = crate::fleet::config::FleetRun::from_file(&self, origin, &scenario, &budget)?;
        self.stations.end = Some([end.x, end.y]);
        Ok(Experiment { seed: self.seed, file: self, scenario, planner, budget, output_dir, fleet })
    }
}
