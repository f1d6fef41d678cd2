use super::*;
use crate::thesis::individual::IndividualFields;

/// An individual whose visit map over one 64-cell row holds `counts`.
fn ind(counts: &[(u32, u32)]) -> Individual {
    Individual::from(IndividualFields { visits: VisitPlanes::from_counts(1, counts), ..Default::default() })
}

#[test]
fn hand_computed_distances() {
    // Maps over 4 cells: a = [1,2,0,0], b = [0,1,3,0], c = [1,0,0,1].
    let a = ind(&[(0, 1), (1, 2)]);
    let b = ind(&[(1, 1), (2, 3)]);
    let c = ind(&[(0, 1), (3, 1)]);
    assert_eq!(distance(&a, &b), 1 + 1 + 3);
    assert_eq!(distance(&a, &c), 2 + 1);
    assert_eq!(distance(&b, &c), 1 + 1 + 3 + 1);
    let pop = vec![a, b, c];
    let mut s = DiversityScratch::default();
    assert_eq!(pair_distance_sum(&pop, &mut s), 5 + 3 + 6);
    // The scratch is left clean: the same answer again.
    assert_eq!(pair_distance_sum(&pop, &mut s), 5 + 3 + 6);
    assert!((diversity(&pop, &mut s) - 14.0 / 3.0).abs() < 1e-12);
    assert_eq!(max_distance(&pop), 6);
    // Literal eq. 3.19: pairs without the last individual: D_ab = 5; 2·5/(3·4).
    assert!((diversity_literal(&pop, &mut s) - 10.0 / 12.0).abs() < 1e-12);
}

/// Counts that fill their top plane (`2^k − 1`) next to a larger population of small
/// ones: the thresholds stop at the planes' range, whatever their number.
#[test]
fn counts_at_the_top_of_their_planes() {
    for k in 1..=9u32 {
        let full = (1u32 << k) - 1;
        let pop = vec![ind(&[(0, full), (1, 1)]), ind(&[(0, 1), (63, 16)]), ind(&[(2, 3)])];
        let expected: u64 = (0..pop.len())
            .flat_map(|i| (i + 1..pop.len()).map(move |j| (i, j)))
            .map(|(i, j)| distance(&pop[i], &pop[j]))
            .sum();
        assert_eq!(pair_distance_sum(&pop, &mut DiversityScratch::default()), expected, "top count {full}");
        assert_eq!(full_pass(&pop), expected, "top count {full}");
    }
}

#[test]
fn identical_maps_have_zero_diversity() {
    let pop = vec![ind(&[(0, 2), (5, 1)]); 4];
    assert_eq!(diversity(&pop, &mut DiversityScratch::default()), 0.0);
}

/// `Div` of one member is 0, of two the one distance between them (2·D / (2·1)).
#[test]
fn diversity_of_one_and_of_two_members() {
    let (a, b) = (ind(&[(0, 1), (1, 2)]), ind(&[(1, 1), (2, 3)]));
    let mut scratch = DiversityScratch::default();
    assert_eq!(diversity(std::slice::from_ref(&a), &mut scratch), 0.0);
    assert_eq!(diversity(&[a, b], &mut scratch), 5.0);
}

/// A scratch grows with the population it serves: reused from 2 individuals to 40, it
/// gives the sums a fresh one gives.
#[test]
fn a_reused_scratch_grows_with_the_population() {
    let pop: Vec<Individual> = (0..40u32).map(|k| ind(&[(k % 7, 1 + k % 5), (20 + k % 3, 2)])).collect();
    let mut scratch = DiversityScratch::default();
    for n in [2, 3, 40] {
        let fresh = pair_distance_sum(&pop[..n], &mut DiversityScratch::default());
        assert_eq!(pair_distance_sum(&pop[..n], &mut scratch), fresh, "n = {n}");
        assert_eq!(fresh, pair_sum_by_cells(&pop[..n]));
    }
}

/// Maps of many words (here 1 000 cells: 16 words per plane) with up to six planes: the
/// kernel reads each word of each plane where it lies.
#[test]
fn wide_maps_sum_as_their_cells_do() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
    let pop: Vec<Individual> = (0..12)
        .map(|k| {
            let top = [1u32, 3, 15, 40][k % 4];
            let mut counts: Vec<(u32, u32)> = Vec::new();
            for c in 0..1000 {
                if rng.random_bool(0.3) {
                    counts.push((c, rng.random_range(1..=top)));
                }
            }
            Individual::from(IndividualFields { visits: VisitPlanes::from_counts(16, &counts), ..Default::default() })
        })
        .collect();
    assert!(pop.iter().any(|i| i.visits.planes() > 4) && pop.iter().all(|i| i.visits.plane_words() == 16));
    assert_eq!(pair_distance_sum(&pop, &mut DiversityScratch::default()), pair_sum_by_cells(&pop));
    assert_eq!(full_pass(&pop), pair_sum_by_cells(&pop));
}

/// The one-pass kernel's sum, without a kept sum.
fn full_pass(pop: &[Individual]) -> u64 {
    pair_distance_sum_by(pop.len(), |i| &pop[i].visits, &mut DiversityScratch::default())
}

/// The sum over cells of the histogram formula, cell by cell (the reference).
fn pair_sum_by_cells(pop: &[Individual]) -> u64 {
    let n = pop.len() as u64;
    let mut per_cell: std::collections::BTreeMap<u32, Vec<u32>> = Default::default();
    for ind in pop {
        ind.visits.for_each_count(|c, k| per_cell.entry(c).or_default().push(k));
    }
    per_cell
        .values()
        .map(|ks| {
            let top = *ks.iter().max().unwrap_or(&0);
            (1..=top).map(|t| ks.iter().filter(|&&k| k >= t).count() as u64).map(|c| c * (n - c)).sum::<u64>()
        })
        .sum()
}

proptest::proptest! {
    /// The thermometer of up to four planes equals the comparison with every threshold.
    #[test]
    fn thermometer_equals_the_comparisons(planes in proptest::collection::vec(proptest::prelude::any::<u64>(), 0..=4)) {
        let mut th = [0u64; LOW + 1];
        thermometer(&planes, &mut th);
        for (t, &mask) in th.iter().enumerate().take(1 << planes.len()).skip(1) {
            proptest::prop_assert_eq!(mask, at_least(&planes, t), "t = {}", t);
        }
    }

    /// The histogram sum equals the sum of pairwise distances by definition (eq. 3.17).
    #[test]
    fn pair_sum_equals_the_sum_of_pair_distances(maps in proptest::collection::vec(proptest::collection::vec(0u32..40, 64), 2..40)) {
        let pop: Vec<Individual> = maps
            .iter()
            .map(|m| ind(&m.iter().enumerate().filter(|(_, k)| **k > 0).map(|(c, k)| (c as u32, *k)).collect::<Vec<_>>()))
            .collect();
        let mut by_pairs = 0;
        for i in 0..pop.len() {
            for j in i + 1..pop.len() {
                let d: u64 = maps[i].iter().zip(&maps[j]).map(|(a, b)| u64::from(a.abs_diff(*b))).sum();
                proptest::prop_assert_eq!(distance(&pop[i], &pop[j]), d);
                by_pairs += d;
            }
        }
        proptest::prop_assert_eq!(pair_distance_sum(&pop, &mut DiversityScratch::default()), by_pairs);
        proptest::prop_assert_eq!(full_pass(&pop), by_pairs);
        proptest::prop_assert_eq!(pair_sum_by_cells(&pop), by_pairs);
    }
}
