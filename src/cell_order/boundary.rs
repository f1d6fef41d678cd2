//! Boundary completion: the cells lanes leave uncovered lie mostly in strips along walls and
//! around clutter, where lane ends stop half a width short. Visiting them one at a time (the
//! patterns' greedy completion) costs a detour and a sideways move each. Here the robot drives
//! along the boundary of the space its centre can occupy instead — the cells whose disc just
//! fits beside a wall — wherever a target cell lies within half a width, in chains ordered as a
//! tour (nearest neighbour, then the memetic step's local search). The planner's targets are
//! every uncovered coverable cell (it aims at full coverage, where the greedy pass skips
//! patches smaller than a robot square); what the chains miss is left to the greedy pass.

use super::local::improve;
use super::search::nearest_neighbour;
use super::tour::{Candidate, Instance, Tour, leg_time};
use crate::geom::{Point, Vector};
use crate::map::clearance::Clearance;

/// The boundary chains worth driving: polylines of fitting cell centres next to non-fitting
/// ones, each within half a width of a cell of `targets` (one flag per map cell), simplified
/// where a straight move fits and strays less than a quarter cell from them.
pub fn chains(clear: &Clearance, targets: &[bool]) -> Vec<Vec<Point>> {
    let map = clear.map();
    chains_within(clear, targets, (0..map.rows(), 0..map.cols()))
}

/// [`chains`] simplified where a straight move strays less than `tolerance_m` from them (the
/// quota completion's chains: fewer, longer segments, fewer turns).
pub fn straightened_chains(clear: &Clearance, targets: &[bool], tolerance_m: f64) -> Vec<Vec<Point>> {
    let map = clear.map();
    chains_in(clear, targets, (0..map.rows(), 0..map.cols()), tolerance_m)
}

/// [`chains`] whose walks start and run only in the map rows and columns of `window` (the
/// targets lie inside it, less half a width): a cell's own completion reads its region alone.
pub fn chains_within(
    clear: &Clearance,
    targets: &[bool],
    window: (std::ops::Range<usize>, std::ops::Range<usize>),
) -> Vec<Vec<Point>> {
    chains_in(clear, targets, window, 0.25 * clear.map().resolution())
}

/// [`chains_within`], simplified within `tolerance_m`.
fn chains_in(
    clear: &Clearance,
    targets: &[bool],
    window: (std::ops::Range<usize>, std::ops::Range<usize>),
    tolerance_m: f64,
) -> Vec<Vec<Point>> {
    let map = clear.map();
    let (rows, cols) = (map.rows() as isize, map.cols() as isize);
    let n = map.rows() * map.cols();
    let (row_range, col_range) = window;
    let inside = |i: usize| row_range.contains(&(i / map.cols())) && col_range.contains(&(i % map.cols()));
    let indices = || row_range.clone().flat_map(|r| col_range.clone().map(move |c| r * map.cols() + c));
    let res = map.resolution();
    let r = clear.radius();
    let centre = |i: usize| map.cell_centre(i / map.cols(), i % map.cols());
    let neighbours = |i: usize, diagonal: bool| {
        let (r0, c0) = ((i / map.cols()) as isize, (i % map.cols()) as isize);
        let steps: &[(isize, isize)] = if diagonal {
            &[(-1, 0), (1, 0), (0, -1), (0, 1), (-1, -1), (-1, 1), (1, -1), (1, 1)]
        } else {
            &[(-1, 0), (1, 0), (0, -1), (0, 1)]
        };
        steps
            .iter()
            .map(move |(dr, dc)| (r0 + dr, c0 + dc))
            .filter(move |&(nr, nc)| nr >= 0 && nc >= 0 && nr < rows && nc < cols)
            .map(move |(nr, nc)| (nr * cols + nc) as usize)
    };
    let fits = |i: usize| clear.centre_fits(i);
    let window = (r / res).ceil() as isize;
    let is_useful = |i: usize| {
        if !fits(i) || neighbours(i, false).all(fits) {
            return false;
        }
        let (r0, c0) = ((i / map.cols()) as isize, (i % map.cols()) as isize);
        let c = centre(i);
        (-window..=window).any(|dr| {
            (-window..=window).any(|dc| {
                let (nr, nc) = (r0 + dr, c0 + dc);
                if nr < 0 || nc < 0 || nr >= rows || nc >= cols {
                    return false;
                }
                let j = (nr * cols + nc) as usize;
                targets[j] && (centre(j) - c).norm() <= r
            })
        })
    };
    let mut useful = vec![false; n];
    for i in indices() {
        useful[i] = is_useful(i);
    }
    let mut seen = vec![false; n];
    let mut out = Vec::new();
    for start in indices() {
        if !useful[start] || seen[start] {
            continue;
        }
        // Walk from `start`, each step to the unseen useful neighbour that turns least; a new
        // chain where the walk ends.
        let mut chain = vec![start];
        seen[start] = true;
        let mut here = start;
        let mut heading: Option<Vector> = None;
        loop {
            let next = neighbours(here, true).filter(|&j| inside(j) && useful[j] && !seen[j]).min_by(|&a, &b| {
                let turn = |j: usize| heading.map_or(0.0, |h| -(centre(j) - centre(here)).normalize().dot(&h));
                turn(a).total_cmp(&turn(b)).then(a.cmp(&b))
            });
            let Some(j) = next else { break };
            seen[j] = true;
            heading = Some((centre(j) - centre(here)).normalize());
            chain.push(j);
            here = j;
        }
        out.push(simplify(clear, &chain.iter().map(|&i| centre(i)).collect::<Vec<_>>(), tolerance_m));
    }
    out
}

/// Drops the points of `pts` a straight move can skip: from each kept point, the farthest
/// point reachable by a fitting segment that passes within `tol` metres of every point
/// between them.
fn simplify(clear: &Clearance, pts: &[Point], tol: f64) -> Vec<Point> {
    let mut out = vec![pts[0]];
    let mut a = 0;
    while a + 1 < pts.len() {
        let mut b = a + 1;
        for k in a + 2..pts.len() {
            let (p, q) = (pts[a], pts[k]);
            let d = q - p;
            let close = pts[a + 1..k].iter().all(|&m| {
                let t = ((m - p).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
                (p + d * t - m).norm() <= tol
            });
            if !close || !clear.segment_fits(p, q) {
                break;
            }
            b = k;
        }
        out.push(pts[b]);
        a = b;
    }
    out
}

/// The chains in the order and direction that a tour from `from` to `to` drives them fastest,
/// straight-line legs standing in for transit; `to` = `None` leaves the tour's end free.
pub fn order(chains: &[Vec<Point>], from: Point, to: Option<Point>, speed: f64) -> Vec<Vec<Point>> {
    let z = Vector::zeros();
    let length = |c: &[Point]| crate::coverage::motion::path_length(c);
    let cells: Vec<Vec<Candidate>> = chains
        .iter()
        .map(|c| {
            let (a, b) = (c[0], *c.last().expect("chains have points"));
            let t = length(c) / speed;
            vec![
                Candidate { time_s: t, entry: (a, z), exit: (b, z), gain: 0.0, completion_s: 0.0 },
                Candidate { time_s: t, entry: (b, z), exit: (a, z), gain: 0.0, completion_s: 0.0 },
            ]
        })
        .collect();
    let flat: Vec<Candidate> = cells.iter().flatten().copied().collect();
    let inst = Instance::new(&cells, |a, b| {
        let p = a.map_or(from, |a| flat[a].exit.0);
        let Some(q) = b.map(|b| flat[b].entry.0).or(to) else { return 0.0 };
        leg_time((q - p).norm(), 0.0, speed, 0.0)
    });
    let mut tour: Tour = nearest_neighbour(&inst);
    improve(&inst, &mut tour, 10_000);
    tour.order
        .iter()
        .map(|&k| {
            let c = &chains[k as usize];
            if tour.choice[k as usize] == 0 { c.clone() } else { c.iter().rev().copied().collect() }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::{CellState, GridMap};

    fn room() -> GridMap {
        let (cols, rows) = (40, 30);
        let cells = (0..rows * cols)
            .map(|i| {
                let (r, c) = (i / cols, i % cols);
                if r == 0 || c == 0 || r == rows - 1 || c == cols - 1 { CellState::Occupied } else { CellState::Free }
            })
            .collect();
        GridMap::new("room", cols, rows, 0.1, Point::origin(), cells).unwrap()
    }

    #[test]
    fn chains_follow_the_walls_near_targets_only() {
        let map = room();
        let clear = Clearance::new(&map, 0.6);
        let n = map.rows() * map.cols();
        assert!(chains(&clear, &vec![false; n]).is_empty(), "nothing to cover, nothing to drive");
        // One target cell by the left wall: a short chain there, every point a fitting centre
        // half a width (plus the wall) from the wall.
        let mut targets = vec![false; n];
        targets[15 * map.cols() + 1] = true;
        let found = chains(&clear, &targets);
        assert_eq!(found.len(), 1, "{found:?}");
        for p in &found[0] {
            assert!(clear.fits(*p) && (p.x - 0.45).abs() < 0.051, "{p:?}");
            assert!((p.y - 1.55).abs() <= 0.3 + 1e-9, "{p:?}");
        }
        // Every cell a target: one chain round the room, simplified to few corners.
        let all = chains(&clear, &vec![true; n]);
        let points: usize = all.iter().map(Vec::len).sum();
        assert!(!all.is_empty() && points < 20, "{all:?}");
    }

    #[test]
    fn chains_are_ordered_into_a_short_tour() {
        let a = vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0)];
        let b = vec![Point::new(5.0, 0.0), Point::new(4.0, 0.0)];
        let c = vec![Point::new(2.0, 0.0), Point::new(3.0, 0.0)];
        let ordered = order(&[b, a, c], Point::new(-1.0, 0.0), Some(Point::new(6.0, 0.0)), 1.0);
        let flat: Vec<f64> = ordered.iter().flatten().map(|p| p.x).collect();
        assert_eq!(flat, vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0]);
    }
}
