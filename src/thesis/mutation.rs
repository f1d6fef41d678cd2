//! Mutation (003 §3.3.3, thesis-ga §8, R15–R16): per individual, `randInit` with `P_mI`, otherwise
//! with `P_mA` one live gene is changed by `randScale` or `randAngleOffset` (½ each).

use super::genome::{Action, live, random_genome};
use super::individual::InitParams;
use crate::geom::normalise_deg;
use rand::Rng;

/// `randScale` (003 eq. 3.23): a non-zero distance is scaled by `r ~ U[0.5, 1.5]`; a zero
/// action gets the mean distance of the live genes (R16).
pub fn rand_scale<R: Rng + ?Sized>(genome: &[Action], gene: usize, rng: &mut R) -> Action {
    let g = genome[gene];
    if !g.is_zero() {
        g.with_dist(g.dist_m() * rng.random_range(0.5..=1.5))
    } else {
        let genes = &genome[live(genome.len())];
        let mean = genes.iter().map(|a| a.dist_m()).sum::<f64>() / genes.len() as f64;
        g.with_dist(mean)
    }
}

/// `randAngleOffset` (003 eq. 3.24): `α + r`, `r ~ U[0, 360]`, reduced modulo 360.
pub fn rand_angle_offset<R: Rng + ?Sized>(gene: Action, rng: &mut R) -> Action {
    Action::new(normalise_deg(gene.alpha_deg() + rng.random_range(0.0..=360.0)), gene.dist_m())
}

/// The action mutation: one live gene, uniformly chosen, gets `randScale` or
/// `randAngleOffset` with probability ½ each.
pub fn mutate_action<R: Rng + ?Sized>(genome: &mut [Action], rng: &mut R) {
    let gene = rng.random_range(live(genome.len()));
    genome[gene] =
        if rng.random_bool(0.5) { rand_scale(genome, gene, rng) } else { rand_angle_offset(genome[gene], rng) };
}

/// What [`mutate`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mutation {
    /// Nothing.
    None,
    /// `randInit`: the genome was replaced.
    Reinit,
    /// One gene was changed.
    Action,
}

/// Per-individual mutation of architecture (a) (R15): `P_mI` first; if it fires, `P_mA` is
/// skipped.
pub fn mutate<R: Rng + ?Sized>(
    genome: &mut Vec<Action>,
    p_mi: f64,
    p_ma: f64,
    init: &InitParams,
    rng: &mut R,
) -> Mutation {
    if rng.random_bool(p_mi.clamp(0.0, 1.0)) {
        random_genome(rng, init.actions, init.dist_max, genome);
        Mutation::Reinit
    } else if rng.random_bool(p_ma.clamp(0.0, 1.0)) {
        mutate_action(genome, rng);
        Mutation::Action
    } else {
        Mutation::None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ga::rng::{Purpose, stream};

    fn a(alpha_deg: f64, dist_m: f64) -> Action {
        Action::new(alpha_deg, dist_m)
    }

    #[test]
    fn rand_scale_scales_or_restores_the_mean() {
        let g = vec![a(0.0, 2.0), a(0.0, 0.0), a(0.0, 4.0), a(0.0, 9.0), a(0.0, 0.0)];
        let mut rng = stream(1, Purpose::Main, &[]);
        for _ in 0..100 {
            let s = rand_scale(&g, 0, &mut rng);
            assert!((1.0..=3.0).contains(&s.dist_m()));
        }
        // Live genes 0..=2: mean of 2, 0, 4 = 2.
        assert_eq!(rand_scale(&g, 1, &mut rng).dist_m(), 2.0);
    }

    #[test]
    fn angle_offset_stays_in_range() {
        let mut rng = stream(2, Purpose::Main, &[]);
        for _ in 0..100 {
            let m = rand_angle_offset(a(359.0, 1.0), &mut rng);
            assert!((0.0..360.0).contains(&m.alpha_deg()));
            assert_eq!(m.dist_m(), 1.0);
        }
    }

    /// eq. 3.24 by value: the new angle is `α + r` modulo 360 for the `r` the stream draws
    /// (`α − r` or `α·r` have the same range and, for `α − r`, the same distribution).
    #[test]
    fn angle_offset_adds_the_drawn_offset() {
        for (seed, alpha) in [(5, 10.0), (6, 200.0), (7, 359.5)] {
            let mut rng = stream(seed, Purpose::Main, &[]);
            let mut replay = rng.clone();
            let r: f64 = replay.random_range(0.0..=360.0);
            let m = rand_angle_offset(a(alpha, 2.0), &mut rng);
            assert!((m.alpha_deg() - (alpha + r).rem_euclid(360.0)).abs() < 1e-9, "{seed}");
        }
    }

    #[test]
    fn action_mutation_touches_one_live_gene() {
        let mut rng = stream(3, Purpose::Main, &[]);
        for _ in 0..200 {
            let before = vec![a(10.0, 1.0), a(20.0, 2.0), a(30.0, 3.0), a(40.0, 4.0), a(0.0, 0.0)];
            let mut g = before.clone();
            mutate_action(&mut g, &mut rng);
            let changed: Vec<usize> = (0..5).filter(|&i| g[i] != before[i]).collect();
            // Exactly one live gene (0..=2 of 5) changes: never none, never a station gene.
            assert!(changed.len() == 1 && changed[0] <= 2, "{changed:?}");
        }
    }

    proptest::proptest! {
        #[test]
        fn mutated_genomes_decode_inside_the_map_between_the_stations(seed in 0u64..5000, n in 3usize..60, p_mi in 0.0..1.0f64) {
            use crate::geom::Point;
            use crate::thesis::genome::{Frame, decode};
            let frame = Frame { start: Point::new(1.3, 1.3), end: Point::new(9.0, 2.0), min: Point::origin(), max: Point::new(11.0, 11.0) };
            let init = InitParams { actions: 20, dist_max: 50.0 };
            let mut rng = stream(seed, Purpose::Individual, &[]);
            let mut g = Vec::new();
            random_genome(&mut rng, n - 2, 8.0, &mut g);
            mutate(&mut g, p_mi, 1.0, &init, &mut rng);
            let mut pts = Vec::new();
            decode(&mut g, &frame, &mut pts);
            proptest::prop_assert_eq!(pts.len(), g.len());
            proptest::prop_assert_eq!(pts[0], frame.start);
            proptest::prop_assert_eq!(*pts.last().unwrap(), frame.end);
            for p in &pts {
                proptest::prop_assert!(p.x >= 0.0 && p.x <= 11.0 && p.y >= 0.0 && p.y <= 11.0);
            }
            proptest::prop_assert!(g.iter().all(|a| a.dist_m() >= 0.0 && (0.0..360.0).contains(&a.alpha_deg())));
        }
    }

    #[test]
    fn mutation_probabilities_zero_and_one() {
        let init = InitParams { actions: 5, dist_max: 1.0 };
        let mut rng = stream(4, Purpose::Main, &[]);
        let mut g = vec![a(0.0, 1.0); 10];
        assert_eq!(mutate(&mut g, 0.0, 0.0, &init, &mut rng), Mutation::None);
        assert_eq!(mutate(&mut g, 0.0, 1.0, &init, &mut rng), Mutation::Action);
        assert_eq!(mutate(&mut g, 1.0, 1.0, &init, &mut rng), Mutation::Reinit);
        assert_eq!(g.len(), 7);
    }
}
