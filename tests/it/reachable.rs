//! The reachable denominator holds every cell a wall-free plan can sweep: random plans whose
//! robot centre keeps clearance ≥ width/2 (checked exactly, segment against every non-free
//! cell and the map's edge) sweep no obstacle cell, and every free cell they sweep is counted
//! reachable (`unique_reach_cells == unique_cells`), on random maps and on the SLAM map.

use covga::coverage::Footprint;
use covga::coverage::fitness::Projection;
use covga::coverage::score::{CameraSpec, Scorer};
use covga::geom::Point;
use covga::map::{CellState, GridMap};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};

fn camera() -> CameraSpec {
    CameraSpec { scale: 0.3, d_min: 0.2, d_max: 3.0, fov_deg: 69.4, sections: 5, band_m: 0.45 }
}

/// Distance from `p` to segment `a → b`.
fn point_segment(p: Point, a: Point, b: Point) -> f64 {
    let d = b - a;
    let t = if d.norm_squared() > 0.0 { ((p - a).dot(&d) / d.norm_squared()).clamp(0.0, 1.0) } else { 0.0 };
    (a + d * t - p).norm()
}

/// Distance from segment `a → b` to the axis-aligned square `[x0, x0+s] × [y0, y0+s]`.
fn segment_square(a: Point, b: Point, x0: f64, y0: f64, s: f64) -> f64 {
    let inside = |p: Point| p.x >= x0 && p.x <= x0 + s && p.y >= y0 && p.y <= y0 + s;
    let corners = [Point::new(x0, y0), Point::new(x0 + s, y0), Point::new(x0 + s, y0 + s), Point::new(x0, y0 + s)];
    let cross = |o: Point, p: Point, q: Point| (p - o).x * (q - o).y - (p - o).y * (q - o).x;
    let intersects = |c: Point, d: Point| {
        let (d1, d2) = (cross(c, d, a), cross(c, d, b));
        let (d3, d4) = (cross(a, b, c), cross(a, b, d));
        d1 * d2 <= 0.0 && d3 * d4 <= 0.0
    };
    if inside(a) || inside(b) || (0..4).any(|k| intersects(corners[k], corners[(k + 1) % 4])) {
        return 0.0;
    }
    let to_square = |p: Point| {
        let dx = (x0 - p.x).max(0.0).max(p.x - x0 - s);
        let dy = (y0 - p.y).max(0.0).max(p.y - y0 - s);
        (dx * dx + dy * dy).sqrt()
    };
    let ends = to_square(a).min(to_square(b));
    corners.iter().map(|&c| point_segment(c, a, b)).fold(ends, f64::min)
}

/// The exact clearance of segment `a → b`: its distance to the nearest non-free cell or to
/// the map's edge.
fn segment_clearance(map: &GridMap, a: Point, b: Point, radius: f64) -> f64 {
    let (o, res) = (map.origin(), map.resolution());
    let edge = [a, b]
        .iter()
        .map(|p| (p.x - o.x).min(p.y - o.y).min(o.x + map.width_m() - p.x).min(o.y + map.height_m() - p.y))
        .fold(f64::INFINITY, f64::min);
    let pad = radius + res;
    let col = |x: f64| (((x - o.x) / res).floor().max(0.0) as usize).min(map.cols() - 1);
    let row = |y: f64| (((y - o.y) / res).floor().max(0.0) as usize).min(map.rows() - 1);
    let mut best = edge;
    for r in row(a.y.min(b.y) - pad)..=row(a.y.max(b.y) + pad) {
        for c in col(a.x.min(b.x) - pad)..=col(a.x.max(b.x) + pad) {
            if !map.is_free(r, c) {
                best = best.min(segment_square(a, b, o.x + c as f64 * res, o.y + r as f64 * res, res));
            }
        }
    }
    best
}

/// A random wall-free walk of up to `steps` moves from `start` (which must fit).
fn random_walk(map: &GridMap, start: Point, width: f64, steps: usize, rng: &mut impl Rng) -> Vec<Point> {
    let mut path = vec![start];
    for _ in 0..steps * 4 {
        if path.len() > steps {
            break;
        }
        let p = *path.last().unwrap();
        let (angle, len) = (rng.random_range(0.0..std::f64::consts::TAU), rng.random_range(0.05..3.0));
        let q = p + nalgebra::Vector2::new(angle.cos(), angle.sin()) * len;
        if segment_clearance(map, p, q, width / 2.0) >= width / 2.0 {
            path.push(q);
        }
    }
    path
}

/// Checks random walks from `start` on `map`; returns how many swept at least one cell.
fn check_walks(map: &GridMap, start: Point, width: f64, walks: usize, steps: usize, seed: u64) -> usize {
    let robot = Footprint { width, speed: 0.2, rot_speed: 0.0 };
    let scorer = Scorer::new(map, robot, Projection::F1, &camera(), &[start]);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut swept = 0;
    for _ in 0..walks {
        let path = random_walk(map, start, width, steps, &mut rng);
        let s = scorer.score(std::slice::from_ref(&path));
        assert_eq!(s.obstacle_cells, 0, "a wall-free walk swept obstacle cells: {path:?}");
        assert!(s.executable, "a wall-free walk is executable");
        assert_eq!(s.unique_reach_cells, s.unique_cells, "a wall-free walk swept unreachable cells: {path:?}");
        swept += usize::from(s.unique_cells > 0);
    }
    swept
}

/// A map of `cols × rows` cells at 0.1 m with a border wall and random blocks.
fn random_map(cols: usize, rows: usize, blocks: &[(usize, usize, usize, usize)]) -> GridMap {
    let mut cells = vec![CellState::Free; cols * rows];
    for r in 0..rows {
        for c in 0..cols {
            if r == 0 || c == 0 || r == rows - 1 || c == cols - 1 {
                cells[r * cols + c] = CellState::Occupied;
            }
        }
    }
    for &(c0, r0, w, h) in blocks {
        for r in r0..(r0 + h).min(rows) {
            for c in c0..(c0 + w).min(cols) {
                cells[r * cols + c] = CellState::Occupied;
            }
        }
    }
    GridMap::new("random", cols, rows, 0.1, Point::origin(), cells).unwrap()
}

/// The counter-example a random run of the property below found: a band 0.8 m high between a
/// block and the wall, where a robot 0.724 m wide fits at heights 2.462–2.538 m, a band that
/// holds no cell centre (2.45 and 2.55). The robot fits and drives there (executable), so the
/// reachable set must hold what it sweeps there: the coverable positions are flooded from the
/// stations themselves, not from the cell centres nearest to them.
#[test]
fn reach_covers_corridors_narrower_than_a_cell_pitch() {
    let map = random_map(40, 30, &[(14, 21, 2, 1), (23, 20, 6, 1), (27, 17, 7, 4), (24, 4, 3, 2)]);
    let width = 0.7243479031514054;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(610);
    let start = (0..200)
        .map(|_| Point::new(rng.random_range(0.1..3.9), rng.random_range(0.1..2.9)))
        .find(|&p| segment_clearance(&map, p, p, width / 2.0) >= width / 2.0)
        .expect("a start that fits");
    check_walks(&map, start, width, 12, 25, 610);
}

proptest! {
    // A fixed seed, so that every run of the suite checks the same cases (a case a random seed
    // found is kept above).
    #![proptest_config(ProptestConfig {
        cases: 200,
        rng_seed: proptest::test_runner::RngSeed::Fixed(2026),
        ..ProptestConfig::default()
    })]
    #[test]
    fn wall_free_walks_sweep_only_reachable_cells(
        blocks in proptest::collection::vec((1usize..38, 1usize..28, 1usize..8, 1usize..8), 0..10),
        width in 0.15..0.9f64,
        seed in 0u64..1000,
    ) {
        let map = random_map(40, 30, &blocks);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        // A start with room for the robot, if the blocks left one.
        let start = (0..200).map(|_| Point::new(rng.random_range(0.1..3.9), rng.random_range(0.1..2.9)))
            .find(|&p| segment_clearance(&map, p, p, width / 2.0) >= width / 2.0);
        if let Some(start) = start {
            check_walks(&map, start, width, 12, 25, seed);
        }
    }
}

#[test]
fn wall_free_walks_on_the_slam_map_sweep_only_reachable_cells() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments/maps/basement.yaml");
    let map = covga::map::ros::load_ros_yaml(&path).unwrap();
    // Open floor of the basement map, clear of the walls for a 0.6 m robot.
    let start = Point::new(2.0, 2.0);
    assert!(segment_clearance(&map, start, start, 0.3) >= 0.3, "the start must fit");
    let swept = check_walks(&map, start, 0.6, 40, 80, 7);
    assert!(swept >= 30, "most walks move: {swept}");
}
