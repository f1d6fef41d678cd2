//! The memetic step: local search on one tour. The best sweep choices for a fixed order by
//! dynamic programming over the order (exact: a shortest path through one layer of candidates
//! per cell), then Or-opt (move a run of one to three cells elsewhere) and 2-opt (reverse a
//! run), first improvement, until none of the three improves. Each function returns the leg
//! reads it spent, which the search charges to the evaluation budget as a share of a tour.

use super::tour::{Instance, Tour};

/// Sets `tour.choice` to the best choices for its order; returns the leg reads.
pub fn best_choices(inst: &Instance, tour: &mut Tour) -> u64 {
    let order = &tour.order;
    if order.is_empty() {
        return 0;
    }
    let mut reads = 0u64;
    let first = order[0] as usize;
    let mut cost: Vec<f64> = (0..inst.choices(first))
        .map(|c| inst.leg(None, Some(inst.flat(first, c))) + inst.own(inst.flat(first, c)))
        .collect();
    reads += cost.len() as u64;
    let mut back: Vec<Vec<u16>> = Vec::with_capacity(order.len());
    back.push(Vec::new());
    for w in order.windows(2) {
        let (p, k) = (w[0] as usize, w[1] as usize);
        let mut next = vec![f64::INFINITY; inst.choices(k)];
        let mut arg = vec![0u16; inst.choices(k)];
        for (c2, slot) in next.iter_mut().enumerate() {
            let g2 = inst.flat(k, c2);
            for (c1, &base) in cost.iter().enumerate() {
                let t = base + inst.leg(Some(inst.flat(p, c1)), Some(g2));
                if t < *slot {
                    *slot = t;
                    arg[c2] = c1 as u16;
                }
            }
            *slot += inst.own(g2);
        }
        reads += (cost.len() * next.len()) as u64;
        cost = next;
        back.push(arg);
    }
    let last = *order.last().expect("not empty") as usize;
    let (mut c, _) = cost
        .iter()
        .enumerate()
        .map(|(c, &t)| (c, t + inst.leg(Some(inst.flat(last, c)), None)))
        .fold((0, f64::INFINITY), |best, x| if x.1 < best.1 { x } else { best });
    reads += cost.len() as u64;
    for i in (0..order.len()).rev() {
        tour.choice[order[i] as usize] = c as u16;
        if i > 0 {
            c = back[i][c] as usize;
        }
    }
    reads
}

/// The leg reads [`best_choices`] spends on `tour` (counted without reading a leg), so that a
/// search can tell whether its budget still holds them.
pub fn choice_reads(inst: &Instance, tour: &Tour) -> u64 {
    let order = &tour.order;
    let (Some(&first), Some(&last)) = (order.first(), order.last()) else { return 0 };
    let pairs: u64 = order.windows(2).map(|w| (inst.choices(w[0] as usize) * inst.choices(w[1] as usize)) as u64).sum();
    inst.choices(first as usize) as u64 + pairs + inst.choices(last as usize) as u64
}

/// One pass of Or-opt: for each run of 1–3 cells in turn, the first move of it to another
/// place that shortens the tour is made, until `max_reads` leg reads are spent (the pass then
/// stops where it is, over by at most one candidate's six); returns whether any move was made
/// and the leg reads.
pub fn or_opt(inst: &Instance, tour: &mut Tour, max_reads: u64) -> (bool, u64) {
    let n = tour.order.len() as isize;
    let mut reads = 0u64;
    let mut moved = false;
    let at = |t: &Tour, i: isize| inst.at(t, i);
    for len in 1..=3isize.min(n - 1).max(0) {
        'runs: for i in 0..=n - len {
            let (prev, first, last, next) = (at(tour, i - 1), at(tour, i), at(tour, i + len - 1), at(tour, i + len));
            let removed = inst.leg(prev, first) + inst.leg(last, next) - inst.leg(prev, next);
            // Insert between positions p and p + 1 of the tour without the run.
            for p in -1..n {
                if p >= i - 1 && p < i + len {
                    continue;
                }
                if reads >= max_reads {
                    return (moved, reads);
                }
                let (a, b) = (at(tour, p), at(tour, p + 1));
                let added = inst.leg(a, first) + inst.leg(last, b) - inst.leg(a, b);
                reads += 6;
                if added < removed - 1e-9 {
                    let run: Vec<u32> = tour.order.drain(i as usize..(i + len) as usize).collect();
                    let to = if p < i { p + 1 } else { p + 1 - len } as usize;
                    for (k, c) in run.into_iter().enumerate() {
                        tour.order.insert(to + k, c);
                    }
                    moved = true;
                    continue 'runs;
                }
            }
        }
    }
    (moved, reads)
}

/// One pass of 2-opt: every reversal of a run `i..=j` that shortens the tour, scanning in
/// order, is made (the legs inside the run are re-read: leg times are not symmetric), until
/// `max_reads` leg reads are spent (over by at most one candidate's `4 + 2n`).
pub fn two_opt(inst: &Instance, tour: &mut Tour, max_reads: u64) -> (bool, u64) {
    let n = tour.order.len() as isize;
    let mut reads = 0u64;
    let mut reversed = false;
    for i in 0..n - 1 {
        for j in i + 1..n {
            if reads >= max_reads {
                return (reversed, reads);
            }
            let before = inst.at(tour, i - 1);
            let after = inst.at(tour, j + 1);
            let mut old = inst.leg(before, inst.at(tour, i)) + inst.leg(inst.at(tour, j), after);
            let mut new = inst.leg(before, inst.at(tour, j)) + inst.leg(inst.at(tour, i), after);
            for k in i..j {
                old += inst.leg(inst.at(tour, k), inst.at(tour, k + 1));
                new += inst.leg(inst.at(tour, k + 1), inst.at(tour, k));
            }
            reads += 4 + 2 * (j - i) as u64;
            if new < old - 1e-9 {
                tour.order[i as usize..=j as usize].reverse();
                reversed = true;
            }
        }
    }
    (reversed, reads)
}

/// Best choices, Or-opt and 2-opt until none improves (at most `rounds` rounds); returns the
/// leg reads.
pub fn improve(inst: &Instance, tour: &mut Tour, rounds: usize) -> u64 {
    improve_within(inst, tour, rounds, u64::MAX)
}

/// As [`improve`], within `max_reads` leg reads (a search's evaluation budget): the passes stop
/// where the reads run out, and the best choices are set only while the budget holds their
/// reads ([`choice_reads`]), so a step overshoots by at most one candidate move of a pass
/// (`4 + 2n` reads for `n` cells). Without a limit it is exactly [`improve`].
pub fn improve_within(inst: &Instance, tour: &mut Tour, rounds: usize, max_reads: u64) -> u64 {
    let mut reads = 0u64;
    let fits = |reads: u64, tour: &Tour| reads.saturating_add(choice_reads(inst, tour)) <= max_reads;
    if fits(reads, tour) {
        reads += best_choices(inst, tour);
    }
    for _ in 0..rounds {
        if reads >= max_reads {
            break;
        }
        let (moved, r1) = or_opt(inst, tour, max_reads - reads);
        reads += r1;
        let (reversed, r2) =
            if moved || reads >= max_reads { (false, 0) } else { two_opt(inst, tour, max_reads - reads) };
        reads += r2;
        if !moved && !reversed {
            break;
        }
        if !fits(reads, tour) {
            break;
        }
        reads += best_choices(inst, tour);
    }
    reads
}

#[cfg(test)]
mod tests {
    use super::super::tour::tests::line;
    use super::*;

    #[test]
    fn best_choices_pick_the_direction_of_travel() {
        let inst = line(4);
        let mut t = Tour { order: vec![0, 1, 2, 3], choice: vec![1, 0, 1, 0] };
        let before = inst.time(&t);
        best_choices(&inst, &mut t);
        assert_eq!(t.choice, vec![0, 0, 0, 0], "left to right along the line");
        assert!(inst.time(&t) < before);
        // Back from the far end: the DP is exact, so no choice vector beats it.
        let mut back = Tour { order: vec![3, 2, 1, 0], choice: vec![0; 4] };
        best_choices(&inst, &mut back);
        for code in 0..16u16 {
            let other = Tour { order: back.order.clone(), choice: (0..4).map(|k| (code >> k) & 1).collect() };
            assert!(inst.time(&back) <= inst.time(&other) + 1e-9, "{other:?}");
        }
    }

    #[test]
    fn choice_reads_counts_what_best_choices_reads() {
        let inst = line(5);
        let mut t = Tour { order: vec![2, 0, 4, 1, 3], choice: vec![1, 0, 1, 0, 1] };
        let expected = choice_reads(&inst, &t);
        assert_eq!(best_choices(&inst, &mut t), expected);
        assert_eq!(choice_reads(&inst, &Tour { order: vec![], choice: vec![] }), 0);
    }

    #[test]
    fn local_search_untangles_a_shuffled_line() {
        let inst = line(7);
        let mut t = Tour { order: vec![3, 0, 6, 1, 5, 2, 4], choice: vec![1; 7] };
        improve(&inst, &mut t, 100);
        let forward = Tour { order: (0..7).collect(), choice: vec![0; 7] };
        assert!((inst.time(&t) - inst.time(&forward)).abs() < 1e-9, "{t:?}");
    }

    #[test]
    fn or_opt_moves_one_cell_into_place() {
        let inst = line(4);
        let mut t = Tour { order: vec![0, 2, 1, 3], choice: vec![0; 4] };
        let before = inst.time(&t);
        let (moved, _) = or_opt(&inst, &mut t, u64::MAX);
        assert!(moved && inst.time(&t) < before, "{t:?}");
        let mut s = t.order.clone();
        s.sort_unstable();
        assert_eq!(s, vec![0, 1, 2, 3]);
    }
}
