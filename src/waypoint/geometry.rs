//! The waypoint geometry of 000 §II-B.2 in metres: grid step, safety buffer, anti-crowding
//! distance, wall band and near-wall distance, each resolved from `[waypoint]` with 000's
//! definition as the default and, where 000 gives only a bound or nothing, the authors'
//! driver's choice (waypoint §3, §19).

use super::config::WaypointSection;
use crate::config::{ConfigError, check_range};
use crate::map::GridMap;

/// How the waypoint grid step follows from the narrowest hallway `h_min`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GridStep {
    /// `h_min / 2` (000 §II-B.2: a grid at half the narrowest hallway).
    #[default]
    HalfHallway,
    /// `floor(h_min / s)` pixels: the full hallway, as the authors' driver places its grid.
    Hallway,
}

/// Factor of the authors' driver between the safety buffer and the near-wall distance
/// (`wall_waypoint_factor`).
pub const NEAR_WALL_FACTOR: f64 = 2.5;

/// The resolved geometry, all in metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Geometry {
    /// Spacing of the initial waypoint grid `g`.
    pub grid_step: f64,
    /// Safety buffer `b`: waypoints keep at least this clearance where the space allows.
    pub buffer: f64,
    /// Waypoints closer than this are merged (anti-crowding).
    pub merge: f64,
    /// Width of the wall band `B` whose coverage is `C_walls` (eq. 2).
    pub wall_band: f64,
    /// The near-wall set keeps waypoints at most this far from a wall.
    pub near_wall: f64,
}

/// The grid step `g` in metres for `h_min` at scale `s` (000 §II-B.2, or the authors' driver).
pub fn grid_step_m(rule: GridStep, hallway: f64, scale: f64) -> f64 {
    match rule {
        GridStep::HalfHallway => hallway / 2.0,
        GridStep::Hallway => (hallway / scale + 1e-9).floor() * scale,
    }
}

impl Geometry {
    /// Resolves and checks the geometry keys of `w` on `map`, whose raster has pixels of
    /// `scale` metres (`scorer.camera.scale`).
    pub fn resolve(w: &WaypointSection, scale: f64, origin: &str, map: &GridMap) -> Result<Self, ConfigError> {
        let err = |key: &str, msg: String| ConfigError::new(origin, key, msg);
        let longest = map.width_m().max(map.height_m());
        if !(w.hallway.is_finite() && w.hallway <= longest) {
            return Err(err(
                "waypoint.hallway",
                format!(
                    "= {} m is out of range: allowed [max(2 x scale, map resolution), the map's longer side = {longest} m]",
                    crate::io::short_number(w.hallway)
                ),
            ));
        }
        if w.hallway < 2.0 * scale || w.hallway < map.resolution() {
            return Err(err(
                "waypoint.hallway",
                format!(
                    "= {} m is below the cell size: the narrowest hallway must be at least 2 x scale = {} m and the map resolution {} m",
                    crate::io::short_number(w.hallway),
                    2.0 * scale,
                    map.resolution()
                ),
            ));
        }
        let grid_step = grid_step_m(w.grid_step, w.hallway, scale);
        let half_uav = w.uav_width / 2.0;
        let buffer = match w.safety_buffer {
            Some(b) => {
                check_range(origin, "waypoint.safety_buffer", b, 0.0, longest, "[0, the map's longer side] metres")?;
                if b <= half_uav {
                    return Err(err(
                        "waypoint.safety_buffer",
                        format!("= {b} m must exceed half the UAV width ({half_uav} m, 000 §II-B.2)"),
                    ));
                }
                b
            }
            None => {
                let b = w.hallway / 2.0;
                if b <= half_uav {
                    return Err(err(
                        "waypoint.hallway",
                        format!(
                            "= {} m gives a safety buffer of {b} m (half the hallway), which must exceed half the UAV width ({half_uav} m): set `waypoint.safety_buffer` or a narrower `uav_width`",
                            w.hallway
                        ),
                    ));
                }
                b
            }
        };
        let merge = match w.merge_distance {
            Some(m) => {
                check_range(origin, "waypoint.merge_distance", m, 0.0, longest, "[0, the map's longer side] metres")?;
                m
            }
            None => grid_step,
        };
        let wall_band = match w.wall_band {
            Some(v) => {
                check_range(origin, "waypoint.wall_band", v, scale, longest, "[scale, the map's longer side] metres")?;
                v
            }
            None => buffer,
        };
        let near_wall = match w.near_wall {
            Some(v) => {
                check_range(origin, "waypoint.near_wall", v, 0.0, longest, "[0, the map's longer side] metres")?;
                if v < buffer {
                    return Err(err(
                        "waypoint.near_wall",
                        format!("= {v} m is below the safety buffer ({buffer} m): every waypoint would be dropped"),
                    ));
                }
                v
            }
            None => NEAR_WALL_FACTOR * buffer,
        };
        Ok(Self { grid_step, buffer, merge, wall_band, near_wall })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::presets::preset;

    fn section(text: &str) -> WaypointSection {
        toml::from_str(text).unwrap()
    }

    #[test]
    fn the_papers_values_resolve_as_000_and_the_driver_define_them() {
        let map = preset("office").unwrap();
        // h_min = 2.5 m at 0.15 m/px: 000's grid is 1.25 m; the driver's 16 px = 2.4 m.
        let g = Geometry::resolve(&section("hallway = 2.5\n"), 0.15, "e.toml", &map).unwrap();
        assert_eq!(g.grid_step, 1.25);
        assert_eq!(g.buffer, 1.25);
        assert_eq!(g.merge, 1.25);
        assert_eq!(g.wall_band, 1.25);
        assert_eq!(g.near_wall, 3.125);
        let d = Geometry::resolve(&section("hallway = 2.5\ngrid_step = \"hallway\"\n"), 0.15, "e.toml", &map).unwrap();
        assert!((d.grid_step - 2.4).abs() < 1e-12, "{}", d.grid_step);
        assert!((d.merge - 2.4).abs() < 1e-12);
        let set = section("hallway = 2.5\nsafety_buffer = 0.4\nwall_band = 1.2\nnear_wall = 3\nmerge_distance = 2\n");
        let s = Geometry::resolve(&set, 0.15, "e.toml", &map).unwrap();
        assert_eq!((s.buffer, s.wall_band, s.near_wall, s.merge), (0.4, 1.2, 3.0, 2.0));
    }

    #[test]
    fn a_buffer_within_half_the_uav_is_refused_by_its_key() {
        let map = preset("office").unwrap();
        for (text, key) in [
            ("safety_buffer = 0.25\nuav_width = 0.5\n", "waypoint.safety_buffer"),
            ("hallway = 0.5\nuav_width = 0.6\n", "waypoint.hallway"),
            ("near_wall = 0.5\nhallway = 2.5\n", "waypoint.near_wall"),
            ("wall_band = 0.01\n", "waypoint.wall_band"),
            ("merge_distance = -1\n", "waypoint.merge_distance"),
        ] {
            let e = Geometry::resolve(&section(text), 0.15, "e.toml", &map).unwrap_err().to_string();
            assert!(e.contains(key), "{text}: {e}");
        }
    }
}
