//! The time-to-coverage curve of a plan: reachable coverage against mission time along the
//! plan, the anytime profile by which plans of different lengths compare at equal coverage.
//! Time runs as the common scorer counts it (003 eqs. 3.1–3.3: length over `R_speed`, turning
//! over `R_rot`, each agent on its own clock); coverage is the scorer's reachable coverage
//! (cells the swept footprint reaches, 003 §3.1, over the cells the robot's body can reach).
//!
//! The curve steps at segment ends: a segment's cells count as covered once the robot has
//! driven the whole segment, so every time read off the curve is an upper bound, exact at
//! segment ends; its last point is the plan's `cov_final_reach` at its time.

use super::motion::{abs_turn_deg, rotation_time};
use super::{CoverageGrid, Footprint};
use crate::geom::{Point, ZERO_LENGTH};
use crate::map::reach::Reach;

/// Coverage levels whose times every run reports.
pub const LEVELS: [f64; 3] = [0.80, 0.90, 0.95];

/// A time-to-coverage curve: `(time_s, coverage)` pairs, both non-decreasing, from `(0, c₀)`
/// (c₀ = 0 but for a plan of no segment) to the plan's end.
#[derive(Clone, Debug, PartialEq)]
pub struct CoverageCurve {
    points: Vec<(f64, f64)>,
}

/// Each segment's end time along `points` driven by `robot`: the turn before a segment (onto
/// its heading from the last non-degenerate one, eq. 3.2) and the segment itself (eq. 3.1)
/// over the robot's speeds (eq. 3.3). A zero-length segment takes no time and keeps the heading.
pub fn segment_end_times(points: &[Point], robot: &Footprint) -> Vec<f64> {
    let mut heading = None;
    let mut t = 0.0;
    points
        .windows(2)
        .map(|w| {
            let v = w[1] - w[0];
            if v.norm() >= ZERO_LENGTH {
                if let Some(h) = heading {
                    t += rotation_time(abs_turn_deg(h, v).to_radians(), robot.rot_speed);
                }
                t += v.norm() / robot.speed;
                heading = Some(v);
            }
            t
        })
        .collect()
}

impl CoverageCurve {
    /// The curve of `paths`, path `k` driven by `robots[k]` on its own clock from time 0 (the
    /// robots of a fleet drive at once): segments are swept in the order they end, each at its
    /// robot's width, and the coverable cells of `reach` each first sweep adds are counted.
    pub fn of_plan(grid: &CoverageGrid, reach: &Reach, paths: &[Vec<Point>], robots: &[Footprint]) -> Self {
        assert_eq!(paths.len(), robots.len(), "one robot per path");
        let mut ends: Vec<(f64, usize, usize)> = Vec::new();
        for (k, (p, r)) in paths.iter().zip(robots).enumerate() {
            ends.extend(segment_end_times(p, r).into_iter().enumerate().map(|(j, t)| (t, k, j)));
        }
        ends.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
        let reachable = reach.coverable_count().max(1) as f64;
        let mut covered = vec![false; grid.len()];
        let mut count = 0usize;
        let mut points = vec![(0.0, 0.0)];
        for (t, k, j) in ends {
            let (a, b) = (paths[k][j], paths[k][j + 1]);
            super::raster::for_each_swept_cell(grid.raster(), a, b, robots[k].width, |i| {
                if !covered[i] && reach.is_coverable(i) {
                    covered[i] = true;
                    count += 1;
                }
            });
            let c = count as f64 / reachable;
            let last = points.last_mut().expect("starts with the origin");
            if t <= last.0 {
                last.1 = c;
            } else if c > last.1 {
                points.push((t, c));
            }
        }
        let end = paths.iter().zip(robots).map(|(p, r)| segment_end_times(p, r).last().copied().unwrap_or(0.0));
        let end = end.fold(0.0, f64::max);
        let last = *points.last().expect("starts with the origin");
        if end > last.0 {
            points.push((end, last.1));
        }
        Self { points }
    }

    /// The curve [`CoverageCurve::csv`] wrote, or `None` for text that is not one (another
    /// header, a field that is no number, times or coverage that fall).
    pub fn parse_csv(text: &str) -> Option<Self> {
        let mut lines = text.lines();
        (lines.next()? == "time_s,coverage_reach").then_some(())?;
        let points: Vec<(f64, f64)> = lines
            .map(|l| {
                let (t, c) = l.split_once(',')?;
                Some((t.parse().ok()?, c.parse().ok()?))
            })
            .collect::<Option<_>>()?;
        let rising = points.windows(2).all(|w| w[0].0 <= w[1].0 && w[0].1 <= w[1].1);
        (rising && !points.is_empty()).then_some(Self { points })
    }

    /// The `(time_s, coverage)` pairs.
    pub fn points(&self) -> &[(f64, f64)] {
        &self.points
    }

    /// The coverage reached by time `t` seconds.
    pub fn coverage_at(&self, t: f64) -> f64 {
        let k = self.points.partition_point(|p| p.0 <= t);
        if k == 0 { 0.0 } else { self.points[k - 1].1 }
    }

    /// The first time the coverage reaches `level` (a share of the reachable cells), or `None`
    /// when the plan never does.
    pub fn time_to(&self, level: f64) -> Option<f64> {
        self.points.iter().find(|p| p.1 >= level - 1e-12).map(|p| p.0)
    }

    /// The area over the curve up to the plan's end, `∫ (1 − c(t)) dt` in seconds: the time the
    /// plan leaves the reachable floor uncovered, summed over the floor's share (lower is a plan
    /// that covers sooner; a plan covering everything at once would score 0).
    pub fn area_over_s(&self) -> f64 {
        self.points.windows(2).map(|w| (w[1].0 - w[0].0) * (1.0 - w[0].1)).sum()
    }

    /// The figures of `summary.json`.
    pub fn summary(&self) -> CurveSummary {
        let [t80, t90, t95] = LEVELS.map(|l| self.time_to(l));
        CurveSummary { time_to_80_s: t80, time_to_90_s: t90, time_to_95_s: t95, area_over_curve_s: self.area_over_s() }
    }

    /// The curve as CSV (`time_s,coverage_reach`), one row per step.
    pub fn csv(&self) -> Vec<u8> {
        let mut out = String::from("time_s,coverage_reach\n");
        for (t, c) in &self.points {
            out.push_str(&format!("{t},{c}\n"));
        }
        out.into_bytes()
    }
}

/// What a run reports of its curve: the times to 80, 90 and 95 % of the reachable cells
/// (`None`: never reached) and the area over the curve.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct CurveSummary {
    /// Seconds until 80 % of the reachable cells are covered.
    pub time_to_80_s: Option<f64>,
    /// Seconds until 90 %.
    pub time_to_90_s: Option<f64>,
    /// Seconds until 95 %.
    pub time_to_95_s: Option<f64>,
    /// `∫ (1 − c(t)) dt` up to the plan's end, in seconds.
    pub area_over_curve_s: f64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::fitness::Projection;
    use crate::coverage::score::{CameraSpec, Scorer};
    use crate::map::presets::preset;

    fn robot(rot_speed: f64) -> Footprint {
        Footprint { width: 0.6, speed: 0.2, rot_speed }
    }

    fn scorer(map: &crate::map::GridMap, r: Footprint, start: Point) -> Scorer {
        let camera = CameraSpec { scale: 0.15, d_min: 0.2, d_max: 7.0, fov_deg: 69.4, sections: 15, band_m: 0.45 };
        Scorer::new(map, r, Projection::F1, &camera, &[start])
    }

    #[test]
    fn segment_times_add_up_to_the_scorers_time() {
        let p = |x, y| Point::new(x, y);
        let path = [p(1.0, 1.0), p(3.0, 1.0), p(3.0, 1.0), p(3.0, 2.0), p(1.0, 2.0)];
        // 2 m, nothing, a quarter turn then 1 m, a quarter turn then 2 m; at 0.2 m/s and 0.5 rad/s.
        let t = segment_end_times(&path, &robot(0.5));
        let q = std::f64::consts::FRAC_PI_2 / 0.5;
        let want = [10.0, 10.0, 15.0 + q, 25.0 + 2.0 * q];
        for (got, want) in t.iter().zip(want) {
            assert!((got - want).abs() < 1e-9, "{t:?}");
        }
    }

    /// A lawnmower over part of map 1: x 1.3–4.0 m, lanes 0.6 m apart from y = 1.3 m.
    fn lawnmower() -> Vec<Point> {
        let mut path = Vec::new();
        for k in 0..6 {
            let y = 1.3 + 0.6 * f64::from(k);
            let (a, b) = if k % 2 == 0 { (1.3, 4.0) } else { (4.0, 1.3) };
            path.extend([Point::new(a, y), Point::new(b, y)]);
        }
        path
    }

    /// The curve ends at the scorer's coverage and time, and steps only upwards.
    #[test]
    fn a_lawnmower_curve_ends_where_the_scorer_does() {
        let map = preset("thesis-1").unwrap();
        let start = Point::new(1.3, 1.3);
        let path = lawnmower();
        for rot in [0.0, 0.5] {
            let r = robot(rot);
            let sc = scorer(&map, r, start);
            let score = sc.score(std::slice::from_ref(&path));
            let curve = CoverageCurve::of_plan(sc.grid(), sc.reach(), std::slice::from_ref(&path), &[r]);
            let last = *curve.points().last().unwrap();
            assert!((last.0 - score.time_s).abs() < 1e-9 * score.time_s, "{last:?} vs {}", score.time_s);
            assert_eq!(last.1, score.cov_final_reach);
            assert!(curve.points().windows(2).all(|w| w[0].0 < w[1].0 && w[0].1 <= w[1].1));
            let half = last.1 / 2.0;
            let t = curve.time_to(half).unwrap();
            assert!(0.0 < t && t < score.time_s);
            assert!(curve.coverage_at(t) >= half && curve.coverage_at(t - 1e-6) < half);
            let area = curve.area_over_s();
            assert!(area > (1.0 - last.1) * score.time_s && area < score.time_s, "{area}");
        }
    }

    /// Two robots sweeping halves of a room at once reach its coverage in half the time one robot
    /// takes over both halves; the area over the curve halves too.
    #[test]
    fn a_fleet_drives_on_parallel_clocks() {
        let map = preset("thesis-1").unwrap();
        let p = |x, y| Point::new(x, y);
        let (a, b) = (vec![p(1.3, 1.3), p(4.0, 1.3)], vec![p(4.0, 1.9), p(1.3, 1.9)]);
        let r = robot(0.0);
        let sc = scorer(&map, r, p(1.3, 1.3));
        let one = CoverageCurve::of_plan(sc.grid(), sc.reach(), &[vec![a[0], a[1], b[0], b[1]]], &[r]);
        let two = CoverageCurve::of_plan(sc.grid(), sc.reach(), &[a.clone(), b.clone()], &[r, r]);
        let (end1, end2) = (*one.points().last().unwrap(), *two.points().last().unwrap());
        // One robot also drives (and sweeps) the 0.6 m between the lanes.
        assert!(end1.1 >= end2.1, "{end1:?} {end2:?}");
        assert!((end1.0 - (2.7 + 0.6 + 2.7) / 0.2).abs() < 1e-9 && (end2.0 - 2.7 / 0.2).abs() < 1e-9);
        assert!(2.0 * two.time_to(end2.1).unwrap() <= one.time_to(end2.1).unwrap() + 1e-9);
        assert!(two.area_over_s() < one.area_over_s());
        // A level never reached has no time.
        assert_eq!(two.time_to(0.999), None);
    }

    #[test]
    fn no_segment_no_time() {
        let map = preset("thesis-1").unwrap();
        let r = robot(0.0);
        let sc = scorer(&map, r, Point::new(1.3, 1.3));
        let c = CoverageCurve::of_plan(sc.grid(), sc.reach(), &[vec![Point::new(1.3, 1.3)]], &[r]);
        assert_eq!(c.points(), &[(0.0, 0.0)]);
        assert_eq!(c.summary().time_to_80_s, None);
        assert_eq!(c.area_over_s(), 0.0);
    }
}
