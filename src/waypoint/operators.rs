//! Path operators of the waypoint GA (000 §II-D, §III-A.2–3; waypoint §8, §11): forward-biased
//! random extension with short-term memory, crossover at a common waypoint, length repair,
//! mutation A (tail regeneration) and mutation B (shortcuts).

use super::graph::Graph;
use crate::coverage::camera::wrap;
use rand::Rng;

/// Operator parameters (Table I, waypoint §18–19).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OperatorParams {
    /// `λ`, log-scale turning weight.
    pub lambda: f64,
    /// `M`, path memory (waypoints).
    pub memory: usize,
    /// `l_min`.
    pub l_min: usize,
    /// `l_max`.
    pub l_max: usize,
    /// `T_x`, crossover threshold (waypoints).
    pub crossover_threshold: usize,
    /// `n_B`, mutation B instances.
    pub b_instances: usize,
    /// `D`, mutation B search distance (waypoints).
    pub b_distance: usize,
    /// `p_acc`, mutation B acceptance probability.
    pub b_accept: f64,
}

fn heading(g: &Graph, a: u32, b: u32) -> f64 {
    let (p, q) = (g.points[a as usize], g.points[b as usize]);
    (q.1 - p.1).atan2(q.0 - p.0)
}

/// Forward-bias weight `10^(−λ·|Δψ|/π)` of a turn (W14).
pub fn forward_weight(lambda: f64, turn: f64) -> f64 {
    10f64.powf(-lambda * wrap(turn).abs() / std::f64::consts::PI)
}

/// Extends `path` with random feasible moves up to `target` waypoints (waypoint §8): neighbours
/// not among the last `M` waypoints (unless none is left), weighted towards going straight.
pub fn extend_random<R: Rng + ?Sized>(path: &mut Vec<u32>, target: usize, g: &Graph, p: &OperatorParams, rng: &mut R) {
    let mut weights = Vec::with_capacity(8);
    let mut allowed: Vec<u32> = Vec::with_capacity(8);
    while path.len() < target {
        let cur = *path.last().expect("a path has a start");
        let cand = &g.adj[cur as usize];
        if cand.is_empty() {
            return;
        }
        let recent = &path[path.len().saturating_sub(p.memory)..];
        allowed.clear();
        allowed.extend(cand.iter().copied().filter(|c| !recent.contains(c)));
        if allowed.is_empty() {
            allowed.extend_from_slice(cand);
        }
        weights.clear();
        if path.len() >= 2 {
            let h = heading(g, path[path.len() - 2], cur);
            weights.extend(allowed.iter().map(|&j| forward_weight(p.lambda, heading(g, cur, j) - h)));
        } else {
            weights.extend(allowed.iter().map(|_| 1.0));
        }
        let total: f64 = weights.iter().sum();
        let mut x = rng.random::<f64>() * total;
        let mut pick = allowed[allowed.len() - 1];
        for (k, w) in weights.iter().enumerate() {
            if x < *w {
                pick = allowed[k];
                break;
            }
            x -= w;
        }
        path.push(pick);
    }
}

/// Crossover at a common waypoint (waypoint §11.1): positions `a ≥ 1`, `b ≥ 1` with
/// `P1[a] = P2[b]` and `|a − b| ≤ T_x`, one pair drawn uniformly; `None` when there is none.
pub fn crossover<R: Rng + ?Sized>(
    p1: &[u32],
    p2: &[u32],
    threshold: usize,
    rng: &mut R,
) -> Option<(Vec<u32>, Vec<u32>)> {
    let mut pairs = Vec::new();
    for (a, &x) in p1.iter().enumerate().skip(1) {
        let lo = a.saturating_sub(threshold).max(1);
        let hi = (a + threshold).min(p2.len().saturating_sub(1));
        pairs.extend((lo..=hi).filter(|&b| b < p2.len() && p2[b] == x).map(|b| (a, b)));
    }
    if pairs.is_empty() {
        return None;
    }
    let (a, b) = pairs[rng.random_range(0..pairs.len())];
    let c1 = p1[..=a].iter().chain(&p2[b + 1..]).copied().collect();
    let c2 = p2[..=b].iter().chain(&p1[a + 1..]).copied().collect();
    Some((c1, c2))
}

/// Length repair (waypoint §11.2): truncate to `l_max`, extend randomly to `l_min`.
pub fn repair<R: Rng + ?Sized>(path: &mut Vec<u32>, g: &Graph, p: &OperatorParams, rng: &mut R) {
    path.truncate(p.l_max);
    if path.len() < p.l_min {
        extend_random(path, p.l_min, g, p, rng);
    }
}

/// Mutation A (waypoint §11.3): keep `path[..=k]` for a uniform `k ≥ 1` and regrow the tail to a
/// uniform length in `[len, l_max]`.
pub fn mutation_a<R: Rng + ?Sized>(path: &mut Vec<u32>, g: &Graph, p: &OperatorParams, rng: &mut R) {
    let len = path.len();
    if len < 2 {
        return;
    }
    let k = rng.random_range(1..len);
    let target = rng.random_range(len..=p.l_max.max(len));
    path.truncate(k + 1);
    extend_random(path, target, g, p, rng);
}

/// Hop distance 0, 1 or 2 between two waypoints, with the best intermediate for 2 (the one
/// minimising `|p_a − p_m| + |p_m − p_b|`); `None` beyond two hops.
pub fn short_hop(g: &Graph, a: u32, b: u32) -> Option<(usize, Option<u32>)> {
    if a == b {
        return Some((0, None));
    }
    if g.has_edge(a as usize, b as usize) {
        return Some((1, None));
    }
    let (pa, pb) = (g.points[a as usize], g.points[b as usize]);
    let cost = |m: u32| {
        let pm = g.points[m as usize];
        (pa.0 - pm.0).hypot(pa.1 - pm.1) + (pm.0 - pb.0).hypot(pm.1 - pb.1)
    };
    g.adj[a as usize]
        .iter()
        .copied()
        .filter(|&m| g.has_edge(m as usize, b as usize))
        .min_by(|&x, &y| cost(x).total_cmp(&cost(y)))
        .map(|m| (2, Some(m)))
}

/// Mutation B (waypoint §11.4, W18): `n_B` instances, each looking in a random window of `D + 1`
/// waypoints for the farthest point reachable from its start in at most two hops by a strictly
/// shorter route, and taking that shortcut with probability `p_acc` (never below `l_min`).
pub fn mutation_b<R: Rng + ?Sized>(path: &mut Vec<u32>, g: &Graph, p: &OperatorParams, rng: &mut R) {
    let d = p.b_distance;
    for _ in 0..p.b_instances {
        if path.len() < d + 1 {
            break;
        }
        let s = rng.random_range(0..=path.len() - 1 - d);
        for j in (s + 2..=s + d).rev() {
            let Some((h, mid)) = short_hop(g, path[s], path[j]) else { continue };
            let removed = j - s - 1;
            if removed <= h.saturating_sub(1) {
                continue;
            }
            let new_len = match h {
                0 => path.len() - removed - 1,
                _ => path.len() - removed + h - 1,
            };
            if rng.random_bool(p.b_accept) && new_len >= p.l_min {
                match (h, mid) {
                    (0, _) => {
                        path.drain(s + 1..=j);
                    }
                    (2, Some(m)) => {
                        path.splice(s + 1..j, [m]);
                    }
                    _ => {
                        path.drain(s + 1..j);
                    }
                }
            }
            break;
        }
    }
}

/// Whether every consecutive pair of `path` is a graph edge.
pub fn is_feasible(path: &[u32], g: &Graph) -> bool {
    path.windows(2).all(|w| g.has_edge(w[0] as usize, w[1] as usize))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ga::rng::{Purpose, stream};
    use proptest::prelude::*;

    /// A 6 x 6 lattice graph (4-neighbour).
    fn lattice() -> Graph {
        let n = 6;
        let points = (0..n * n).map(|i| ((i % n) as f64 * 5.0, (i / n) as f64 * 5.0)).collect();
        let adj = (0..n * n)
            .map(|i| {
                let (x, y) = (i % n, i / n);
                let mut l = Vec::new();
                if y > 0 {
                    l.push((i - n) as u32)
                }
                if x > 0 {
                    l.push((i - 1) as u32)
                }
                if x + 1 < n {
                    l.push((i + 1) as u32)
                }
                if y + 1 < n {
                    l.push((i + n) as u32)
                }
                l
            })
            .collect();
        Graph { points, adj }
    }

    fn params() -> OperatorParams {
        OperatorParams {
            lambda: 0.7,
            memory: 10,
            l_min: 8,
            l_max: 40,
            crossover_threshold: 10,
            b_instances: 20,
            b_distance: 5,
            b_accept: 1.0,
        }
    }

    #[test]
    fn forward_weights_of_spec_8() {
        use std::f64::consts::PI;
        assert!((forward_weight(0.7, PI / 2.0) - 10f64.powf(-0.35)).abs() < 1e-12);
        assert!((forward_weight(0.7, PI) - 10f64.powf(-0.7)).abs() < 1e-12);
        assert_eq!(forward_weight(0.0, 2.0), 1.0);
    }

    #[test]
    fn headings_of_lattice_moves_by_hand() {
        use std::f64::consts::PI;
        let g = lattice();
        // (from, to, heading): the lattice has 6 columns, 5 m apart; ids run row by row.
        let cases =
            [(0, 1, 0.0), (0, 6, PI / 2.0), (1, 0, PI), (6, 0, -PI / 2.0), (0, 7, PI / 4.0), (8, 13, 3.0 * PI / 4.0)];
        for (a, b, expected) in cases {
            assert!((heading(&g, a, b) - expected).abs() < 1e-12, "{a} → {b}: {}", heading(&g, a, b));
        }
    }

    #[test]
    fn extension_stops_at_the_target_length_and_goes_straight_under_a_strong_bias() {
        let g = lattice();
        let p = OperatorParams { lambda: 50.0, ..params() };
        let mut rng = stream(3, Purpose::Main, &[]);
        // Heading north from 0: every turn weighs 10^-25 or less against going straight on.
        let mut path = vec![0, 6];
        extend_random(&mut path, 6, &g, &p, &mut rng);
        assert_eq!(path, vec![0, 6, 12, 18, 24, 30]);
        // Westward along the second row.
        let mut path = vec![11, 10];
        extend_random(&mut path, 5, &g, &p, &mut rng);
        assert_eq!(path, vec![11, 10, 9, 8, 7]);
    }

    #[test]
    fn extension_avoids_the_last_m_waypoints_unless_every_neighbour_is_among_them() {
        let g = lattice();
        let p = OperatorParams { lambda: 0.0, memory: 3, ..params() };
        for seed in 0..50 {
            let mut rng = stream(seed, Purpose::Main, &[]);
            let mut path = vec![14];
            extend_random(&mut path, 40, &g, &p, &mut rng);
            assert_eq!(path.len(), 40);
            for k in 1..path.len() {
                let recent = &path[k.saturating_sub(3)..k];
                let forced = g.adj[path[k - 1] as usize].iter().all(|c| recent.contains(c));
                assert!(forced || !recent.contains(&path[k]), "seed {seed}: {path:?} at {k}");
            }
        }
        // Cornered: both neighbours of 0 (1 and 6) are recent, so one of them is taken; with
        // only 1 recent, 6 is.
        let mut rng = stream(1, Purpose::Main, &[]);
        let mut path = vec![6, 1, 0];
        extend_random(&mut path, 4, &g, &p, &mut rng);
        assert!([1, 6].contains(&path[3]), "{path:?}");
        for _ in 0..20 {
            let mut path = vec![1, 0];
            extend_random(&mut path, 3, &g, &p, &mut rng);
            assert_eq!(path, vec![1, 0, 6]);
        }
    }

    #[test]
    fn without_a_bias_every_neighbour_is_equally_likely() {
        // From 14 (interior: neighbours 8, 13, 15, 20) with λ = 0 and no history, each of the
        // four is drawn with probability 1/4: 4 000 draws, each count within 4 000/4 ± 120
        // (about 4.4 standard deviations).
        let g = lattice();
        let p = OperatorParams { lambda: 0.0, ..params() };
        let mut rng = stream(4, Purpose::Main, &[]);
        let mut counts = std::collections::BTreeMap::new();
        for _ in 0..4000 {
            let mut path = vec![14];
            extend_random(&mut path, 2, &g, &p, &mut rng);
            *counts.entry(path[1]).or_insert(0) += 1;
        }
        assert_eq!(counts.keys().copied().collect::<Vec<u32>>(), vec![8, 13, 15, 20]);
        assert!(counts.values().all(|&c| (880..=1120).contains(&c)), "{counts:?}");
    }

    #[test]
    fn mutation_a_keeps_a_prefix_of_two_or_more_and_regrows_within_bounds() {
        let g = lattice();
        let p = OperatorParams { l_max: 12, ..params() };
        // A walk along the first row and up the last column: 0 1 2 3 4 5 11 17.
        let original: Vec<u32> = vec![0, 1, 2, 3, 4, 5, 11, 17];
        let mut kept_lengths = std::collections::BTreeSet::new();
        for seed in 0..300 {
            let mut rng = stream(seed, Purpose::Main, &[]);
            let mut path = original.clone();
            mutation_a(&mut path, &g, &p, &mut rng);
            assert!((original.len()..=12).contains(&path.len()), "seed {seed}: {path:?}");
            assert!(is_feasible(&path, &g));
            let kept = path.iter().zip(&original).take_while(|(x, y)| x == y).count();
            assert!(kept >= 2, "seed {seed}: the start and its first move stay: {path:?}");
            kept_lengths.insert(kept);
        }
        assert_eq!(kept_lengths.first(), Some(&2), "k = 1 is drawn");
        // A path of two waypoints is regrown from its first move; one of one is left alone.
        let grown = (0..50).any(|seed| {
            let mut path = vec![0, 1];
            mutation_a(&mut path, &g, &p, &mut stream(seed, Purpose::Main, &[]));
            assert_eq!(&path[..2], &[0, 1]);
            path.len() > 2
        });
        assert!(grown);
        let mut path = vec![7];
        mutation_a(&mut path, &g, &p, &mut stream(1, Purpose::Main, &[]));
        assert_eq!(path, vec![7]);
    }

    #[test]
    fn crossover_joins_at_the_common_waypoint() {
        let mut rng = stream(1, Purpose::Main, &[]);
        let (c1, c2) = crossover(&[0, 1, 2, 3, 9], &[0, 6, 2, 8], 5, &mut rng).unwrap();
        assert_eq!(c1, vec![0, 1, 2, 8]);
        assert_eq!(c2, vec![0, 6, 2, 3, 9]);
        assert!(crossover(&[0, 1], &[0, 2], 5, &mut rng).is_none(), "only the start is shared");
        // The shared 5 lies at positions 1 and 3: within T_x = 2 of each other, not within 1.
        let (c1, c2) = crossover(&[0, 5, 9], &[0, 1, 2, 5, 4], 2, &mut rng).expect("|1 − 3| ≤ 2");
        assert_eq!((c1, c2), (vec![0, 5, 4], vec![0, 1, 2, 5, 9]));
        assert!(crossover(&[0, 5, 9], &[0, 1, 2, 5, 4], 1, &mut rng).is_none());
    }

    #[test]
    fn repair_truncates_to_l_max_and_extends_to_l_min() {
        let g = lattice();
        let p = OperatorParams { l_min: 4, l_max: 6, ..params() };
        let mut rng = stream(6, Purpose::Main, &[]);
        let mut long: Vec<u32> = vec![0, 1, 2, 3, 4, 5, 11, 17];
        repair(&mut long, &g, &p, &mut rng);
        assert_eq!(long, vec![0, 1, 2, 3, 4, 5]);
        let mut short = vec![0, 1];
        repair(&mut short, &g, &p, &mut rng);
        assert_eq!((short.len(), &short[..2]), (4, &[0, 1][..]));
        assert!(is_feasible(&short, &g));
        let mut fine = vec![0, 1, 7, 8, 9];
        repair(&mut fine, &g, &p, &mut rng);
        assert_eq!(fine, vec![0, 1, 7, 8, 9]);
    }

    #[test]
    fn short_hop_by_hand() {
        // a = 0 and b = 1 are not adjacent; 2, 3 and 4 each join them. Route lengths through
        // (-1, 5), (1, 1) and (6, -4): 14.56 + 6.71, 11.66 + 10.0, 5.10 + 17.0 px; the second
        // is the shortest (20.34 against 21.27 and 22.10).
        let points = vec![(7.0, -9.0), (-7.0, 7.0), (-1.0, 5.0), (1.0, 1.0), (6.0, -4.0)];
        let adj = vec![vec![2, 3, 4], vec![2, 3, 4], vec![0, 1], vec![0, 1], vec![0, 1]];
        let g = Graph { points, adj };
        assert_eq!(short_hop(&g, 0, 1), Some((2, Some(3))));
        assert_eq!(short_hop(&g, 0, 0), Some((0, None)));
        assert_eq!(short_hop(&g, 0, 2), Some((1, None)));
        // From 2 to 3 through 0 (27.8 px) or 1 (16.3 px).
        assert_eq!(short_hop(&g, 2, 3), Some((2, Some(1))));
        let far = Graph { points: vec![(0.0, 0.0); 3], adj: vec![vec![1], vec![0], vec![]] };
        assert_eq!(short_hop(&far, 0, 2), None);
    }

    #[test]
    fn mutation_b_by_hand() {
        // The 6 × 6 lattice: waypoint y·6 + x at (5x, 5y). A window of D + 1 = 6 waypoints; a
        // path of exactly six puts it at s = 0. p_acc = 1. The farthest j with a shorter route
        // is the one examined; if l_min forbids it, the instance changes nothing.
        let g = lattice();
        let op = |l_min: usize, b_instances: usize| OperatorParams {
            l_min,
            b_instances,
            b_distance: 5,
            b_accept: 1.0,
            ..params()
        };
        // (path, l_min, instances, expected)
        let cases: [(&[u32], usize, usize, &[u32]); 10] = [
            // Back at the start (0 hops) at j = 5: 1, 7, 6, 12 and the return go; new length
            // 6 − 4 − 1 = 1.
            (&[0, 1, 7, 6, 12, 0], 1, 1, &[0]),
            (&[0, 1, 7, 6, 12, 0], 2, 1, &[0, 1, 7, 6, 12, 0]),
            // One hop from 0 to 6 at j = 5: new length 6 − 4 + 1 − 1 = 2.
            (&[0, 1, 2, 8, 7, 6], 2, 1, &[0, 6]),
            (&[0, 1, 2, 8, 7, 6], 3, 1, &[0, 1, 2, 8, 7, 6]),
            // Two hops from 0 to 7 at j = 5, through 1 or 6 (equally long: the first, 1); new
            // length 6 − 4 + 2 − 1 = 3.
            (&[0, 1, 2, 8, 14, 7], 3, 1, &[0, 1, 7]),
            (&[0, 1, 2, 8, 14, 7], 4, 1, &[0, 1, 2, 8, 14, 7]),
            // A straight path has no shorter route (0 → 2 through 1 is as long).
            (&[0, 1, 2, 3, 4, 5], 2, 1, &[0, 1, 2, 3, 4, 5]),
            // Shorter than the window: untouched.
            (&[0, 1, 7, 6, 0], 1, 1, &[0, 1, 7, 6, 0]),
            // Seven waypoints, windows at s = 0 (nothing within two hops of 30) and s = 1 (back
            // at 0 at j = 6, removing j − s − 1 = 4): twenty instances find it.
            (&[30, 0, 1, 7, 6, 12, 0], 2, 20, &[30, 0]),
            (&[30, 0, 1, 7, 6, 12, 0], 3, 20, &[30, 0, 1, 7, 6, 12, 0]),
        ];
        for (path, l_min, instances, expected) in cases {
            let mut p = path.to_vec();
            mutation_b(&mut p, &g, &op(l_min, instances), &mut stream(4, Purpose::Main, &[]));
            assert_eq!(p, expected, "{path:?}, l_min {l_min}");
        }
    }

    #[test]
    fn feasibility_needs_every_step_to_be_an_edge() {
        let g = lattice();
        assert!(is_feasible(&[0, 1, 7, 13], &g));
        assert!(is_feasible(&[5], &g), "a single waypoint has no step");
        assert!(!is_feasible(&[0, 1, 8], &g), "1 → 8 is a diagonal");
        assert!(!is_feasible(&[0, 2, 3], &g), "0 → 2 skips a waypoint");
    }

    #[test]
    fn shortcut_replaces_a_detour() {
        let g = lattice();
        // 0 → 1 → 7 → 13 → 12 → 6: 0 and 6 are adjacent, so the detour collapses to 0 → 6.
        let mut p = vec![0, 1, 7, 13, 12, 6, 12, 18, 24, 30, 31];
        let mut rng = stream(2, Purpose::Main, &[]);
        let before = p.len();
        mutation_b(&mut p, &g, &OperatorParams { l_min: 2, ..params() }, &mut rng);
        assert!(p.len() < before);
        assert!(is_feasible(&p, &g));
        assert_eq!(p[0], 0);
    }

    proptest! {
        #[test]
        fn operators_keep_paths_feasible_and_within_bounds(seed in 0u64..2000) {
            let g = lattice();
            let p = params();
            let mut rng = stream(seed, Purpose::Individual, &[]);
            let mut a = vec![0u32];
            extend_random(&mut a, 20, &g, &p, &mut rng);
            let mut b = vec![0u32];
            extend_random(&mut b, 30, &g, &p, &mut rng);
            prop_assert!(is_feasible(&a, &g) && is_feasible(&b, &g));
            let (mut c1, mut c2) = crossover(&a, &b, p.crossover_threshold, &mut rng).unwrap_or((a.clone(), b.clone()));
            for c in [&mut c1, &mut c2] {
                repair(c, &g, &p, &mut rng);
                mutation_a(c, &g, &p, &mut rng);
                mutation_b(c, &g, &p, &mut rng);
                repair(c, &g, &p, &mut rng);
                prop_assert!(is_feasible(c, &g));
                prop_assert_eq!(c[0], 0);
                prop_assert!(c.len() >= p.l_min && c.len() <= p.l_max);
            }
        }
    }
}
