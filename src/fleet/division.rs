//! Area division for a fleet in the style of DARP (Kapoutsis et al., cited by 003 §2.1.3): the
//! cells the robots can cover are split into one connected region per robot, sized by the
//! robot's sweep rate (width × speed) and grown around its start; each robot then sweeps its
//! region with a boustrophedon. A baseline for the fleet planners: it plans in one pass,
//! without search.
//!
//! The split is an additively weighted geodesic Voronoi partition: cell `c` goes to the robot
//! minimising `d_i(c) − w_i`, where `d_i` is the geodesic distance from robot `i`'s start over
//! free cells (8-connected, no corner cutting) and `∞` where robot `i` cannot sweep `c`. The
//! weights are adjusted until every region holds its share of cells (DARP's iteration, with
//! additive instead of multiplicative weights so that regions stay connected); cells still cut
//! off from their robot's start are then handed to a neighbouring region.

use super::Fleet;
use crate::geom::Point;
use crate::lanes::PatternError;
use crate::map::clearance::Clearance;
use crate::map::reach::Reach;
use crate::map::{CellState, GridMap};
use crate::patterns::{self, Pattern};
use std::cmp::Reverse;
use std::collections::{BinaryHeap, VecDeque};

/// Weight iterations before the split is accepted as it is.
pub const MAX_ITERATIONS: usize = 1000;

/// Why a fleet cannot be divided or its regions swept.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum DivisionError {
    /// Two robots start in the same cell: a geodesic split needs distinct starts.
    #[error(
        "robots \"{0}\" and \"{1}\" start in the same cell (or, where a start lies off the free cells, the nearest cell each fits in): area division needs distinct start stations"
    )]
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
    /// A robot's region holds no lane: its share of the area, by sweep rate, is too small.
    #[error(
        "robot \"{robot}\" was given {area_m2:.2} m² ({cells} cells): its share of the area by width × speed, \
         {share_pct:.2} % of the team's sweep rate, is too small for one lane of a robot {width} m wide; give it more \
         speed or width, or plan without it"
    )]
    RegionTooSmall {
        /// The robot.
        robot: String,
        /// Cells of its region.
        cells: usize,
        /// Their area.
        area_m2: f64,
        /// Its sweep rate over the team's, in per cent.
        share_pct: f64,
        /// Its width.
        width: f64,
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
    /// Each robot's share of the assigned cells by its sweep rate.
    pub targets: Vec<f64>,
    /// Cells given to a robot apart from its connected region: only robots whose regions lie
    /// apart from them can sweep them (a narrow robot's strips along walls on a SLAM map).
    pub detached: usize,
    /// The weight iteration whose split was kept.
    pub iterations: usize,
}

/// Robot `r`'s travel distance in metres to every cell it can sweep: Dijkstra over the cell
/// centres its disc can occupy from its start (the moves of [`Clearance::steps`]), then to a
/// swept cell from the nearest reachable centre within half the width; `∞` elsewhere. Gaps a
/// map has but the robot cannot pass (SLAM maps have many) do not shorten it.
fn robot_distance(map: &GridMap, r: &super::Robot) -> Vec<f64> {
    let n = map.rows() * map.cols();
    let clear = Clearance::new(map, r.footprint.width);
    let reach = Reach::new(&clear, &[r.start]);
    let mut centre = vec![f64::INFINITY; n];
    if let Some(s) = clear.snap(r.start) {
        // Non-negative f64 bits order like the numbers.
        let mut heap = BinaryHeap::new();
        centre[s] = 0.0;
        heap.push(Reverse((0u64, s)));
        while let Some(Reverse((bits, i))) = heap.pop() {
            let d = f64::from_bits(bits);
            if d > centre[i] {
                continue;
            }
            for (j, step) in clear.steps(i) {
                // Steps are counted in cells.
                let nd = d + step * map.resolution();
                if nd < centre[j] {
                    centre[j] = nd;
                    heap.push(Reverse((nd.to_bits(), j)));
                }
            }
        }
    }
    let (rows, cols, res) = (map.rows() as isize, map.cols() as isize, map.resolution());
    let k = (clear.radius() / res).floor() as isize;
    let offsets: Vec<(isize, isize, f64)> = (-k..=k)
        .flat_map(|dr| (-k..=k).map(move |dc| (dr, dc)))
        .map(|(dr, dc)| (dr, dc, ((dr * dr + dc * dc) as f64).sqrt() * res))
        .filter(|&(_, _, d)| d <= clear.radius() + 1e-9)
        .collect();
    let mut dist = vec![f64::INFINITY; n];
    for (i, &d0) in centre.iter().enumerate().filter(|(_, d)| d.is_finite()) {
        let (r0, c0) = ((i as isize) / cols, (i as isize) % cols);
        for &(dr, dc, extra) in &offsets {
            let (nr, nc) = (r0 + dr, c0 + dc);
            if nr >= 0 && nc >= 0 && nr < rows && nc < cols {
                let j = (nr * cols + nc) as usize;
                if reach.is_coverable(j) && d0 + extra < dist[j] {
                    dist[j] = d0 + extra;
                }
            }
        }
    }
    dist
}

/// The cell robot `r` starts its sweep from: the nearest cell centre its disc fits on (its start
/// cell, unless the start lies on or too near an obstacle, as stations on SLAM maps can);
/// `None` if it fits nowhere.
fn anchor(map: &GridMap, r: &super::Robot) -> Option<usize> {
    Clearance::new(map, r.footprint.width).snap(r.start)
}

/// The first two robots `(j, i)`, `j < i`, that start from the same cell (see `anchor`), which
/// a geodesic split cannot separate; checked when a fleet's configuration is validated.
pub fn shared_start(map: &GridMap, fleet: &Fleet) -> Option<(usize, usize)> {
    let anchors: Vec<Option<usize>> = fleet.robots().iter().map(|r| anchor(map, r)).collect();
    (0..anchors.len()).find_map(|i| (0..i).find(|&j| anchors[i] == anchors[j]).map(|j| (j, i)))
}

/// Splits the cells the robots can sweep between them (see the module documentation).
pub fn divide(map: &GridMap, fleet: &Fleet) -> Result<Division, DivisionError> {
    let robots = fleet.robots();
    if let Some((j, i)) = shared_start(map, fleet) {
        return Err(DivisionError::SharedStart(robots[j].name.clone(), robots[i].name.clone()));
    }
    let anchors: Vec<Option<usize>> = robots.iter().map(|r| anchor(map, r)).collect();
    let n = map.rows() * map.cols();
    // d_i(c): robot i's travel distance where it can sweep c, else infinity.
    let dist: Vec<Vec<f64>> = robots.iter().map(|r| robot_distance(map, r)).collect();
    let cells: Vec<usize> = (0..n).filter(|&c| dist.iter().any(|d| d[c].is_finite())).collect();
    let shares: Vec<f64> = robots.iter().map(|r| r.sweep_rate() / fleet.sweep_rate()).collect();
    // Additive weights: cell c goes to the robot with the least d_i(c) − w_i, then each region
    // keeps the part connected to its start (robots of different widths reach different
    // cells, so a narrow robot's strips along walls can lie apart from its region). The
    // weights are tuned on the connected sizes; the most even split seen is kept.
    let mut weights = vec![0.0f64; robots.len()];
    let scale = (cells.len() as f64).sqrt() * map.resolution();
    let mut owner = vec![None; n];
    let mut best: Option<(f64, Division)> = None;
    for iterations in 1..=MAX_ITERATIONS {
        for &c in &cells {
            let best = (0..robots.len())
                .filter(|&i| dist[i][c].is_finite())
                .min_by(|&a, &b| (dist[a][c] - weights[a]).total_cmp(&(dist[b][c] - weights[b])))
                .expect("some robot sweeps every listed cell");
            owner[c] = Some(best as u16);
        }
        // A robot keeps the cell it starts from, however the weights lean.
        for (k, a) in anchors.iter().enumerate() {
            if let Some(a) = *a {
                owner[a] = Some(k as u16);
            }
        }
        let assigned_by_weight = owner.clone();
        connect_regions(map, &anchors, &dist, &mut owner);
        // Cells no connected region could take go back to their robot by weight: only robots
        // whose regions lie apart from them can sweep them (a narrow robot's strips along
        // walls), and its plan reaches them travelling through the others' regions.
        let mut detached = 0;
        for &c in &cells {
            if owner[c].is_none() {
                owner[c] = assigned_by_weight[c];
                detached += 1;
            }
        }
        let mut sizes = vec![0usize; robots.len()];
        for o in owner.iter().flatten() {
            sizes[*o as usize] += 1;
        }
        let assigned: usize = sizes.iter().sum();
        debug_assert_eq!(assigned, cells.len(), "every sweepable cell has a robot");
        let targets: Vec<f64> = shares.iter().map(|s| s * assigned as f64).collect();
        let error = sizes.iter().zip(&targets).map(|(&s, &t)| (s as f64 - t).abs() / t.max(1.0)).fold(0.0, f64::max);
        if best.as_ref().is_none_or(|(e, _)| error < *e) {
            let division =
                Division { owner: owner.clone(), sizes: sizes.clone(), targets: targets.clone(), detached, iterations };
            best = Some((error, division));
        }
        if error <= 0.01 {
            break;
        }
        // A region short of its share reaches farther; the step shrinks as the split settles.
        let step = 0.5 * scale * 0.995f64.powi(iterations as i32);
        for (w, (&s, &t)) in weights.iter_mut().zip(sizes.iter().zip(&targets)) {
            *w += step * (t - s as f64) / assigned.max(1) as f64;
        }
        owner.iter_mut().for_each(|o| *o = None);
    }
    Ok(best.expect("at least one iteration").1)
}

const STEPS: [(isize, isize); 8] = [(-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1)];

/// Keeps each region's part connected (8-connected) to its robot's start and hands the cut-off
/// cells to a neighbouring region whose robot can sweep them (breadth first from the kept
/// regions, neighbours in a fixed order, so the result is deterministic).
fn connect_regions(map: &GridMap, anchors: &[Option<usize>], dist: &[Vec<f64>], owner: &mut [Option<u16>]) {
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
    for (k, a) in anchors.iter().enumerate() {
        if let Some(i) = *a
            && owner[i] == Some(k as u16)
        {
            kept[i] = true;
            queue.push_back(i);
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
    robot.path_time_s(points)
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
        // The route returns to the end through the nearest cell it fits on (as for a start).
        let end_cell = Clearance::new(map, robot.footprint.width).snap(robot.end);
        if !end_cell.is_some_and(|i| open[i]) {
            return Err(DivisionError::EndOutside { robot: robot.name.clone(), x: robot.end.x, y: robot.end.y });
        }
        // The region's shape decides which lane direction is quick; try four.
        let mut best: Option<(f64, Vec<Point>)> = None;
        for turn in LANE_TURNS {
            let planned = patterns::plan_region(
                map,
                &region,
                &open,
                Pattern::Boustrophedon { angle_deg: angle_deg + turn },
                robot.footprint.width,
                robot.start,
                robot.end,
            )
            .map_err(|source| match source {
                // The region, not the map, is what holds no lane for this robot.
                PatternError::NoRoom { width } => {
                    let team: f64 = fleet.robots().iter().map(|r| r.sweep_rate()).sum();
                    DivisionError::RegionTooSmall {
                        robot: robot.name.clone(),
                        cells: division.sizes[k],
                        area_m2: division.sizes[k] as f64 * map.resolution().powi(2),
                        share_pct: 100.0 * robot.sweep_rate() / team,
                        width,
                    }
                }
                PatternError::TooManyLanes { .. } | PatternError::NotExecutable(_) => {
                    DivisionError::Pattern { robot: robot.name.clone(), source }
                }
            })?;
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

    /// A robot so slow that its share of the area holds no lane is told so, not that the map
    /// has no room for it.
    #[test]
    fn a_share_too_small_for_a_lane_names_the_share() {
        let map = preset("thesis-1").unwrap();
        let f = fleet(
            "[[robots]]\nname = \"slow\"\nwidth = 0.6\nspeed = 0.001\nstart = [1.5, 1.5]\n\
             [[robots]]\nname = \"fast\"\nwidth = 0.6\nspeed = 0.2\nstart = [9.5, 9.5]\n",
            &map,
        );
        let e = plan(&map, &f, 0.0).unwrap_err();
        assert!(matches!(&e, DivisionError::RegionTooSmall { robot, .. } if robot == "slow"), "{e}");
        let text = e.to_string();
        assert!(text.contains("0.50 % of the team's sweep rate") && text.contains("more"), "{text}");
    }

    #[test]
    fn travel_distance_by_hand() {
        // thesis-1 cells are 0.2 m; a 0.4 m robot at (2.1, 2.1): 3 cells straight = 0.6 m,
        // 2 diagonal steps = 2·0.2·√2 m; walls and what lies beyond are out of reach.
        let map = preset("thesis-1").unwrap();
        let f = fleet("[[robots]]\nname = \"a\"\nwidth = 0.4\nstart = [2.1, 2.1]\n", &map);
        let d = robot_distance(&map, &f.robots()[0]);
        let at = |x: f64, y: f64| {
            let (r, c) = map.cell_at(Point::new(x, y)).unwrap();
            d[r * map.cols() + c]
        };
        assert_eq!(at(2.1, 2.1), 0.0);
        assert!((at(2.7, 2.1) - 0.6).abs() < 1e-9, "{}", at(2.7, 2.1));
        assert!((at(2.5, 2.5) - 0.4 * 2f64.sqrt()).abs() < 1e-9, "{}", at(2.5, 2.5));
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
        // Each region is one 8-connected piece around its start, but for the detached cells
        // (corner cells only the wider robot's disc reaches, at this cell size).
        let mut outside = 0;
        for (k, r) in f.robots().iter().enumerate() {
            let k = k as u16;
            let (row, col) = map.cell_at(r.start).unwrap();
            let first = row * map.cols() + col;
            let mut seen = vec![false; d.owner.len()];
            let mut stack = vec![first];
            seen[first] = true;
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
            outside += d.sizes[k as usize] - count;
        }
        assert_eq!(outside, d.detached);
        assert!(d.detached < 20, "{} detached cells", d.detached);
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
    fn a_robot_whose_share_is_all_rooms_only_it_can_enter_keeps_its_start() {
        // A 3 x 2.8 m room and, behind a 0.5 m door, a 2.8 m room that only the 0.4 m robot
        // can enter. Its share (4 % of the cells) is smaller than that room: the weights then
        // give every shared cell to the 0.9 m robot, its start cell included, and its region
        // used to vanish ("end station outside its region"). It keeps the cell it starts
        // from, and both plans are drivable.
        use crate::map::CellState;
        let (cols, rows) = (60, 30);
        let mut cells = vec![CellState::Occupied; cols * rows];
        for r in 1..29 {
            for c in 1..59 {
                if c != 30 || (12..17).contains(&r) {
                    cells[r * cols + c] = CellState::Free;
                }
            }
        }
        let map = GridMap::new("rooms", cols, rows, 0.1, Point::origin(), cells).unwrap();
        let f = fleet(
            "[[robots]]\nname = \"slow\"\nwidth = 0.4\nspeed = 0.05\nstart = [1.0, 1.0]\n\
             [[robots]]\nname = \"fast\"\nwidth = 0.9\nspeed = 0.5\nstart = [2.0, 2.0]\n",
            &map,
        );
        let (paths, d) = plan(&map, &f, 0.0).unwrap();
        assert_eq!(d.owner[anchor(&map, &f.robots()[0]).unwrap()], Some(0));
        let s = FleetScorer::new(&map, &f).score(&paths).unwrap();
        assert_eq!(s.obstacle_cells, 0);
        assert!(s.union_free > 0.85, "{}", s.union_free);
        assert!(paths[0].iter().any(|p| p.x > 4.0), "the slow robot sweeps the room behind the door");
        assert!(d.sizes[0] >= 700, "that room is the slow robot's: {:?}", d.sizes);
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
