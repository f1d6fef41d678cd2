//! `[[robots]]` entries of an experiment (or fleet) file and their validation into a [`Fleet`].
//! Every field but the name defaults to the file's `[robot]` and `[stations]`.

use super::negotiation::NegotiationParams;
use super::{Fleet, Robot};
use crate::config::{ConfigError, check_range};
use crate::coverage::Footprint;
use crate::geom::Point;
use crate::map::GridMap;
use crate::planner::Context;
use crate::thesis::params::ThesisParams;
use crate::waypoint::config::{WaypointConfig, WaypointSection};
use serde::{Deserialize, Serialize};

/// Most robots a fleet may hold (a study of fleets goes to 5; the bound keeps a typo such as a
/// pasted table from allocating one visit map per row).
pub const MAX_ROBOTS: usize = 64;

/// One `[[robots]]` entry: a robot of a fleet, its settings defaulting to `[robot]` and
/// `[stations]`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobotEntry {
    /// Name (required, unique in the fleet).
    pub name: String,
    /// `R_width` in metres (default `[robot].width`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<f64>,
    /// `R_speed` in m/s (default `[robot].speed`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed: Option<f64>,
    /// `R_rot` in rad/s (default `[robot].rot_speed`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rot_speed: Option<f64>,
    /// Start station in metres (default `[stations].start`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start: Option<[f64; 2]>,
    /// End station in metres (default: this robot's start).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub end: Option<[f64; 2]>,
}

/// Validates `entries` (read from `origin`) into a fleet on `map`, with `robot` and `start`
/// as the defaults. Each error names the entry (`robots[2]`, and the robot's name) and its key.
pub fn validate(
    entries: &[RobotEntry],
    robot: Footprint,
    start: [f64; 2],
    origin: &str,
    map: &GridMap,
) -> Result<Fleet, ConfigError> {
    if entries.is_empty() {
        return Err(ConfigError::new(origin, "robots", "is empty: a fleet needs at least one [[robots]] entry"));
    }
    if entries.len() > MAX_ROBOTS {
        return Err(ConfigError::new(
            origin,
            "robots",
            format!("has {} entries: allowed at most {MAX_ROBOTS}", entries.len()),
        ));
    }
    let mut robots: Vec<Robot> = Vec::with_capacity(entries.len());
    for (k, e) in entries.iter().enumerate() {
        let key = |field: &str| format!("robots[{k}].{field}");
        if e.name.trim().is_empty() {
            return Err(ConfigError::new(origin, &key("name"), "is empty: every robot needs a name"));
        }
        if e.name.chars().any(|c| matches!(c, ',' | '"' | '\n' | '\r')) {
            return Err(ConfigError::new(
                origin,
                &key("name"),
                format!("= {:?} holds a comma, quote or line break: names go into CSV columns", e.name),
            ));
        }
        if let Some(j) = robots.iter().position(|r| r.name == e.name) {
            return Err(ConfigError::new(
                origin,
                &key("name"),
                format!("= \"{}\" is already the name of robots[{j}]: names must be distinct", e.name),
            ));
        }
        let named = |field: &str| format!("{} (robot \"{}\")", key(field), e.name);
        let width = e.width.unwrap_or(robot.width);
        let speed = e.speed.unwrap_or(robot.speed);
        let rot_speed = e.rot_speed.unwrap_or(robot.rot_speed);
        let footprint = Footprint { width, speed, rot_speed };
        if let Some((name, v, allowed)) = footprint.out_of_range() {
            let v = crate::io::short_number(v);
            return Err(ConfigError::new(origin, &named(name), format!("= {v} is out of range: allowed {allowed}")));
        }
        footprint.check_fits(map).map_err(|m| ConfigError::new(origin, &named("width"), m))?;
        let s = e.start.unwrap_or(start);
        let s = Point::new(s[0], s[1]);
        let end = e.end.map_or(s, |p| Point::new(p[0], p[1]));
        map.check_station(s, "the start").map_err(|m| ConfigError::new(origin, &named("start"), m))?;
        map.check_station(end, "the end").map_err(|m| ConfigError::new(origin, &named("end"), m))?;
        {
            use crate::map::reach::{station_misfit, unreachable_end};
            let clear = crate::map::clearance::Clearance::new(map, width);
            if let Some(why) = station_misfit(&clear, s, "the start") {
                return Err(ConfigError::new(origin, &named("start"), why));
            }
            if let Some(why) = station_misfit(&clear, end, "the end") {
                return Err(ConfigError::new(origin, &named("end"), why));
            }
            if end != s
                && let Some(why) = unreachable_end(&clear, s, end)
            {
                return Err(ConfigError::new(origin, &named("end"), why));
            }
        }
        robots.push(Robot { name: e.name.clone(), footprint, start: s, end });
    }
    Ok(Fleet { robots })
}

/// How a fleet is planned.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FleetMode {
    /// Decentralised negotiation: one thesis GA per robot, plans exchanged every
    /// `round_iterations` ([`super::negotiation`]).
    #[default]
    Negotiate,
    /// The centralised fleet GA: one genome per robot in every member ([`super::central`]).
    Central,
    /// Area division in the style of DARP, a boustrophedon per region ([`super::division`]).
    Divide,
    /// The waypoint planner's multi-agent mode (000), one agent per robot from its start; the
    /// robots must all be the experiment's `[robot]`.
    Waypoint,
}

impl FleetMode {
    /// The planner's name in summaries and study tables.
    pub fn planner_name(self) -> &'static str {
        match self {
            FleetMode::Negotiate => "fleet-negotiate",
            FleetMode::Central => "fleet-central",
            FleetMode::Divide => "fleet-divide",
            FleetMode::Waypoint => "fleet-waypoint",
        }
    }

    /// Whether a fleet planned this way ignores the seed (area division plans in one step).
    pub fn is_deterministic(self) -> bool {
        match self {
            FleetMode::Divide => true,
            FleetMode::Negotiate | FleetMode::Central | FleetMode::Waypoint => false,
        }
    }
}

/// `[fleet]`: how the fleet of `[[robots]]` is planned.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FleetSection {
    /// How the fleet is planned.
    pub mode: FleetMode,
    /// A label for the fleet in study tables (e.g. `hetero-3`); no effect on the plan.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Iterations of every robot's GA between two exchanges (`k`, negotiation).
    pub round_iterations: u32,
    /// Largest plan change (share of swept cells) that counts as settled (negotiation).
    pub tolerance: f64,
    /// Lane angle of the regions' boustrophedons in degrees (division).
    pub angle_deg: f64,
}

impl Default for FleetSection {
    fn default() -> Self {
        Self { mode: FleetMode::Negotiate, name: None, round_iterations: 100, tolerance: 0.02, angle_deg: 0.0 }
    }
}

/// How a validated fleet is planned, with what each method needs.
#[derive(Clone, Debug)]
pub enum FleetMethod {
    /// The centralised fleet GA with the thesis GA's parameters.
    Central(ThesisParams),
    /// Decentralised negotiation: the thesis GA's parameters per robot and the rounds.
    Negotiate(ThesisParams, NegotiationParams),
    /// Area division, a boustrophedon per region at this lane angle in degrees.
    Divide {
        /// Lane angle in degrees.
        angle_deg: f64,
    },
    /// The waypoint planner's team of identical robots, one agent per robot.
    Waypoint(Box<WaypointConfig>),
}

impl FleetMethod {
    /// The mode's name in the experiment file.
    pub fn mode(&self) -> FleetMode {
        match self {
            FleetMethod::Central(_) => FleetMode::Central,
            FleetMethod::Negotiate(..) => FleetMode::Negotiate,
            FleetMethod::Divide { .. } => FleetMode::Divide,
            FleetMethod::Waypoint(_) => FleetMode::Waypoint,
        }
    }
}

/// The planner a fleet's experiment names, validated, as the fleet's method needs it.
#[derive(Clone, Debug)]
pub enum Team {
    /// `planner = "thesis"`: central, negotiate or divide.
    Thesis(ThesisParams),
    /// `planner = "waypoint"`: the waypoint planner's teams.
    Waypoint(Box<WaypointConfig>),
}

impl FleetSection {
    /// Validates this section and the `[[robots]]` entries (`start` is the default start
    /// station, `retrain` whether the file has a `[retrain]`) into the fleet planner, with
    /// `team` the validated planner the file names; `planner` is that planner's name.
    pub fn validate(
        &self,
        robots: &[RobotEntry],
        start: [f64; 2],
        retrain: bool,
        team: Team,
        ctx: &Context,
    ) -> Result<super::planner::FleetPlanner, ConfigError> {
        let (origin, scenario, budget) = (ctx.origin, ctx.scenario, ctx.budget);
        let method = self.method(team, budget, origin)?;
        self.check_keys(retrain, origin)?;
        let fleet = validate(robots, scenario.robot, start, origin, &scenario.map)?;
        self.check_fleet(&fleet, scenario, origin)?;
        Ok(super::planner::FleetPlanner { fleet, name: self.name.clone(), method })
    }

    /// How the team plans under `fleet.mode`, refused where the file's planner cannot.
    fn method(&self, team: Team, budget: &crate::planner::Budget, origin: &str) -> Result<FleetMethod, ConfigError> {
        Ok(match (self.mode, team) {
            (FleetMode::Central, Team::Thesis(t)) => FleetMethod::Central(t),
            (FleetMode::Negotiate, Team::Thesis(t)) => FleetMethod::Negotiate(
                t,
                NegotiationParams {
                    round_iterations: self.round_iterations,
                    iterations: budget.iterations,
                    evaluations: budget.evaluations,
                    tolerance: self.tolerance,
                },
            ),
            (FleetMode::Divide, Team::Thesis(_)) => FleetMethod::Divide { angle_deg: self.angle_deg },
            (FleetMode::Waypoint, Team::Waypoint(w)) => FleetMethod::Waypoint(w),
            (mode @ (FleetMode::Central | FleetMode::Negotiate | FleetMode::Divide), Team::Waypoint(_)) => {
                return Err(wrong_planner(origin, "waypoint", mode));
            }
            (mode @ FleetMode::Waypoint, Team::Thesis(_)) => return Err(wrong_planner(origin, "thesis", mode)),
        })
    }

    /// The section's own keys, and `[retrain]`, which no fleet honours.
    fn check_keys(&self, retrain: bool, origin: &str) -> Result<(), ConfigError> {
        if retrain {
            return Err(ConfigError::new(
                origin,
                "retrain",
                "is not available for fleets (the negotiation pre-marks cells itself)",
            ));
        }
        if self.round_iterations == 0 || self.round_iterations > 1_000_000 {
            return Err(ConfigError::new(
                origin,
                "fleet.round_iterations",
                format!("= {} is out of range [1, 1000000]", self.round_iterations),
            ));
        }
        check_range(origin, "fleet.tolerance", self.tolerance, 0.0, 1.0, "[0, 1]")?;
        check_range(origin, "fleet.angle_deg", self.angle_deg, -360.0, 360.0, "[-360, 360] degrees")?;
        if let Some(name) = &self.name
            && (name.trim().is_empty() || name.len() > 64 || name.chars().any(|c| matches!(c, ',' | '"' | '\n' | '\r')))
        {
            return Err(ConfigError::new(
                origin,
                "fleet.name",
                format!(
                    "= {name:?} must be 1 to 64 characters without comma, quote or line break (it goes into CSV columns)"
                ),
            ));
        }
        Ok(())
    }

    /// The robots as the mode needs them: identical for the waypoint planner's team, distinct
    /// start cells for area division.
    fn check_fleet(&self, fleet: &Fleet, scenario: &crate::planner::Scenario, origin: &str) -> Result<(), ConfigError> {
        let r = scenario.robot;
        if self.mode == FleetMode::Waypoint
            && let Some(k) = fleet.robots().iter().position(|x| x.footprint != r)
        {
            return Err(ConfigError::new(
                origin,
                &format!("robots[{k}]"),
                format!(
                    "(robot \"{}\") differs from [robot]: the waypoint planner plans teams of identical robots \
                     (leave width, speed and rot_speed to [robot])",
                    fleet.robots()[k].name
                ),
            ));
        }
        if self.mode == FleetMode::Divide
            && let Some((j, k)) = super::division::shared_start(&scenario.map, fleet)
        {
            let names = (&fleet.robots()[j].name, &fleet.robots()[k].name);
            return Err(ConfigError::new(
                origin,
                &format!("robots[{k}].start"),
                format!(
                    "(robot \"{}\") starts in the same cell as robots[{j}] (robot \"{}\") (or, where a start lies off \
                     the free cells, the nearest cell each fits in): fleet.mode = \"divide\" needs distinct start stations",
                    names.1, names.0
                ),
            ));
        }
        Ok(())
    }
}

/// The error for `planner = "<planner>"` where `mode` needs another planner.
pub fn wrong_planner(origin: &str, planner: &str, mode: FleetMode) -> ConfigError {
    ConfigError::new(
        origin,
        "planner",
        format!(
            "= \"{planner}\" cannot plan for [[robots]] with fleet.mode = \"{}\": a fleet is planned by the thesis GA \
             (planner = \"thesis\", fleet.mode = \"central\" or \"negotiate\"), by area division (planner = \"thesis\", \
             fleet.mode = \"divide\") or by the waypoint planner's teams (planner = \"waypoint\", fleet.mode = \"waypoint\")",
            mode.planner_name().trim_start_matches("fleet-")
        ),
    )
}

/// For `fleet.mode = "waypoint"`: the `[waypoint]` section that plans one agent per robot of
/// `robots`, each from the robot's start (`start` by default), as the waypoint planner
/// validates it; the file's own section is left as written. Otherwise the section itself.
pub fn waypoint_team(
    waypoint: &WaypointSection,
    robots: &[RobotEntry],
    fleet: Option<&FleetSection>,
    start: [f64; 2],
    origin: &str,
) -> Result<WaypointSection, ConfigError> {
    if robots.is_empty() || fleet.is_none_or(|f| f.mode != FleetMode::Waypoint) {
        return Ok(waypoint.clone());
    }
    let agents = robots.len().min(MAX_ROBOTS);
    let starts: Vec<[f64; 2]> = robots.iter().take(agents).map(|r| r.start.unwrap_or(start)).collect();
    let unset = waypoint.agents == 1 && waypoint.starts.is_empty();
    if !unset && (waypoint.agents != agents || waypoint.starts != starts) {
        return Err(ConfigError::new(
            origin,
            "waypoint.agents",
            "and waypoint.starts come from [[robots]] with fleet.mode = \"waypoint\": leave them out",
        ));
    }
    Ok(WaypointSection { agents, starts, ..waypoint.clone() })
}

/// A fleet file for `covga eval --fleet`: `[robot]` defaults, `[stations]` defaults and the
/// `[[robots]]` entries, as in an experiment file.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FleetFile {
    /// Defaults of the robots' widths and speeds.
    #[serde(default)]
    pub robot: crate::planner::sections::RobotSection,
    /// Default start station.
    #[serde(default)]
    pub stations: crate::planner::sections::StationsSection,
    /// The robots.
    #[serde(default)]
    pub robots: Vec<RobotEntry>,
}

impl FleetFile {
    /// Parses `text` (from `origin`) and validates it on `map`.
    pub fn parse(text: &str, origin: &str, map: &GridMap) -> Result<Fleet, ConfigError> {
        let file: FleetFile = toml::from_str(text).map_err(|e| ConfigError::from_toml(origin, text, &e))?;
        let r = file.robot;
        validate(
            &file.robots,
            Footprint { width: r.width, speed: r.speed, rot_speed: r.rot_speed },
            file.stations.start,
            origin,
            map,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::presets::preset;

    fn parse(text: &str) -> Result<Fleet, ConfigError> {
        FleetFile::parse(text, "fleet.toml", &preset("thesis-1").unwrap())
    }

    #[test]
    fn defaults_come_from_robot_and_stations() {
        let f = parse(
            "[robot]\nwidth = 0.5\nspeed = 0.25\n[stations]\nstart = [2.0, 2.0]\n\
             [[robots]]\nname = \"a\"\n[[robots]]\nname = \"b\"\nwidth = 0.9\nstart = [8.0, 8.0]\nend = [5.0, 5.0]\n",
        )
        .unwrap();
        let [a, b] = f.robots() else { panic!("two robots") };
        assert_eq!((a.footprint.width, a.footprint.speed, a.start, a.end), (0.5, 0.25, Point::new(2.0, 2.0), a.start));
        assert_eq!((b.footprint.width, b.footprint.speed), (0.9, 0.25));
        assert_eq!((b.start, b.end), (Point::new(8.0, 8.0), Point::new(5.0, 5.0)));
        assert!(!f.is_homogeneous());
        assert!((f.sweep_rate() - (0.5 * 0.25 + 0.9 * 0.25)).abs() < 1e-12);
    }

    #[test]
    fn bad_entries_name_the_robot_and_key() {
        // (file, text every message must contain)
        let cases = [
            ("", "robots"),
            ("[[robots]]\nname = \"\"\n", "robots[0].name"),
            ("[[robots]]\nname = \"a,b\"\n", "comma"),
            ("[[robots]]\nname = \"a\"\n[[robots]]\nname = \"a\"\n", "robots[1].name"),
            ("[[robots]]\nname = \"x\"\nwidth = 0.0\n", "robots[0].width (robot \"x\")"),
            ("[[robots]]\nname = \"x\"\nwidth = 50.0\n", "wider than the map"),
            ("[[robots]]\nname = \"x\"\nspeed = -1.0\n", "robots[0].speed"),
            ("[[robots]]\nname = \"x\"\nrot_speed = nan\n", "robots[0].rot_speed"),
            (
                "[[robots]]\nname = \"x\"\n[[robots]]\nname = \"y\"\nstart = [0.5, 5.0]\n",
                "robots[1].start (robot \"y\")",
            ),
            ("[[robots]]\nname = \"x\"\nend = [50.0, 5.0]\n", "outside map"),
            ("[[robots]]\nname = \"x\"\ncolour = 3\n", "colour"),
        ];
        for (text, needle) in cases {
            let e = parse(text).err().unwrap_or_else(|| panic!("{text:?} must be refused")).to_string();
            assert!(e.contains("fleet.toml") && e.contains(needle), "{text:?}: {e}");
        }
    }
}
