//! The area bound beside a plan's times to coverage: no plan covers the share `L` of the
//! reachable cells sooner than `L` times their area over the robots' combined sweep rate
//! (`Σ R_width · R_speed`), since driving straight is the fastest the scorer's footprint sweeps
//! new ground and turning in place sweeps none (003 §3.3; the bound `covga eval` and the
//! cell-order planner write). The report reads each run's robots and map resolution from the
//! study's grid file and its reachable cells from `runs.csv`, so the bound needs no run folder.

use crate::experiment::file::ExperimentFile;
use crate::study::records::RunsTable;
use std::collections::BTreeMap;
use std::path::Path;

/// Each run's time to cover all its reachable cells at the area bound, in seconds, or why the
/// study's runs have none.
pub(super) struct AreaBounds {
    full_s: BTreeMap<String, f64>,
    /// Why no bound is given, where some run has none.
    pub missing: Option<String>,
}

/// The combined sweep rate of a run's robots in m²/s: its `[[robots]]` (each defaulting to
/// `[robot]`), else its one robot.
fn sweep_rate(file: &ExperimentFile) -> f64 {
    let r = &file.robot;
    if file.robots.is_empty() {
        return r.width * r.speed;
    }
    file.robots.iter().map(|e| e.width.unwrap_or(r.width) * e.speed.unwrap_or(r.speed)).sum()
}

impl AreaBounds {
    /// The bounds of the runs in `t`, read with the grid file of study folder `dir`.
    pub fn of(dir: &Path, t: &RunsTable) -> Self {
        match Self::read(dir, t) {
            Ok(full_s) => Self { full_s, missing: None },
            Err(why) => Self { full_s: BTreeMap::new(), missing: Some(why) },
        }
    }

    fn read(dir: &Path, t: &RunsTable) -> Result<BTreeMap<String, f64>, String> {
        let grid_file = dir.join("grid.toml");
        let grid = crate::study::grid::Study::load(&grid_file).map_err(|e| e.to_string())?;
        let files: BTreeMap<&str, &ExperimentFile> = grid.runs.iter().map(|r| (r.id.as_str(), &r.file)).collect();
        let (id_col, cells_col) = (t.col("run_id"), t.col("reachable_cells"));
        let (Some(id_col), Some(cells_col)) = (id_col, cells_col) else {
            return Err("runs.csv has no `run_id` or `reachable_cells` column".into());
        };
        // Each map once: the resolution is all the bound needs of it.
        let mut resolutions: Vec<(crate::planner::sections::MapSection, f64)> = Vec::new();
        let load = |src: &str, image: &crate::map::ros::BareImage| crate::map::ros::load_map(src, image);
        let mut out = BTreeMap::new();
        for row in &t.rows {
            let id = &row[id_col];
            let file =
                files.get(id.as_str()).ok_or_else(|| format!("run {id} is not one of {}", grid_file.display()))?;
            let resolution = match resolutions.iter().find(|(m, _)| *m == file.map) {
                Some((_, r)) => *r,
                None => {
                    let map = file
                        .load_map(&grid_file.display().to_string(), Path::new("."), &load)
                        .map_err(|e| e.to_string())?;
                    resolutions.push((file.map.clone(), map.resolution()));
                    map.resolution()
                }
            };
            let cells: f64 =
                row[cells_col].parse().map_err(|_| format!("run {id}: reachable_cells `{}`", row[cells_col]))?;
            out.insert(id.clone(), cells * resolution * resolution / sweep_rate(file));
        }
        Ok(out)
    }

    /// Run `id`'s bound on the time to the share `level` of its reachable cells.
    pub fn to_level_s(&self, id: &str, level: f64) -> Option<f64> {
        self.full_s.get(id).map(|t| level * t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fleet_sweeps_at_the_sum_of_its_robots_rates() {
        let mut file = ExperimentFile::default();
        (file.robot.width, file.robot.speed) = (0.6, 0.3);
        assert!((sweep_rate(&file) - 0.18).abs() < 1e-12);
        let entry = |width: Option<f64>, speed: Option<f64>| crate::fleet::config::RobotEntry {
            name: "r".into(),
            width,
            speed,
            rot_speed: None,
            start: None,
            end: None,
        };
        file.robots = vec![entry(None, None), entry(Some(0.4), None), entry(None, Some(0.5))];
        assert!((sweep_rate(&file) - (0.18 + 0.4 * 0.3 + 0.6 * 0.5)).abs() < 1e-12);
    }
}
