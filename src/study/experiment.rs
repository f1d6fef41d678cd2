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
            output_dir,
        })
    }
}
