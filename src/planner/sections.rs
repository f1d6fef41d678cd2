//! The sections of an experiment file that make its [`Scenario`](super::Scenario) and
//! [`Budget`](super::Budget): `[map]`, `[robot]`, `[stations]` and `[budget]`, as written, with
//! the thesis's settings as defaults. The experiment file (one layer up) embeds them and
//! validates them into the scenario every planner plans for.

use crate::coverage::Footprint;
use serde::{Deserialize, Serialize};

/// `[map]`.
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
