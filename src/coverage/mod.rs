//! Coverage of a path on a grid map: the swept footprint of 003 §3.1 ([`raster`], [`sweep`])
//! and the motion metrics ([`motion`]), combined into [`PathMetrics`] by [`Footprint`]; the
//! thesis fitness equations that turn them into `cov_final`, `t_final` and `f` ([`fitness`],
//! 003 §3.2.1); visit maps as bit planes that GAs edit segment by segment ([`bits`],
//! [`planes`]); the camera model of 000 on its working raster ([`camera`], [`work_map`]); and
//! the common scorer every planner is compared by ([`score`]), and the lower bounds on the time
//! to cover an area that every time is read against ([`bound`]). Wall-free routes and transit
//! lengths live one layer up, in [`crate::routing`]. Planners build on this layer; it depends
//! on none of them.

pub mod account;
pub mod bits;
pub mod bound;
pub mod camera;
pub mod curve;
#[cfg(test)]
pub(crate) mod exact;
pub mod fitness;
pub mod motion;
pub mod planes;
pub mod raster;
pub mod rows;
pub mod score;
pub mod sweep;
pub mod views;
pub mod work_map;

pub use sweep::{CoverageGrid, SweepCounts, SweepScratch};

use crate::geom::Point;

/// The robot's cleaning footprint and motion (003 §3.1, Table 4.2).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Footprint {
    /// `R_width`: width of the swept rectangle in metres.
    pub width: f64,
    /// `R_speed`: translation speed in m/s.
    pub speed: f64,
    /// `R_rot`: rotation speed in rad/s; 0 disables the rotation cost.
    pub rot_speed: f64,
}

/// The robot's three numbers with their allowed ranges (name, least, most, the range in words):
/// the one validation every front uses (experiment files, fleets, `covga eval`, Python), each
/// naming the key or flag its user wrote.
pub const ROBOT_RANGES: [(&str, f64, f64, &str); 3] = [
    ("width", f64::MIN_POSITIVE, f64::MAX, "a finite number > 0 metres"),
    ("speed", 1e-9, f64::MAX, "a finite number >= 1e-9 m/s"),
    ("rot_speed", 0.0, f64::MAX, "a finite number >= 0 rad/s (0 disables the rotation cost)"),
];

impl Footprint {
    /// The first of the robot's numbers outside [`ROBOT_RANGES`] (NaN and infinities included):
    /// its name, its value and the range in words; `None` where all three are allowed.
    pub fn out_of_range(&self) -> Option<(&'static str, f64, &'static str)> {
        let values = [self.width, self.speed, self.rot_speed];
        ROBOT_RANGES
            .iter()
            .zip(values)
            .find(|&(&(_, lo, hi, _), v)| !(v.is_finite() && v >= lo && v <= hi))
            .map(|(&(name, _, _, allowed), v)| (name, v, allowed))
    }

    /// The time this robot takes to drive `length_m` and turn `turn_rad` in place
    /// ([`motion::drive_time_s`], 003 eqs. 3.1–3.3).
    pub fn time_s(&self, length_m: f64, turn_rad: f64) -> f64 {
        motion::drive_time_s(length_m, turn_rad, self.speed, self.rot_speed)
    }

    /// The time this robot takes to drive `points`: their length (003 eq. 3.1) and turning
    /// (eq. 3.2) through [`Footprint::time_s`].
    pub fn path_time_s(&self, points: &[crate::geom::Point]) -> f64 {
        self.time_s(motion::path_length(points), motion::turning(points).0)
    }
}

impl Default for Footprint {
    /// The thesis robot: 0.6 m wide, 0.2 m/s, no rotation cost.
    fn default() -> Self {
        Self { width: 0.6, speed: 0.2, rot_speed: 0.0 }
    }
}

/// Everything the footprint model measures of one path.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct PathMetrics {
    /// `cov_pix`: free-cell traversals.
    pub cells_swept: u64,
    /// `cov_pix − cross_pix`: distinct free cells newly covered.
    pub unique_cells: u64,
    /// `cross_pix`: revisits of free cells.
    pub crossings: u64,
    /// `obj_pix`: traversals of obstacle cells.
    pub obstacle_cells: u64,
    /// `A_pix`: cells to cover.
    pub area_cells: u64,
    /// `PA_len` in metres.
    pub length_m: f64,
    /// Sum of absolute turns in radians.
    pub total_turn_rad: f64,
    /// Number of non-zero turns.
    pub turns: u64,
    /// `T_rot` in seconds.
    pub t_rot_s: f64,
}

impl PathMetrics {
    /// The Listing 3.1 counts these metrics were made from.
    pub fn counts(&self) -> SweepCounts {
        SweepCounts { cov_pix: self.cells_swept, cross_pix: self.crossings, obj_pix: self.obstacle_cells }
    }
}

impl Footprint {
    /// The one check of a robot against the map it is to cover, shared by `run`, `grid` and
    /// `eval`: it must fit on the map. Returns the message for the offending width.
    pub fn check_fits(&self, map: &crate::map::GridMap) -> Result<(), String> {
        let side = map.width_m().min(map.height_m());
        if self.width > side {
            return Err(format!(
                "= {} m is wider than the map's shorter side ({side} m): the robot must fit on the map",
                crate::io::short_number(self.width)
            ));
        }
        Ok(())
    }

    /// Measures a path: sweeps it on `grid` with `scratch` (no allocation once the scratch has
    /// grown) and adds length, turning and rotation time.
    pub fn measure(&self, grid: &CoverageGrid, scratch: &mut SweepScratch, points: &[Point]) -> PathMetrics {
        let counts = scratch.sweep(grid, points, self.width);
        let (total_turn_rad, turns) = motion::turning(points);
        self.metrics(grid, counts, motion::path_length(points), total_turn_rad, turns)
    }

    /// Measures a multi-agent plan: all paths sweep one shared visit grid; lengths, turns and
    /// rotation times add up.
    pub fn measure_plan(&self, grid: &CoverageGrid, scratch: &mut SweepScratch, paths: &[Vec<Point>]) -> PathMetrics {
        let counts = scratch.sweep_all(grid, paths, self.width);
        let (length, turn, turns) = motion::plan_totals(paths);
        self.metrics(grid, counts, length, turn, turns)
    }

    /// Measures a plan whose path `k` sweeps at `widths[k]` (a team of robots of different
    /// widths) on one shared visit grid; lengths and turns add up, rotation at this robot's
    /// speed. With every width this robot's, it equals [`Footprint::measure_plan`].
    pub fn measure_fleet(
        &self,
        grid: &CoverageGrid,
        scratch: &mut SweepScratch,
        paths: &[Vec<Point>],
        widths: &[f64],
    ) -> PathMetrics {
        let mut shares = vec![SweepCounts::default(); paths.len()];
        let counts = scratch.sweep_fleet(grid, paths, widths, &mut shares);
        let (length, turn, turns) = motion::plan_totals(paths);
        self.metrics(grid, counts, length, turn, turns)
    }

    fn metrics(
        &self,
        grid: &CoverageGrid,
        counts: SweepCounts,
        length_m: f64,
        total_turn_rad: f64,
        turns: usize,
    ) -> PathMetrics {
        PathMetrics {
            cells_swept: counts.cov_pix,
            unique_cells: counts.unique(),
            crossings: counts.cross_pix,
            obstacle_cells: counts.obj_pix,
            area_cells: grid.area_cells() as u64,
            length_m,
            total_turn_rad,
            turns: turns as u64,
            t_rot_s: motion::rotation_time(total_turn_rad, self.rot_speed),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::presets::preset;

    /// The one robot check: each number against its range, NaN and infinities refused.
    #[test]
    fn a_robot_out_of_range_is_named_by_its_first_bad_number() {
        let r = |width, speed, rot_speed| Footprint { width, speed, rot_speed }.out_of_range().map(|(n, ..)| n);
        let table = [
            (0.6, 0.2, 0.52, None),
            (0.0, 0.2, 0.0, Some("width")),
            (f64::NAN, 0.2, 0.0, Some("width")),
            (0.6, 0.0, 0.0, Some("speed")),
            (0.6, 1e-10, 0.0, Some("speed")),
            (0.6, 0.2, -1.0, Some("rot_speed")),
            (0.6, 0.2, f64::INFINITY, Some("rot_speed")),
        ];
        for (w, v, o, expected) in table {
            assert_eq!(r(w, v, o), expected, "{w} {v} {o}");
        }
    }

    /// The five hand-computed cases of thesis-ga §3.3 on map 1.
    #[test]
    fn spec_table_3_3_cases() {
        let map = preset("thesis-1").unwrap();
        let grid = CoverageGrid::new(&map);
        let mut scratch = SweepScratch::new(&grid);
        let fp = Footprint { width: 0.6, speed: 0.2, rot_speed: std::f64::consts::TAU };
        let p = |x, y| Point::new(x, y);
        let cases: [(&[Point], u64, u64, u64, f64); 5] = [
            (&[p(1.3, 1.3), p(4.3, 1.3)], 45, 0, 0, 0.0),
            (&[p(1.3, 1.3), p(4.3, 1.3), p(4.3, 4.3)], 90, 2, 0, 90.0),
            (&[p(1.3, 1.3), p(4.3, 1.3), p(1.3, 1.3)], 90, 42, 0, 180.0),
            (&[p(1.3, 1.3), p(4.3, 1.3), p(4.3, 4.3), p(1.3, 1.3)], 165, 14, 0, 225.0),
            (&[p(1.3, 1.3), p(0.5, 1.3)], 6, 0, 6, 0.0),
        ];
        for (i, (path, cov, cross, obj, turn_deg)) in cases.into_iter().enumerate() {
            let m = fp.measure(&grid, &mut scratch, path);
            assert_eq!((m.cells_swept, m.crossings, m.obstacle_cells), (cov, cross, obj), "case {i}");
            assert_eq!(m.unique_cells, cov - cross, "case {i}: unique = cov_pix − cross_pix");
            assert!((m.total_turn_rad.to_degrees() - turn_deg).abs() < 1e-9, "case {i}");
        }
        let m = fp.measure(&grid, &mut scratch, cases[3].0);
        assert!((m.t_rot_s - 0.625).abs() < 1e-12);
        // Out and back along one lane: 45 cells, then 42 of the return's 45 already swept.
        assert_eq!(fp.measure(&grid, &mut scratch, cases[2].0).unique_cells, 48);
    }
}
