use super::*;
use crate::coverage::Footprint;
use crate::coverage::fitness::Projection;
use crate::map::presets::preset;
use crate::thesis::objective::CameraObjective;

fn a(dist_m: f64) -> Action {
    Action::new(90.0, dist_m)
}

/// Thesis map 1 with this robot, S and E, projection f2.
fn thesis1(robot: Footprint, s: Point, e: Point) -> ThesisScenario {
    ThesisScenario::new(preset("thesis-1").unwrap(), robot, s, e, Projection::F2)
}

/// One move 3 m east, then two zero genes (the connector's slot and E's).
fn three_metres_east() -> Individual {
    Individual::with_genome(vec![Action::new(0.0, 3.0), Action::new(0.0, 0.0), Action::new(0.0, 0.0)])
}

#[test]
fn zero_runs_shrink_to_two() {
    // Genes: S(1) 0 0 0 0 1 0 conn E → the middle two of the four zeros go.
    let mut ind = Individual::with_genome(vec![a(1.0), a(0.0), a(0.0), a(0.0), a(0.0), a(1.0), a(0.0), a(2.0), a(0.0)]);
    ind.points = (0..9).map(|i| Point::new(i as f64, 0.0)).collect();
    assert_eq!(remove_zero_actions(&mut ind), 2);
    let d: Vec<f64> = ind.genome.iter().map(|x| x.dist_m()).collect();
    assert_eq!(d, vec![1.0, 0.0, 0.0, 1.0, 0.0, 2.0, 0.0]);
    assert_eq!(ind.points.len(), 7);
    assert_eq!(ind.points[2], Point::new(4.0, 0.0));
}

#[test]
fn a_premarked_rectangle_makes_its_cells_revisits_in_both_evaluations() {
    // The 3 m lane east from (1.3, 1.3) on thesis map 1 sweeps 45 cells; with the 1 m square
    // at (1, 1) pre-marked, its 12 lane cells are revisits (as the sweep's own case says).
    let (s, e) = (Point::new(1.3, 1.3), Point::new(4.3, 1.3));
    let mut scenario = thesis1(Footprint::default(), s, e);
    let eval = |scenario: &ThesisScenario, mode| {
        let mut ind = three_metres_east();
        evaluate(&mut ind, scenario, Base::None, mode, &mut EvalScratch::default());
        ind
    };
    for mode in [EvaluationMode::Full, EvaluationMode::Incremental] {
        assert_eq!(eval(&scenario, mode).sweep, SweepCounts { cov_pix: 45, cross_pix: 0, obj_pix: 0 });
    }
    scenario.premark_rect(1.0, 1.0, 2.0, 2.0);
    for mode in [EvaluationMode::Full, EvaluationMode::Incremental] {
        let ind = eval(&scenario, mode);
        assert_eq!(ind.sweep, SweepCounts { cov_pix: 45, cross_pix: 12, obj_pix: 0 }, "{mode:?}");
        // The accessors read the member.
        assert_eq!(ind.fitness(), ind.score.fitness);
        assert!(ind.fitness() > 0.0 && ind.fitness() != 1.0, "{}", ind.fitness());
        assert_eq!((ind.len(), ind.is_empty()), (3, false));
    }
    assert!(Individual::default().is_empty());
}

#[test]
fn turning_costs_r_rot_and_nothing_without_it() {
    // East 3 m, then the connector north 3 m to E: a quarter turn, T_rot = (π/2) / R_rot.
    let (s, e) = (Point::new(1.3, 1.3), Point::new(4.3, 4.3));
    for (rot_speed, t_rot) in [(0.5, std::f64::consts::PI), (0.0, 0.0)] {
        let robot = Footprint { rot_speed, ..Footprint::default() };
        let scenario = thesis1(robot, s, e);
        let mut ind = three_metres_east();
        evaluate(&mut ind, &scenario, Base::None, EvaluationMode::Incremental, &mut EvalScratch::default());
        assert!((ind.t_rot_s - t_rot).abs() < 1e-12, "R_rot {rot_speed}: {}", ind.t_rot_s);
    }
}

#[test]
fn a_child_equal_to_its_parent_up_to_its_connector_evaluates_as_in_full() {
    // Parent: five equal moves of 0.5 m east, the connector, E. Child: the same five genes,
    // the fifth now in its connector's slot, and E. All the child's genes before E are the
    // parent's bit for bit, one more than the child's stable prefix can hold.
    let (s, e) = (Point::new(1.3, 1.3), Point::new(1.3, 3.3));
    let scenario = thesis1(Footprint::default(), s, e);
    let (g, zero) = (Action::new(0.0, 0.5), Action::new(0.0, 0.0));
    let mut scratch = EvalScratch::default();
    let mut parent = Individual::with_genome(vec![g, g, g, g, g, zero, zero]);
    evaluate(&mut parent, &scenario, Base::None, EvaluationMode::Incremental, &mut scratch);
    assert_eq!(parent.stable_genes, 5);
    let mut child = Individual::with_genome(vec![g, g, g, g, g, zero]);
    let mut full = Individual::with_genome(child.genome.clone());
    evaluate(&mut child, &scenario, Base::Parent(&parent), EvaluationMode::Incremental, &mut scratch);
    evaluate(&mut full, &scenario, Base::None, EvaluationMode::Full, &mut scratch);
    assert_eq!((&child.genome, &child.points, child.sweep), (&full.genome, &full.points, full.sweep));
    assert_eq!((child.stable_genes, child.score), (full.stable_genes, full.score));
    assert_eq!(child.visits, full.visits);
    assert!((child.points[4] - Point::new(3.3, 1.3)).norm() < 1e-9, "four moves east, then the connector to E");
}

#[test]
fn an_edit_skips_only_the_segments_both_paths_share() {
    // A path's visit map edited into another's equals the other's fresh sweep, however
    // many viewpoints the two share at either end (`same`: leading viewpoints known shared).
    let s = Point::new(1.3, 1.3);
    let scenario = thesis1(Footprint::default(), s, s);
    let (layers, width) = (&scenario.layers, scenario.robot.width);
    let p = Point::new;
    let old = [s, p(4.3, 1.3), p(4.3, 4.3), p(2.3, 6.3), p(6.3, 6.3), p(6.3, 2.3), s];
    let cases: [(Vec<Point>, usize); 9] = [
        // The third viewpoint from the end differs; the last two are shared.
        (vec![s, p(4.3, 1.3), p(4.3, 4.3), p(2.3, 6.3), p(8.3, 8.3), p(6.3, 2.3), s], 3),
        // The second differs; all after it are shared.
        (vec![s, p(4.3, 1.3), p(5.3, 4.3), p(2.3, 6.3), p(6.3, 6.3), p(6.3, 2.3), s], 1),
        // The same, with nothing known shared beyond S.
        (vec![s, p(4.3, 1.3), p(5.3, 4.3), p(2.3, 6.3), p(6.3, 6.3), p(6.3, 2.3), s], 0),
        // A viewpoint inserted, one removed.
        (vec![s, p(4.3, 1.3), p(4.3, 4.3), p(3.3, 3.3), p(2.3, 6.3), p(6.3, 6.3), p(6.3, 2.3), s], 2),
        (vec![s, p(4.3, 1.3), p(2.3, 6.3), p(6.3, 6.3), p(6.3, 2.3), s], 1),
        // S again where the other path has a viewpoint, and S twice at the end: a shared
        // tail is two equal segments, not one equal viewpoint matched with a neighbour.
        (vec![s, p(4.3, 1.3), p(4.3, 4.3), p(2.3, 6.3), s, p(6.3, 2.3), s], 1),
        (vec![s, p(4.3, 1.3), p(4.3, 4.3), p(2.3, 6.3), p(6.3, 6.3), s, s], 1),
        // Nothing shared but S and E; and the same path.
        (vec![s, p(9.3, 9.3), s], 0),
        (old.to_vec(), 6),
    ];
    let counts = |v: &VisitPlanes| {
        let mut c = Vec::new();
        v.for_each_count(|cell, k| c.push((cell, k)));
        c
    };
    // Each pair both ways: from `old` to the case's path and back.
    for (i, (path, same)) in cases.iter().enumerate() {
        for (from, to) in [(&old[..], &path[..]), (&path[..], &old[..])] {
            let mut visits = VisitPlanes::default();
            let tally = layers.sweep(&mut visits, from, width);
            let edited = edit(
                layers,
                &mut SegmentCache::default(),
                &mut Vec::new(),
                None,
                &mut visits,
                tally,
                from,
                to,
                *same,
                width,
            );
            let mut fresh = VisitPlanes::default();
            assert_eq!(edited, layers.sweep(&mut fresh, to, width), "case {i}");
            assert_eq!(counts(&visits), counts(&fresh), "case {i}");
        }
    }
}

/// Zero-action removal by its definition: marks on the unchanged genome, then deletion;
/// the indices of the genes kept.
fn kept_by_marks(genome: &[Action]) -> Vec<usize> {
    let n = genome.len();
    let z = |i: usize| genome[i].is_zero();
    (0..n).filter(|&i| !(n >= 5 && i >= 1 && i <= n - 3 && z(i - 1) && z(i) && z(i + 1))).collect()
}

proptest::proptest! {
    /// The in-place pass deletes exactly the marked genes and their viewpoints (with one
    /// viewpoint per gene, or one fewer), and the stable prefix loses the genes deleted
    /// from it.
    #[test]
    fn zero_action_removal_follows_its_marks(zeros in proptest::collection::vec(proptest::prelude::any::<bool>(), 0..40), stable in 0usize..41, short in proptest::bool::ANY) {
        let genome: Vec<Action> = zeros.iter().enumerate().map(|(i, &z)| a(if z { 0.0 } else { 1.0 + i as f64 })).collect();
        let n_points = if short { genome.len().saturating_sub(1) } else { genome.len() };
        let points: Vec<Point> = (0..n_points).map(|i| Point::new(i as f64, 0.0)).collect();
        let stable = stable.min(genome.len());
        let kept = kept_by_marks(&genome);
        let fields = IndividualFields { genome: genome.clone(), points: points.clone(), stable_genes: stable, ..Default::default() };
        let mut ind = Individual::from(fields);
        proptest::prop_assert_eq!(remove_zero_actions(&mut ind), genome.len() - kept.len());
        proptest::prop_assert_eq!(&ind.genome, &kept.iter().map(|&i| genome[i]).collect::<Vec<_>>());
        let kept_points: Vec<Point> = kept.iter().filter(|&&i| i < n_points).map(|&i| points[i]).collect();
        proptest::prop_assert_eq!(&ind.points[..kept_points.len().min(ind.points.len())], &kept_points[..]);
        proptest::prop_assert_eq!(ind.stable_genes, kept.iter().filter(|&&i| i < stable).count());
    }

    /// Told that its first `known` genes end no run of three zeros (as a child's genes shared
    /// with a corrected parent), the removal deletes what the whole search deletes.
    #[test]
    fn a_known_prefix_changes_no_removal(zeros in proptest::collection::vec(proptest::prelude::any::<bool>(), 0..40), known in 0usize..41) {
        let genome: Vec<Action> = zeros.iter().enumerate().map(|(i, &z)| a(if z { 0.0 } else { 1.0 + i as f64 })).collect();
        let n = genome.len();
        // The longest prefix in which no run of three zeros ends (searched as the removal does,
        // up to gene n − 2).
        let clean = (2..n.saturating_sub(1)).find(|&e| (e - 2..=e).all(|i| genome[i].is_zero())).unwrap_or(n);
        let known = known.min(clean);
        let (mut plain, mut told) = (Individual::with_genome(genome.clone()), Individual::with_genome(genome));
        let removed = remove_zero_actions(&mut plain);
        proptest::prop_assert_eq!(remove_zero_actions_after(&mut told, known), removed);
        proptest::prop_assert_eq!(&told.genome, &plain.genome);
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]
    /// A crossover child, a mutated copy and a mutated child evaluated against their base
    /// equal their full evaluation in every field, visit map included.
    #[test]
    fn incremental_evaluation_equals_full(seed in 0u64..1_000_000, na in 3usize..70, nb in 3usize..70, c_len in 0.0..0.6f64, mode in 0u8..3, map in 0usize..2, dist in 0.5..12.0f64, camera in proptest::bool::ANY) {
        use crate::thesis::crossover::{ChildMode, Parent, ShortGenomes, crossover};
        use crate::thesis::mutation::mutate_action;
        let m = preset(["thesis-1", "thesis-2"][map]).unwrap();
        let s = Point::new(1.3, 1.3);
        let spec = crate::coverage::score::CameraSpec { scale: 0.15, d_min: 0.2, d_max: 7.0, fov_deg: 69.4, sections: 15, band_m: 0.45 };
        let objective = camera.then(|| CameraObjective::new(&m, &spec, 0.1, &[s]));
        let sc = ThesisScenario::new(m, Footprint { rot_speed: 0.7, ..Footprint::default() }, s, Point::new(9.7, 1.3), Projection::F2)
            .with_camera(objective);
        let mut rng = crate::ga::rng::stream(seed, crate::ga::rng::Purpose::Main, &[]);
        let mut scratch = EvalScratch::default();
        let mut parents = Vec::new();
        for n in [na, nb] {
            let mut ind = Individual::default();
            random_genome(&mut rng, n - 2, dist, &mut ind.genome);
            evaluate(&mut ind, &sc, Base::None, EvaluationMode::Full, &mut scratch);
            remove_zero_actions(&mut ind);
            parents.push(ind);
        }
        let both = |ind: &Individual, base: Base, scratch: &mut EvalScratch| {
            let (mut inc, mut full) = (ind.clone(), ind.clone());
            evaluate(&mut inc, &sc, base, EvaluationMode::Incremental, scratch);
            evaluate(&mut full, &sc, Base::None, EvaluationMode::Full, scratch);
            (inc, full)
        };
        let same = |a: &Individual, b: &Individual| {
            a.genome == b.genome && a.points == b.points && a.sweep == b.sweep && a.score == b.score
                && a.stable_genes == b.stable_genes && {
                let (mut x, mut y) = (Vec::new(), Vec::new());
                a.visits.for_each_count(|c, k| x.push((c, k)));
                b.visits.for_each_count(|c, k| y.push((c, k)));
                x == y
            }
        };
        let pa = Parent { genome: &parents[0].genome, points: &parents[0].points, stable: parents[0].stable_genes };
        let pb = Parent { genome: &parents[1].genome, points: &parents[1].points, stable: parents[1].stable_genes };
        let kids = crossover(pa, pb, c_len, ShortGenomes::Clamp, ChildMode::from_index(mode).unwrap(), 300, &sc.frame, &mut rng);
        for (k, genome) in kids.into_iter().flatten().enumerate() {
            let receiver = &parents[k % 2];
            let mut child = Individual::with_genome(genome);
            if rng.random_bool(0.3) {
                mutate_action(&mut child.genome, &mut rng);
            }
            let (inc, full) = both(&child, Base::Parent(receiver), &mut scratch);
            proptest::prop_assert!(same(&inc, &full), "child {k}");
        }
        // A copy whose genome was mutated, against its own former self.
        let mut copy = parents[0].clone();
        mutate_action(&mut copy.genome, &mut rng);
        let (inc, full) = both(&copy, Base::Own, &mut scratch);
        proptest::prop_assert!(same(&inc, &full), "mutated copy");
    }
}

#[test]
fn dead_genomes_are_reinitialised() {
    let map = preset("thesis-1").unwrap();
    let s = Point::new(1.3, 1.3);
    let sc = ThesisScenario::new(map, Footprint::default(), s, s, Projection::F1);
    let mut scratch = EvalScratch::default();
    let mut ind = Individual::with_genome(vec![a(0.0), a(0.0), a(0.0), a(0.0)]);
    assert!(is_dead(&ind.genome));
    let mut rng = crate::ga::rng::stream(9, crate::ga::rng::Purpose::Main, &[]);
    let init = InitParams { actions: 10, dist_max: 5.0 };
    let evals =
        correct_and_evaluate(&mut ind, &sc, Base::None, EvaluationMode::Incremental, &mut scratch, &init, &mut rng);
    assert_eq!(evals, 2);
    assert!(!is_dead(&ind.genome));
    assert!(ind.score.cov_final > 0.0);
    assert_eq!(ind.points.len(), ind.genome.len());
}
