use super::*;
use crate::map::CellState;
use proptest::prelude::*;

/// The plain definition: every lattice point kept by its own full-window clearance, the
/// 8-connected flood from the seeds, and every reached point within r + δ of a free cell's
/// centre looked at.
fn coverable_reference(map: &GridMap, radius: f64, seeds: &[Point]) -> Vec<bool> {
    let s = LATTICE_PER_CELL;
    let lat = Lattice { map, cols: map.cols() * s, rows: map.rows() * s, h: map.resolution() / s as f64 };
    let delta = lat.h * std::f64::consts::FRAC_1_SQRT_2;
    let need = (radius - delta).max(0.0);
    let kept: Vec<bool> = (0..lat.cols * lat.rows)
        .map(|k| {
            let p = lat.point(k % lat.cols, k / lat.cols);
            map.is_free_point(p) && clearance_full(map, p, need + 1e-9) >= need
        })
        .collect();
    let mut reached = vec![false; kept.len()];
    let mut stack: Vec<usize> = seeds.iter().map(|&p| lat.nearest(p)).filter(|&k| kept[k]).collect();
    while let Some(k) = stack.pop() {
        if reached[k] {
            continue;
        }
        reached[k] = true;
        let (i, j) = ((k % lat.cols) as isize, (k / lat.cols) as isize);
        for (di, dj) in [(-1, 0), (1, 0), (0, -1), (0, 1), (-1, -1), (-1, 1), (1, -1), (1, 1)] {
            let (ni, nj) = (i + di, j + dj);
            if ni >= 0 && nj >= 0 && ni < lat.cols as isize && nj < lat.rows as isize {
                let n = nj as usize * lat.cols + ni as usize;
                if kept[n] && !reached[n] {
                    stack.push(n);
                }
            }
        }
    }
    let reach_r = radius + delta;
    (0..map.rows() * map.cols())
        .map(|cell| {
            let (row, col) = (cell / map.cols(), cell % map.cols());
            let c = map.cell_centre(row, col);
            map.is_free(row, col)
                && (0..reached.len())
                    .any(|k| reached[k] && (lat.point(k % lat.cols, k / lat.cols) - c).norm() <= reach_r)
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// The cell-level shortcuts (whole cells kept from their centre's clearance, the row
    /// index of the walls, cells passed over by their square's distance) change nothing.
    #[test]
    fn shortcuts_give_the_plain_definition(
        walls in proptest::collection::vec(proptest::bool::weighted(0.25), 80),
        radius in 0.02f64..0.3,
        sx in 0.0f64..1.0, sy in 0.0f64..0.8,
    ) {
        let cells = walls.iter().map(|&w| if w { CellState::Occupied } else { CellState::Free }).collect();
        let Ok(map) = GridMap::new("random", 10, 8, 0.1, Point::new(-0.3, 0.2), cells) else { return Ok(()) };
        let seeds = [Point::new(-0.3 + sx, 0.2 + sy)];
        prop_assert_eq!(coverable_cells(&map, radius, &seeds), coverable_reference(&map, radius, &seeds));
    }

    /// The row index gives the full window's clearance to the bit.
    #[test]
    fn clearance_is_the_full_windows(
        walls in proptest::collection::vec(proptest::bool::weighted(0.25), 80),
        x in -0.5f64..1.0, y in 0.0f64..1.2, cap in 0.0f64..0.5,
    ) {
        let cells = walls.iter().map(|&w| if w { CellState::Occupied } else { CellState::Free }).collect();
        let Ok(map) = GridMap::new("random", 10, 8, 0.1, Point::new(-0.3, 0.2), cells) else { return Ok(()) };
        let p = Point::new(x, y);
        prop_assert_eq!(clearance(&map, &WallRows::new(&map), p, cap).to_bits(), clearance_full(&map, p, cap).to_bits());
    }
}

/// [`clearance`] scanning every cell of the window: the reference for the row index.
fn clearance_full(map: &GridMap, p: Point, cap: f64) -> f64 {
    let (ox, oy, res) = (map.origin().x, map.origin().y, map.resolution());
    let edge = (p.x - ox).min(p.y - oy).min(ox + map.width_m() - p.x).min(oy + map.height_m() - p.y);
    let mut best = edge.min(cap);
    let window = (cap / res).ceil() as isize + 1;
    let (cc, cr) = (((p.x - ox) / res).floor() as isize, ((p.y - oy) / res).floor() as isize);
    for r in (cr - window).max(0)..=(cr + window).min(map.rows() as isize - 1) {
        for c in (cc - window).max(0)..=(cc + window).min(map.cols() as isize - 1) {
            if map.is_free(r as usize, c as usize) {
                continue;
            }
            let (x0, y0) = (ox + c as f64 * res, oy + r as f64 * res);
            let dx = (x0 - p.x).max(0.0).max(p.x - x0 - res);
            let dy = (y0 - p.y).max(0.0).max(p.y - y0 - res);
            best = best.min((dx * dx + dy * dy).sqrt());
        }
    }
    best
}
