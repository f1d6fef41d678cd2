//! Tests of routed moves.

use super::*;
use crate::coverage::CoverageGrid;
use crate::map::presets::preset;
use crate::map::{CellState, GridMap};

fn layers(map: &GridMap) -> BitLayers {
    BitLayers::new(&CoverageGrid::new(map))
}

/// Random places the robot stands on `map`, seeded.
fn standing_points(router: &Router, map: &GridMap, seed: u64) -> impl FnMut() -> Point {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let (w, h, o) = (map.width_m(), map.height_m(), map.origin());
    let router = router.clone();
    move || {
        loop {
            let p = Point::new(o.x + rng.random_range(0.0..w), o.y + rng.random_range(0.0..h));
            if router.can_stand(p) {
                return p;
            }
        }
    }
}

#[test]
fn a_segment_is_clear_exactly_when_the_body_rule_finds_it_clear() {
    for name in ["office", "thesis-2"] {
        let map = preset(name).unwrap();
        let router = Router::new(&map, 0.6, &[Point::new(2.0, 2.0)]);
        let mut stand = standing_points(&router, &map, 11);
        let (mut clear, mut blocked) = (0, 0);
        for _ in 0..3000 {
            let (p, q) = (stand(), stand());
            let rule = crate::map::body::touched_cells(&map, &[p, q], 0.6).0.is_empty();
            assert_eq!(router.segment_clear(p, q), rule, "{name}: {p:?} → {q:?}");
            if rule { clear += 1 } else { blocked += 1 }
        }
        assert!(clear > 100 && blocked > 100, "{name}: {clear} clear, {blocked} blocked");
    }
}

#[test]
fn every_route_between_places_to_stand_passes_the_body_rule() {
    // Short moves near walls, where a route joins the grid beside the wall, as well as long ones.
    for name in ["office", "office-ring", "thesis-2"] {
        let map = preset(name).unwrap();
        let router = Router::new(&map, 0.6, &[Point::new(2.0, 2.0)]);
        let mut stand = standing_points(&router, &map, 5);
        let mut scratch = RouteScratch::default();
        for k in 0..1500 {
            let p = stand();
            let q = if k % 2 == 0 { stand() } else { p + (stand() - p) * 0.05 };
            let route = router.route(p, q, &mut scratch);
            let mut path = vec![route.start];
            path.extend_from_slice(route.points);
            let (cells, off_map) = crate::map::body::touched_cells(&map, &path, 0.6);
            assert!(cells.is_empty() && !off_map, "{name}: {p:?} → {q:?} touches {cells:?}");
        }
    }
}

#[test]
fn a_move_through_the_disc_goes_around_it_and_sweeps_no_obstacle() {
    let map = preset("thesis-2").unwrap();
    let (router, bits) = (Router::new(&map, 0.6, &[Point::new(1.3, 1.3)]), layers(&map));
    let (a, b) = (Point::new(2.0, 5.5), Point::new(9.0, 5.5));
    assert!(bits.obstacle_cells(a, b, 0.6) > 0);
    let mut scratch = RouteScratch::default();
    let route = router.route(a, b, &mut scratch);
    assert_eq!((route.start, *route.points.last().unwrap()), (a, b));
    assert!(route.points.len() >= 2, "a detour, not the straight segment");
    let mut prev = route.start;
    let mut length = 0.0;
    for &p in route.points {
        assert_eq!(bits.obstacle_cells(prev, p, 0.6), 0, "{prev:?} → {p:?}");
        length += (p - prev).norm();
        prev = p;
    }
    // Around a 2 m disc with 0.3 m clearance: longer than 7 m, far shorter than the way
    // round the map.
    assert!(length > 7.0 && length < 10.0, "{length}");
    // The cache returns the same route.
    let again: Vec<Point> = router.route(a, b, &mut scratch).points.to_vec();
    assert_eq!(scratch.searches(), 1);
    let fresh = router.route(a, b, &mut RouteScratch::default()).points.to_vec();
    assert_eq!(again, fresh);
}

#[test]
fn a_clear_move_is_the_straight_segment() {
    let map = preset("thesis-2").unwrap();
    let router = Router::new(&map, 0.6, &[Point::new(1.3, 1.3)]);
    let (a, b) = (Point::new(1.5, 1.5), Point::new(8.5, 1.5));
    let mut scratch = RouteScratch::default();
    assert_eq!(router.route(a, b, &mut scratch), MoveRoute { start: a, points: &[b] });
}

#[test]
fn targets_in_walls_and_closed_rooms_are_replaced_by_reachable_places() {
    // Two rooms of 4 m at 0.1 m with a closed wall between them (x in [4, 4.2)).
    let (cols, rows) = (84, 40);
    let cells: Vec<CellState> = (0..rows * cols)
        .map(|i| if (40..42).contains(&(i % cols)) { CellState::Occupied } else { CellState::Free })
        .collect();
    let map = GridMap::new("two-rooms", cols, rows, 0.1, Point::origin(), cells).unwrap();
    let (router, bits) = (Router::new(&map, 0.6, &[Point::new(1.0, 1.0)]), layers(&map));
    let wall = Point::new(4.1, 2.0);
    let closed = Point::new(6.0, 2.0);
    for p in [wall, closed] {
        let q = router.position(p);
        assert!(router.can_stand(q), "{p:?} → {q:?}");
        assert!(q.x < 4.0 - 0.3 + 1e-9, "{q:?} is on the stations' side");
    }
    let mut scratch = RouteScratch::default();
    let route = router.route(Point::new(1.0, 2.0), closed, &mut scratch);
    let mut prev = route.start;
    for &p in route.points {
        assert_eq!(bits.obstacle_cells(prev, p, 0.6), 0);
        prev = p;
    }
    assert_eq!(prev, router.position(closed));
}

#[test]
fn on_a_map_without_obstacles_every_move_is_straight_between_places_the_body_fits() {
    let map = GridMap::new("open", 40, 30, 0.2, Point::origin(), vec![CellState::Free; 1200]).unwrap();
    let router = Router::new(&map, 0.6, &[Point::new(1.0, 1.0)]);
    let mut scratch = RouteScratch::default();
    // Where the body fits at both ends: the straight move itself.
    for (a, b) in [((0.3, 0.3), (7.7, 5.7)), ((0.35, 5.6), (7.65, 0.4)), ((4.0, 3.0), (4.0, 3.0))] {
        let (a, b) = (Point::new(a.0, a.1), Point::new(b.0, b.1));
        assert_eq!(router.route(a, b, &mut scratch), MoveRoute { start: a, points: &[b] });
    }
    // A viewpoint past the reach of the body (on the map's edge) is driven to the nearest
    // place it fits, then straight.
    let (a, b) = (Point::new(0.0, 0.0), Point::new(8.0, 6.0));
    let (pa, pb) = (router.position(a), router.position(b));
    assert!(pa != a && pb != b && router.can_stand(pa) && router.can_stand(pb));
    assert_eq!(router.route(a, b, &mut scratch), MoveRoute { start: pa, points: &[pb] });
}
