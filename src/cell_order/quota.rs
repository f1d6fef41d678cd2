//! The quota completion (`completion = "quota"`), the no-search control of what to complete:
//! what the sweeps leave splits into pieces (the boundary chains of [`super::boundary`] — wall
//! strips, rings round pillars, the edges of pockets — cut to at most [`PIECE_MAX_M`]), each with
//! the target cells it would newly cover and a time that counts its turning (length / v +
//! turning / ω, 003 eqs. 3.1–3.3). A plan stops at its coverage goal, so the goal is a quota:
//! the pieces that cost least per cell are taken first until they cover what the goal still
//! needs, and driven in the boundary pass's tour order from where the sweeps end. The pieces
//! left follow in the same order, and the greedy pass takes what the chains miss, so a plan that
//! runs past its goal still covers all it can.

use super::boundary;
use crate::coverage::CoverageGrid;
use crate::coverage::motion::{drive_time_s, path_length, turning};
use crate::geom::Point;
use crate::lanes::GrowingRoute;
use crate::map::clearance::Clearance;
use crate::map::reach::Reach;

/// One piece of the completion: a boundary chain with the cells it sweeps and its time.
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// The chain's points, in the order it was found (it may be driven either way).
    pub points: Vec<Point>,
    /// The map cells (indices) of the targets it sweeps.
    pub cells: Vec<u32>,
    /// Its own time in seconds: length over speed plus its turning over the rotation speed.
    pub time_s: f64,
}

/// The pieces of the completion for `targets` (one flag per map cell): the boundary chains
/// near them, each with the targets its band `width` wide sweeps (a chain of one point sweeps
/// the targets within half a width of it) and its time at `speed` and `rot_speed`.
pub fn pieces(
    clear: &Clearance,
    grid: &CoverageGrid,
    targets: &[bool],
    width: f64,
    speed: f64,
    rot_speed: f64,
) -> Vec<Piece> {
    let map = clear.map();
    let mut seen = vec![false; targets.len()];
    boundary::straightened_chains(clear, targets, width * CHAIN_TOLERANCE_WIDTHS)
        .into_iter()
        .flat_map(|chain| split(&chain, PIECE_MAX_M))
        .map(|points| {
            let mut cells = Vec::new();
            let mut take = |i: usize| {
                if targets[i] && !seen[i] {
                    seen[i] = true;
                    cells.push(i as u32);
                }
            };
            if let ([p], Some((row, col))) = (points.as_slice(), map.cell_at(points[0])) {
                let reach = (width / 2.0 / map.resolution()).ceil() as isize;
                for dr in -reach..=reach {
                    for dc in -reach..=reach {
                        let (r, c) = (row as isize + dr, col as isize + dc);
                        if r < 0 || c < 0 || r >= map.rows() as isize || c >= map.cols() as isize {
                            continue;
                        }
                        let i = r as usize * map.cols() + c as usize;
                        if (map.cell_centre(r as usize, c as usize) - *p).norm() <= width / 2.0 {
                            take(i);
                        }
                    }
                }
            }
            for w in points.windows(2) {
                crate::coverage::raster::for_each_swept_cell(grid.raster(), w[0], w[1], width, &mut take);
            }
            for &i in &cells {
                seen[i as usize] = false;
            }
            let time_s = drive_time_s(path_length(&points), turning(&points).0, speed, rot_speed);
            Piece { points, cells, time_s }
        })
        .collect()
}

/// The longest piece in metres: a long chain is cut, so that the quota takes the parts of it
/// that add much and leaves the rest. Measured with the no-search control (turning robot, goal
/// 0.9) on basement, office-1 and house-1-noisy with quarter-cell chains, seconds to the goal:
/// 1 m 5 246 / 3 656 / 7 136, 2 m 5 098 / 3 779 / 7 225, 4 m 5 086 / 3 663 / 7 327, uncut
/// 5 058 / 3 844 / 7 392, the boundary pass 6 122 / 3 741 / 7 343. 1 m and 4 m beat the
/// boundary pass on all three; 4 m, the faster of the two on the SLAM map, is kept (not measured
/// again with the straightened chains).
pub const PIECE_MAX_M: f64 = 4.0;

/// How far, in robot widths, a piece may stray from the boundary it follows where a straight
/// move saves its wiggles: a SLAM map's walls are ragged, and the boundary pass's quarter-cell
/// tolerance keeps a turn at every step of them. Measured with the no-search control (turning
/// robot, goal 0.9) at 0.25 cell (the boundary pass's) and 0.5, 1, 2, 3, 4, 6 cells of 0.05 m:
/// basement 5 086, 4 926, 4 712, 4 796, 4 879, 4 884, 4 986 s; house-1-noisy 7 327, 7 061,
/// 7 027, 6 700, 6 331, 6 374, 7 292 s; office-1 (clean walls) within 3 625–3 757 s at every
/// one. A sixth of the width (2 cells for the 0.6 m robot) is among the best on both.
pub const CHAIN_TOLERANCE_WIDTHS: f64 = 1.0 / 6.0;

/// `chain` cut into pieces of at most `max_len` metres (at its points where it can, a longer
/// segment into equal parts); consecutive pieces share their end points.
pub fn split(chain: &[Point], max_len: f64) -> Vec<Vec<Point>> {
    let mut dense = vec![chain[0]];
    for w in chain.windows(2) {
        let parts = ((w[1] - w[0]).norm() / max_len).ceil().max(1.0) as usize;
        for k in 1..=parts {
            dense.push(w[0] + (w[1] - w[0]) * (k as f64 / parts as f64));
        }
    }
    let mut out = Vec::new();
    let mut piece = vec![dense[0]];
    let mut length = 0.0;
    for w in dense.windows(2) {
        let step = (w[1] - w[0]).norm();
        if length + step > max_len + 1e-9 && piece.len() > 1 {
            out.push(std::mem::replace(&mut piece, vec![w[0]]));
            length = 0.0;
        }
        piece.push(w[1]);
        length += step;
    }
    out.push(piece);
    out
}

/// The pieces the quota heuristic takes: the cheapest per still-uncovered target cell by their
/// own time first, until they cover `needed` cells (every piece that adds a cell where `needed`
/// is `None`); in that order.
pub fn cheapest_first(pieces: &[Piece], needed: Option<usize>, cells: usize) -> Vec<usize> {
    let mut rank: Vec<usize> = (0..pieces.len()).filter(|&k| !pieces[k].cells.is_empty()).collect();
    let rate = |k: usize| pieces[k].time_s / pieces[k].cells.len() as f64;
    rank.sort_by(|&a, &b| rate(a).total_cmp(&rate(b)).then(a.cmp(&b)));
    let mut covered = vec![false; cells];
    let (mut count, mut out) = (0usize, Vec::new());
    for k in rank {
        if needed.is_some_and(|n| count >= n) {
            break;
        }
        let gain = pieces[k].cells.iter().filter(|&&i| !covered[i as usize]).count();
        if gain == 0 {
            continue;
        }
        for &i in &pieces[k].cells {
            covered[i as usize] = true;
        }
        count += gain;
        out.push(k);
    }
    out
}

/// `route` completed by the quota heuristic for `goal` (a share of `reach`'s coverable cells;
/// `None`: every piece by the same rule), the pieces it leaves in the boundary pass's order,
/// then the greedy pass. With `searched` (and a goal) the pieces that meet the goal, their order
/// and their directions are [`super::piece_search::search`]'s, started from the heuristic's.
pub fn complete(
    clear: &Clearance,
    reach: &Reach,
    robot: &crate::coverage::Footprint,
    (goal, searched): (Option<f64>, bool),
    route: &mut GrowingRoute,
) {
    let width = robot.width;
    let grid = CoverageGrid::new(clear.map());
    let mut covered = vec![false; grid.len()];
    for w in route.points().windows(2) {
        crate::coverage::raster::for_each_swept_cell(grid.raster(), w[0], w[1], width, |i| covered[i] = true);
    }
    let swept = covered.iter().zip(reach.coverable()).filter(|&(&c, &k)| c && k).count();
    let targets: Vec<bool> = covered.iter().zip(reach.coverable()).map(|(&c, &k)| k && !c).collect();
    let all = pieces(clear, &grid, &targets, width, robot.speed, robot.rot_speed);
    let needed = goal.map(|g| ((g * reach.coverable_count() as f64 - 1e-9).ceil() as usize).saturating_sub(swept));
    let chosen = cheapest_first(&all, needed, grid.len());
    let mut used = vec![false; all.len()];
    if let (true, Some(needed)) = (searched, needed) {
        let start = (route.last(), last_heading(route.points()));
        for (k, reversed) in super::piece_search::search(&all, &chosen, needed, grid.len(), start, robot) {
            used[k] = true;
            let points = &all[k].points;
            let mut go = |p: &Point| {
                route.go(clear, *p);
            };
            if reversed { points.iter().rev().for_each(&mut go) } else { points.iter().for_each(&mut go) }
        }
    } else {
        for &k in &chosen {
            used[k] = true;
        }
        let first: Vec<Vec<Point>> = chosen.iter().map(|&k| all[k].points.clone()).collect();
        drive_in_order(clear, robot, &first, route);
    }
    let rest: Vec<Vec<Point>> = (0..all.len()).filter(|&k| !used[k]).map(|k| all[k].points.clone()).collect();
    drive_in_order(clear, robot, &rest, route);
    crate::lanes::complete::complete(clear, reach, width, route);
}

/// `chains` driven in the boundary pass's order from where `route` ends.
fn drive_in_order(
    clear: &Clearance,
    robot: &crate::coverage::Footprint,
    chains: &[Vec<Point>],
    route: &mut GrowingRoute,
) {
    for chain in boundary::order(chains, route.last(), None, robot.speed) {
        for p in chain {
            route.go(clear, p);
        }
    }
}

/// The heading of a path's last move (zero for a path that has not moved).
fn last_heading(points: &[Point]) -> crate::geom::Vector {
    let end = *points.last().expect("a route has its start");
    points
        .iter()
        .rev()
        .find(|p| (end - **p).norm() > crate::geom::ZERO_LENGTH)
        .map_or(crate::geom::Vector::zeros(), |p| (end - p).normalize())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn piece(points: &[(f64, f64)], cells: &[u32], time_s: f64) -> Piece {
        Piece { points: points.iter().map(|&(x, y)| Point::new(x, y)).collect(), cells: cells.to_vec(), time_s }
    }

    #[test]
    fn the_quota_takes_the_cheapest_cells_first_and_stops_at_the_goal() {
        // A long strip with many cells, a ring with few: the strip first; the ring only when the
        // goal needs its cells; a piece whose cells were all taken adds nothing.
        let strip = piece(&[(1.0, 0.0), (11.0, 0.0)], &(0..100).collect::<Vec<u32>>(), 10.0);
        let ring = piece(&[(50.0, 0.0), (50.0, 1.0), (49.0, 1.0)], &[200, 201, 202], 20.0);
        let pillar = piece(&[(2.0, 2.0), (2.0, 3.0)], &[300, 301], 30.0);
        let twin = piece(&[(1.0, 0.5), (11.0, 0.5)], &(0..100).collect::<Vec<u32>>(), 12.0);
        let pieces = [ring, strip, pillar, twin, piece(&[(0.0, 0.0)], &[], 0.0)];
        for (needed, want) in [
            (Some(0), vec![]),
            (Some(50), vec![1]),
            (Some(100), vec![1]),
            (Some(101), vec![1, 0]),
            (Some(104), vec![1, 0, 2]),
            (Some(1000), vec![1, 0, 2]),
            (None, vec![1, 0, 2]),
        ] {
            assert_eq!(cheapest_first(&pieces, needed, 400), want, "{needed:?}");
        }
    }

    #[test]
    fn chains_split_into_pieces_of_bounded_length_that_join_up() {
        let chain: Vec<Point> =
            [(0.0, 0.0), (10.0, 0.0), (10.0, 1.0), (10.0, 2.0)].iter().map(|&(x, y)| Point::new(x, y)).collect();
        let pieces = split(&chain, 4.0);
        for p in &pieces {
            assert!(path_length(p) <= 4.0 + 1e-9, "{p:?}");
        }
        for w in pieces.windows(2) {
            assert_eq!(w[0].last(), w[1].first());
        }
        let total: f64 = pieces.iter().map(|p| path_length(p)).sum();
        assert!((total - 12.0).abs() < 1e-9);
        assert_eq!(split(&chain, f64::INFINITY), vec![chain.clone()]);
        assert_eq!(split(&chain[..1], 4.0), vec![chain[..1].to_vec()]);
    }
}
