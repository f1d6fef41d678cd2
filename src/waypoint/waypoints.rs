//! Waypoint placement (000 §II-B.2, Fig. 3; spec §3, W3–W5): a grid at half the narrowest
//! hallway, occluded points removed, points in the safety buffer nudged away from walls (or
//! deleted where the UAV cannot fit), crowded points merged into centroids, and optionally only
//! the points near walls kept.

use super::raster::WorkMap;

/// Places waypoints (px coordinates). `g` is the grid spacing and `b` the safety buffer (px);
/// `min_clearance` is half the UAV width (px).
pub fn place(map: &WorkMap, g: f64, b: f64, min_clearance: f64) -> Vec<(f64, f64)> {
    let mut pts = Vec::new();
    let mut j = 0;
    while (j as f64 + 0.5) * g < map.height as f64 {
        let mut i = 0;
        while (i as f64 + 0.5) * g < map.width as f64 {
            let p = ((i as f64 + 0.5) * g, (j as f64 + 0.5) * g);
            if map.clearance(p) > 0.0 {
                pts.push(p);
            }
            i += 1;
        }
        j += 1;
    }
    let pts: Vec<(f64, f64)> = pts.into_iter().filter_map(|p| nudge(map, p, g, b, min_clearance)).collect();
    merge_crowded(map, pts, g, b)
}

/// The nearest occluded pixel centre to `p` (searching a growing window).
fn nearest_occluded(map: &WorkMap, p: (f64, f64)) -> (f64, f64) {
    let (pc, pr) = map.pixel_of(p);
    let mut best = (f64::INFINITY, (p.0, p.1));
    let reach = (map.clearance(p).ceil() as i64 + 2).max(2);
    for r in pr - reach..=pr + reach {
        for c in pc - reach..=pc + reach {
            if map.is_occluded(c, r) {
                let q = (c as f64 + 0.5, r as f64 + 0.5);
                let d = (q.0 - p.0).hypot(q.1 - p.1);
                if d < best.0 {
                    best = (d, q);
                }
            }
        }
    }
    best.1
}

/// Moves a point in the buffer away from the nearest wall (W3); `None` where the UAV cannot fit.
fn nudge(map: &WorkMap, p0: (f64, f64), g: f64, b: f64, min_clearance: f64) -> Option<(f64, f64)> {
    let mut p = p0;
    for _ in 0..5 {
        if map.clearance(p) >= b {
            return Some(p);
        }
        let q = nearest_occluded(map, p);
        let (dx, dy) = (p.0 - q.0, p.1 - q.1);
        let n = dx.hypot(dy).max(1e-9);
        p = (q.0 + (b + 0.5) * dx / n, q.1 + (b + 0.5) * dy / n);
    }
    if map.clearance(p) >= b {
        return Some(p);
    }
    // Fall back to the pixel of largest clearance within g of the original point.
    let (pc, pr) = map.pixel_of(p0);
    let reach = g.ceil() as i64;
    let mut best = (0.0, p0);
    for r in pr - reach..=pr + reach {
        for c in pc - reach..=pc + reach {
            let q = (c as f64 + 0.5, r as f64 + 0.5);
            if (q.0 - p0.0).hypot(q.1 - p0.1) <= g && map.clearance(q) > best.0 {
                best = (map.clearance(q), q);
            }
        }
    }
    (best.0 >= min_clearance).then_some(best.1)
}

/// Replaces every single-linkage cluster of points closer than `g` by its centroid (or its
/// best-clearance member if the centroid is in the buffer), until no pair is closer (W4).
pub fn merge_crowded(map: &WorkMap, mut pts: Vec<(f64, f64)>, g: f64, b: f64) -> Vec<(f64, f64)> {
    for _ in 0..10 {
        let n = pts.len();
        let mut parent: Vec<usize> = (0..n).collect();
        fn find(p: &mut [usize], i: usize) -> usize {
            let mut r = i;
            while p[r] != r {
                r = p[r];
            }
            let mut k = i;
            while p[k] != r {
                let next = p[k];
                p[k] = r;
                k = next;
            }
            r
        }
        let mut merged_any = false;
        for i in 0..n {
            for j in i + 1..n {
                if (pts[i].0 - pts[j].0).hypot(pts[i].1 - pts[j].1) < g - 1e-9 {
                    let (a, c) = (find(&mut parent, i), find(&mut parent, j));
                    if a != c {
                        parent[a.max(c)] = a.min(c);
                        merged_any = true;
                    }
                }
            }
        }
        if !merged_any {
            break;
        }
        let mut clusters: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
        for i in 0..n {
            let r = find(&mut parent, i);
            clusters.entry(r).or_default().push(i);
        }
        pts = clusters
            .values()
            .map(|members| {
                if members.len() == 1 {
                    return pts[members[0]];
                }
                let k = members.len() as f64;
                let c = (
                    members.iter().map(|&i| pts[i].0).sum::<f64>() / k,
                    members.iter().map(|&i| pts[i].1).sum::<f64>() / k,
                );
                if map.clearance(c) >= b {
                    c
                } else {
                    let best = members
                        .iter()
                        .copied()
                        .max_by(|&x, &y| map.clearance(pts[x]).total_cmp(&map.clearance(pts[y])))
                        .expect("non-empty");
                    pts[best]
                }
            })
            .collect();
    }
    pts
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::presets::preset;

    #[test]
    fn waypoints_keep_spacing_and_clearance() {
        let map = WorkMap::new(&preset("office").unwrap(), 0.15);
        let (g, b) = (5.0, 2.0);
        let pts = place(&map, g, b, 0.5 / 0.3);
        assert!(pts.len() > 300, "{}", pts.len());
        for (i, p) in pts.iter().enumerate() {
            assert!(map.clearance(*p) >= 0.5 / 0.3, "clearance at {p:?}");
            for q in &pts[i + 1..] {
                assert!((p.0 - q.0).hypot(p.1 - q.1) >= g - 1e-6, "{p:?} {q:?} closer than g");
            }
        }
        // Most points keep the full buffer.
        let inside = pts.iter().filter(|p| map.clearance(**p) >= b).count();
        assert!(inside * 10 >= pts.len() * 9);
    }
}
