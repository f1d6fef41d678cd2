//! The sections of an experiment file that make its [`Scenario`](super::Scenario) and
//! [`Budget`](super::Budget): `[map]`, `[robot]`, `[stations]`, `[scorer]` and `[budget]`, as
//! written, with the thesis's settings as defaults. The experiment file (one layer up) embeds
//! them and validates them into the scenario every planner plans for.

use crate::config::{ConfigError, check_range};
use crate::coverage::Footprint;
use crate::coverage::fitness::Projection;
use crate::coverage::score::CameraSpec;
use crate::map::GridMap;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// `[map]`: the occupancy grid to plan on: a preset, a ROS map_server YAML or a bare image.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MapSection {
    /// Preset name, ROS YAML or image path (a relative path is read from the working directory,
    /// in run and grid files alike).
    pub source: String,
    /// Metres per pixel for a bare image.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub resolution: Option<f64>,
    /// For a bare image: grey values at or above this are free, darker ones occupied (the ipa
    /// room-segmentation benchmark uses 250). Unset: map_server's default thresholds (grey
    /// ≥ 206 free, ≤ 89 occupied, unknown between).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub free_threshold: Option<u8>,
}

impl MapSection {
    /// How a bare image of this section is read.
    pub fn bare_image(&self) -> crate::map::ros::BareImage {
        crate::map::ros::BareImage { resolution: self.resolution, free_threshold: self.free_threshold }
    }
}

/// `[robot]`: the robot's width, speed and turning speed (003 Table 4.2's robot by default,
/// which turns for free: set `rot_speed` for a real robot).
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

/// `[stations]`: where every plan starts and ends, in metres in the map's frame (R3).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct StationsSection {
    /// `S_pos` in metres.
    pub start: [f64; 2],
    /// `E_pos` in metres (default: the start).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub end: Option<[f64; 2]>,
}

/// Whether a dotted `key` is the section or key `prefix`, or lies within it.
pub fn within(key: &str, prefix: &str) -> bool {
    key == prefix || key.strip_prefix(prefix).is_some_and(|rest| rest.starts_with('.'))
}

/// `[scorer]`: how the common scorer measures every plan, whichever planner made it. Planners
/// that optimise the same quantities read it too: the thesis GA's fitness uses the projection,
/// the waypoint planner's camera objective (000 eq. 1) this camera.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub struct ScorerSection {
    /// Projection of the fitness `f` (`f1`, 003 eq. 3.14, or `f2`, eq. 3.15, the default).
    pub projection: Projection,
    /// The camera of the camera coverage (`cov_cam`, 000 eq. 1).
    pub camera: CameraSection,
}

/// `[scorer.camera]`: 000's camera and the raster it is measured on (000 Table I's settings by
/// default).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CameraSection {
    /// Pixel scale `s` of the working raster (m/px); the waypoint planner's raster too.
    pub scale: f64,
    /// Camera `d_min` (m).
    pub d_min: f64,
    /// Camera `d_max` (m).
    pub d_max: f64,
    /// Camera field of view `θ_fov` (degrees).
    pub fov_deg: f64,
    /// Coverage sections `m` (000 eq. 1).
    pub sections: usize,
    /// Width of the wall band `B` (m): the free cells this close to an obstacle count as wall
    /// in `cov_cam`'s walls and open split. Absent: [`DEFAULT_WALL_BAND_M`], for every
    /// planner alike (the measure does not follow any planner's settings, so that a study
    /// sweeping one compares plans on one scale).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wall_band: Option<f64>,
}

/// The scorer's wall band when `scorer.camera.wall_band` is absent (m): 000's safety buffer at
/// its narrowest hallway of 1.5 m (half of it, 000 §II-B.2 and eq. 2).
pub const DEFAULT_WALL_BAND_M: f64 = 0.75;

/// The most pixels the camera's working raster may have on one map.
const MAX_CAMERA_RASTER_PIXELS: f64 = 4.0e8;

impl Default for CameraSection {
    fn default() -> Self {
        Self { scale: 0.15, d_min: 0.2, d_max: 7.0, fov_deg: 69.4, sections: 15, wall_band: None }
    }
}

impl CameraSection {
    /// The checked camera on `map`; `origin` names the file in messages.
    pub fn spec(&self, origin: &str, map: &GridMap) -> Result<CameraSpec, ConfigError> {
        let err = |key: &str, msg: String| ConfigError::new(origin, key, msg);
        check_range(origin, "scorer.camera.scale", self.scale, 1e-4, 10.0, "(0, 10] metres per pixel")?;
        check_range(origin, "scorer.camera.d_min", self.d_min, 0.0, 1e6, "[0, 1e6] metres")?;
        if !(self.d_max.is_finite() && self.d_max > self.d_min) {
            return Err(err(
                "scorer.camera.d_max",
                format!("= {} must exceed d_min = {} (camera depth range)", self.d_max, self.d_min),
            ));
        }
        if !(self.fov_deg > 0.0 && self.fov_deg <= 360.0) {
            return Err(err("scorer.camera.fov_deg", format!("= {} is out of range (0, 360] degrees", self.fov_deg)));
        }
        if self.sections == 0 || self.sections > 3600 {
            return Err(err("scorer.camera.sections", format!("= {} is out of range [1, 3600]", self.sections)));
        }
        let pixels = (map.width_m() / self.scale) * (map.height_m() / self.scale);
        if pixels > MAX_CAMERA_RASTER_PIXELS {
            return Err(err(
                "scorer.camera.scale",
                format!("= {} m gives a working raster of {pixels:.3e} pixels for this map (at most 4e8)", self.scale),
            ));
        }
        let longest = map.width_m().max(map.height_m());
        let band_m = match self.wall_band {
            Some(b) => {
                check_range(
                    origin,
                    "scorer.camera.wall_band",
                    b,
                    self.scale,
                    longest,
                    "[scale, the map's longer side] metres",
                )?;
                b
            }
            None => DEFAULT_WALL_BAND_M,
        };
        Ok(CameraSpec {
            scale: self.scale,
            d_min: self.d_min,
            d_max: self.d_max,
            fov_deg: self.fov_deg,
            sections: self.sections,
            band_m,
        })
    }
}

/// `[budget]`: when a run stops: at the first limit reached (0 means no limit).
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

impl Default for MapSection {
    fn default() -> Self {
        Self { source: "thesis-1".into(), resolution: None, free_threshold: None }
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

/// `[output]`: where a run writes and what beyond its usual files.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub struct OutputSection {
    /// Results folder (default `out/<file stem>`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dir: Option<PathBuf>,
    /// `history.csv` records the population diversity every this many iterations (and at
    /// iteration 0); the other rows leave it empty. Measuring it is a pass over every visit
    /// map, about a fifth of a thesis GA run when done every iteration. Absent means 1, every
    /// iteration, so that the written `config.toml` and run ids of files without it stay as
    /// they were.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub diversity_every: Option<u32>,
    /// The thesis GA also writes its final population's genomes (`population_genomes.csv`:
    /// each member's live moves, in the order of `population.csv`), for a notebook to decode
    /// or re-score them. Absent means false (a study's runs never write them).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub population_genomes: Option<bool>,
}
