use super::*;
use crate::coverage::motion::{path_length, turning};
use crate::coverage::raster::for_each_swept_cell;
use crate::map::CellState;
use proptest::prelude::*;

fn free_map(cols: usize, rows: usize, resolution: f64) -> GridMap {
    GridMap::new("free", cols, rows, resolution, Point::origin(), vec![CellState::Free; cols * rows]).unwrap()
}

/// The area of the distinct cells the scorer's sweep of `path` covers on `map` (003 §3.1.2).
fn swept_area_m2(map: &GridMap, path: &[Point], width: f64) -> f64 {
    let grid = crate::coverage::CoverageGrid::new(map);
    let mut covered = vec![false; grid.len()];
    for w in path.windows(2) {
        for_each_swept_cell(grid.raster(), w[0], w[1], width, |i| covered[i] = true);
    }
    covered.iter().filter(|&&c| c).count() as f64 * map.resolution().powi(2)
}

#[test]
fn an_area_one_piece_covers_needs_no_turning() {
    // 9 m² at 0.5 m wide on fine cells is an 18 m path: one piece of a 20 m region holds it.
    assert_eq!(min_turning_rad(9.0, 0.5, 0.01, 20.0), 0.0);
    assert_eq!(min_turning_rad(0.0, 0.5, 0.01, 20.0), 0.0);
    assert_eq!(min_turning_rad(5.0, 0.5, 0.01, 0.0), 0.0);
}

#[test]
fn an_area_longer_than_the_region_turns_a_right_angle_or_more() {
    // 12.5 m² at 0.5 m (25 m of path) in a 10 m region: a piece turning less than π/2 covers
    // at most 0.5 × 10.5 / cos(π/4) + area(K) ≈ 7.6 m², so two pieces and π/2 of turning at
    // least; a boustrophedon of 3 lanes turns 2π.
    let t = min_turning_rad(12.5, 0.5, 0.001, 10.0);
    assert!(t >= std::f64::consts::FRAC_PI_2 - 1e-9, "{t}");
    assert!(t <= 2.0 * PI, "{t}");
}

#[test]
fn the_turning_bound_grows_about_linearly_with_the_area() {
    // The best θ·cos(θ/2) is about 1.122, so the bound tends to 1.12 · A / (w (D + w)).
    let (a, b) = (min_turning_rad(500.0, 0.5, 0.0, 10.0), min_turning_rad(1000.0, 0.5, 0.0, 10.0));
    assert!((a / (500.0 / (0.5 * 10.5)) - 1.122).abs() < 0.03, "{a}");
    assert!(b > 1.9 * a && b < 2.1 * a, "{a} {b}");
}

/// The lengths the grid allows: on cells as wide as the robot a strip of centres can be
/// swept at `w + r` per metre, which the length bound must allow (and does, at `w + √2·r`).
#[test]
fn the_length_bound_allows_what_a_grid_strip_holds() {
    let table = [(0.6, 0.05), (0.61, 0.2), (0.1, 0.5), (1.5, 0.6), (0.05, 0.02)];
    for (w, r) in table {
        let strip = 10.0 * (w + r);
        assert!(min_length_m(strip, w, r) <= 10.0, "w {w} r {r}: {}", min_length_m(strip, w, r));
    }
    assert_eq!(min_length_m(0.1, 0.6, 0.05), 0.0, "less than the start's area needs no driving");
}

/// The cases: a short diagonal that sweeps more cells than width × length, lanes on
/// cell borders that sweep two rows of centres each, and a straight corridor that turns none.
#[test]
fn plans_that_beat_the_old_bound_do_not_beat_this_one() {
    let thesis_like = free_map(45, 45, 0.2);
    let cases: Vec<(Vec<Point>, f64)> = vec![
        (vec![Point::new(5.0, 5.0), Point::new(6.0, 6.0)], 0.61),
        (
            (0..5)
                .flat_map(|i| [Point::new(0.2, 0.8 * i as f64 + 0.4), Point::new(8.8, 0.8 * i as f64 + 0.4)])
                .collect(),
            0.61,
        ),
        (vec![Point::new(0.1, 4.5), Point::new(8.9, 4.5)], 0.6),
    ];
    for (path, width) in cases {
        let area = swept_area_m2(&thesis_like, &path, width);
        let b = TimeBound::one_robot(area, (width, 0.3, 0.52), 0.2, free_diameter_m(&thesis_like));
        let time = path_length(&path) / 0.3 + turning(&path).0 / 0.52;
        assert!(b.total_s() <= time + 1e-9, "{path:?}: bound {} > time {time}", b.total_s());
    }
    let corridor = free_map(290, 3, 0.1);
    let straight = [Point::new(0.0, 0.15), Point::new(29.0, 0.15)];
    let area = swept_area_m2(&corridor, &straight, 0.3);
    assert_eq!(min_turning_rad(area, 0.3, 0.1, free_diameter_m(&corridor)), 0.0);
}

#[test]
fn boustrophedons_of_a_square_turn_more_than_the_bound() {
    for lanes in [2usize, 5, 12, 40] {
        let (side, width) = (10.0, 10.0 / lanes as f64);
        let map = free_map(200, 200, 0.05);
        let path: Vec<Point> = (0..lanes)
            .flat_map(|i| {
                let y = width * (i as f64 + 0.5);
                let (a, b) = (0.5 * width, side - 0.5 * width);
                if i % 2 == 0 { [Point::new(a, y), Point::new(b, y)] } else { [Point::new(b, y), Point::new(a, y)] }
            })
            .collect();
        let area = swept_area_m2(&map, &path, width);
        let bound = min_turning_rad(area, width, 0.05, free_diameter_m(&map));
        assert!(bound <= turning(&path).0 + 1e-9, "{lanes} lanes: bound {bound} > turning {}", turning(&path).0);
        assert!(min_length_m(area, width, 0.05) <= path_length(&path) + 1e-9);
    }
}

#[test]
fn the_diameter_of_a_free_rectangle_is_its_diagonal() {
    // 8 m × 6 m, all free: diagonal 10 m; with a wall column in the middle, the same.
    let (cols, rows) = (80, 60);
    let d = free_diameter_m(&free_map(cols, rows, 0.1));
    assert!((10.0..=10.0 * 1.0001).contains(&d), "{d}");
    let mut cells = vec![CellState::Free; cols * rows];
    (0..rows).for_each(|r| cells[r * cols + 40] = CellState::Occupied);
    assert!((free_diameter_m(&GridMap::new("w", cols, rows, 0.1, Point::origin(), cells).unwrap()) - d).abs() < 1e-9);
    // Only the lower-left quarter free: half the diagonal.
    let cells = (0..rows * cols)
        .map(|i| if i / cols < 30 && i % cols < 40 { CellState::Free } else { CellState::Occupied })
        .collect();
    let quarter = free_diameter_m(&GridMap::new("q", cols, rows, 0.1, Point::origin(), cells).unwrap());
    assert!((5.0..=5.0 * 1.0001).contains(&quarter), "{quarter}");
}

#[test]
fn free_turning_adds_nothing() {
    let free = TimeBound::one_robot(100.0, (0.6, 0.3, 0.0), 0.05, 10.0);
    assert_eq!(free.turning_s, 0.0);
    let expected = (100.0 - start_area_m2(0.6, 0.05)) / (sweep_width_m(0.6, 0.05) * 0.3);
    assert!((free.total_s() - expected).abs() < 1e-9);
    let turning = TimeBound::one_robot(100.0, (0.6, 0.3, 0.52), 0.05, 10.0);
    assert!(turning.turning_s > 0.0 && turning.area_s == free.area_s);
}

#[test]
fn a_fleet_sweeps_at_its_summed_rates() {
    let one = area_time_s(100.0, &[(0.6, 0.3)], 0.05);
    let two = area_time_s(100.0, &[(0.6, 0.3), (0.6, 0.3)], 0.05);
    let (k, rate) = (start_area_m2(0.6, 0.05), sweep_width_m(0.6, 0.05) * 0.3);
    assert!((one - (100.0 - k) / rate).abs() < 1e-9 && (two - (100.0 - 2.0 * k) / (2.0 * rate)).abs() < 1e-9);
    assert_eq!(area_time_s(100.0, &[], 0.05), 0.0);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// No path beats either bound, whatever its cells, width and shape: paths that leave the
    /// map or cross it at any angle included (cells off the grid count nothing).
    #[test]
    fn no_path_beats_the_bound(
        resolution in 0.02..0.6f64,
        width in 0.05..1.5f64,
        cells in 4usize..40,
        raw in proptest::collection::vec((-0.2..1.2f64, -0.2..1.2f64), 2..14),
        axis in proptest::bool::ANY,
    ) {
        let map = free_map(cells, cells, resolution);
        let side = cells as f64 * resolution;
        // Half the cases drive axis-parallel lanes (the grid's densest strips).
        let path: Vec<Point> = raw
            .iter()
            .enumerate()
            .map(|(i, &(x, y))| if axis && i % 2 == 1 { Point::new(x * side, raw[i - 1].1 * side) } else { Point::new(x * side, y * side) })
            .collect();
        let area = swept_area_m2(&map, &path, width);
        let (length, turned) = (path_length(&path), turning(&path).0);
        prop_assert!(min_length_m(area, width, resolution) <= length + 1e-9,
            "length {length} < bound {}", min_length_m(area, width, resolution));
        let bound = min_turning_rad(area, width, resolution, free_diameter_m(&map));
        prop_assert!(bound <= turned + 1e-9, "turning {turned} < bound {bound}");
    }
}
