//! Coverage completion after a pattern: lanes and rings one robot width apart leave strips
//! along walls and around pillars uncovered wherever the free space is not a multiple of the
//! width wide (on SLAM maps, nearly everywhere). This pass visits what is left: repeatedly the
//! uncovered coverable cell nearest to the robot, driving to the reachable robot centre
//! nearest to it and, when the arrival did not sweep it, one short sideways move past it. A
//! cell that no such move sweeps is given up. Only uncovered patches of at least one robot
//! square (`width²`) are visited: slivers in corners cost a detour each for a few cells.
//! `[pattern] complete = false` turns the pass off.

use super::Route;
use crate::coverage::CoverageGrid;
use crate::coverage::raster::for_each_swept_cell;
use crate::geom::Point;
use crate::map::clearance::Clearance;
use crate::map::reach::Reach;

/// Visits the uncovered coverable cells after `route`'s pattern.
pub fn complete(clear: &Clearance, reach: &Reach, width: f64, route: &mut Route) {
    complete_patches(clear, reach, width, route, min_patch(clear.map(), width));
}

/// [`complete`], visiting uncovered patches of at least `min_patch` cells.
pub fn complete_patches(clear: &Clearance, reach: &Reach, width: f64, route: &mut Route, min_patch: usize) {
    let map = clear.map();
    let grid = CoverageGrid::new(map);
    let raster = *grid.raster();
    let cols = map.cols();
    let mut covered = vec![false; grid.len()];
    let sweep = |covered: &mut Vec<bool>, pts: &[Point]| {
        for w in pts.windows(2) {
            for_each_swept_cell(&raster, w[0], w[1], width, |i| covered[i] = true);
        }
    };
    sweep(&mut covered, &route.points);
    let centre = |i: usize| map.cell_centre(i / cols, i % cols);
    let mut open = patches(map, &covered, reach, min_patch);
    let window = (clear.radius() / map.resolution()).ceil() as isize + 2;
    let near = |i: usize, k: isize| {
        let (r, c) = ((i / cols) as isize, (i % cols) as isize);
        let mut out: Vec<usize> = Vec::new();
        for dr in -k..=k {
            for dc in -k..=k {
                let (nr, nc) = (r + dr, c + dc);
                if nr >= 0 && nc >= 0 && (nr as usize) < map.rows() && (nc as usize) < cols {
                    let j = nr as usize * cols + nc as usize;
                    if clear.centre_fits(j) {
                        out.push(j);
                    }
                }
            }
        }
        let p = centre(i);
        out.sort_by(|&a, &b| (centre(a) - p).norm().total_cmp(&(centre(b) - p).norm()).then(a.cmp(&b)));
        out
    };
    while !open.is_empty() {
        let here = route.last();
        let (k, &target) = open
            .iter()
            .enumerate()
            .min_by(|a, b| (centre(*a.1) - here).norm().total_cmp(&(centre(*b.1) - here).norm()))
            .expect("open is not empty");
        open.swap_remove(k);
        if covered[target] {
            continue;
        }
        let Some(&c) = near(target, window).first() else { continue };
        let before = route.points.len();
        route.go(clear, centre(c));
        sweep(&mut covered, &route.points[before.saturating_sub(1)..]);
        if !covered[target] {
            // One short move from the arrival past the cell.
            let from = route.last();
            for c2 in near(c, 2) {
                let to = centre(c2);
                let mut hit = false;
                for_each_swept_cell(&raster, from, to, width, |i| hit |= i == target);
                if hit && clear.segment_fits(from, to) {
                    let before = route.points.len();
                    route.go(clear, to);
                    sweep(&mut covered, &route.points[before.saturating_sub(1)..]);
                    break;
                }
            }
        }
        open.retain(|&i| !covered[i]);
    }
}

/// The smallest uncovered patch the pass visits, in cells: one robot square.
pub fn min_patch(map: &crate::map::GridMap, width: f64) -> usize {
    ((width / map.resolution()).powi(2)).ceil() as usize
}

/// The uncovered coverable cells in 8-connected patches of at least `min_patch` cells.
pub fn patches(map: &crate::map::GridMap, covered: &[bool], reach: &Reach, min_patch: usize) -> Vec<usize> {
    let (rows, cols) = (map.rows() as isize, map.cols() as isize);
    let open = |i: usize| reach.is_coverable(i) && !covered[i];
    let mut seen = vec![false; covered.len()];
    let mut out = Vec::new();
    for start in 0..covered.len() {
        if seen[start] || !open(start) {
            continue;
        }
        seen[start] = true;
        let mut patch = vec![start];
        let mut k = 0;
        while k < patch.len() {
            let i = patch[k];
            k += 1;
            let (r, c) = ((i as isize) / cols, (i as isize) % cols);
            for dr in -1..=1 {
                for dc in -1..=1 {
                    let (nr, nc) = (r + dr, c + dc);
                    if nr >= 0 && nc >= 0 && nr < rows && nc < cols {
                        let j = (nr * cols + nc) as usize;
                        if !seen[j] && open(j) {
                            seen[j] = true;
                            patch.push(j);
                        }
                    }
                }
            }
        }
        if patch.len() >= min_patch {
            out.extend(patch);
        }
    }
    out.sort_unstable();
    out
}
