use super::*;
use crate::ga::rng::stream;
use crate::thesis::params::Selection;

proptest::proptest! {
    /// The two survivors are the first two of a stable sort by descending fitness.
    #[test]
    fn family_survivors_equal_the_head_of_a_stable_sort(levels in proptest::collection::vec(0usize..4, 2..8)) {
        let fitness: Vec<f64> = levels.iter().map(|&l| [f64::NEG_INFINITY, 0.25, 0.5, 0.5 + 1e-16][l]).collect();
        let mut idx: Vec<usize> = (0..fitness.len()).collect();
        idx.sort_by(|&x, &y| fitness[y].total_cmp(&fitness[x]));
        proptest::prop_assert_eq!(family_survivors(&fitness), [idx[0], idx[1]]);
    }
}

#[test]
fn family_contest_keeps_the_two_best_and_children_win_ties() {
    // (fitness of [kids..., parent1, parent2], survivors)
    let cases: [(&[f64], [usize; 2]); 4] = [
        (&[0.2, 0.9, 0.5, 0.7], [1, 3]),
        (&[0.1, 0.2, 0.8, 0.9], [3, 2]),
        (&[0.5, 0.3, 0.5, 0.5], [0, 2]),
        (&[0.4, 0.4, 0.4, 0.4, 0.9, 0.1], [4, 0]),
    ];
    for (fitness, expected) in cases {
        assert_eq!(family_survivors(fitness), expected, "{fitness:?}");
    }
}

#[test]
fn adaptive_rate_spares_the_best() {
    let r = MutationRate::Adaptive { diversity_part: 0.2, k: 0.5, f_min: 0.1, f_max: 0.9 };
    assert!((r.for_fitness(0.9) - 0.1).abs() < 1e-12);
    assert!((r.for_fitness(0.1) - 0.35).abs() < 1e-12);
    assert_eq!(MutationRate::Fixed(0.3).for_fitness(0.5), 0.3);
}

// ---- The steps of both architectures, watched through a probe member ----
//
// A `Probe` stands in for an individual: its "evaluation" records what the step asked of it
// (the operator and its rates, the parent it was made from, the first draw of its stream), so
// a test can check by value who was selected, who received which child, which stream each job
// drew from, what passed on and what was put aside.

use crate::coverage::fitness::ThesisScore;
use crate::thesis::diversity::DiversityScratch;
use crate::thesis::individual::EvaluationMode;
use crate::thesis::member::ReachMask;
use rand::{RngCore, SeedableRng};

/// How a probe came to be.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
enum Made {
    /// A member of the population the step was given.
    #[default]
    Given,
    /// Re-initialised.
    Fresh,
    /// A copy of this member.
    Copy(u64),
    /// Child `k` of a crossover of `a` and `b`, received by `receiver`.
    Child { k: usize, a: u64, b: u64, receiver: u64 },
}

#[derive(Clone, Debug, Default)]
struct Probe {
    id: u64,
    fit: f64,
    made: Made,
    /// `(P_mI, P_mA)` of its job (`P_mI` is NaN for the children of architecture (b)).
    rates: Option<(f64, f64)>,
    /// The first `u64` of its job's stream.
    draw: u64,
    /// Child genes set before evaluation: `(k, a, b)`.
    genes: Option<(usize, u64, u64)>,
}

/// What the probes' crossover and evaluation do.
struct World {
    /// Children per crossover (`None`: the crossover makes none).
    children: Option<usize>,
    /// Fitness of child `k`, by `k`.
    child_fitness: Vec<f64>,
    /// Evaluations each job reports.
    evaluations: u64,
}

impl Member for Probe {
    type World = World;
    fn fitness(&self) -> f64 {
        self.fit
    }
    fn score(&self) -> ThesisScore {
        ThesisScore { fitness: self.fit, ..Default::default() }
    }
    fn genome_len(&self) -> usize {
        1
    }
    fn obstacle_cells(&self) -> u64 {
        0
    }
    /// Probes sweep nothing: an empty map.
    fn reach_mask(_: &World) -> ReachMask {
        ReachMask::default()
    }
    fn reached(&self, _: &ReachMask) -> u64 {
        0
    }
    fn cross(a: &Self, b: &Self, _: &ThesisParams, world: &World, _: &mut Rng, kids: &mut Vec<Self>) -> bool {
        let Some(c) = world.children else { return false };
        kids.resize_with(c, Default::default);
        for (k, kid) in kids.iter_mut().enumerate() {
            kid.genes = Some((k, a.id, b.id));
        }
        true
    }
    fn vary_and_evaluate(
        &mut self,
        op: Op,
        origin: Origin<'_, Self>,
        world: &World,
        _: &Variation,
        _: &mut EvalScratch,
        rng: &mut Rng,
    ) -> u64 {
        self.draw = rng.next_u64();
        self.rates = match op {
            Op::Mutate { p_mi, p_ma } => Some((p_mi, p_ma)),
            Op::MutateAction { p_ma } => Some((f64::NAN, p_ma)),
            Op::Reinit | Op::Evaluate => None,
        };
        self.made = match origin {
            Origin::New => Made::Fresh,
            Origin::Copy => Made::Copy(self.id),
            Origin::Child(parent) => {
                let (k, a, b) = self.genes.take().expect("a child holds its genes");
                self.fit = world.child_fitness[k];
                Made::Child { k, a, b, receiver: parent.id }
            }
        };
        if self.made == Made::Fresh {
            self.fit = 0.0;
        }
        self.id = self.draw;
        world.evaluations
    }
    fn reevaluate(&mut self, _: &World, _: EvaluationMode, _: &mut EvalScratch) -> u64 {
        unreachable!("the steps do not re-evaluate")
    }
    fn diversity(_: &[Self], _: &mut DiversityScratch) -> f64 {
        unreachable!("the steps do not read diversity")
    }
    fn max_distance(_: &[Self]) -> u64 {
        unreachable!("the steps do not read diversity")
    }
}

/// A population of probes with ids 0, 1, … and these fitnesses.
fn probes(fitness: &[f64]) -> Vec<Probe> {
    fitness.iter().enumerate().map(|(i, &fit)| Probe { id: i as u64, fit, ..Default::default() }).collect()
}

fn params(selection: Selection, keep: usize, select: usize, pop_min: usize) -> ThesisParams {
    ThesisParams { selection, keep, select, pop_min, ..ThesisParams::thesis_elite() }
}

fn effective(p_c: f64, p_mi: f64, p_ma: MutationRate) -> Effective {
    Effective { p_c, p_mi, p_ma, tournament_size: 2, pressure: 2.0 }
}

/// No crossover, no re-initialisation, a fixed `P_mA`: members are only selected and copied.
fn quiet() -> Effective {
    effective(0.0, 0.0, MutationRate::Fixed(0.1))
}

const SEED: u64 = 17;
const ITERATION: u32 = 5;

/// The first `u64` of the job stream of `slot` in iteration [`ITERATION`].
fn slot_draw(slot: usize) -> u64 {
    stream(SEED, Purpose::Individual, &[u64::from(ITERATION), slot as u64]).next_u64()
}

struct Outcome {
    next: Vec<Probe>,
    evaluations: u64,
    spare: Vec<Probe>,
}

fn step(pop: Vec<Probe>, p: &ThesisParams, e: Effective, world: &World, rng: &mut Rng) -> Outcome {
    let generation =
        Generation { scenario: world, params: p, effective: e, seed: SEED, iteration: ITERATION, bounds: &[] };
    let mut spare = Vec::new();
    let mut scratches = vec![EvalScratch::default(); 2];
    let (next, evaluations) = match p.selection.draw() {
        None => generation.step_b(pop, rng, &mut scratches, &mut spare),
        Some(draw) => generation.step_a(draw, pop, rng, &mut scratches, &mut spare),
    };
    Outcome { next, evaluations, spare }
}

fn no_crossover() -> World {
    World { children: None, child_fitness: Vec::new(), evaluations: 3 }
}

fn main_rng() -> Rng {
    Rng::seed_from_u64(99)
}

/// The parents of architecture (a)'s copies, pair by pair (`P_c` = 0: each pair is copied).
fn copied_pairs(next: &[Probe], keep: usize) -> Vec<(u64, u64)> {
    let parent = |m: &Probe| match m.made {
        Made::Copy(q) => q,
        other => panic!("expected a copy, got {other:?}"),
    };
    next[keep..].chunks_exact(2).map(|c| (parent(&c[0]), parent(&c[1]))).collect()
}

#[test]
fn prws_selects_in_proportion_to_fitness() {
    // Member 2 holds the whole wheel: every parent is member 2, the redraw included.
    let p = params(Selection::prws(), 0, 6, 0);
    let out = step(probes(&[0.0, 0.0, 1.0, 0.0]), &p, quiet(), &no_crossover(), &mut main_rng());
    assert_eq!(copied_pairs(&out.next, 0), vec![(2, 2); 6]);
}

#[test]
fn rrws_with_full_pressure_never_selects_the_worst() {
    // SP = 2 gives the worst rank the weight 2 − SP = 0 (003 §2.2.1.3).
    let p = params(Selection::rrws(2.0), 0, 40, 0);
    let out = step(probes(&[0.5, 0.1, 0.9]), &p, quiet(), &no_crossover(), &mut main_rng());
    let pairs = copied_pairs(&out.next, 0);
    assert_eq!(pairs.len(), 40);
    assert!(pairs.iter().all(|&(a, b)| a != 1 && b != 1), "{pairs:?}");
    assert!(pairs.iter().any(|&(a, _)| a == 0) && pairs.iter().any(|&(a, _)| a == 2));
}

#[test]
fn the_second_parent_is_redrawn_until_it_differs_from_the_first() {
    // Two members and uniform picks (TS 1): a pair of one member twice survives ten redraws
    // with probability 2^-11, where a single draw gives it half the time.
    let p = params(Selection::tournament(1), 0, 40, 0);
    let e = Effective { tournament_size: 1, ..quiet() };
    let out = step(probes(&[0.5, 0.6]), &p, e, &no_crossover(), &mut main_rng());
    let pairs = copied_pairs(&out.next, 0);
    assert_eq!(pairs.len(), 40);
    let same = pairs.iter().filter(|(a, b)| a == b).count();
    assert!(same <= 1, "{same} of 40 pairs are one member twice");
}

#[test]
fn a_population_of_one_is_paired_with_itself_without_redraws() {
    // PRWS on one member: each pair draws two spins and the crossover decision, one u64 (two
    // ChaCha words) each; redrawing a second parent that cannot differ would draw more.
    let p = params(Selection::prws(), 0, 5, 0);
    let mut rng = main_rng();
    let before = rng.get_word_pos();
    let out = step(probes(&[0.5]), &p, quiet(), &no_crossover(), &mut rng);
    assert_eq!(copied_pairs(&out.next, 0), vec![(0, 0); 5]);
    assert_eq!(rng.get_word_pos() - before, 5 * 3 * 2);
}

#[test]
fn architecture_a_children_go_to_their_receivers_with_their_rates_and_slots() {
    // Four children per crossover: child k is received by the first parent for even k, by
    // the second for odd k, and mutated with the adaptive P_mA of its receiver's fitness.
    let fitness = [0.2, 0.5, 0.9, 0.4];
    let p = params(Selection::tournament(2), 1, 3, 0);
    let rate = MutationRate::Adaptive { diversity_part: 0.2, k: 0.5, f_min: 0.2, f_max: 0.9 };
    let world = World { children: Some(4), child_fitness: vec![0.1; 4], evaluations: 3 };
    let out = step(probes(&fitness), &p, effective(1.0, 0.25, rate), &world, &mut main_rng());
    assert_eq!(out.next.len(), 1 + 3 * 4);
    assert_eq!((out.next[0].id, out.next[0].made), (2, Made::Given), "the elite copy passes unchanged");
    for (slot, child) in out.next[1..].iter().enumerate() {
        let Made::Child { k, a, b, receiver } = child.made else { panic!("{:?}", child.made) };
        assert_eq!(k, slot % 4);
        assert_eq!(receiver, if k % 2 == 0 { a } else { b }, "child {k} of ({a}, {b})");
        assert_eq!(child.rates, Some((0.25, rate.for_fitness(fitness[receiver as usize]))));
        assert_eq!(child.draw, slot_draw(slot), "job {slot} draws from its own slot's stream");
    }
    assert_eq!(out.evaluations, 3 * 12);
}

#[test]
fn architecture_a_refills_to_pop_min_from_the_members_left() {
    // keep 1 + 2 copies < Pop_min 6: three of the nine members left pass on unchanged (R22);
    // the six others are put aside for reuse.
    let fitness = [0.3, 0.1, 0.8, 0.5, 0.2, 0.6, 0.7, 0.4, 0.05, 0.15];
    let p = params(Selection::tournament(2), 1, 1, 6);
    let out = step(probes(&fitness), &p, quiet(), &no_crossover(), &mut main_rng());
    assert_eq!(out.next.len(), 6);
    assert_eq!(out.next[0].id, 2);
    assert!(matches!((out.next[1].made, out.next[2].made), (Made::Copy(_), Made::Copy(_))));
    let refilled: Vec<u64> = out.next[3..].iter().map(|m| m.id).collect();
    assert!(out.next[3..].iter().all(|m| m.made == Made::Given && m.id != 2), "{refilled:?}");
    let mut ids: Vec<u64> = refilled.iter().chain(out.spare.iter().map(|m| &m.id)).copied().collect();
    ids.sort_unstable();
    assert_eq!(ids, vec![0, 1, 3, 4, 5, 6, 7, 8, 9], "each member left is refilled or put aside");
    assert_eq!(out.evaluations, 3 * 2);
}

#[test]
fn architecture_a_without_refill_keeps_its_size() {
    // keep 2 + 2·2 copies = Pop_min 6: nothing is refilled, and the refill draws nothing.
    let p = params(Selection::tournament(2), 2, 2, 6);
    let fitness = [0.3, 0.1, 0.8, 0.5, 0.2, 0.6, 0.7];
    let mut with_refill_off = main_rng();
    let out = step(probes(&fitness), &p, quiet(), &no_crossover(), &mut with_refill_off);
    assert_eq!(out.next.len(), 6);
    let unrefilled = params(Selection::tournament(2), 2, 2, 0);
    let mut reference = main_rng();
    step(probes(&fitness), &unrefilled, quiet(), &no_crossover(), &mut reference);
    assert_eq!(with_refill_off.get_word_pos(), reference.get_word_pos());
}

#[test]
fn architecture_b_keeps_an_odd_member_and_every_member_apart() {
    // P_c = 0, P_mI = 0: every member passes on unchanged, the odd one included.
    let p = params(Selection::Elite, 0, 0, 5);
    let out = step(probes(&[0.1, 0.2, 0.3, 0.4, 0.5]), &p, quiet(), &no_crossover(), &mut main_rng());
    let mut ids: Vec<u64> = out.next.iter().map(|m| m.id).collect();
    ids.sort_unstable();
    assert_eq!(ids, vec![0, 1, 2, 3, 4]);
    assert!(out.next.iter().all(|m| m.made == Made::Given));
    assert_eq!(out.evaluations, 0);
}

#[test]
fn architecture_b_reinitialises_members_apart_with_p_mi() {
    // P_mI = 1: all four members apart are replaced by fresh ones, which pass on; the old
    // ones are put aside.
    let p = params(Selection::Elite, 0, 0, 4);
    let out = step(
        probes(&[0.1, 0.2, 0.3, 0.4]),
        &p,
        effective(0.0, 1.0, MutationRate::Fixed(0.1)),
        &no_crossover(),
        &mut main_rng(),
    );
    assert_eq!(out.next.len(), 4);
    assert!(out.next.iter().all(|m| m.made == Made::Fresh && m.rates.is_none()));
    let mut left: Vec<u64> = out.spare.iter().map(|m| m.id).collect();
    left.sort_unstable();
    assert_eq!(left, vec![0, 1, 2, 3]);
    assert_eq!(out.evaluations, 4 * 3);
}

#[test]
fn a_member_re_initialised_by_p_mi_goes_on_with_its_slot_s_stream() {
    // P_mI = 0.5: a member apart is re-initialised when the first draw of its slot's stream
    // says so, and its new genome is drawn from the same stream, after that draw.
    let p = params(Selection::Elite, 0, 0, 16);
    let out =
        step(probes(&[0.5; 16]), &p, effective(0.0, 0.5, MutationRate::Fixed(0.1)), &no_crossover(), &mut main_rng());
    let mut expected: Vec<u64> = (0..16)
        .filter_map(|slot| {
            let mut s = stream(SEED, Purpose::Individual, &[u64::from(ITERATION), slot as u64]);
            s.random_bool(0.5).then(|| s.next_u64())
        })
        .collect();
    let mut fresh: Vec<u64> = out.next.iter().filter(|m| m.made == Made::Fresh).map(|m| m.draw).collect();
    expected.sort_unstable();
    fresh.sort_unstable();
    assert!(!fresh.is_empty() && fresh.len() < 16, "{} of 16 re-initialised", fresh.len());
    assert_eq!(fresh, expected);
    assert_eq!(out.evaluations, 3 * fresh.len() as u64);
}

#[test]
fn architecture_b_families_keep_their_two_best_with_receivers_and_slots() {
    // Four children per family, fitter than both parents, the fittest last: each family keeps
    // children 3 and 2, received by the second and the first parent.
    let p = params(Selection::Elite, 0, 0, 4);
    let world = World { children: Some(4), child_fitness: vec![0.6, 0.7, 0.8, 0.9], evaluations: 2 };
    let rate = MutationRate::Adaptive { diversity_part: 0.2, k: 0.5, f_min: 0.1, f_max: 0.4 };
    let fitness = [0.1, 0.2, 0.3, 0.4];
    let out = step(probes(&fitness), &p, effective(1.0, 0.0, rate), &world, &mut main_rng());
    assert_eq!(out.next.len(), 4);
    let draws: Vec<u64> = (0..8).map(slot_draw).collect();
    for (family, pair) in out.next.chunks_exact(2).enumerate() {
        for (child, k) in pair.iter().zip([3, 2]) {
            let Made::Child { k: got, a, b, receiver } = child.made else { panic!("{:?}", child.made) };
            assert_eq!(got, k);
            assert_eq!(receiver, if k % 2 == 0 { a } else { b });
            assert!(child.rates.unwrap().0.is_nan());
            assert_eq!(child.rates.unwrap().1, rate.for_fitness(fitness[receiver as usize]));
            assert_eq!(child.draw, draws[4 * family + k], "family {family} child {k}");
        }
    }
    // The losers (two children and two parents per family) are put aside, as many as the
    // generation made (eight), so that the next one finds a member to reuse for each child.
    assert_eq!(out.spare.len(), 8);
    assert_eq!(out.evaluations, 8 * 2);
}
