//! NSGA-II selection (Deb et al. 2002) over two maximised objectives with a constraint
//! violation: constrained non-dominated sorting, the crowding distance, the crowded binary
//! tournament for mating and the `(μ + λ)` survivor choice. Any GA in covga can use it; the
//! thesis GA applies it to 003's two objectives (`cov_final`, `t_final`, §4.1.2) with the swept
//! obstacle cells as the violation. Ties are broken by index, so results never depend on the
//! order of floating-point sorts.

use rand::Rng;

/// Whether `a` beats `b` under constrained domination: a plan without violation beats one
/// with; of two with violations the smaller violation wins; of two without, Pareto dominance
/// (both objectives maximised).
pub fn constrained_dominates(a: (f64, f64), va: f64, b: (f64, f64), vb: f64) -> bool {
    match (va > 0.0, vb > 0.0) {
        (false, true) => true,
        (true, false) => false,
        (true, true) => va < vb,
        (false, false) => crate::ga::pareto::dominates(a, b),
    }
}

/// The front of every point: 0 for the non-dominated, 1 for those dominated only by front 0,
/// and so on (the fast non-dominated sort, `O(n²)`), under [`constrained_dominates`].
pub fn front_ranks(points: &[(f64, f64)], violation: &[f64]) -> Vec<usize> {
    let n = points.len();
    debug_assert_eq!(violation.len(), n);
    let mut beaten_by = vec![0usize; n];
    let mut beats: Vec<Vec<usize>> = vec![Vec::new(); n];
    for i in 0..n {
        for j in i + 1..n {
            if constrained_dominates(points[i], violation[i], points[j], violation[j]) {
                beats[i].push(j);
                beaten_by[j] += 1;
            } else if constrained_dominates(points[j], violation[j], points[i], violation[i]) {
                beats[j].push(i);
                beaten_by[i] += 1;
            }
        }
    }
    let mut rank = vec![usize::MAX; n];
    let mut current: Vec<usize> = (0..n).filter(|&i| beaten_by[i] == 0).collect();
    let mut r = 0;
    while !current.is_empty() {
        let mut next = Vec::new();
        for &i in &current {
            rank[i] = r;
            for &j in &beats[i] {
                beaten_by[j] -= 1;
                if beaten_by[j] == 0 {
                    next.push(j);
                }
            }
        }
        next.sort_unstable();
        current = next;
        r += 1;
    }
    rank
}

/// The crowding distance of each member of `front` (indices into `points`), in the order of
/// `front`: for each objective, the gap between a member's two neighbours divided by the
/// objective's range on the front; the extreme members of either objective get infinity.
pub fn crowding_distances(points: &[(f64, f64)], front: &[usize]) -> Vec<f64> {
    let m = front.len();
    let mut distance = vec![0.0; m];
    if m <= 2 {
        return vec![f64::INFINITY; m];
    }
    for objective in 0..2 {
        let value = |k: usize| if objective == 0 { points[front[k]].0 } else { points[front[k]].1 };
        let mut order: Vec<usize> = (0..m).collect();
        order.sort_by(|&a, &b| value(a).total_cmp(&value(b)).then(front[a].cmp(&front[b])));
        let (lo, hi) = (value(order[0]), value(order[m - 1]));
        distance[order[0]] = f64::INFINITY;
        distance[order[m - 1]] = f64::INFINITY;
        if hi > lo {
            for w in order.windows(3) {
                distance[w[1]] += (value(w[2]) - value(w[0])) / (hi - lo);
            }
        }
    }
    distance
}

/// Rank and crowding distance of every point (the crowded-comparison keys of NSGA-II).
pub fn crowded_keys(points: &[(f64, f64)], violation: &[f64]) -> (Vec<usize>, Vec<f64>) {
    let rank = front_ranks(points, violation);
    let mut crowding = vec![0.0; points.len()];
    let fronts = rank.iter().copied().max().map_or(0, |r| r + 1);
    for r in 0..fronts {
        let front: Vec<usize> = (0..points.len()).filter(|&i| rank[i] == r).collect();
        for (k, d) in crowding_distances(points, &front).into_iter().enumerate() {
            crowding[front[k]] = d;
        }
    }
    (rank, crowding)
}

/// Whether `a` is better than `b` by the crowded comparison: a lower front, or the same front
/// and a larger crowding distance.
pub fn crowded_better(rank: &[usize], crowding: &[f64], a: usize, b: usize) -> bool {
    rank[a] < rank[b] || (rank[a] == rank[b] && crowding[a] > crowding[b])
}

/// The binary crowded tournament: two members drawn at random (distinct when there are two),
/// the better by [`crowded_better`] wins, the first drawn on a tie.
pub fn crowded_tournament<R: Rng + ?Sized>(rank: &[usize], crowding: &[f64], rng: &mut R) -> usize {
    let n = rank.len();
    let a = rng.random_range(0..n);
    if n < 2 {
        return a;
    }
    let b = (a + rng.random_range(1..n)) % n;
    if crowded_better(rank, crowding, b, a) { b } else { a }
}

/// The `keep` survivors of `points` (parents and offspring together): whole fronts in order,
/// then the members of the first front that does not fit by descending crowding distance
/// (lower index first on a tie). Returned in ascending index order.
pub fn survivors(points: &[(f64, f64)], violation: &[f64], keep: usize) -> Vec<usize> {
    let (rank, crowding) = crowded_keys(points, violation);
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| rank[a].cmp(&rank[b]).then(crowding[b].total_cmp(&crowding[a])).then(a.cmp(&b)));
    order.truncate(keep);
    order.sort_unstable();
    order
}

/// The knee of a front (indices into `points`, both objectives maximised): with each
/// objective scaled to [0, 1] over the front, the extremes lie at (1, 0) and (0, 1), and the
/// member farthest beyond the line through them, `x + y = 1`, is the one with the largest
/// scaled sum (lower index first on a tie). An objective that does not vary counts 1 for every
/// member. `None` for an empty front.
pub fn knee(points: &[(f64, f64)], front: &[usize]) -> Option<usize> {
    let first = *front.first()?;
    let (mut lo, mut hi) = (points[first], points[first]);
    for &i in front {
        lo = (lo.0.min(points[i].0), lo.1.min(points[i].1));
        hi = (hi.0.max(points[i].0), hi.1.max(points[i].1));
    }
    let scale = |v: f64, l: f64, h: f64| if h > l { (v - l) / (h - l) } else { 1.0 };
    let sum = |i: usize| scale(points[i].0, lo.0, hi.0) + scale(points[i].1, lo.1, hi.1);
    Some(front.iter().copied().fold(first, |best, i| if sum(i) > sum(best) { i } else { best }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    const POINTS: [(f64, f64); 6] = [(0.9, 0.1), (0.1, 0.9), (0.5, 0.5), (0.4, 0.4), (0.2, 0.2), (0.6, 0.6)];

    #[test]
    fn fronts_by_hand() {
        // Front 0: (0.9, 0.1), (0.1, 0.9), (0.6, 0.6); front 1: (0.5, 0.5); 2: (0.4, 0.4); 3: (0.2, 0.2).
        assert_eq!(front_ranks(&POINTS, &[0.0; 6]), vec![0, 0, 1, 2, 3, 0]);
        // A violation sends a point behind every feasible one; the smaller violation leads.
        let violation = [0.0, 0.0, 0.0, 0.0, 2.0, 5.0];
        assert_eq!(front_ranks(&POINTS, &violation), vec![0, 0, 0, 1, 2, 3]);
        // Equal points do not dominate each other.
        assert_eq!(front_ranks(&[(0.5, 0.5), (0.5, 0.5)], &[0.0, 0.0]), vec![0, 0]);
    }

    #[test]
    fn constrained_domination_table() {
        let cases = [
            ((0.1, 0.1), 0.0, (0.9, 0.9), 1.0, true),
            ((0.9, 0.9), 1.0, (0.1, 0.1), 0.0, false),
            ((0.1, 0.1), 1.0, (0.9, 0.9), 2.0, true),
            ((0.9, 0.9), 2.0, (0.1, 0.1), 2.0, false),
            ((0.6, 0.6), 0.0, (0.5, 0.6), 0.0, true),
            ((0.6, 0.6), 0.0, (0.6, 0.6), 0.0, false),
        ];
        for (a, va, b, vb, expected) in cases {
            assert_eq!(constrained_dominates(a, va, b, vb), expected, "{a:?} {va} vs {b:?} {vb}");
        }
    }

    #[test]
    fn crowding_distance_by_hand() {
        // Front sorted by x: (0.1, 0.9), (0.4, 0.7), (0.5, 0.4), (0.9, 0.1); ranges 0.8 and 0.8.
        let points = [(0.5, 0.4), (0.1, 0.9), (0.9, 0.1), (0.4, 0.7)];
        let d = crowding_distances(&points, &[0, 1, 2, 3]);
        // (0.5, 0.4): x neighbours 0.4 and 0.9 → 0.5/0.8; y neighbours 0.1 and 0.7 → 0.6/0.8.
        assert!((d[0] - 1.1 / 0.8).abs() < 1e-12, "{}", d[0]);
        // (0.4, 0.7): x neighbours 0.1, 0.5 → 0.4/0.8; y neighbours 0.4, 0.9 → 0.5/0.8.
        assert!((d[3] - 0.9 / 0.8).abs() < 1e-12, "{}", d[3]);
        assert!(d[1].is_infinite() && d[2].is_infinite());
        assert_eq!(crowding_distances(&points, &[0, 3]), vec![f64::INFINITY; 2]);
    }

    #[test]
    fn survivors_take_whole_fronts_then_the_least_crowded() {
        // Front 0 holds 0, 1, 5 (3 members); keeping 4 takes front 0 and the best of front 1.
        assert_eq!(survivors(&POINTS, &[0.0; 6], 4), vec![0, 1, 2, 5]);
        // Keeping 2 of front 0's three: the extremes (infinite crowding) stay.
        assert_eq!(survivors(&POINTS, &[0.0; 6], 2), vec![0, 1]);
        assert_eq!(survivors(&POINTS, &[0.0; 6], 6), vec![0, 1, 2, 3, 4, 5]);
    }

    #[test]
    fn the_crowded_tournament_prefers_lower_fronts() {
        let (rank, crowding) = crowded_keys(&POINTS, &[0.0; 6]);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let mut wins = [0usize; 6];
        for _ in 0..6000 {
            wins[crowded_tournament(&rank, &crowding, &mut rng)] += 1;
        }
        // The last front (index 4) wins only when drawn against itself, which cannot happen.
        assert_eq!(wins[4], 0);
        assert!(wins[0] > wins[2] && wins[2] > wins[3], "{wins:?}");
        assert!(crowded_better(&rank, &crowding, 0, 2) && !crowded_better(&rank, &crowding, 3, 2));
    }

    #[test]
    fn knee_of_a_bent_front() {
        let points = [(1.0, 0.0), (0.8, 0.75), (0.5, 0.85), (0.0, 1.0)];
        assert_eq!(knee(&points, &[0, 1, 2, 3]), Some(1));
        assert_eq!(knee(&points, &[2]), Some(2));
        assert_eq!(knee(&points, &[]), None);
    }
}
