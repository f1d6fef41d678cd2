//! Area division for a fleet in the style of DARP (Kapoutsis et al., cited by 003 §2.1.3): the
//! cells the robots can cover are split into one connected region per robot, sized by the
//! robot's sweep rate (width × speed) and grown around its start; each robot then sweeps its
//! region with a boustrophedon. A baseline for the fleet planners: it plans in one pass,
//! without search.
//!
//! The split is a multiplicatively weighted geodesic Voronoi partition: cell `c` goes to the
//! robot minimising `m_i · d_i(c)`, where `d_i` is the geodesic distance from robot `i`'s start
//! over free cells (8-connected, no corner cutting) and `∞` where robot `i` cannot sweep `c`.
//! The weights are adjusted until every region holds its share of cells (DARP's iteration);
//! cells cut off from their robot's start are then handed to a neighbouring region.

use super::Fleet;
use crate::geom::Point;
use crate::map::clearance::Clearance;
use crate::map::reach::Reach;
use crate::map::{CellState, GridMap};
use crate::patterns::{self, Pattern, PatternError};
use std::cmp::Reverse;
use std::collections::{BinaryHeap, VecDeque};

/// Weight iterations before the split is accepted as it is.
pub const MAX_ITERATIONS: usize = 1000;

/// Why a fleet cannot be divided or its regions swept.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum DivisionError {
    /// Two robots start in the same cell: a geodesic split needs distinct starts.
    #[error("robots \"{0}\" and \"{1}\" start in the same cell: area division needs distinct start stations")]
    SharedStart(String, String),
    /// A robot's end station lies outside its region.
    #[error("robot \"{robot}\"'s end station ({x}, {y}) m lies outside its region: give it an end inside, or none")]
    EndOutside {
        /// The robot.
        robot: String,
        /// End x.
        x: f64,
        /// End y.
        y: f64,
    },
    /// The boustrophedon of a region failed.
    #[error("robot \"{robot}\": {source}")]
    Pattern {
        /// The robot.
        robot: String,
        /// Why.
        source: PatternError,
    },
}

/// A split of the coverable cells between the robots.
#[derive(Clone, Debug, PartialEq)]
pub struct Division {
    /// Owner of every cell (`None`: obstacle, or no robot can sweep it).
    pub owner: Vec<Option<u16>>,
    /// Cells per robot.
    pub sizes: Vec<usize>,
    /// Each robot's share of the coverable cells by its sweep rate.
    pub targets: Vec<f64>,
    /// Weight iterations used.
    pub iterations: usize,
}

/// Geodesic distances in metres from `start` over free cells (8-connected, no corner cutting).
fn geodesic(map: &GridMap, start: Point) -> Vec<f64> {
    let (rows, cols, res) = (map.rows(), map.cols(), map.resolution());
    let mut dist = vec![f64::INFINITY; rows * cols];
    let Some((r0, c0)) = map.cell_at(start) else { return dist };
    // Integer chamfer costs (5 straight, 7 diagonal) keep the heap order exact.
    let mut cost = vec![u64::MAX; rows * cols];
    let mut heap = BinaryHeap::new();
    cost[r0 * cols + c0] = 0;
    heap.push(Reverse((0u64, r0 * cols + c0)));
    while let Some(Reverse((d, i))) = heap.pop() {
        if d > cost[i] {
            continue;
        }
        let (r, c) = ((i / cols) as isize, (i % cols) as isize);
        for (dr, dc) in [(-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1)] {
            let (nr, nc) = (r + dr, c + dc);
            if nr < 0 || nc < 0 || nr >= rows as isize || nc >= cols as isize {
                continue;
            }
            let free = |rr: isize, cc: isize| map.is_free(rr as usize, cc as usize);
            if !free(nr, nc) || (dr != 0 && dc != 0 && (!free(r + dr, c) || !free(r, c + dc))) {
                continue;
            }
            let j = nr as usize * cols + nc as usize;
            let nd = d + if dr != 0 && dc != 0 { 7 } else { 5 };
            if nd < cost[j] {
                cost[j] = nd;
                heap.push(Reverse((nd, j)));
            }
        }
    }
    for (d, &k) in dist.iter_mut().zip(&cost) {
        if k != u64::MAX {
            *d = k as f64 * res / 5.0;
        }
    }
    dist
}

/// Splits the cells the robots can sweep between them (see the module documentation).
pub fn divide(map: &GridMap, fleet: &Fleet) -> Result<Division, DivisionError> {
    let robots = fleet.robots();
    let starts: Vec<Option<(usize, usize)>> = robots.iter().map(|r| map.cell_at(r.start)).collect();
    for i in 0..robots.len() {
        for j in 0..i {
            if starts[i] == starts[j] {
                return Err(DivisionError::SharedStart(robots[j].name.clone(), robots[i].name.clone()));
            }
        }
    }
    let n = map.rows() * map.cols();
    // d_i(c): geodesic distance where robot i can sweep c, else infinity.
    let dist: Vec<Vec<f64>> = robots
        .iter()
        .map(|r| {
            let reach = Reach::new(&Clearance::new(map, r.footprint.width), &[r.start]);
            let mut d = geodesic(map, r.start);
            for (i, x) in d.iter_mut().enumerate() {
                if !reach.is_coverable(i) {
                    *x = f64::INFINITY;
                }
            }
            d
        })
        .collect();
    let cells: Vec<usize> = (0..n).filter(|&c| dist.iter().any(|d| d[c].is_finite())).collect();
    let rate = fleet.sweep_rate();
    let targets: Vec<f64> = robots.iter().map(|r| cells.len() as f64 * r.sweep_rate() / rate).collect();
    let mut weights = vec![1.0f64; robots.len()];
    let mut owner = vec![None; n];
    let mut sizes = vec![0usize; robots.len()];
    let mut iterations = 0;
    while iterations < MAX_ITERATIONS {
        iterations += 1;
        sizes.iter_mut().for_each(|s| *s = 0);
        for &c in &cells {
            let best = (0..robots.len())
                .filter(|&i| dist[i][c].is_finite())
                .min_by(|&a, &b| (weights[a] * dist[a][c]).total_cmp(&(weights[b] * dist[b][c])))
                .expect("some robot sweeps every listed cell");
            owner[c] = Some(best as u16);
            sizes[best] += 1;
        }
        let balanced = sizes.iter().zip(&targets).all(|(&s, &t)| (s as f64 - t).abs() <= (0.01 * t).max(1.0));
        if balanced {
            break;
        }
        // A region over its share gets a larger weight (it looks farther away) and shrinks.
        for (w, (&s, &t)) in weights.iter_mut().zip(sizes.iter().zip(&targets)) {
            *w *= ((s.max(1) as f64) / t.max(1.0)).powf(0.25);
        }
    }
    connect_regions(map, robots.iter().map(|r| r.start).collect::<Vec<_>>().as_slice(), &dist, &mut owner);
    sizes.iter_mut().for_each(|s| *s = 0);
    for o in owner.iter().flatten() {
        sizes[*o as usize] += 1;
    }
    Ok(Division { owner, sizes, targets, iterations })
}

const STEPS: [(isize, isize); 8] = [(-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1)];

/// Keeps each region's part connected (8-connected) to its robot's start and hands the cut-off
/// cells to a neighbouring region whose robot can sweep them (breadth first from the kept
/// regions, neighbours in a fixed order, so the result is deterministic).
fn connect_regions(map: &GridMap, starts: &[Point], dist: &[Vec<f64>], owner: &mut [Option<u16>]) {
    let (rows, cols) = (map.rows() as isize, map.cols() as isize);
    let neighbours = |i: usize| {
        let (r, c) = ((i as isize) / cols, (i as isize) % cols);
        STEPS.iter().filter_map(move |&(dr, dc)| {
            let (nr, nc) = (r + dr, c + dc);
            (nr >= 0 && nc >= 0 && nr < rows && nc < cols).then_some((nr * cols + nc) as usize)
        })
    };
    let mut kept = vec![false; owner.len()];
    let mut queue = VecDeque::new();
    for (k, s) in starts.iter().enumerate() {
        if let Some((r, c)) = map.cell_at(*s) {
            let i = r * map.cols() + c;
            if owner[i] == Some(k as u16) {
                kept[i] = true;
                queue.push_back(i);
            }
        }
    }
    while let Some(i) = queue.pop_front() {
        for j in neighbours(i) {
            if !kept[j] && owner[j] == owner[i] {
                kept[j] = true;
                queue.push_back(j);
            }
        }
    }
    // Cut-off cells: unassigned, then grown into from the kept regions.
    for (i, o) in owner.iter_mut().enumerate() {
        if !kept[i] {
            *o = None;
        }
    }
    let mut frontier: VecDeque<usize> = (0..owner.len()).filter(|&i| kept[i]).collect();
    while let Some(i) = frontier.pop_front() {
        let k = owner[i].expect("frontier cells are owned");
        for j in neighbours(i) {
            if owner[j].is_none() && dist[k as usize][j].is_finite() {
                owner[j] = Some(k);
                frontier.push_back(j);
            }
        }
    }
}

/// Robot `k`'s region widened by `margin` metres into the neighbouring regions' free cells:
/// closing the neighbours off at the border itself would keep the robot's centre half a width
/// inside it and leave the border strip unswept.
fn widened_region(map: &GridMap, owner: &[Option<u16>], k: u16, margin: f64) -> Vec<bool> {
    let (rows, cols) = (map.rows() as isize, map.cols() as isize);
    let reach = (margin / map.resolution()).ceil() as isize;
    let r2 = (margin / map.resolution()).powi(2) + 1e-9;
    let mut open = vec![false; owner.len()];
    for (i, _) in owner.iter().enumerate().filter(|(_, o)| **o == Some(k)) {
        let (r, c) = ((i as isize) / cols, (i as isize) % cols);
        for dr in -reach..=reach {
            for dc in -reach..=reach {
                let (nr, nc) = (r + dr, c + dc);
                if ((dr * dr + dc * dc) as f64) <= r2 && nr >= 0 && nc >= 0 && nr < rows && nc < cols {
                    open[(nr * cols + nc) as usize] = true;
                }
            }
        }
    }
    open
}

/// Lane directions tried in each region, in degrees from the requested one.
pub const LANE_TURNS: [f64; 4] = [0.0, 45.0, 90.0, 135.0];

/// Length over speed plus rotation time (003 eqs. 3.1–3.3).
fn robot_time(points: &[Point], robot: &crate::coverage::Footprint) -> f64 {
    let (turn, _) = crate::coverage::motion::turning(points);
    crate::coverage::motion::path_length(points) / robot.speed
        + crate::coverage::motion::rotation_time(turn, robot.rot_speed)
}

/// Plans a boustrophedon in each robot's region, with the quickest of the lane directions
/// `angle_deg + LANE_TURNS` (the rest of the map closed to it
/// beyond half the robot's width), from its start to its end station. Returns one path per robot and the division.
pub fn plan(map: &GridMap, fleet: &Fleet, angle_deg: f64) -> Result<(Vec<Vec<Point>>, Division), DivisionError> {
    let division = divide(map, fleet)?;
    let mut paths = Vec::with_capacity(fleet.len());
    for (k, robot) in fleet.robots().iter().enumerate() {
        let open = widened_region(map, &division.owner, k as u16, 0.5 * robot.footprint.width);
        let cells: Vec<CellState> = map
            .cells()
            .iter()
            .zip(&open)
            .map(|(&s, &mine)| if s == CellState::Free && !mine { CellState::Occupied } else { s })
            .collect();
        let region = GridMap::new(map.name(), map.cols(), map.rows(), map.resolution(), map.origin(), cells)
            .expect("a region holds its robot's start");
        if !region.cell_at(robot.end).is_some_and(|(r, c)| region.is_free(r, c)) {
            return Err(DivisionError::EndOutside { robot: robot.name.clone(), x: robot.end.x, y: robot.end.y });
        }
        // The region's shape decides which lane direction is quick; try four.
        let mut best: Option<(f64, Vec<Point>)> = None;
        for turn in LANE_TURNS {
            let planned = patterns::plan(
                &region,
                Pattern::Boustrophedon { angle_deg: angle_deg + turn },
                robot.footprint.width,
                robot.start,
                robot.end,
                true,
            )
            .map_err(|source| DivisionError::Pattern { robot: robot.name.clone(), source })?;
            let time = robot_time(&planned.points, &robot.footprint);
            if best.as_ref().is_none_or(|(t, _)| time < *t) {
                best = Some((time, planned.points));
            }
        }
        paths.push(best.expect("four lane directions were tried").1);
    }
    Ok((paths, division))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fleet::config::FleetFile;
    use crate::fleet::metrics::FleetScorer;
    use crate::map::presets::preset;

    fn fleet(text: &str, map: &GridMap) -> Fleet {
        FleetFile::parse(text, "f.toml", map).unwrap()
    }

    #[test]
    fn geodesic_distance_by_hand() {
        // thesis-1 cells are 0.2 m: 3 cells straight = 0.6 m, 2 diagonal steps = 2·0.28 m.
        let map = preset("thesis-1").unwrap();
        let d = geodesic(&map, Point::new(1.1, 1.1));
        let at = |x: f64, y: f64| {
            let (r, c) = map.cell_at(Point::new(x, y)).unwrap();
            d[r * map.cols() + c]
        };
        assert_eq!(at(1.1, 1.1), 0.0);
        assert!((at(1.7, 1.1) - 0.6).abs() < 1e-12);
        assert!((at(1.5, 1.5) - 0.56).abs() < 1e-12);
        assert!(at(0.5, 0.5).is_infinite(), "the wall");
    }

    #[test]
    fn regions_are_sized_by_rate_connected_and_hold_their_starts() {
        let map = preset("thesis-2").unwrap();
        let f = fleet(
            "[[robots]]\nname = \"slow\"\nwidth = 0.4\nspeed = 0.2\nstart = [1.5, 1.5]\n\
             [[robots]]\nname = \"fast\"\nwidth = 0.6\nspeed = 0.4\nstart = [9.5, 9.5]\n",
            &map,
        );
        let d = divide(&map, &f).unwrap();
        // Rates 0.08 and 0.24: a quarter and three quarters.
        assert!((d.targets[0] / (d.targets[0] + d.targets[1]) - 0.25).abs() < 1e-9);
        for k in 0..2 {
            assert!(
                (d.sizes[k] as f64 - d.targets[k]).abs() <= 0.03 * d.targets[k],
                "{:?} vs {:?}",
                d.sizes,
                d.targets
            );
        }
        for (k, r) in f.robots().iter().enumerate() {
            let (row, col) = map.cell_at(r.start).unwrap();
            assert_eq!(d.owner[row * map.cols() + col], Some(k as u16), "{} owns its start", r.name);
        }
        // Each region is one 8-connected piece.
        for k in 0..2u16 {
            let cells: Vec<usize> = (0..d.owner.len()).filter(|&i| d.owner[i] == Some(k)).collect();
            let mut seen = vec![false; d.owner.len()];
            let mut stack = vec![cells[0]];
            seen[cells[0]] = true;
            let mut count = 0;
            while let Some(i) = stack.pop() {
                count += 1;
                let (r, c) = ((i / map.cols()) as isize, (i % map.cols()) as isize);
                for (dr, dc) in STEPS {
                    let j = ((r + dr) * map.cols() as isize + c + dc) as usize;
                    if d.owner[j] == Some(k) && !seen[j] {
                        seen[j] = true;
                        stack.push(j);
                    }
                }
            }
            assert_eq!(count, cells.len(), "region {k} is connected");
        }
    }

    #[test]
    fn each_robot_sweeps_its_region_and_the_fleet_covers_the_map() {
        let map = preset("thesis-1").unwrap();
        let f = fleet(
            "[[robots]]\nname = \"a\"\nwidth = 0.4\nspeed = 0.2\nstart = [1.3, 1.3]\n\
             [[robots]]\nname = \"b\"\nwidth = 0.6\nspeed = 0.3\nstart = [9.7, 1.3]\n\
             [[robots]]\nname = \"c\"\nwidth = 0.9\nspeed = 0.5\nstart = [5.5, 9.5]\n",
            &map,
        );
        let (paths, division) = plan(&map, &f, 0.0).unwrap();
        assert_eq!(paths.len(), 3);
        let s = FleetScorer::new(&map, &f).score(&paths).unwrap();
        assert!(s.union_reach > 0.97, "union {}", s.union_reach);
        assert!(s.overlap_fraction < 0.15, "overlap {}", s.overlap_fraction);
        // The fleet finishes sooner than the quickest of its robots sweeping the map alone
        // (a fleet of one: the whole map, the quickest lane direction).
        let alone = f
            .robots()
            .iter()
            .map(|r| {
                let one = fleet(
                    &format!(
                        "[[robots]]\nname = \"{}\"\nwidth = {}\nspeed = {}\nstart = [{}, {}]\n",
                        r.name, r.footprint.width, r.footprint.speed, r.start.x, r.start.y
                    ),
                    &map,
                );
                let (p, _) = plan(&map, &one, 0.0).unwrap();
                FleetScorer::new(&map, &one).score(&p).unwrap().makespan_s
            })
            .fold(f64::INFINITY, f64::min);
        assert!(s.makespan_s < alone, "fleet {} s, best alone {alone} s ({:?})", s.makespan_s, division.sizes);
    }

    #[test]
    fn shared_starts_and_ends_outside_are_refused() {
        let map = preset("thesis-1").unwrap();
        let two = "[[robots]]\nname = \"a\"\n[[robots]]\nname = \"b\"\n";
        assert_eq!(divide(&map, &fleet(two, &map)).unwrap_err(), DivisionError::SharedStart("a".into(), "b".into()));
        let far = "[[robots]]\nname = \"a\"\nstart = [1.3, 1.3]\nend = [9.5, 9.5]\n\
                   [[robots]]\nname = \"b\"\nstart = [9.7, 9.7]\n";
        let e = plan(&map, &fleet(far, &map), 0.0).unwrap_err();
        assert!(matches!(e, DivisionError::EndOutside { ref robot, .. } if robot == "a"), "{e}");
    }
}
