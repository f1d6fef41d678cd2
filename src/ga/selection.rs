//! Selection schemes as pure functions over fitness slices (higher is better): tournament,
//! proportionate and rank-based roulette wheels (003 §2.2.1, thesis-ga §10), the `keep` best, and
//! low-variance sampling. Shared by the thesis GA and the waypoint planner. Pareto selection
//! over two objectives (NSGA-II) is in [`nsga2`].

pub mod nsga2;

use rand::Rng;

/// Tournament ("Turn", 003 §2.2.1.1): `ts` distinct contestants drawn uniformly, the fittest
/// wins; ties go to the contestant drawn first (R19). `ts` is clamped to `[1, n]`.
pub fn tournament<R: Rng + ?Sized>(fitness: &[f64], ts: usize, rng: &mut R) -> usize {
    let n = fitness.len();
    let ts = ts.clamp(1, n);
    let contestants = rand::seq::index::sample(rng, n, ts);
    let mut best = contestants.index(0);
    for k in 1..ts {
        let c = contestants.index(k);
        if fitness[c] > fitness[best] {
            best = c;
        }
    }
    best
}

/// PRWS probabilities `p_i = f_i / Σ f` (003 §2.2.1.2); uniform when `Σ f = 0`.
pub fn proportionate_probabilities(fitness: &[f64]) -> Vec<f64> {
    let total: f64 = fitness.iter().map(|f| f.max(0.0)).sum();
    let n = fitness.len() as f64;
    if total <= 0.0 {
        return vec![1.0 / n; fitness.len()];
    }
    fitness.iter().map(|f| f.max(0.0) / total).collect()
}

/// Linear rank value `Rank(Pos) = 2 − SP + 2(SP − 1)(Pos − 1)/(n − 1)` (003 §2.2.1.3).
pub fn linear_rank(pos: f64, n: usize, sp: f64) -> f64 {
    if n <= 1 {
        return 1.0;
    }
    2.0 - sp + 2.0 * (sp - 1.0) * (pos - 1.0) / (n as f64 - 1.0)
}

/// RRWS probabilities: worst gets `Pos = 1`, best `Pos = n`, tied individuals share the mean of
/// their positions (R21); `p = Rank(Pos)/n`, so the best gets `SP/n` and the sum is 1.
pub fn rank_probabilities(fitness: &[f64], sp: f64) -> Vec<f64> {
    let n = fitness.len();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| fitness[a].total_cmp(&fitness[b]).then(a.cmp(&b)));
    let mut probs = vec![0.0; n];
    let mut k = 0;
    while k < n {
        let mut end = k + 1;
        while end < n && fitness[order[end]] == fitness[order[k]] {
            end += 1;
        }
        // Positions k+1 ..= end share their mean.
        let pos = (k + 1 + end) as f64 / 2.0;
        let p = linear_rank(pos, n, sp) / n as f64;
        for &i in &order[k..end] {
            probs[i] = p;
        }
        k = end;
    }
    probs
}

/// One spin of a roulette wheel over `cumulative` (non-decreasing, last = total).
pub fn spin<R: Rng + ?Sized>(cumulative: &[f64], rng: &mut R) -> usize {
    let total = *cumulative.last().expect("non-empty wheel");
    let x = rng.random::<f64>() * total;
    cumulative.partition_point(|&c| c <= x).min(cumulative.len() - 1)
}

/// Running sums of probabilities, for [`spin`].
pub fn cumulative(probs: &[f64]) -> Vec<f64> {
    probs
        .iter()
        .scan(0.0, |acc, p| {
            *acc += p;
            Some(*acc)
        })
        .collect()
}

/// Indices of the `k` fittest, best first; ties keep the lower index first.
pub fn best_k(fitness: &[f64], k: usize) -> Vec<usize> {
    let mut order: Vec<usize> = (0..fitness.len()).collect();
    order.sort_by(|&a, &b| fitness[b].total_cmp(&fitness[a]).then(a.cmp(&b)));
    order.truncate(k);
    order
}

/// Low-variance (stochastic universal) sampling: `count` picks with one random offset and
/// equally spaced pointers, so individual `i` is picked `⌊count·p_i⌋` or `⌈count·p_i⌉` times
/// (000 §III-A.6).
pub fn low_variance_sample<R: Rng + ?Sized>(probs: &[f64], count: usize, rng: &mut R) -> Vec<usize> {
    let step = probs.iter().sum::<f64>() / count as f64;
    low_variance_picks(probs, count, rng.random::<f64>() * step)
}

/// The picks of [`low_variance_sample`] for a given first pointer `offset` in `[0, step)`,
/// `step = Σp / count`. A pointer exactly on the boundary between two individuals picks the
/// first (the `while U > c` of the low-variance sampler); a pointer that rounding carries past
/// the last running sum picks the last individual.
pub fn low_variance_picks(probs: &[f64], count: usize, offset: f64) -> Vec<usize> {
    let total: f64 = probs.iter().sum();
    let step = total / count as f64;
    let mut pointer = offset;
    let mut out = Vec::with_capacity(count);
    let mut acc = probs[0];
    let mut i = 0;
    for _ in 0..count {
        while pointer > acc && i + 1 < probs.len() {
            i += 1;
            acc += probs[i];
        }
        out.push(i);
        pointer += step;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ga::rng::{Purpose, stream};

    #[test]
    fn tournament_of_everyone_returns_the_best() {
        let f = [0.3, 0.9, 0.1, 0.5, 0.7];
        let mut rng = stream(1, Purpose::Main, &[]);
        for _ in 0..200 {
            assert_eq!(tournament(&f, f.len(), &mut rng), 1);
        }
    }

    #[test]
    fn tournament_of_one_is_uniform() {
        let f = [0.3, 0.9, 0.1, 0.5];
        let mut rng = stream(2, Purpose::Main, &[]);
        let mut counts = [0usize; 4];
        for _ in 0..4000 {
            counts[tournament(&f, 1, &mut rng)] += 1;
        }
        assert!(counts.iter().all(|&c| (800..1200).contains(&c)), "{counts:?}");
    }

    #[test]
    fn rank_probabilities_sum_to_one_and_rise_with_rank() {
        let f = [0.2, 0.8, 0.5, 0.1, 0.9, 0.3];
        for sp in [1.0, 1.4, 2.0] {
            let p = rank_probabilities(&f, sp);
            assert!((p.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            let mut by_fitness: Vec<usize> = (0..f.len()).collect();
            by_fitness.sort_by(|&a, &b| f[a].total_cmp(&f[b]));
            for w in by_fitness.windows(2) {
                assert!(p[w[1]] >= p[w[0]]);
            }
            assert!((p[4] - sp / 6.0).abs() < 1e-12, "best gets SP/n");
            assert!((p[3] - (2.0 - sp) / 6.0).abs() < 1e-12, "worst gets (2-SP)/n");
        }
    }

    #[test]
    fn rank_ties_share_positions() {
        let p = rank_probabilities(&[0.5, 0.5, 0.1], 2.0);
        assert_eq!(p[0], p[1]);
        assert!((p.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn proportionate_is_proportional() {
        let p = proportionate_probabilities(&[1.0, 3.0, 0.0]);
        assert_eq!(p, vec![0.25, 0.75, 0.0]);
        assert_eq!(proportionate_probabilities(&[0.0, 0.0]), vec![0.5, 0.5]);
        let cum = cumulative(&p);
        let mut rng = stream(3, Purpose::Main, &[]);
        let mut counts = [0usize; 3];
        for _ in 0..8000 {
            counts[spin(&cum, &mut rng)] += 1;
        }
        assert_eq!(counts[2], 0);
        assert!((5700..6300).contains(&counts[1]), "{counts:?}");
    }

    #[test]
    fn best_k_orders_by_fitness() {
        assert_eq!(best_k(&[0.1, 0.7, 0.7, 0.3], 3), vec![1, 2, 3]);
    }

    /// R19: among equally fit contestants the one drawn first wins (a `>=` would pick the
    /// last).
    #[test]
    fn tournament_ties_go_to_the_first_drawn() {
        let fitness = [0.5; 6];
        for seed in 0..50 {
            let mut rng = stream(seed, Purpose::Main, &[]);
            let mut replay = rng.clone();
            let winner = tournament(&fitness, 4, &mut rng);
            assert_eq!(winner, rand::seq::index::sample(&mut replay, 6, 4).index(0), "seed {seed}");
        }
        // A strictly fitter contestant beats a tie drawn earlier.
        let fitness = [0.5, 0.5, 0.9, 0.5];
        let mut rng = stream(1, Purpose::Main, &[]);
        assert_eq!(tournament(&fitness, 4, &mut rng), 2);
    }

    /// The pointers start at a random offset in `[0, step)`: with two halves and one pick, each
    /// half is picked about half the time (an offset fixed at 0 would always pick the first).
    #[test]
    fn low_variance_sampling_offset_is_random() {
        let mut rng = stream(9, Purpose::Main, &[]);
        let second = (0..2000).filter(|_| low_variance_sample(&[0.5, 0.5], 1, &mut rng)[0] == 1).count();
        assert!((900..1100).contains(&second), "{second} of 2000");
        // Pointers are one step apart: four picks over four equal shares take each once.
        let picks = low_variance_sample(&[0.25; 4], 4, &mut rng);
        assert_eq!(picks, vec![0, 1, 2, 3]);
    }

    /// Hand-worked pointers: shares 0.5 / 0.5, two picks, step 0.5.
    #[test]
    fn low_variance_picks_by_hand() {
        let cases: &[(&[f64], usize, f64, &[usize])] = &[
            // Pointers 0.2, 0.7: one each.
            (&[0.5, 0.5], 2, 0.2, &[0, 1]),
            // Pointers 0, 0.5: the second lies exactly on the boundary and stays with the first.
            (&[0.5, 0.5], 2, 0.0, &[0, 0]),
            // Pointers 0.1, 0.35, 0.6, 0.85 over running sums 0.25, 0.5, 1.0.
            (&[0.25, 0.25, 0.5], 4, 0.1, &[0, 1, 2, 2]),
            // A zero share between two others is never picked.
            (&[0.5, 0.0, 0.5], 2, 0.25, &[0, 2]),
        ];
        for (probs, count, offset, want) in cases {
            assert_eq!(low_variance_picks(probs, *count, *offset), *want, "{probs:?} × {count} from {offset}");
        }
        // With the largest offset below one step, rounding carries the last of ten pointers
        // past the last running sum of [0.15, 0.15]: it picks the last individual.
        let step = 0.3 / 10.0;
        let picks = low_variance_picks(&[0.15, 0.15], 10, (1.0 - f64::EPSILON / 2.0) * step);
        assert_eq!(picks, vec![0, 0, 0, 0, 0, 1, 1, 1, 1, 1]);
    }

    /// A wheel whose total is not 1 is spun over its whole length, and a wheel of zero weights
    /// still returns an individual (the last).
    #[test]
    fn spin_covers_the_whole_wheel() {
        let cum = cumulative(&[1.0, 3.0]);
        let mut rng = stream(5, Purpose::Main, &[]);
        let second = (0..4000).filter(|_| spin(&cum, &mut rng) == 1).count();
        assert!((2850..3150).contains(&second), "{second} of 4000");
        assert_eq!(spin(&[0.0, 0.0, 0.0], &mut rng), 2);
    }

    #[test]
    fn low_variance_sampling_is_floor_or_ceil() {
        let probs = [0.05, 0.3, 0.15, 0.4, 0.1];
        let mut rng = stream(4, Purpose::Main, &[]);
        for _ in 0..200 {
            let picks = low_variance_sample(&probs, 37, &mut rng);
            for (i, p) in probs.iter().enumerate() {
                let n = picks.iter().filter(|&&k| k == i).count() as f64;
                let expected = 37.0 * p;
                assert!(n >= expected.floor() && n <= expected.ceil(), "{i}: {n} vs {expected}");
            }
        }
    }
}
