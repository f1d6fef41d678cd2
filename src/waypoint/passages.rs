//! Waypoints in narrow passages. The safety buffer pushes waypoints out of doors and other
//! openings narrower than twice the buffer, and the octant graph (000 §II-D) then often has no
//! collision-free edge through them: a room the UAV fits into silently drops out of the
//! graph. This step finds each waypoint the UAV could reach through free space but the graph
//! does not, and adds a waypoint where the connecting passage is narrowest, then along the
//! passage, until the graph reaches it or both fail.

use super::graph::Graph;
use super::waypoints::{fits_mask, geodesic, pixel_index};
use crate::coverage::work_map::WorkMap;

/// At most this many passage waypoints are added to one map.
const MAX_ADDED: usize = 512;

/// Builds the graph over `pts` (px) with edges up to `max_len` px, adding passage waypoints
/// (on a second attempt, one every `step` px along the passage) until every waypoint connected to the
/// start `start` through space where the UAV fits (`min_clearance` px) is in the start's graph
/// component. Returns the graph and the number of waypoints added.
pub fn connect(
    map: &WorkMap,
    mut pts: Vec<(f64, f64)>,
    start: (f64, f64),
    max_len: f64,
    step: f64,
    min_clearance: f64,
) -> (Graph, usize) {
    let fits = fits_mask(map, min_clearance);
    let mut tries: std::collections::BTreeMap<usize, u8> = Default::default();
    let mut added = 0;
    loop {
        let graph = Graph::build(map, pts.clone(), max_len);
        if added >= MAX_ADDED || pts.is_empty() {
            return (graph, added);
        }
        let reached = graph.component(graph.nearest(start));
        let on_raster = |i: usize| pixel_index(map, pts[i]).filter(|&p| fits[p]);
        let sources: Vec<usize> = (0..pts.len()).filter(|&i| reached[i]).filter_map(on_raster).collect();
        let mut dist = vec![u32::MAX; fits.len()];
        let mut parent = vec![u32::MAX; fits.len()];
        geodesic(map, &fits, &mut dist, Some(&mut parent), &sources, true);
        // The unreached waypoint nearest to the graph through free space (not yet given up).
        let target = (0..pts.len())
            .filter(|&i| !reached[i])
            .filter_map(|i| on_raster(i).map(|p| (dist[p], p)))
            .filter(|&(d, p)| d < u32::MAX && tries.get(&p).is_none_or(|&t| t < 2))
            .min();
        let Some((_, target)) = target else { return (graph, added) };
        let mut path = vec![target];
        while parent[*path.last().expect("non-empty")] as usize != *path.last().expect("non-empty") {
            path.push(parent[*path.last().expect("non-empty")] as usize);
        }
        let attempt = tries.entry(target).or_insert(0);
        *attempt += 1;
        let centre = |p: usize| ((p % map.width) as f64 + 0.5, (p / map.width) as f64 + 0.5);
        if *attempt == 1 {
            // The throat: the path's pixel of least clearance between its ends (first on ties).
            let inner = if path.len() > 2 { &path[1..path.len() - 1] } else { &path[..] };
            let throat = inner.iter().copied().min_by(|&a, &b| map.dist[a].total_cmp(&map.dist[b])).expect("non-empty");
            pts.push(centre(throat));
            added += 1;
        } else {
            // Along the whole passage, one waypoint per `step` pixels of path.
            let every = (step.round() as usize).max(1);
            for &p in path.iter().skip(every).step_by(every).filter(|&&p| dist[p] > 0) {
                pts.push(centre(p));
                added += 1;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point;
    use crate::map::{CellState, GridMap};

    /// Two 6 m × 6 m rooms joined by a 1 m door in a 0.3 m wall, at 0.1 m/px.
    fn two_rooms() -> WorkMap {
        let (cols, rows) = (130, 60);
        let mut cells = vec![CellState::Free; cols * rows];
        for r in 0..rows {
            for c in 60..63 {
                if !(25..35).contains(&r) {
                    cells[r * cols + c] = CellState::Occupied;
                }
            }
        }
        let map = GridMap::new("two-rooms", cols, rows, 0.1, Point::origin(), cells).unwrap();
        WorkMap::new(&map, 0.1)
    }

    #[test]
    fn a_door_narrower_than_the_buffer_gets_a_waypoint() {
        let map = two_rooms();
        // One waypoint in each room, far from the door and out of each other's sight.
        let pts = vec![(20.5, 45.5), (110.5, 45.5)];
        let plain = Graph::build(&map, pts.clone(), 200.0);
        assert!(!plain.component(0)[1], "the straight edge crosses the wall");
        let (graph, added) = connect(&map, pts, (20.5, 45.5), 200.0, 10.0, 2.5);
        assert!(added >= 1);
        assert!(graph.component(0).iter().all(|r| *r), "both rooms reached");
        // The first added waypoint lies in the door (x 60–63 px, y 25–35 px), at most a pixel
        // outside its opening.
        let (x, y) = graph.points[2];
        assert!((59.0..64.0).contains(&x) && (27.0..33.0).contains(&y), "{x} {y}");
    }

    #[test]
    fn a_closed_room_stays_out() {
        let map = two_rooms();
        // A wall with no door: the second room cannot be reached through free space.
        let mut closed = map.clone();
        for r in 25..35 {
            for c in 60..63 {
                let i = closed.index(c, r);
                closed.occluded[i] = true;
            }
        }
        closed.dist = crate::coverage::work_map::distance_transform(closed.width, closed.height, &closed.occluded);
        let (graph, added) = connect(&closed, vec![(20.5, 45.5), (110.5, 45.5)], (20.5, 45.5), 200.0, 10.0, 2.5);
        assert_eq!(added, 0);
        assert!(!graph.component(0)[1]);
    }
}
