use super::super::{DiversityScratch, kept_pair_distance_sum, pair_distance_sum_by};
use super::*;
use proptest::prelude::*;

/// A visit map of `words` words holding `counts` (cell, visits).
fn map(words: usize, counts: &[(u32, u32)]) -> VisitPlanes {
    VisitPlanes::from_counts(words, counts)
}

fn full(maps: &[VisitPlanes]) -> u64 {
    pair_distance_sum_by(maps.len(), |i| &maps[i], &mut DiversityScratch::default())
}

/// The kept sum, or the full pass where the kept sum declines (as `kept_pair_distance_sum`).
fn kept(sum: &mut KeptPairSum, maps: &[VisitPlanes]) -> u64 {
    sum.update(maps.len(), |i| &maps[i]).unwrap_or_else(|| full(maps))
}

/// A population changing by one member a call is counted, not passed over in full, from the
/// second call on; one that changes wholly is left to the full pass.
#[test]
fn few_changes_are_counted_and_many_passed_in_full() {
    let pool: Vec<VisitPlanes> = (0..30u32).map(|k| map(1, &[(k, 1 + k % 3), (k + 1, 1)])).collect();
    let mut sum = KeptPairSum::default();
    assert_eq!(sum.update(10, |i| &pool[i]), None, "nothing kept yet");
    for shift in 1..=5 {
        let got = sum.update(10, |i| &pool[i + shift]);
        assert_eq!(got, Some(full(&pool[shift..shift + 10])), "shift {shift}");
    }
    assert_eq!(sum.update(10, |i| &pool[i + 20]), None, "a new population");
    assert_eq!(sum.update(10, |i| &pool[i + 20]), Some(full(&pool[20..30])), "counted afresh");
}

/// A copy keeps its map's stamp and any change gives a new one.
#[test]
fn stamps_follow_the_content() {
    let a = map(2, &[(3, 2), (70, 1)]);
    let b = a.clone();
    assert_eq!(a.stamp(), b.stamp());
    let mut c = VisitPlanes::default();
    c.copy_from(&a);
    assert_eq!(c.stamp(), a.stamp());
    let same_counts = map(2, &[(3, 2), (70, 1)]);
    assert_eq!(same_counts, a);
    assert_ne!(same_counts.stamp(), a.stamp(), "made apart: equal counts, other stamps");
    c.reset(2);
    assert_ne!(c.stamp(), a.stamp());
    assert_eq!(c.stamp(), c.stamp(), "a stamp stays while the map does");
}

/// Hand-computed: a = [1,2,0,0], b = [0,1,3,0], c = [1,0,0,1] have D_ab = 5, D_ac = 3,
/// D_bc = 6; members leave, join and come back.
#[test]
fn members_leave_join_and_return() {
    let (a, b, c) = (map(1, &[(0, 1), (1, 2)]), map(1, &[(1, 1), (2, 3)]), map(1, &[(0, 1), (3, 1)]));
    let mut sum = KeptPairSum::default();
    assert_eq!(kept(&mut sum, &[a.clone(), b.clone(), c.clone()]), 14);
    assert_eq!(kept(&mut sum, &[c.clone(), a.clone()]), 3);
    assert_eq!(kept(&mut sum, std::slice::from_ref(&b)), 0);
    assert_eq!(kept(&mut sum, &[]), 0);
    assert_eq!(kept(&mut sum, &[b.clone(), b.clone(), a.clone()]), 10);
    assert_eq!(kept(&mut sum, &[b.clone(), a, c, b]), 5 + 5 + 6 + 6 + 3);
}

/// Populations that outgrow the counts' bit planes (1 → 2 → 4 → … → 300 members) and shrink
/// again count as the full pass does.
#[test]
fn counts_grow_past_their_planes() {
    let maps: Vec<VisitPlanes> = (0..300u32).map(|k| map(2, &[(k % 90, 1 + k % 4), (100 + k % 7, 1)])).collect();
    let mut sum = KeptPairSum::default();
    for n in [1, 2, 3, 4, 7, 8, 64, 127, 128, 300, 5, 255, 256] {
        assert_eq!(kept(&mut sum, &maps[..n]), full(&maps[..n]), "n = {n}");
    }
}

/// Counts of many planes (up to `2^9 − 1` visits) and maps of different widths.
#[test]
fn high_counts_and_mixed_widths() {
    let maps = vec![map(1, &[(0, 511), (3, 17)]), map(3, &[(0, 2), (150, 40)]), map(2, &[(3, 17), (70, 1)])];
    let mut sum = KeptPairSum::default();
    assert_eq!(kept(&mut sum, &maps), full(&maps));
    assert_eq!(kept(&mut sum, &maps[1..]), full(&maps[1..]));
    assert_eq!(kept(&mut sum, &maps), full(&maps));
}

/// A fleet's robots keep their sums apart: alternating channels each see their own population.
#[test]
fn channels_keep_their_own_populations() {
    let first = vec![map(1, &[(0, 1)]), map(1, &[(1, 2)])];
    let second = vec![map(1, &[(5, 3)]), map(1, &[(5, 3)]), map(1, &[(6, 1)])];
    let mut scratch = DiversityScratch::default();
    for _ in 0..3 {
        assert_eq!(kept_pair_distance_sum(2, |i| &first[i], &mut scratch, 0), full(&first));
        assert_eq!(kept_pair_distance_sum(3, |i| &second[i], &mut scratch, 1), full(&second));
    }
}

/// A random map of `words` words, counts up to `top`.
fn random_map() -> impl Strategy<Value = VisitPlanes> {
    (1usize..=3, prop::sample::select(vec![1u32, 3, 7, 15, 40]))
        .prop_flat_map(|(words, top)| (Just(words), prop::collection::vec((0..(words * 64) as u32, 1..=top), 0..40)))
        .prop_map(|(words, mut counts)| {
            counts.sort_unstable_by_key(|c| c.0);
            counts.dedup_by_key(|c| c.0);
            map(words, &counts)
        })
}

proptest! {
    /// A sequence of populations, each made of members of the previous one (kept, repeated or
    /// dropped) and new maps, gives the full pass's sum at every step.
    #[test]
    fn kept_sum_equals_the_full_pass(
        pool in prop::collection::vec(random_map(), 1..30),
        steps in prop::collection::vec(prop::collection::vec(any::<prop::sample::Index>(), 0..40), 1..8),
    ) {
        let mut sum = KeptPairSum::default();
        for picks in &steps {
            let pop: Vec<VisitPlanes> = picks.iter().map(|i| pool[i.index(pool.len())].clone()).collect();
            prop_assert_eq!(kept(&mut sum, &pop), full(&pop));
        }
    }
}

/// In a run of the thesis GA (row (e) on thesis-1, and architecture (a) with tournaments),
/// the diversity kept from generation to generation equals the full pass over each
/// generation's population.
#[test]
fn a_run_keeps_the_full_pass_diversity() {
    use crate::coverage::Footprint;
    use crate::coverage::fitness::Projection;
    use crate::geom::Point;
    use crate::map::presets::preset;
    use crate::thesis::params::{Selection, ThesisParams};
    use crate::thesis::run::ThesisGa;
    use crate::thesis::scenario::ThesisScenario;
    let s = Point::new(1.3, 1.3);
    let tournament = ThesisParams {
        selection: Selection::tournament(3),
        init_individuals: 200,
        keep: 10,
        select: 20,
        ..ThesisParams::thesis_elite()
    };
    for params in [ThesisParams::thesis_elite(), tournament] {
        let scenario =
            ThesisScenario::new(preset("thesis-1").expect("preset"), Footprint::default(), s, s, Projection::F2);
        let ga = ThesisGa { scenario, params, seed: 7, seeds: (Vec::new(), 0) };
        let mut state = ga.init(true);
        let mut scratches = ga.new_scratches();
        for _ in 0..60 {
            let effective = ga.effective(&state, state.iteration + 1, 60);
            ga.step(&mut state, effective, &mut scratches, true);
            let pop = &state.population;
            let sum = pair_distance_sum_by(pop.len(), |i| &pop[i].visits, &mut DiversityScratch::default());
            let n = pop.len() as f64;
            let full = 2.0 * sum as f64 / (n * (n - 1.0));
            assert_eq!(state.diversity, Some(full), "iteration {}", state.iteration);
        }
    }
}
