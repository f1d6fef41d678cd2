//! The traversability graph (000 §II-D, waypoint §4, W6–W7): each waypoint links to its nearest
//! neighbour in each of the eight 45° octants (undirected union), then edges whose segment
//! touches an occluded pixel or that exceed the maximum traverse distance are removed, and only
//! the component(s) of the start waypoint(s) are kept.

use crate::coverage::work_map::WorkMap;

/// Waypoints and undirected edges (adjacency lists, sorted).
#[derive(Clone, Debug)]
pub struct Graph {
    /// Waypoint positions (px).
    pub points: Vec<(f64, f64)>,
    /// Sorted neighbour lists.
    pub adj: Vec<Vec<u32>>,
}

/// Octant `k = ⌊(atan2(dy, dx) mod 2π) / (π/4)⌋` of an offset.
pub fn octant(dx: f64, dy: f64) -> usize {
    let a = dy.atan2(dx).rem_euclid(std::f64::consts::TAU);
    ((a / std::f64::consts::FRAC_PI_4) as usize).min(7)
}

impl Graph {
    /// Builds the octant graph over `points`, pruning colliding edges and edges longer than
    /// `max_len` px.
    pub fn build(map: &WorkMap, points: Vec<(f64, f64)>, max_len: f64) -> Self {
        let n = points.len();
        let mut edges = std::collections::BTreeSet::new();
        for i in 0..n {
            let mut best: [Option<(f64, usize)>; 8] = [None; 8];
            for j in 0..n {
                if i == j {
                    continue;
                }
                let (dx, dy) = (points[j].0 - points[i].0, points[j].1 - points[i].1);
                let d = dx.hypot(dy);
                let k = octant(dx, dy);
                if best[k].is_none_or(|(bd, _)| d < bd) {
                    best[k] = Some((d, j));
                }
            }
            for (d, j) in best.into_iter().flatten() {
                if d <= max_len {
                    edges.insert((i.min(j), i.max(j)));
                }
            }
        }
        let mut adj = vec![Vec::new(); n];
        for (a, b) in edges {
            if !map.segment_hits(points[a], points[b]) {
                adj[a].push(b as u32);
                adj[b].push(a as u32);
            }
        }
        for l in &mut adj {
            l.sort_unstable();
        }
        Self { points, adj }
    }

    /// Waypoints reachable from `start`.
    pub fn component(&self, start: usize) -> Vec<bool> {
        let mut seen = vec![false; self.points.len()];
        let mut stack = vec![start];
        seen[start] = true;
        while let Some(i) = stack.pop() {
            for &j in &self.adj[i] {
                if !seen[j as usize] {
                    seen[j as usize] = true;
                    stack.push(j as usize);
                }
            }
        }
        seen
    }

    /// Keeps only the waypoints in `keep`, renumbering; returns the new graph and the old→new map.
    pub fn restrict(&self, keep: &[bool]) -> (Self, Vec<Option<u32>>) {
        let mut map = vec![None; self.points.len()];
        let mut points = Vec::new();
        for (i, &k) in keep.iter().enumerate() {
            if k {
                map[i] = Some(points.len() as u32);
                points.push(self.points[i]);
            }
        }
        let adj = (0..self.points.len())
            .filter(|&i| keep[i])
            .map(|i| self.adj[i].iter().filter_map(|&j| map[j as usize]).collect())
            .collect();
        (Self { points, adj }, map)
    }

    /// The waypoint nearest to `p` (px), lowest id on ties.
    pub fn nearest(&self, p: (f64, f64)) -> usize {
        let mut best = (f64::INFINITY, 0);
        for (i, q) in self.points.iter().enumerate() {
            let d = (q.0 - p.0).hypot(q.1 - p.1);
            if d < best.0 {
                best = (d, i);
            }
        }
        best.1
    }

    /// Number of undirected edges.
    pub fn edge_count(&self) -> usize {
        self.adj.iter().map(Vec::len).sum::<usize>() / 2
    }

    /// Whether `a`–`b` is an edge.
    pub fn has_edge(&self, a: usize, b: usize) -> bool {
        self.adj[a].binary_search(&(b as u32)).is_ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::presets::preset;

    #[test]
    fn octants_are_45_degree_sectors() {
        assert_eq!(octant(1.0, 0.0), 0);
        assert_eq!(octant(1.0, 1.01), 1);
        assert_eq!(octant(-1.0, 0.1), 3);
        assert_eq!(octant(0.0, -1.0), 6);
        assert_eq!(octant(1.0, -0.1), 7);
    }

    #[test]
    fn no_edge_crosses_an_obstacle() {
        let map = WorkMap::new(&preset("office").unwrap(), 0.15);
        let spacing = super::super::waypoints::Spacing { step: 5.0, buffer: 2.0, merge: 5.0, min_clearance: 1.67 };
        let (pts, _) = super::super::waypoints::place(&map, &spacing);
        let g = Graph::build(&map, pts, 4.0 / 0.15);
        assert!(g.edge_count() > g.points.len());
        for (i, l) in g.adj.iter().enumerate() {
            for &j in l {
                let (a, b) = (g.points[i], g.points[j as usize]);
                // Dense sampling of the segment never meets an occluded pixel.
                for k in 0..=200 {
                    let t = k as f64 / 200.0;
                    let p = (a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t);
                    assert!(map.clearance(p) > 0.0, "edge {i}-{j} crosses an obstacle at {p:?}");
                }
                assert!((a.0 - b.0).hypot(a.1 - b.1) <= 4.0 / 0.15 + 1e-9);
            }
        }
        // The office is one connected building.
        let start = g.nearest((10.0, 10.0));
        let comp = g.component(start);
        assert!(comp.iter().filter(|c| **c).count() * 100 >= g.points.len() * 95);
    }
}
