use super::*;
use crate::map::presets::preset;

fn pts(v: &[(f64, f64)]) -> Vec<Point> {
    v.iter().map(|&(x, y)| Point::new(x, y)).collect()
}

/// Map 1 is a 45 × 45-cell room inside walls 1 m thick (0.2 m cells): free x, y in [1, 10].
#[test]
fn the_body_is_checked_at_vertices_turns_and_end_caps() {
    let m = preset("thesis-1").unwrap();
    // (path, width, touches a wall)
    type Case = (&'static [(f64, f64)], f64, bool);
    let cases: &[Case] = &[
        // A lane half a width off the wall: exactly at the clearance, executable.
        (&[(1.3, 5.0), (5.0, 5.0)], 0.6, false),
        // The reversal of the reproduction: the segment's rectangle stays off the wall,
        // but the body at the vertex x = 0.91 reaches x = 0.61.
        (&[(5.0, 5.0), (0.91, 5.0), (5.0, 5.0)], 0.6, true),
        // An end cap: the path stops 0.2 m from the wall's face.
        (&[(5.0, 5.0), (5.0, 9.8)], 0.6, true),
        // A turn in a corner, half a width from both walls: the disc keeps 0.42 m from the
        // corner cell, so turning there is executable (a square body would not be).
        (&[(5.0, 1.3), (9.7, 1.3), (9.7, 5.0)], 0.6, false),
        // One point: the disc standing there.
        (&[(1.29, 5.0)], 0.6, true),
        (&[(1.31, 5.0)], 0.6, false),
        // A narrower robot fits where a wider one does not.
        (&[(1.11, 5.0), (1.11, 8.0)], 0.2, false),
        (&[(1.11, 5.0), (1.11, 8.0)], 0.3, true),
        // A diagonal that crosses the wall band.
        (&[(5.0, 5.0), (0.5, 0.5)], 0.1, true),
    ];
    for &(path, width, touches) in cases {
        let (cells, off) = touched_cells(&m, &pts(path), width);
        assert_eq!(!cells.is_empty(), touches, "{path:?} width {width}: {cells:?}");
        assert!(!off, "{path:?}");
    }
}

#[test]
fn the_body_past_the_map_s_edge_is_off_the_map() {
    let m = preset("thesis-1").unwrap();
    let (_, off) = touched_cells(&m, &pts(&[(0.2, 5.0), (0.2, 6.0)]), 0.6);
    assert!(off);
    let (_, off) = touched_cells(&m, &pts(&[(0.3, 5.0), (0.3, 6.0)]), 0.6);
    assert!(!off, "half a width from the edge is on the map");
    let c = contact(&m, &[pts(&[(5.0, 5.0), (5.0, 6.0)]), pts(&[(11.5, 5.0)])], &[0.6, 0.6]);
    assert!(c.off_map && !c.is_clear());
}

#[test]
fn distinct_cells_are_counted_once_over_paths_and_segments() {
    let m = preset("thesis-1").unwrap();
    let path = pts(&[(5.0, 5.0), (0.91, 5.0), (5.0, 5.0)]);
    let (cells, _) = touched_cells(&m, &path, 0.6);
    let twice = contact(&m, &[path.clone(), path], &[0.6, 0.6]);
    assert_eq!(twice.wall_cells, cells.len() as u64);
    // The disc of radius 0.3 at x = 0.91 reaches the wall column x in [0.8, 1.0) over the rows
    // within 0.3 m: the cells whose square is nearer than 0.3 to (0.91, 5).
    assert!(cells.len() >= 3 && cells.len() <= 8, "{}", cells.len());
}

/// The slack is the planners' sampling error: 4.2 mm for a 0.6 m robot on 0.2 m cells, under
/// 0.3 mm on 0.05 m cells; never more than half the radius.
#[test]
fn the_contact_slack_is_the_sampling_error() {
    assert!((contact_slack(0.2, 0.3) - (0.3 - (0.09f64 - 0.0025).sqrt())).abs() < 1e-15);
    assert!(contact_slack(0.2, 0.3) < 0.0043 && contact_slack(0.05, 0.3) < 0.0003);
    assert_eq!(contact_slack(1.0, 0.1), 0.05);
}

#[test]
fn segment_box_distance_by_hand() {
    let (lo, hi) = (Point::new(0.0, 0.0), Point::new(1.0, 1.0));
    let d2 = |a: (f64, f64), b: (f64, f64)| segment_box_d2(Point::new(a.0, a.1), Point::new(b.0, b.1), lo, hi);
    assert_eq!(d2((-1.0, 0.5), (2.0, 0.5)), 0.0);
    assert_eq!(d2((2.0, 0.0), (2.0, 1.0)), 1.0);
    assert!((d2((2.0, 2.0), (3.0, 3.0)) - 2.0).abs() < 1e-12);
    // A segment passing a corner diagonally: nearest at the corner.
    assert!((d2((2.0, 1.0), (1.0, 2.0)) - 0.5).abs() < 1e-12);
    assert!((d2((0.5, 0.5), (0.5, 0.5)) - 0.0).abs() < 1e-12);
}

/// Brute force: the least distance from any sampled body centre along the path to any non-free
/// cell square of the whole map, and to the map's edge.
fn brute_min_clearance(m: &GridMap, path: &[Point], step: f64) -> (f64, f64) {
    let mut centres = vec![path[0]];
    for w in path.windows(2) {
        let n = ((w[1] - w[0]).norm() / step).ceil().max(1.0) as usize;
        centres.extend((1..=n).map(|i| w[0] + (w[1] - w[0]) * (i as f64 / n as f64)));
    }
    let (o, res) = (m.origin(), m.resolution());
    let (mut least, mut least_edge) = (f64::INFINITY, f64::INFINITY);
    for p in centres {
        let edge = (p.x - o.x).min(p.y - o.y).min(o.x + m.width_m() - p.x).min(o.y + m.height_m() - p.y);
        least_edge = least_edge.min(edge);
        for r in 0..m.rows() {
            for c in 0..m.cols() {
                if m.is_free(r, c) {
                    continue;
                }
                let lo = Point::new(o.x + c as f64 * res, o.y + r as f64 * res);
                let hi = Point::new(lo.x + res, lo.y + res);
                least = least.min(point_box_d2(p, lo, hi).sqrt());
            }
        }
    }
    (least, least_edge)
}

proptest::proptest! {
    /// A random path on a random small map is clear iff no body pose along it (sampled every
    /// millimetre) comes nearer than the radius less the contact slack to a non-free cell, or
    /// nearer than the radius to the edge; paths whose least clearance lies within the
    /// sampling's error of either limit are left out.
    #[test]
    fn clear_iff_no_sampled_pose_touches_a_non_free_cell(
        cells in proptest::collection::vec(0u8..30, 12 * 10),
        xs in proptest::collection::vec((0.0f64..2.4, 0.0f64..2.0), 1..5),
        width in 0.02f64..0.4,
    ) {
        use crate::map::CellState;
        let states = cells.iter().map(|&v| match v { 0 => CellState::Occupied, 1 => CellState::Unknown, _ => CellState::Free }).collect();
        let m = GridMap::new("random", 12, 10, 0.2, Point::origin(), states).unwrap();
        let path: Vec<Point> = xs.iter().map(|&(x, y)| Point::new(x, y)).collect();
        let step = 1e-3;
        let (least, least_edge) = brute_min_clearance(&m, &path, step);
        let radius = 0.5 * width;
        let lim = radius - contact_slack(m.resolution(), radius);
        proptest::prop_assume!((least - lim).abs() > step && (least_edge - radius).abs() > step);
        let (cells, off) = touched_cells(&m, &path, width);
        proptest::prop_assert_eq!(cells.is_empty(), least >= lim, "least clearance {} limit {} cells {:?}", least, lim, cells);
        proptest::prop_assert_eq!(off, least_edge < radius, "least edge distance {} radius {}", least_edge, radius);
    }
}
