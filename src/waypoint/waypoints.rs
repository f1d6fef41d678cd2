//! Waypoint placement (000 §II-B.2, Fig. 3; waypoint §3, W3–W5): a grid at the grid step, occluded
//! points removed, points in the safety buffer nudged away from walls (or deleted where the UAV
//! cannot fit), crowded points merged into centroids, and space left without a waypoint filled
//! again, so that no corridor or room loses all its waypoints.

use crate::coverage::work_map::WorkMap;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Spacings of the placement, in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spacing {
    /// Grid step `g`.
    pub step: f64,
    /// Safety buffer `b`.
    pub buffer: f64,
    /// Anti-crowding distance: points closer than this are merged.
    pub merge: f64,
    /// Half the UAV width: the least clearance a waypoint may have.
    pub min_clearance: f64,
}

/// Places waypoints (px coordinates); also returns how many were added to fill gaps left by
/// nudging and merging (see [`fill_gaps`]).
pub fn place(map: &WorkMap, s: &Spacing) -> (Vec<(f64, f64)>, usize) {
    place_until(map, s, &|| false).expect("a placement that never gives up")
}

/// [`place`], giving up (`None`) when `give_up` says so: between its passes and within the
/// geodesic spreads of [`fill_gaps`], which take most of a second on a fine raster of a large map.
pub fn place_until(map: &WorkMap, s: &Spacing, give_up: &dyn Fn() -> bool) -> Option<(Vec<(f64, f64)>, usize)> {
    let (g, b, min_clearance) = (s.step, s.buffer, s.min_clearance);
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
    if give_up() {
        return None;
    }
    let pts: Vec<(f64, f64)> = pts.into_iter().filter_map(|p| nudge(map, p, g, b, min_clearance)).collect();
    if give_up() {
        return None;
    }
    let mut pts = merge_crowded(map, pts, s.merge, b);
    let added = fill_gaps(map, &mut pts, s, give_up)?;
    Some((pts, added))
}

/// Chamfer costs of a straight and a diagonal pixel step (5-7 chamfer: the geodesic distance in
/// pixels is the cost / 5, within 2 %).
const STEP_COST: [u32; 2] = [5, 7];

/// Pixels where the UAV's centre fits: free, with clearance at least `min_clearance` px.
pub fn fits_mask(map: &WorkMap, min_clearance: f64) -> Vec<bool> {
    (0..map.occluded.len()).map(|i| !map.occluded[i] && map.dist[i] >= min_clearance).collect()
}

/// How a step into pixel `j` is priced: by length, or (`centred`) by length times a factor
/// that grows as the clearance shrinks, so that paths keep to the middle of passages.
fn step_cost(map: &WorkMap, j: usize, diagonal: bool, centred: bool) -> u32 {
    let base = STEP_COST[usize::from(diagonal)];
    if centred { base * (1 + (32.0 / map.dist[j].max(1.0)).round() as u32) } else { base }
}

/// Spreads geodesic (chamfer) distances from `sources` (pixel indices) through the pixels
/// where the UAV fits, lowering `dist` wherever a source is nearer; `parent` (if given)
/// records each lowered pixel's predecessor (a source is its own). `centred` prices steps
/// near walls higher (see `step_cost`).
pub fn geodesic(
    map: &WorkMap,
    fits: &[bool],
    dist: &mut [u32],
    parent: Option<&mut [u32]>,
    sources: &[usize],
    centred: bool,
) {
    geodesic_until(map, fits, dist, parent, sources, centred, &|| false);
}

/// Pixels settled between two looks at a geodesic spread's `give_up` (a few milliseconds).
const PIXELS_PER_LOOK: u32 = 1 << 16;

/// [`geodesic`], asking `give_up` every [`PIXELS_PER_LOOK`] pixels; `false` when it gave up
/// (`dist` then holds a partial spread).
fn geodesic_until(
    map: &WorkMap,
    fits: &[bool],
    dist: &mut [u32],
    mut parent: Option<&mut [u32]>,
    sources: &[usize],
    centred: bool,
    give_up: &dyn Fn() -> bool,
) -> bool {
    let mut heap = BinaryHeap::new();
    for &s in sources {
        dist[s] = 0;
        if let Some(p) = parent.as_deref_mut() {
            p[s] = s as u32;
        }
        heap.push(Reverse((0u32, s)));
    }
    let (w, h) = (map.width as i64, map.height as i64);
    let mut settled = 0u32;
    while let Some(Reverse((d, i))) = heap.pop() {
        if d > dist[i] {
            continue;
        }
        settled = settled.wrapping_add(1);
        if settled.is_multiple_of(PIXELS_PER_LOOK) && give_up() {
            return false;
        }
        let (c, r) = ((i % map.width) as i64, (i / map.width) as i64);
        for (dc, dr) in [(-1, 0), (1, 0), (0, -1), (0, 1), (-1, -1), (1, -1), (-1, 1), (1, 1)] {
            let (nc, nr) = (c + dc, r + dr);
            if nc < 0 || nr < 0 || nc >= w || nr >= h {
                continue;
            }
            let j = (nr * w + nc) as usize;
            if !fits[j] {
                continue;
            }
            let nd = d.saturating_add(step_cost(map, j, dc != 0 && dr != 0, centred));
            if nd < dist[j] {
                dist[j] = nd;
                if let Some(p) = parent.as_deref_mut() {
                    p[j] = i as u32;
                }
                heap.push(Reverse((nd, j)));
            }
        }
    }
    true
}

/// The pixel index of a px-coordinate point, if it lies on the raster.
pub fn pixel_index(map: &WorkMap, p: (f64, f64)) -> Option<usize> {
    let (c, r) = map.pixel_of(p);
    (c >= 0 && r >= 0 && (c as usize) < map.width && (r as usize) < map.height)
        .then(|| map.index(c as usize, r as usize))
}

/// Adds waypoints where the space the UAV fits in lies farther than `g + b` (geodesic, through
/// that space) from every waypoint: a corridor or room whose waypoints were all nudged or
/// merged away gets one back, as does a region with none. The farthest pixel is served
/// first, by a waypoint nudged from it like a grid point (or the pixel itself when the nudge
/// would leave it unserved). Returns how many were added; `None` when `give_up` said so.
pub fn fill_gaps(map: &WorkMap, pts: &mut Vec<(f64, f64)>, s: &Spacing, give_up: &dyn Fn() -> bool) -> Option<usize> {
    let fits = fits_mask(map, s.min_clearance);
    let mut dist = vec![u32::MAX; fits.len()];
    let index = |p: (f64, f64)| pixel_index(map, p);
    let sources: Vec<usize> = pts.iter().filter_map(|&p| index(p)).filter(|&i| fits[i]).collect();
    if !geodesic_until(map, &fits, &mut dist, None, &sources, false, give_up) {
        return None;
    }
    let reach = ((s.step + s.buffer) * f64::from(STEP_COST[0])).ceil() as u32;
    let mut added = 0;
    loop {
        // The farthest pixel (lowest index on ties); unserved regions are at u32::MAX.
        let Some((far, &d)) =
            dist.iter().enumerate().filter(|&(i, _)| fits[i]).max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(&a.0)))
        else {
            return Some(added);
        };
        if d <= reach {
            return Some(added);
        }
        if give_up() {
            return None;
        }
        let pixel = ((far % map.width) as f64 + 0.5, (far / map.width) as f64 + 0.5);
        let nudged = nudge(map, pixel, s.step, s.buffer, s.min_clearance)
            .and_then(|p| index(p).filter(|&i| fits[i]).map(|i| (p, i)));
        let mut trial = dist.clone();
        let chosen = match nudged {
            Some((p, i)) => {
                if !geodesic_until(map, &fits, &mut trial, None, &[i], false, give_up) {
                    return None;
                }
                (trial[far] <= reach).then_some(p)
            }
            None => None,
        };
        match chosen {
            Some(p) => {
                dist = trial;
                pts.push(p);
            }
            None => {
                if !geodesic_until(map, &fits, &mut dist, None, &[far], false, give_up) {
                    return None;
                }
                pts.push(pixel);
            }
        }
        added += 1;
    }
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

/// Replaces every single-linkage cluster of points closer than `g` (the anti-crowding
/// distance) by its centroid (or its best-clearance member if the centroid is in the buffer
/// `b`), until no pair is closer (W4).
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
        let (pts, _) = place(&map, &Spacing { step: g, buffer: b, merge: g, min_clearance: 0.5 / 0.3 });
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

    #[test]
    fn a_corridor_emptied_by_merging_gets_a_waypoint_back() {
        // The office corridor runs at y 8.6-11.0 m = 57.3-73.3 px at 0.15 m/px.
        let map = WorkMap::new(&preset("office").unwrap(), 0.15);
        let s = Spacing { step: 8.0, buffer: 6.0, merge: 8.0, min_clearance: 0.25 / 0.15 };
        let in_corridor = |p: &(f64, f64)| (57.3..73.3).contains(&p.1);
        let (placed, _) = place(&map, &s);
        assert!(placed.iter().any(in_corridor));
        let mut pts: Vec<(f64, f64)> = placed.into_iter().filter(|p| !in_corridor(p)).collect();
        let before = pts.len();
        let added = fill_gaps(&map, &mut pts, &s, &|| false).unwrap();
        assert!(added >= 1);
        assert_eq!(pts.len(), before + added);
        let back: Vec<_> = pts[before..].iter().filter(|p| in_corridor(p)).collect();
        assert!(!back.is_empty(), "no waypoint returned to the corridor: {:?}", &pts[before..]);
        // Every point where the UAV fits is again within g + b (geodesic) of a waypoint.
        assert_eq!(fill_gaps(&map, &mut pts, &s, &|| false), Some(0));
    }
}
