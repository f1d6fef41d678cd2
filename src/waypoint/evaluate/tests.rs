use super::*;
use crate::waypoint::precompute::{Mask, Traversal};

#[test]
fn loop_closure_counting_by_hand() {
    // 0-1-2-3-0-1-2: edges 0→1 and 1→2 repeat 4 steps later: one run, one closure.
    let p = [0, 1, 2, 3, 0, 1, 2];
    assert_eq!(loop_closures(&p, &p, true, 4), 1);
    assert_eq!(loop_closures(&p, &p, true, 5), 0, "separation below the threshold");
    // Opposite direction does not count.
    let q = [0, 1, 2, 3, 2, 1, 0];
    assert_eq!(loop_closures(&q, &q, true, 1), 0);
    // Two separate re-traversals count twice.
    let r = [0, 1, 5, 6, 7, 0, 1, 8, 6, 7];
    assert_eq!(loop_closures(&r, &r, true, 3), 2);
    // Between agents, no separation threshold.
    assert_eq!(loop_closures(&[4, 0, 1, 2], &[9, 0, 1, 2, 3], false, 0), 1);
    assert_eq!(loop_closures(&[4, 0, 1], &[1, 0, 4], false, 0), 0);
    // A match at the other path's first edge (j = 0) has no predecessor to extend.
    assert_eq!(loop_closures(&[4, 0, 1, 2], &[0, 1, 2], false, 0), 1);
    assert_eq!(loop_closures(&[0, 1, 2], &[4, 0, 1, 2], false, 0), 1);
}

#[test]
fn edge_rule_counts_each_reflown_edge_once() {
    // The same paths as above, counted per distinct re-flown edge.
    let p = [0, 1, 2, 3, 0, 1, 2];
    assert_eq!(edge_loop_closures(&p, &p, true, 4), 2, "0→1 and 1→2");
    assert_eq!(edge_loop_closures(&p, &p, true, 5), 0);
    let q = [0, 1, 2, 3, 2, 1, 0];
    assert_eq!(edge_loop_closures(&q, &q, true, 1), 0, "reverse direction");
    let r = [0, 1, 5, 6, 7, 0, 1, 8, 6, 7];
    assert_eq!(edge_loop_closures(&r, &r, true, 3), 2, "0→1 and 6→7");
    // An edge flown three times counts once; separation from its first occurrence.
    let t = [0, 1, 0, 1, 0, 1];
    assert_eq!(edge_loop_closures(&t, &t, true, 2), 2, "0→1 and 1→0");
    assert_eq!(edge_loop_closures(&t, &t, true, 4), 1, "only 0→1 recurs 4 later");
    assert_eq!(edge_loop_closures(&[4, 0, 1, 2], &[9, 0, 1, 2, 3], false, 0), 2);
    for (rule, expected) in [(LoopClosureRule::Run, 1), (LoopClosureRule::Edge, 2)] {
        assert_eq!(rule.count(&p, &p, true, 4), expected, "{}", rule.name());
    }
}

#[test]
fn laplacian_zero_eigenvalues_count_components() {
    let f = false;
    let t = true;
    let connected = vec![vec![f, t, f], vec![t, f, t], vec![f, t, f]];
    let two = vec![vec![f, t, f, f], vec![t, f, f, f], vec![f, f, f, t], vec![f, f, t, f]];
    let isolated = vec![vec![f, t, f], vec![t, f, f], vec![f, f, f]];
    for (adj, expected) in [(connected, 1), (two, 2), (isolated, 2)] {
        assert_eq!(components(&adj), expected);
        assert_eq!(laplacian_zero_eigenvalues(&adj, 1e-9), expected);
    }
    assert_eq!(components(&[vec![false]]), 1);
    // A triangle is not bipartite: the Laplacian has one zero eigenvalue, the signless
    // Laplacian D + A none.
    let triangle = vec![vec![f, t, t], vec![t, f, t], vec![t, t, f]];
    assert_eq!(components(&triangle), 1);
    assert_eq!(laplacian_zero_eigenvalues(&triangle, 1e-9), 1);
    assert_eq!(laplacian_zero_eigenvalues(&triangle, 3.1), 3, "its other eigenvalues are 3 and 3");
    // The tolerance is a strict bound: a lone agent's Laplacian is exactly [0].
    assert_eq!(laplacian_zero_eigenvalues(&[vec![false]], 0.0), 0);
    assert_eq!(laplacian_zero_eigenvalues(&[vec![false]], 1e-300), 1);
}

#[test]
fn turning_cost_values_of_spec_6() {
    use std::f64::consts::PI;
    assert!((turn_cost(8.0, PI / 4.0) - 8.0 * 0.5f64.powi(8)).abs() < 1e-12);
    assert!((turn_cost(8.0, PI / 2.0) - 8.0).abs() < 1e-12);
    assert!((turn_cost(8.0, PI) - 2048.0).abs() < 1e-9);
    assert!((turn_cost(8.0, -3.0 * PI / 2.0) - 8.0).abs() < 1e-9, "wrapped to 90°");
}

/// The objective parameters of the hand-worked cases.
fn objective_params() -> ObjectiveParams {
    ObjectiveParams {
        alpha_cov: 0.1,
        rho: 8.0,
        scale_coverage: -1.0,
        scale_time: 1e-4,
        c_start: 0.3,
        c_end: 0.8,
        aging: 60,
        lc_separation: 30,
        lc_min: 2,
        lc_rule: LoopClosureRule::Run,
        penalty: 1000.0,
    }
}

#[test]
fn ramp_and_blend() {
    let p = objective_params();
    assert_eq!(required_coverage(&p, 0), 0.3);
    assert!((required_coverage(&p, 30) - 0.55).abs() < 1e-12);
    assert_eq!(required_coverage(&p, 600), 0.8);
    assert!((blended_coverage(0.1, 0.5, 1.0) - 0.95).abs() < 1e-12);
    assert!((blended_coverage(0.25, 0.4, 0.8) - 0.7).abs() < 1e-12);
    assert_eq!(LoopClosureRule::Run.name(), "run");
    assert_eq!(LoopClosureRule::Edge.name(), "edge");
    let e =
        Evaluation { coverage: 0.5, flight_time: 1000.0, closures: vec![vec![1]], components: 1, ..Default::default() };
    assert_eq!(e.objectives(&p, 0.6), [-0.5 + 1000.0, 0.1 + 1000.0]);
    assert_eq!(e.violations(&p, 0.4), 1);
}

/// A square of four waypoints 10 px apart (0 (0,0), 1 (10,0), 2 (10,10), 3 (0,10)) with
/// one pixel per view: `i → j` departs seeing pixel `10i + j` and arrives seeing
/// `100 + 10i + j`; the wall band is pixels 0–63, of 256.
fn square() -> (Graph, Traversals) {
    let points = vec![(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)];
    let adj = vec![vec![1, 3], vec![0, 2], vec![1, 3], vec![0, 2]];
    let pixel = |i: usize| Mask { first: (i / 64) as u32, words: vec![1 << (i % 64)] };
    let edges = (0..4)
        .map(|i| {
            adj[i]
                .iter()
                .map(|&j| {
                    let (a, b): ((f64, f64), (f64, f64)) = (points[i], points[j as usize]);
                    Traversal {
                        dist: (b.0 - a.0).hypot(b.1 - a.1),
                        heading: (b.1 - a.1).atan2(b.0 - a.0),
                        depart: pixel(10 * i + j as usize),
                        arrive: pixel(100 + 10 * i + j as usize),
                    }
                })
                .collect()
        })
        .collect();
    (Graph { points, adj }, Traversals { edges, words: 4 })
}

#[test]
fn flight_time_and_views_of_a_square_by_hand() {
    let (g, tr) = square();
    // 0 → 1 → 2 → 1: three 10 px legs, a quarter turn at 1 (ρ = 8: 8·1⁸) and a half turn
    // at 2 (8·2⁸ = 2048).
    assert!((flight_time(&[0, 1, 2, 1], &g, &tr, 8.0) - 2086.0).abs() < 1e-9);
    assert!((flight_time(&[0, 1], &g, &tr, 8.0) - 10.0).abs() < 1e-12);
    assert_eq!(flight_time(&[0], &g, &tr, 8.0), 0.0);
    // The run's table gives the same times to the bit.
    let turns = TurnCosts::new(&g, &tr, 8.0);
    for path in [&[0, 1, 2, 1][..], &[0, 1], &[0], &[], &[1, 2, 1, 0, 1]] {
        assert_eq!(turns.flight_time(path, &g, &tr).to_bits(), flight_time(path, &g, &tr, 8.0).to_bits(), "{path:?}");
    }
    let mut u = Union::new(4);
    add_views(&[0, 1, 2, 1], &g, &tr, &mut u);
    let seen: Vec<usize> = (0..256).filter(|&i| u.contains(i)).collect();
    assert_eq!(seen, vec![1, 12, 21, 121], "three departures and the last arrival");
}

#[test]
fn evaluation_of_two_agents_by_hand() {
    let (g, tr) = square();
    let band = [u64::MAX, 0, 0, 0];
    let params = ObjectiveParams { alpha_cov: 0.25, lc_separation: 1, lc_min: 1, ..objective_params() };
    let turns = TurnCosts::new(&g, &tr, params.rho);
    let ev = Evaluator { graph: &g, traversals: &tr, band: &band, free: 200, band_count: 64, params, turns: &turns };
    let mut scratch = Union::new(4);
    // A flies 0 1 2 1, B flies 3 2 1 2: views {1, 12, 21, 121} ∪ {32, 21, 12, 112} = six
    // pixels, four of them in the band; A's 1→2 and 2→1 are B's too (two runs); B turns
    // a quarter at 2 and half at 1, like A.
    let e = ev.evaluate(&[vec![0, 1, 2, 1], vec![3, 2, 1, 2]], &mut scratch);
    assert!((e.open - 6.0 / 200.0).abs() < 1e-15 && (e.walls - 4.0 / 64.0).abs() < 1e-15, "{e:?}");
    assert!((e.coverage - (0.25 * 0.03 + 0.75 * 0.0625)).abs() < 1e-15);
    assert!((e.flight_time - 2.0 * 2086.0).abs() < 1e-9);
    assert_eq!(e.closures, vec![vec![0, 2], vec![2, 0]]);
    assert_eq!(e.components, 1);
    // B now flies 3 0 3 0 3: nothing in common with A, and 3→0 twice with itself.
    let e = ev.evaluate(&[vec![0, 1, 2, 1], vec![3, 0, 3, 0, 3]], &mut scratch);
    assert_eq!(e.closures, vec![vec![0, 0], vec![0, 1]]);
    assert_eq!(e.components, 2);
    assert_eq!(e.violations(&params, 0.0), 2, "A has no loop closure, and the agents are apart");
}

#[test]
fn penalties_and_violations_by_constraint() {
    let p = objective_params();
    /// (closures, components, coverage, C_req, loops ok, connected, [f1, f2], violations)
    type Case = (Vec<Vec<usize>>, usize, f64, f64, bool, bool, [f64; 2], usize);
    let cases: [Case; 6] = [
        (vec![vec![2]], 1, 0.5, 0.5, true, true, [-0.5, 0.2], 0),
        (vec![vec![2]], 1, 0.5, 0.75, true, true, [-0.5, 1000.2], 1),
        (vec![vec![1]], 1, 0.5, 0.25, false, true, [999.5, 0.2], 1),
        (vec![vec![3, 0], vec![0, 2]], 2, 0.5, 0.25, true, false, [999.5, 0.2], 1),
        (vec![vec![3, 1], vec![1, 1]], 1, 0.5, 0.25, false, true, [999.5, 0.2], 1),
        (vec![vec![0, 0], vec![0, 0]], 2, 0.25, 0.5, false, false, [999.75, 1000.2], 3),
    ];
    for (closures, components, coverage, c_req, loops, connected, objectives, violations) in cases {
        let e = Evaluation { coverage, flight_time: 2000.0, closures, components, ..Default::default() };
        assert_eq!(e.loops_ok(p.lc_min), loops, "{e:?}");
        assert_eq!(e.connected(), connected, "{e:?}");
        let f = e.objectives(&p, c_req);
        assert!((f[0] - objectives[0]).abs() < 1e-9 && (f[1] - objectives[1]).abs() < 1e-9, "{e:?}: {f:?}");
        assert_eq!(e.violations(&p, c_req), violations, "{e:?}");
    }
}

/// Loop closures by their definition (W23), pair by pair: the reference the sorted-edge
/// count must equal.
fn loop_closures_by_pairs(a: &[u32], b: &[u32], same: bool, separation: usize) -> usize {
    let (ea, eb) = (a.len().saturating_sub(1), b.len().saturating_sub(1));
    let is_match = |i: usize, j: usize| (!same || j >= i + separation.max(1)) && a[i] == b[j] && a[i + 1] == b[j + 1];
    (0..ea)
        .flat_map(|i| (0..eb).map(move |j| (i, j)))
        .filter(|&(i, j)| is_match(i, j) && !(i > 0 && j > 0 && is_match(i - 1, j - 1)))
        .count()
}

/// The authors' driver's count by its definition: each edge of `a` at its first occurrence,
/// if `b` flies it at or after `from`.
fn edge_loop_closures_by_scan(a: &[u32], b: &[u32], same: bool, separation: usize) -> usize {
    let (ea, eb) = (a.len().saturating_sub(1), b.len().saturating_sub(1));
    let edge = |p: &[u32], i: usize| (p[i], p[i + 1]);
    (0..ea)
        .filter(|&i| !(0..i).any(|k| edge(a, k) == edge(a, i)))
        .filter(|&i| {
            let from = if same { i + separation.max(1) } else { 0 };
            (from..eb).any(|j| edge(b, j) == edge(a, i))
        })
        .count()
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(2000))]
    /// The sorted-edge counts equal the counts by definition on random walks over few nodes
    /// (many repeated edges, runs, and matches at either path's first edge), with a path and
    /// itself and between two paths.
    #[test]
    fn closure_counts_equal_their_definitions(
        a in proptest::collection::vec(0u32..5, 0..40),
        b in proptest::collection::vec(0u32..5, 0..40),
        separation in 0usize..8,
    ) {
        for (x, y, same) in [(&a, &a, true), (&a, &b, false), (&b, &a, false)] {
            proptest::prop_assert_eq!(loop_closures(x, y, same, separation), loop_closures_by_pairs(x, y, same, separation));
            proptest::prop_assert_eq!(edge_loop_closures(x, y, same, separation), edge_loop_closures_by_scan(x, y, same, separation));
        }
    }
}
