//! Fleet metrics of the common scorer: every robot's swept cells on one shared visit map (each
//! with its own width), union coverage over all free and over reachable cells, overlap between
//! robots, per-robot length and time, makespan, balance, and 003's `cov_final` / `t_final` with
//! the fleet's time taken as the makespan ([`super::fleet_t_final`]).

use super::{Fleet, fleet_t_final, fleet_t_optimal};
use crate::coverage::fitness::{area_m2, cov_actual, cov_final, t_actual};
use crate::coverage::{CoverageGrid, SweepCounts, SweepScratch, motion};
use crate::geom::Point;
use crate::map::GridMap;
use crate::map::clearance::Clearance;
use crate::map::reach::Reach;

/// Everything measured of one fleet plan (one path per robot, in the fleet's order).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct FleetScore {
    /// Robot names, in order.
    pub robots: Vec<String>,
    /// Distinct free cells swept by any robot.
    pub union_cells: u64,
    /// `union_cells` over all free cells.
    pub union_free: f64,
    /// Swept cells some robot can reach from its start, over the cells the robots can reach.
    pub union_reach: f64,
    /// Cells some robot can reach from its start (each with its own width).
    pub reachable_cells: u64,
    /// Free cells swept by two robots or more.
    pub overlap_cells: u64,
    /// `overlap_cells / union_cells` (0 for an empty union).
    pub overlap_fraction: f64,
    /// Distinct free cells each robot sweeps.
    pub robot_cells: Vec<u64>,
    /// Each robot's path length in metres.
    pub robot_length_m: Vec<f64>,
    /// Each robot's time: length / speed + turn / rotation speed (003 eqs. 3.1–3.3), seconds.
    pub robot_time_s: Vec<f64>,
    /// Each robot's time model, in words ([`motion::time_model`]): a fleet's robots each
    /// drive at their own speeds, so no one robot's model describes the fleet's times.
    pub robot_time_model: Vec<String>,
    /// The slowest robot's time in seconds.
    pub makespan_s: f64,
    /// Slowest over fastest robot time (`None` when a robot does not move).
    pub balance: Option<f64>,
    /// Sweeps of obstacle cells, all robots.
    pub obstacle_cells: u64,
    /// 003 eq. 3.10 over the union (`cov_actual = cov − cross` on the shared visit map).
    pub cov_final: f64,
    /// [`super::fleet_t_optimal`] in seconds.
    pub t_optimal_s: f64,
    /// [`super::fleet_t_final`].
    pub t_final: f64,
}

/// Scores fleet plans on one map: the shared visit grid and every robot's reachable cells.
pub struct FleetScorer {
    fleet: Fleet,
    grid: CoverageGrid,
    reachable: Vec<bool>,
    reachable_count: u64,
    resolution: f64,
}

impl FleetScorer {
    /// Prepares the visit grid and the union of the robots' reachable cells (each robot's
    /// width from its own start).
    pub fn new(map: &GridMap, fleet: &Fleet) -> Self {
        let grid = CoverageGrid::new(map);
        let mut reachable = vec![false; grid.len()];
        for r in fleet.robots() {
            let reach = Reach::new(&Clearance::new(map, r.footprint.width), &[r.start]);
            for (i, flag) in reachable.iter_mut().enumerate() {
                *flag |= reach.is_coverable(i);
            }
        }
        let reachable_count = reachable.iter().filter(|r| **r).count() as u64;
        Self { fleet: fleet.clone(), grid, reachable, reachable_count, resolution: map.resolution() }
    }

    /// Scores `paths` (one per robot, in the fleet's order).
    pub fn score(&self, paths: &[Vec<Point>]) -> Result<FleetScore, String> {
        let robots = self.fleet.robots();
        if paths.len() != robots.len() {
            return Err(format!("the plan has {} paths for a fleet of {} robots", paths.len(), robots.len()));
        }
        let widths: Vec<f64> = robots.iter().map(|r| r.footprint.width).collect();
        let mut shares = vec![SweepCounts::default(); robots.len()];
        let mut scratch = SweepScratch::new(&self.grid);
        let total = scratch.sweep_fleet(&self.grid, paths, &widths, &mut shares);
        let union_cells = total.unique();
        // Who swept what: one robot at a time, counting the robots per cell.
        let mut owners = vec![0u16; self.grid.len()];
        let mut robot_cells = Vec::with_capacity(robots.len());
        for (p, &w) in paths.iter().zip(&widths) {
            scratch.sweep(&self.grid, p, w);
            let mut n = 0;
            for (cell, _) in scratch.visit_counts() {
                owners[cell as usize] += 1;
                n += 1;
            }
            robot_cells.push(n);
        }
        let overlap_cells = owners.iter().filter(|&&k| k >= 2).count() as u64;
        let union_reach_cells =
            owners.iter().zip(&self.reachable).filter(|&(&k, &reach)| k > 0 && reach).count() as u64;
        let res = self.resolution;
        let (mut lengths, mut times, mut eq_3_13_times) = (Vec::new(), Vec::new(), Vec::new());
        for ((p, r), share) in paths.iter().zip(robots).zip(&shares) {
            let length = motion::path_length(p);
            let (turn, _) = motion::turning(p);
            let t_rot = motion::rotation_time(turn, r.footprint.rot_speed);
            lengths.push(length);
            times.push(r.footprint.time_s(length, turn));
            eq_3_13_times.push(t_actual(area_m2(share.cov_pix, res), r.footprint.speed, r.footprint.width) + t_rot);
        }
        let actual = cov_actual(area_m2(total.cov_pix, res), area_m2(total.cross_pix, res));
        let t_optimal_s = fleet_t_optimal(actual, self.fleet.sweep_rate());
        let fastest = times.iter().copied().fold(f64::INFINITY, f64::min);
        let makespan_s = times.iter().copied().fold(0.0, f64::max);
        let free = self.grid.area_cells() as u64;
        Ok(FleetScore {
            robots: robots.iter().map(|r| r.name.clone()).collect(),
            union_cells,
            union_free: ratio(union_cells, free),
            union_reach: ratio(union_reach_cells, self.reachable_count),
            reachable_cells: self.reachable_count,
            overlap_cells,
            overlap_fraction: ratio(overlap_cells, union_cells),
            robot_cells,
            robot_length_m: lengths,
            robot_time_s: times,
            robot_time_model: robots.iter().map(|r| motion::time_model(&r.footprint)).collect(),
            makespan_s,
            balance: (fastest > 0.0).then(|| makespan_s / fastest),
            obstacle_cells: total.obj_pix,
            cov_final: cov_final(actual, area_m2(free, res)),
            t_optimal_s,
            t_final: fleet_t_final(t_optimal_s, &eq_3_13_times),
        })
    }
}

fn ratio(a: u64, b: u64) -> f64 {
    if b > 0 { a as f64 / b as f64 } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::Footprint;
    use crate::coverage::fitness::{Projection, score};
    use crate::fleet::config::{FleetFile, validate};
    use crate::map::presets::preset;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    #[test]
    fn a_fleet_of_one_scores_as_the_thesis_does() {
        let map = preset("thesis-2").unwrap();
        let robot = Footprint { width: 0.6, speed: 0.2, rot_speed: 0.5 };
        let fleet = validate(
            &[Default::default()].map(|e: crate::fleet::config::RobotEntry| crate::fleet::config::RobotEntry {
                name: "solo".into(),
                ..e
            }),
            robot,
            [1.3, 1.3],
            "f.toml",
            &map,
        )
        .unwrap();
        let path = vec![p(1.3, 1.3), p(9.7, 1.3), p(9.7, 2.5), p(1.3, 2.5), p(1.3, 9.0), p(9.0, 9.0)];
        let fs = FleetScorer::new(&map, &fleet).score(std::slice::from_ref(&path)).unwrap();
        let grid = CoverageGrid::new(&map);
        let m = robot.measure_plan(&grid, &mut SweepScratch::new(&grid), std::slice::from_ref(&path));
        let th = score(&m, &robot, map.resolution(), Projection::F1);
        assert_eq!(fs.cov_final.to_bits(), th.cov_final.to_bits());
        assert_eq!(fs.t_final.to_bits(), th.t_final.to_bits());
        assert_eq!(fs.union_cells, m.unique_cells);
        assert_eq!((fs.overlap_cells, fs.balance), (0, Some(1.0)));
    }

    #[test]
    fn union_overlap_and_makespan_of_hand_made_plans() {
        // thesis-1: free [1, 10)² m at 0.2 m cells. Robot a (0.4 m, 0.2 m/s) sweeps the row band
        // y in [2.8, 3.2) from x = 2 to 6; robot b (0.8 m, 0.4 m/s) sweeps y in [2.6, 3.4) from
        // x = 4 to 8. Cells are 0.2 m: a sweeps 2 rows × 20 columns = 40 cells, b 4 × 20 = 80;
        // they share 2 rows × x in [4, 6) = 20 cells; the union is 100 cells.
        let map = preset("thesis-1").unwrap();
        let text = "[[robots]]\nname = \"a\"\nwidth = 0.4\nspeed = 0.2\nstart = [2.0, 3.0]\n\
                    [[robots]]\nname = \"b\"\nwidth = 0.8\nspeed = 0.4\nstart = [4.0, 3.0]\n";
        let fleet = FleetFile::parse(text, "f.toml", &map).unwrap();
        let paths = vec![vec![p(2.0, 3.0), p(6.0, 3.0)], vec![p(4.0, 3.0), p(8.0, 3.0)]];
        let s = FleetScorer::new(&map, &fleet).score(&paths).unwrap();
        assert_eq!(s.robot_cells, vec![40, 80]);
        assert_eq!((s.union_cells, s.overlap_cells), (100, 20));
        assert!((s.overlap_fraction - 0.2).abs() < 1e-12);
        assert!((s.union_free - 100.0 / 2025.0).abs() < 1e-12);
        // Times 4 m / 0.2 = 20 s and 4 m / 0.4 = 10 s: makespan 20 s, balance 2.
        assert_eq!(s.robot_time_s, vec![20.0, 10.0]);
        assert_eq!((s.makespan_s, s.balance), (20.0, Some(2.0)));
        // cov_actual = 100 cells · 0.04 m² = 4 m²; rates 0.08 + 0.32 = 0.4 m²/s → 10 s.
        assert!((s.t_optimal_s - 10.0).abs() < 1e-9);
        // Eq. 3.12 times: a 40 · 0.04 / 0.08 = 20 s, b 80 · 0.04 / 0.32 = 10 s → t_final 0.5.
        assert!((s.t_final - 0.5).abs() < 1e-9);
        assert!(FleetScorer::new(&map, &fleet).score(&paths[..1]).unwrap_err().contains("2 robots"));
    }
}
