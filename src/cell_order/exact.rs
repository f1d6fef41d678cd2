//! The exact reference: Held–Karp dynamic programming (Held & Karp 1962) over (set of swept
//! cells, last cell, its sweep choice), from the start station to the end station. Time and
//! memory grow as 2^n · (n·C)², so it is offered up to [`MAX_EXACT_CELLS`] cells.

use super::tour::{Instance, Tour};

/// The most cells the exact solver accepts.
pub const MAX_EXACT_CELLS: usize = 12;

/// The optimal tour of `inst` and its time, or `None` above [`MAX_EXACT_CELLS`] cells.
pub fn held_karp(inst: &Instance) -> Option<(Tour, f64)> {
    let n = inst.cells();
    if n > MAX_EXACT_CELLS {
        return None;
    }
    if n == 0 {
        return Some((Tour { order: Vec::new(), choice: Vec::new() }, inst.start_to_end));
    }
    // Flat candidates of every cell; states indexed [mask][flat candidate].
    let m: usize = (0..n).map(|k| inst.choices(k)).sum();
    let cell_of: Vec<usize> = (0..n).flat_map(|k| std::iter::repeat_n(k, inst.choices(k))).collect();
    let full = (1usize << n) - 1;
    let mut cost = vec![f64::INFINITY; (full + 1) * m];
    let mut parent = vec![u16::MAX; (full + 1) * m];
    for g in 0..m {
        cost[(1 << cell_of[g]) * m + g] = inst.leg(None, Some(g)) + inst.own(g);
    }
    for mask in 1..=full {
        for g in 0..m {
            let here = cost[mask * m + g];
            if here.is_infinite() || mask & (1 << cell_of[g]) == 0 {
                continue;
            }
            for (h, &cell) in cell_of.iter().enumerate() {
                let bit = 1 << cell;
                if mask & bit != 0 {
                    continue;
                }
                let t = here + inst.leg(Some(g), Some(h)) + inst.own(h);
                let slot = (mask | bit) * m + h;
                if t < cost[slot] {
                    cost[slot] = t;
                    parent[slot] = g as u16;
                }
            }
        }
    }
    let (mut g, best) = (0..m)
        .map(|g| (g, cost[full * m + g] + inst.leg(Some(g), None)))
        .fold((0, f64::INFINITY), |b, x| if x.1 < b.1 { x } else { b });
    if best.is_infinite() {
        return None;
    }
    let mut order = Vec::with_capacity(n);
    let mut choice = vec![0u16; n];
    let mut mask = full;
    loop {
        let k = cell_of[g];
        order.push(k as u32);
        choice[k] = (g - inst.flat(k, 0)) as u16;
        let p = parent[mask * m + g];
        mask &= !(1 << k);
        if mask == 0 {
            break;
        }
        g = p as usize;
    }
    order.reverse();
    Some((Tour { order, choice }, best))
}

#[cfg(test)]
mod tests {
    use super::super::tour::tests::line;
    use super::*;

    /// Every order and choice of a small instance, by brute force.
    fn brute_force(inst: &Instance) -> f64 {
        fn permute(k: usize, order: &mut Vec<u32>, inst: &Instance, best: &mut f64) {
            if k == order.len() {
                let n = order.len();
                let counts: Vec<usize> = (0..n).map(|c| inst.choices(c)).collect();
                let total: usize = counts.iter().product();
                for code in 0..total {
                    let mut rest = code;
                    let choice: Vec<u16> = counts
                        .iter()
                        .map(|&c| {
                            let x = rest % c;
                            rest /= c;
                            x as u16
                        })
                        .collect();
                    *best = best.min(inst.time(&Tour { order: order.clone(), choice }));
                }
                return;
            }
            for i in k..order.len() {
                order.swap(k, i);
                permute(k + 1, order, inst, best);
                order.swap(k, i);
            }
        }
        let mut best = f64::INFINITY;
        permute(0, &mut (0..inst.cells() as u32).collect(), inst, &mut best);
        best
    }

    #[test]
    fn held_karp_matches_brute_force() {
        for n in 1..=5 {
            let inst = line(n);
            let (tour, t) = held_karp(&inst).unwrap();
            assert!((inst.time(&tour) - t).abs() < 1e-9, "the tour has the time it claims");
            assert!((t - brute_force(&inst)).abs() < 1e-9, "n = {n}");
        }
        assert!(held_karp(&line(MAX_EXACT_CELLS + 1)).is_none());
    }
}
