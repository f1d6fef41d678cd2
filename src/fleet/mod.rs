//! Robot fleets (beyond 003, whose title names heterogeneous fleets and whose conclusion leaves
//! them as the next step): several robots of their own width, speed and stations on one map.
//! [`Fleet`] is the validated team; [`metrics`] scores a fleet's plan on one shared visit map;
//! [`planner::FleetPlanner`] plans it through the common `Planner` interface — the
//! centralised GA ([`central`]), the negotiation ([`negotiation`]), area division
//! ([`division`]) or the waypoint planner's teams — as `[fleet]` ([`config`]) says.

pub mod central;
pub mod config;
pub mod details;
pub mod division;
pub mod metrics;
pub mod negotiation;
pub mod planner;

use crate::coverage::Footprint;
use crate::geom::Point;

/// One robot of a fleet: the planner layer's [`Agent`](crate::planner::Agent), so that a
/// fleet's plan hands its robots to the run's output as they are.
pub use crate::planner::Agent as Robot;

/// A validated, non-empty fleet with distinct robot names (see [`config`] for the checks).
#[derive(Clone, Debug, PartialEq)]
pub struct Fleet {
    robots: Vec<Robot>,
}

impl Fleet {
    /// A team of identical robots named `agent 0`, `agent 1`, … with the given start and end
    /// stations (a multi-agent plan of one robot type, e.g. the waypoint planner's teams).
    /// `None` without stations.
    pub fn homogeneous(footprint: Footprint, stations: &[(Point, Point)]) -> Option<Self> {
        (!stations.is_empty()).then(|| Self {
            robots: stations
                .iter()
                .enumerate()
                .map(|(k, &(start, end))| Robot { name: format!("agent {k}"), footprint, start, end })
                .collect(),
        })
    }

    /// The fleet of `robots`, as validated before (a plan's agents); `None` when empty.
    pub fn from_agents(robots: Vec<Robot>) -> Option<Self> {
        (!robots.is_empty()).then_some(Self { robots })
    }

    /// The robots, in the order of the experiment file.
    pub fn robots(&self) -> &[Robot] {
        &self.robots
    }

    /// Number of robots.
    pub fn len(&self) -> usize {
        self.robots.len()
    }

    /// Always false: a fleet has at least one robot.
    pub fn is_empty(&self) -> bool {
        self.robots.is_empty()
    }

    /// The fleet's combined sweep rate `Σ R_width,i · R_speed,i` in m²/s.
    pub fn sweep_rate(&self) -> f64 {
        self.robots.iter().map(Robot::sweep_rate).sum()
    }

    /// Whether every robot has the same width, speed and rotation speed.
    pub fn is_homogeneous(&self) -> bool {
        self.robots.windows(2).all(|w| w[0].footprint == w[1].footprint)
    }
}

/// `t_optimal` of a fleet: 003 eq. 3.11 with the fleet's combined sweep rate,
/// `cov_actual / Σ_i R_speed,i · R_width,i` — the time the robots would need if the area they
/// covered were split between them in proportion to their rates, swept without overlap and
/// finished together. For one robot it is eq. 3.11.
pub fn fleet_t_optimal(cov_actual_m2: f64, sweep_rate: f64) -> f64 {
    cov_actual_m2 / sweep_rate
}

/// `t_final` of a fleet: 003 eq. 3.13 with the fleet's time taken as the makespan,
/// `t_optimal / max_i (t_actual,i + T_rot,i)`, where `t_actual,i` is robot `i`'s eq. 3.12
/// (`cov_[m²],i / (R_speed,i · R_width,i)`) and `T_rot,i` its rotation time; 0 when nothing was
/// covered (R10). For one robot it is eq. 3.13.
pub fn fleet_t_final(t_optimal: f64, robot_times: &[f64]) -> f64 {
    let makespan = robot_times.iter().copied().fold(0.0, f64::max);
    if makespan <= 0.0 { 0.0 } else { t_optimal / makespan }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_homogeneous_team_names_its_agents() {
        let fp = Footprint { width: 0.5, speed: 0.25, rot_speed: 0.0 };
        let (a, b) = (Point::new(1.0, 2.0), Point::new(3.0, 4.0));
        let team = Fleet::homogeneous(fp, &[(a, b), (b, a)]).unwrap();
        assert_eq!((team.len(), team.is_empty(), team.is_homogeneous()), (2, false, true));
        let names: Vec<&str> = team.robots().iter().map(|r| r.name.as_str()).collect();
        assert_eq!(names, ["agent 0", "agent 1"]);
        assert_eq!((team.robots()[1].start, team.robots()[1].end), (b, a));
        assert!((team.sweep_rate() - 0.25).abs() < 1e-15, "2 × 0.5 m × 0.25 m/s");
        assert!(Fleet::homogeneous(fp, &[]).is_none());
        assert!(Fleet { robots: Vec::new() }.is_empty());
    }

    #[test]
    fn fleet_time_by_hand() {
        // Rates 0.4·0.2 + 0.6·0.3 + 0.9·0.5 = 0.08 + 0.18 + 0.45 = 0.71 m²/s; 71 m² → 100 s.
        assert!((fleet_t_optimal(71.0, 0.71) - 100.0).abs() < 1e-9);
        // Slowest robot 125 s: t_final = 100 / 125.
        assert!((fleet_t_final(100.0, &[80.0, 125.0, 90.0]) - 0.8).abs() < 1e-12);
        assert_eq!(fleet_t_final(0.0, &[0.0, 0.0]), 0.0);
    }
}
