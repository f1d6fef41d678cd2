//! `[layouts]`: the idealised lane control's settings as written, validated once into
//! [`LayoutsConfig`]; which keys of the planner sections it reads.

use crate::config::{ConfigError, check_range};
use crate::planner::Context;
use crate::planner::section::{Placement, Section, SectionDecl};
use serde::{Deserialize, Serialize};

/// The lane spacings tried where `lane_spacing` is absent, as shares of the robot's width: a
/// spacing of one width leaves cells between the lanes' bands on the scorer's raster (issue
/// 102's model on basement: 87 % of the reachable cells at 0.6 m for a 0.6 m robot, 90 % at
/// 0.55 m), so narrower spacings compete by their time to the goal.
pub const AUTO_SPACINGS: [f64; 4] = [1.0, 0.95, 0.9, 0.85];

/// `[layouts]` as the lane control's entry declares it: held where a file writes it, and
/// written in full for a run of the lane control.
pub static LAYOUTS_SECTION: Section<LayoutsSection> = Section::new(
    SectionDecl {
        name: "layouts",
        readers: "only the lane control (planner = \"layouts\") reads",
        placement: Placement::BeforeBudget,
        always_held: false,
        type_name: "LayoutsSection",
        tables: &[],
        source: include_str!("config.rs"),
    },
    Some(LayoutsSection::default),
);

/// `[layouts]`: straight lanes at the best of a few directions, spacings and offsets, in the
/// greedy nearest order, completed up to the coverage goal (issue 102, item 1).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LayoutsSection {
    /// Lane directions tried, in degrees from +x.
    pub directions: Vec<f64>,
    /// How many of the map's dominant wall orientations are tried beside `directions`.
    pub wall_directions: usize,
    /// Distance between lanes in metres; absent: each of [`AUTO_SPACINGS`] times the width.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lane_spacing: Option<f64>,
    /// Offsets of the first lane tried, each a `1 / lane_offsets` share of the spacing further.
    pub lane_offsets: usize,
    /// Lane pieces shorter than this after trimming are dropped (metres); absent: the width.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_lane: Option<f64>,
    /// How many layouts, those with the best estimates, are driven in full and scored.
    pub finalists: usize,
    /// The share of the reachable coverable cells the plan covers before it returns; absent:
    /// everything it can, the fastest plan within a tie of the best coverage chosen.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coverage_goal: Option<f64>,
}

impl Default for LayoutsSection {
    fn default() -> Self {
        Self {
            directions: vec![0.0, 90.0],
            wall_directions: 0,
            lane_spacing: None,
            lane_offsets: 12,
            min_lane: None,
            finalists: 8,
            coverage_goal: None,
        }
    }
}

/// The validated `[layouts]`.
#[derive(Clone, Debug, PartialEq)]
pub struct LayoutsConfig {
    /// Lane directions in degrees (the wall orientations added after those given).
    pub directions: Vec<f64>,
    /// Lane spacings in metres.
    pub spacings: Vec<f64>,
    /// Offsets of the first lane per direction and spacing.
    pub offsets: usize,
    /// The shortest lane piece kept, in metres.
    pub min_lane_m: f64,
    /// Layouts driven in full and scored.
    pub finalists: usize,
    /// The coverage goal.
    pub coverage_goal: Option<f64>,
}

impl LayoutsSection {
    /// Checks every key against its range for the run's map and robot.
    pub fn validate(&self, ctx: &Context) -> Result<LayoutsConfig, ConfigError> {
        let o = ctx.origin;
        let (map, width) = (&ctx.scenario.map, ctx.scenario.robot.width);
        crate::lanes::check_lane_count(map, width).map_err(|e| ctx.error("robot.width", e.to_string()))?;
        if self.directions.is_empty() || self.directions.len() > 36 {
            return Err(ctx.error("layouts.directions", "needs 1 to 36 lane directions in degrees"));
        }
        for &d in &self.directions {
            check_range(o, "layouts.directions", d, -360.0, 360.0, "[-360, 360] degrees")?;
        }
        check_range(o, "layouts.wall_directions", self.wall_directions as f64, 0.0, 8.0, "integers 0..=8")?;
        let mut directions = self.directions.clone();
        if self.wall_directions > 0 {
            for a in crate::map::orientation::wall_orientations(map, self.wall_directions) {
                let apart = |d: f64| {
                    let gap = (d - a).rem_euclid(180.0);
                    gap.min(180.0 - gap) > 1.0
                };
                if directions.iter().all(|&d| apart(d)) {
                    directions.push(a);
                }
            }
        }
        let spacings = match self.lane_spacing {
            Some(s) => {
                check_range(o, "layouts.lane_spacing", s, 0.25 * width, width, "[width / 4, width] metres")?;
                vec![s]
            }
            None => AUTO_SPACINGS.iter().map(|f| f * width).collect(),
        };
        check_range(o, "layouts.lane_offsets", self.lane_offsets as f64, 1.0, 64.0, "integers 1..=64")?;
        let min_lane_m = self.min_lane.unwrap_or(width);
        check_range(o, "layouts.min_lane", min_lane_m, 0.0, 100.0, "[0, 100] metres")?;
        check_range(o, "layouts.finalists", self.finalists as f64, 1.0, 10_000.0, "integers 1..=10000")?;
        if let Some(g) = self.coverage_goal
            && !(g > 0.0 && g <= 1.0)
        {
            return Err(
                ctx.error("layouts.coverage_goal", format!("= {g} is outside (0, 1] (a share of the reachable cells)"))
            );
        }
        Ok(LayoutsConfig {
            directions,
            spacings,
            offsets: self.lane_offsets,
            min_lane_m,
            finalists: self.finalists,
            coverage_goal: self.coverage_goal,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planner::{Budget, Checks, Scenario};

    fn validated(section: &LayoutsSection) -> Result<LayoutsConfig, ConfigError> {
        let map = crate::map::presets::preset("office").unwrap();
        let start = crate::geom::Point::new(2.0, 2.0);
        let s = Scenario {
            map,
            robot: crate::coverage::Footprint { width: 0.6, speed: 0.3, rot_speed: 0.52 },
            start,
            end: start,
            projection: crate::coverage::fitness::Projection::F2,
            camera: crate::coverage::score::CameraSpec {
                scale: 0.1,
                d_min: 0.2,
                d_max: 7.0,
                fov_deg: 69.4,
                sections: 15,
                band_m: 0.45,
            },
        };
        let budget = Budget::iterations(1);
        section.validate(&Context { origin: "t.toml", scenario: &s, budget: &budget, checks: Checks::Full })
    }

    #[test]
    fn absent_spacing_tries_the_automatic_ones_and_a_given_one_alone() {
        let auto = validated(&LayoutsSection::default()).unwrap();
        assert_eq!(auto.spacings, AUTO_SPACINGS.iter().map(|f| f * 0.6).collect::<Vec<_>>());
        assert_eq!(auto.min_lane_m, 0.6, "the width by default");
        let given = validated(&LayoutsSection { lane_spacing: Some(0.55), ..LayoutsSection::default() }).unwrap();
        assert_eq!(given.spacings, vec![0.55]);
    }

    #[test]
    fn wall_directions_join_the_given_ones_once() {
        let c = validated(&LayoutsSection { wall_directions: 2, ..LayoutsSection::default() }).unwrap();
        assert!(c.directions.starts_with(&[0.0, 90.0]) && c.directions.len() <= 4, "{:?}", c.directions);
    }

    #[test]
    fn out_of_range_settings_name_their_key() {
        for (section, key) in [
            (LayoutsSection { lane_spacing: Some(0.7), ..LayoutsSection::default() }, "layouts.lane_spacing"),
            (LayoutsSection { lane_offsets: 0, ..LayoutsSection::default() }, "layouts.lane_offsets"),
            (LayoutsSection { finalists: 0, ..LayoutsSection::default() }, "layouts.finalists"),
            (LayoutsSection { min_lane: Some(-1.0), ..LayoutsSection::default() }, "layouts.min_lane"),
            (LayoutsSection { coverage_goal: Some(0.0), ..LayoutsSection::default() }, "layouts.coverage_goal"),
            (LayoutsSection { directions: vec![], ..LayoutsSection::default() }, "layouts.directions"),
        ] {
            let e = validated(&section).unwrap_err().to_string();
            assert!(e.contains(key) && e.contains("t.toml"), "{key}: {e}");
        }
    }
}
