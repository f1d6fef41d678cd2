//! The lower bound beside a plan's times to coverage ([`crate::coverage::bound`]): no plan
//! covers the share `L` of the reachable cells sooner than the length bound allows (their area
//! over what the robots' sweeps can add per second on the map's cells, 003 §3.3: turning in
//! place sweeps nothing); one robot that turns at a finite rate also needs the turning any path
//! covering that area must make (the bound `covga eval` writes). The report reads each run's
//! robots and map from the study's grid file and its reachable cells from `runs.csv`, so the
//! bound needs no run folder.

use crate::coverage::bound::{TimeBound, area_time_s, free_diameter_m};
use crate::experiment::file::ExperimentFile;
use crate::study::records::RunsTable;
use std::collections::BTreeMap;
use std::path::Path;

/// What a run's bound is made of.
#[derive(Debug, Clone)]
struct RunBound {
    /// The reachable cells' area, m².
    reachable_m2: f64,
    /// One robot's (width, speed, rot_speed), or a fleet's robots.
    robot: Robots,
    /// The map's cell size, m.
    resolution: f64,
    /// An upper bound on the map's free-space diameter, m.
    diameter_m: f64,
}

#[derive(Debug, Clone)]
enum Robots {
    One(f64, f64, f64),
    /// Each robot's (width, speed): a fleet's bound is its makespan's length bound.
    Fleet(Vec<(f64, f64)>),
}

/// Each run's lower bound on its times to coverage, or why the study's runs have none.
pub struct AreaBounds {
    runs: BTreeMap<String, RunBound>,
    /// Why no bound is given, where some run has none.
    pub missing: Option<String>,
}

/// A run's robots: its `[[robots]]` (each defaulting to `[robot]`) as their widths and speeds,
/// else its one robot.
fn robots(file: &ExperimentFile) -> Robots {
    let r = &file.robot;
    if file.robots.is_empty() {
        return Robots::One(r.width, r.speed, r.rot_speed);
    }
    Robots::Fleet(file.robots.iter().map(|e| (e.width.unwrap_or(r.width), e.speed.unwrap_or(r.speed))).collect())
}

/// The study's grid: its folder's `grid.toml`, or where that copy names a `base` it cannot
/// resolve from the study folder (a study committed before the copy inlined its base), the grid
/// file `study.json` names, read from the repository root two folders up
/// (`results/<study>/`), which expands to the same run ids.
fn load_grid(dir: &Path) -> Result<(std::path::PathBuf, crate::study::grid::Study), String> {
    let copy = dir.join("grid.toml");
    let first = match crate::study::grid::Study::load(&copy) {
        Ok(grid) => return Ok((copy, grid)),
        Err(e) => e.to_string(),
    };
    let named = std::fs::read_to_string(dir.join("study.json"))
        .ok()
        .and_then(|text| serde_json::from_str::<serde_json::Value>(&text).ok())
        .and_then(|meta| meta["grid_file"].as_str().map(|f| dir.join("../..").join(f)));
    match named {
        Some(original) if original.exists() => {
            let grid = crate::study::grid::Study::load(&original).map_err(|e| format!("{first}; {e}"))?;
            Ok((original, grid))
        }
        _ => Err(first),
    }
}

impl AreaBounds {
    /// The bounds of the runs in `t`, read with the grid file of study folder `dir`.
    pub fn of(dir: &Path, t: &RunsTable) -> Self {
        match Self::read(dir, t) {
            Ok(runs) => Self { runs, missing: None },
            Err(why) => Self::none(why),
        }
    }

    /// No run has a bound, for the reason `why`.
    pub fn none(why: String) -> Self {
        Self { runs: BTreeMap::new(), missing: Some(why) }
    }

    /// Run `id`'s robot as a figure names it: "robot 0.60 m wide, 0.30 m/s, 0.52 rad/s" (or
    /// "turning free"), or a fleet's size.
    pub fn robot_text(&self, id: &str) -> Option<String> {
        self.runs.get(id).map(|b| match &b.robot {
            &Robots::One(w, v, o) if o > 0.0 => format!("robot {w:.2} m wide, {v:.2} m/s, {o:.2} rad/s"),
            &Robots::One(w, v, _) => format!("robot {w:.2} m wide, {v:.2} m/s, turning free"),
            Robots::Fleet(robots) => format!("fleet of {} robots", robots.len()),
        })
    }

    fn read(dir: &Path, t: &RunsTable) -> Result<BTreeMap<String, RunBound>, String> {
        let (grid_file, grid) = load_grid(dir)?;
        let files: BTreeMap<&str, &ExperimentFile> = grid.runs.iter().map(|r| (r.id.as_str(), &r.file)).collect();
        let (id_col, cells_col) = (t.col("run_id"), t.col("reachable_cells"));
        let (Some(id_col), Some(cells_col)) = (id_col, cells_col) else {
            return Err("runs.csv has no `run_id` or `reachable_cells` column".into());
        };
        // Each map once: its resolution and free-space diameter are all the bound needs of it.
        let mut maps: Vec<(crate::planner::sections::MapSection, f64, f64)> = Vec::new();
        let load = |src: &str, image: &crate::map::ros::BareImage| crate::map::ros::load_map(src, image);
        let mut out = BTreeMap::new();
        for row in &t.rows {
            let id = &row[id_col];
            let file =
                files.get(id.as_str()).ok_or_else(|| format!("run {id} is not one of {}", grid_file.display()))?;
            let (resolution, diameter_m) = match maps.iter().find(|(m, ..)| *m == file.map) {
                Some((_, r, d)) => (*r, *d),
                None => {
                    let map = file
                        .load_map(&grid_file.display().to_string(), Path::new("."), &load)
                        .map_err(|e| e.to_string())?;
                    let d = free_diameter_m(&map);
                    maps.push((file.map.clone(), map.resolution(), d));
                    (map.resolution(), d)
                }
            };
            let cells: f64 =
                row[cells_col].parse().map_err(|_| format!("run {id}: reachable_cells `{}`", row[cells_col]))?;
            let reachable_m2 = cells * resolution * resolution;
            out.insert(id.clone(), RunBound { reachable_m2, robot: robots(file), resolution, diameter_m });
        }
        Ok(out)
    }

    /// Run `id`'s bound on the time to the share `level` of its reachable cells.
    pub fn to_level_s(&self, id: &str, level: f64) -> Option<f64> {
        self.runs.get(id).map(|b| b.time_to_level_s(level))
    }
}

impl RunBound {
    fn time_to_level_s(&self, level: f64) -> f64 {
        let area = level * self.reachable_m2;
        match &self.robot {
            &Robots::One(width, speed, rot_speed) => {
                TimeBound::one_robot(area, (width, speed, rot_speed), self.resolution, self.diameter_m).total_s()
            }
            Robots::Fleet(robots) => area_time_s(area, robots, self.resolution),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fleet_sweeps_at_the_sum_of_its_robots_rates() {
        let mut file = ExperimentFile::default();
        (file.robot.width, file.robot.speed, file.robot.rot_speed) = (0.6, 0.3, 0.52);
        assert!(matches!(robots(&file), Robots::One(w, v, o) if (w, v, o) == (0.6, 0.3, 0.52)));
        let entry = |width: Option<f64>, speed: Option<f64>| crate::fleet::config::RobotEntry {
            name: "r".into(),
            width,
            speed,
            rot_speed: None,
            start: None,
            end: None,
        };
        file.robots = vec![entry(None, None), entry(Some(0.4), None), entry(None, Some(0.5))];
        let Robots::Fleet(fleet) = robots(&file) else { panic!("a fleet") };
        assert_eq!(fleet, vec![(0.6, 0.3), (0.4, 0.3), (0.6, 0.5)]);
    }

    #[test]
    fn one_turning_robot_adds_the_turning_bound_and_a_fleet_does_not() {
        use crate::coverage::bound::{area_time_s, min_turning_rad};
        let one =
            RunBound { reachable_m2: 100.0, robot: Robots::One(0.5, 0.2, 0.5), resolution: 0.05, diameter_m: 10.0 };
        // 90 m² at 0.5 m and 0.2 m/s on 0.05 m cells, and in a 10 m region the turning too.
        let t = one.time_to_level_s(0.9);
        let (length_s, turning) =
            (area_time_s(90.0, &[(0.5, 0.2)], 0.05), min_turning_rad(90.0, 0.5, 0.05, 10.0) / 0.5);
        assert!(turning > 0.0 && length_s > 700.0 && (t - (length_s + turning)).abs() < 1e-9, "{t}");
        let fleet = RunBound { robot: Robots::Fleet(vec![(0.5, 0.2)]), ..one.clone() };
        assert!((fleet.time_to_level_s(0.9) - length_s).abs() < 1e-9);
        let free = RunBound { robot: Robots::One(0.5, 0.2, 0.0), ..one };
        assert!((free.time_to_level_s(0.9) - length_s).abs() < 1e-9);
    }
}
