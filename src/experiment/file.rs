//! Experiment files (TOML): one seeded run of a planner on a map with a robot (or a fleet).
//! Parsed with unknown keys rejected, then validated once into an [`Experiment`]: the scenario
//! and budget from the sections of [`crate::planner::sections`], the chosen planner's typed
//! parameters (each planner validates its own section beside its algorithm, through
//! [`super::registry`]), the seed and the output folder. Nothing downstream reads the raw file
//! except to write `config.toml`.

use super::registry::{PlannerConfig, PlannerKind};
use crate::config::{ConfigError, check_range};
use crate::coverage::Footprint;
use crate::geom::Point;
use crate::map::GridMap;
use crate::planner::section::PlannerSections;
pub use crate::planner::sections::OutputSection;
use crate::planner::sections::{BudgetSection, MapSection, RobotSection, ScorerSection, StationsSection};
use crate::planner::{Budget, Checks, Context, Scenario};
use std::any::Any;
use std::path::{Path, PathBuf};
use std::time::Duration;

mod written;

/// The file as written (all sections optional; defaults are the thesis's settings).
#[derive(Clone, Debug, PartialEq)]
pub struct ExperimentFile {
    /// The run's seed.
    pub seed: u64,
    /// Which planner runs: the name of a registered planner (covga's own: `thesis`,
    /// `waypoint`, `random_search`, `boustrophedon`, `spiral`, `cell_order`, `layouts`).
    pub planner: PlannerKind,
    /// The map.
    pub map: MapSection,
    /// The robot.
    pub robot: RobotSection,
    /// Start and end stations.
    pub stations: StationsSection,
    /// How the common scorer measures every plan (projection, camera).
    pub scorer: ScorerSection,
    /// The planners' own sections (`[thesis]`, `[waypoint]`, `[pattern]`, `[cell_order]`,
    /// `[retrain]`, …), each as its planner's entry declares it, read and written by its
    /// declaration (unknown keys refused); a section that not every file
    /// holds is absent from files that do not set it, so that the written file (and a study's
    /// run ids, which hash it) of other planners stays as it was.
    pub sections: PlannerSections,
    /// When to stop.
    pub budget: BudgetSection,
    /// Where results go.
    pub output: OutputSection,
    /// A fleet instead of one robot: `[[robots]]` entries (defaults from `[robot]` and
    /// `[stations]`), planned by the thesis GA as `[fleet]` says.
    pub robots: Vec<crate::fleet::config::RobotEntry>,
    /// How a fleet is planned.
    pub fleet: Option<crate::fleet::config::FleetSection>,
    /// The settings of planners added from outside covga, one table per planner
    /// (`[plugins.<name>]`, [`super::plugins`]); each checks its own.
    pub plugins: std::collections::BTreeMap<String, toml::Table>,
}

impl Default for ExperimentFile {
    fn default() -> Self {
        Self {
            seed: 1,
            planner: PlannerKind::default(),
            map: MapSection::default(),
            robot: RobotSection::default(),
            stations: StationsSection::default(),
            scorer: ScorerSection::default(),
            sections: written::default_sections(),
            budget: BudgetSection::default(),
            output: OutputSection::default(),
            robots: Vec::new(),
            fleet: None,
            plugins: std::collections::BTreeMap::new(),
        }
    }
}
/// Whether `name` is a key of the experiment file's own (`seed`, `[map]`, `[budget]`, …),
/// which no planner section may be called.
pub fn is_shared_key(name: &str) -> bool {
    written::is_shared(name)
}

/// Loads a map from its resolved source and how a bare image is read.
pub type MapLoader<'a> = dyn Fn(&str, &crate::map::ros::BareImage) -> Result<GridMap, crate::map::MapError> + 'a;

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
    /// Iterations between diversity measurements in `history.csv` (at least 1).
    pub diversity_every: u32,
}

impl ExperimentFile {
    /// Parses TOML text; `origin` names the file in messages.
    /// A text that sets nothing (empty, or only comments) is refused: it is more often a wrong
    /// or truncated file than a wish for every default, which is said with one key, e.g.
    /// `planner = "thesis"`.
    /// Keys of their old spelling ([`super::renamed`]) move to their new place first.
    pub fn parse(text: &str, origin: &str) -> Result<Self, ConfigError> {
        let mut table: toml::Table = text.parse().map_err(|e| ConfigError::from_toml(origin, text, &e))?;
        let file = if super::renamed::rename_in_table(&mut table, origin)?.is_empty() {
            // Straight from the text, so that a message names the line of a bad value.
            toml::from_str(text)
                .map_err(|e| ConfigError::from_toml(origin, text, &written::in_place(text, &table, e)))?
        } else {
            toml::Value::Table(table).try_into().map_err(|e| ConfigError::new(origin, "", e.message().trim()))?
        };
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
        crate::io::read_text_bounded(path, crate::io::MAX_TEXT_FILE_BYTES)
            .map_err(|e| ConfigError::new(path.display(), "", format!("cannot read experiment file: {e}")))
    }

    /// Validates every value and loads the map. `base` resolves relative map paths (the CLI and
    /// Python pass the working directory, one rule for run and grid files); `origin`
    /// names the file in messages; `stem` names the default output folder.
    pub fn validate(self, origin: &str, base: &Path, stem: &str) -> Result<Experiment, ConfigError> {
        self.validate_with(
            origin,
            base,
            stem,
            &|src: &str, image: &crate::map::ros::BareImage| crate::map::ros::load_map(src, image),
            Checks::Full,
        )
    }

    /// [`Self::validate`] with a map loader (studies share one cache of loaded maps).
    pub fn validate_with(
        mut self,
        origin: &str,
        base: &Path,
        stem: &str,
        load: &MapLoader<'_>,
        checks: Checks,
    ) -> Result<Experiment, ConfigError> {
        let err = |key: &str, msg: String| ConfigError::new(origin, key, msg);
        if let Some(section) = self.planner.entry().written_in_full() {
            // The written config.toml shows every setting of the planner that ran.
            self.sections.insert_default(section);
        }
        self.check_numbers(origin)?;
        super::plugins::check_sections(&self.plugins, origin)?;
        let map = self.load_map(origin, base, load)?;
        let (robot, start, end) = self.robot_and_stations(origin, &map)?;
        let camera = self.scorer.camera.spec(origin, &map)?;
        let scenario = Scenario { map, robot, start, end, projection: self.scorer.projection, camera };
        if self.planner.plans_on_refined_raster() {
            // Before the planner's checks, some of which decompose the planning raster; the
            // lanes' own cap first, as it names the narrowest width a pattern is planned for.
            crate::lanes::check_lane_count(&scenario.map, robot.width)
                .map_err(|e| err("robot.width", e.to_string()))?;
            crate::map::refine::check_planning_size(&scenario.map, robot.width, "robot.width")
                .map_err(|m| err("", m))?;
        }
        let b = self.budget;
        let budget = Budget {
            iterations: b.iterations,
            evaluations: (b.evaluations > 0).then_some(b.evaluations),
            wall_clock: (b.wall_clock_s > 0.0).then(|| Duration::from_secs_f64(b.wall_clock_s)),
            stall_iterations: (b.stall_iterations > 0).then_some(b.stall_iterations),
            interrupt: None,
        };
        let planner =
            PlannerConfig::from_file(&self, &Context { origin, scenario: &scenario, budget: &budget, checks })?;
        let output_dir = self.output.dir.clone().unwrap_or_else(|| PathBuf::from("out").join(stem));
        let diversity_every = self.output.diversity_every.unwrap_or(1);
        if diversity_every == 0 {
            return Err(err(
                "output.diversity_every",
                "= 0 is out of range: iterations between diversity measurements, at least 1".into(),
            ));
        }
        self.stations.end = Some([end.x, end.y]);
        Ok(Experiment { seed: self.seed, file: self, scenario, planner, budget, output_dir, diversity_every })
    }

    /// The seed, the robot's and the budget's numbers against their ranges.
    fn check_numbers(&self, origin: &str) -> Result<(), ConfigError> {
        let err = |key: &str, msg: String| ConfigError::new(origin, key, msg);
        if self.seed > i64::MAX as u64 {
            return Err(err(
                "seed",
                format!("= {} is out of range [0, {}] (TOML integers are signed 64-bit)", self.seed, i64::MAX),
            ));
        }
        let r = self.robot;
        if let Some((name, v, allowed)) =
            (Footprint { width: r.width, speed: r.speed, rot_speed: r.rot_speed }).out_of_range()
        {
            let v = crate::io::short_number(v);
            return Err(err(&format!("robot.{name}"), format!("= {v} is out of range: allowed {allowed}")));
        }
        let b = self.budget;
        check_range(origin, "budget.wall_clock_s", b.wall_clock_s, 0.0, 1e9, "[0, 1e9] seconds (0 = no limit)")?;
        if b.evaluations > i64::MAX as u64 {
            return Err(err("budget.evaluations", format!("= {} is out of range [0, {}]", b.evaluations, i64::MAX)));
        }
        Ok(())
    }

    /// The map of `[map]` (a preset by name, else a path, relative ones read from `base`),
    /// loaded by `load` once its keys are checked; messages name `origin`.
    pub fn load_map(&self, origin: &str, base: &Path, load: &MapLoader<'_>) -> Result<GridMap, ConfigError> {
        let err = |key: &str, msg: String| ConfigError::new(origin, key, msg);
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
            check_range(origin, "map.resolution", res, 1e-9, 1e6, "[1e-9, 1e6] metres per pixel")?;
        }
        if self.map.free_threshold == Some(0) {
            return Err(err(
                "map.free_threshold",
                "= 0 is out of range: allowed [1, 255] (grey values at or above it are free; 0 would free every pixel)"
                    .into(),
            ));
        }
        load(&source, &self.map.bare_image()).map_err(|e| err("map.source", e.to_string()))
    }

    /// The robot and the stations on `map`: free, the robot's body fitting at both, and the end
    /// reachable from the start.
    fn robot_and_stations(&self, origin: &str, map: &GridMap) -> Result<(Footprint, Point, Point), ConfigError> {
        let err = |key: &str, msg: String| ConfigError::new(origin, key, msg);
        let r = self.robot;
        let start = Point::new(self.stations.start[0], self.stations.start[1]);
        let end = self.stations.end.map_or(start, |e| Point::new(e[0], e[1]));
        map.check_station(start, "start").map_err(|m| err("stations.start", m))?;
        map.check_station(end, "end").map_err(|m| err("stations.end", m))?;
        let robot = Footprint { width: r.width, speed: r.speed, rot_speed: r.rot_speed };
        robot.check_fits(map).map_err(|m| err("robot.width", m))?;
        {
            use crate::map::reach::{station_misfit, unreachable_end};
            let clear = crate::map::clearance::Clearance::new(map, robot.width);
            if let Some(why) = station_misfit(&clear, start, "the start") {
                return Err(err("stations.start", why));
            }
            if let Some(why) = station_misfit(&clear, end, "the end") {
                return Err(err("stations.end", why));
            }
            if end != start
                && let Some(why) = unreachable_end(&clear, start, end)
            {
                return Err(err("stations.end", why));
            }
        }
        Ok((robot, start, end))
    }
}

impl crate::planner::entry::FileSections for ExperimentFile {
    /// The planner sections the file holds, `[output]` and the plugins' tables, as the
    /// planners' entries read them.
    fn section(&self, name: &str) -> Option<&dyn Any> {
        match name {
            "output" => Some(&self.output),
            "plugins" => Some(&self.plugins),
            _ => self.sections.get(name).map(|s| s.as_any()),
        }
    }
}
