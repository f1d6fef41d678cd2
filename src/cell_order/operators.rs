//! Variation operators on tours, as small pure functions: order crossover (OX, Davis 1985),
//! inversion, insertion and swap of the order, uniform crossover and reset mutation of the
//! sweep choices.

use rand::Rng;

/// Order crossover (OX): the child keeps `a[i..j]` in place and fills the other positions,
/// from `j` on and wrapping round, with the cells of `b` in `b`'s order from `j` on.
pub fn order_crossover(a: &[u32], b: &[u32], i: usize, j: usize) -> Vec<u32> {
    let n = a.len();
    let mut taken = vec![false; n];
    for &k in &a[i..j] {
        taken[k as usize] = true;
    }
    let mut child = a.to_vec();
    let mut pos = j % n.max(1);
    for step in 0..n {
        let k = b[(j + step) % n];
        if taken[k as usize] {
            continue;
        }
        child[pos] = k;
        pos = (pos + 1) % n;
    }
    child
}

/// Reverses `order[i..=j]` (inversion).
pub fn inversion(order: &mut [u32], i: usize, j: usize) {
    order[i.min(j)..=i.max(j)].reverse();
}

/// Moves the cell at `from` to position `to` (insertion).
pub fn insertion(order: &mut Vec<u32>, from: usize, to: usize) {
    let k = order.remove(from);
    order.insert(to, k);
}

/// Two cuts `i < j` in `0..=n` for a segment of at least one element (n ≥ 1).
pub fn cuts<R: Rng + ?Sized>(n: usize, rng: &mut R) -> (usize, usize) {
    let (a, b) = (rng.random_range(0..=n), rng.random_range(0..=n));
    if a == b { (a.min(n - 1), a.min(n - 1) + 1) } else { (a.min(b), a.max(b)) }
}

/// Each cell's choice from `a` or `b` with equal odds.
pub fn uniform_choices<R: Rng + ?Sized>(a: &[u16], b: &[u16], rng: &mut R) -> Vec<u16> {
    a.iter().zip(b).map(|(&x, &y)| if rng.random::<bool>() { x } else { y }).collect()
}

/// Each cell's choice redrawn uniformly among its `counts[k]` candidates with probability `p`.
pub fn choice_mutation<R: Rng + ?Sized>(choice: &mut [u16], counts: &[usize], p: f64, rng: &mut R) {
    for (c, &n) in choice.iter_mut().zip(counts) {
        if n > 1 && rng.random::<f64>() < p {
            *c = rng.random_range(0..n) as u16;
        }
    }
}

/// One of inversion, insertion or swap, drawn with equal odds, at random positions.
pub fn mutate_order<R: Rng + ?Sized>(order: &mut Vec<u32>, rng: &mut R) {
    let n = order.len();
    if n < 2 {
        return;
    }
    let (i, j) = (rng.random_range(0..n), rng.random_range(0..n));
    match rng.random_range(0..3) {
        0 => inversion(order, i, j),
        1 => insertion(order, i, j),
        _ => order.swap(i, j),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn is_permutation(o: &[u32]) -> bool {
        let mut s = o.to_vec();
        s.sort_unstable();
        s.iter().enumerate().all(|(i, &k)| i as u32 == k)
    }

    #[test]
    fn order_crossover_by_hand() {
        // Davis's example: the segment 3 4 5 kept, the rest in b's order after the cut.
        let a = [0, 1, 2, 3, 4, 5, 6, 7];
        let b = [7, 6, 5, 4, 3, 2, 1, 0];
        let c = order_crossover(&a, &b, 3, 6);
        assert_eq!(c, vec![7, 6, 2, 3, 4, 5, 1, 0]);
        assert!(is_permutation(&c));
        // The whole of a: a itself.
        assert_eq!(order_crossover(&a, &b, 0, 8), a.to_vec());
    }

    #[test]
    fn order_mutations_keep_a_permutation() {
        let cases: &[(&str, Vec<u32>)] = &[
            ("inversion", {
                let mut o = vec![0, 1, 2, 3, 4];
                inversion(&mut o, 3, 1);
                o
            }),
            ("insertion", {
                let mut o = vec![0, 1, 2, 3, 4];
                insertion(&mut o, 0, 3);
                o
            }),
        ];
        assert_eq!(cases[0].1, vec![0, 3, 2, 1, 4], "{}", cases[0].0);
        assert_eq!(cases[1].1, vec![1, 2, 3, 0, 4], "{}", cases[1].0);
        let mut rng = crate::ga::rng::stream(5, crate::ga::rng::Purpose::Main, &[]);
        let mut o: Vec<u32> = (0..9).collect();
        for _ in 0..500 {
            mutate_order(&mut o, &mut rng);
            assert!(is_permutation(&o));
            let (i, j) = cuts(9, &mut rng);
            assert!(i < j && j <= 9);
        }
    }

    #[test]
    fn choice_operators_stay_in_range() {
        let mut rng = crate::ga::rng::stream(6, crate::ga::rng::Purpose::Main, &[]);
        let counts = [1, 4, 16];
        let mut c = vec![0u16, 3, 15];
        for _ in 0..200 {
            choice_mutation(&mut c, &counts, 0.5, &mut rng);
            assert_eq!(c[0], 0, "a cell with one candidate keeps it");
            assert!(c[1] < 4 && c[2] < 16);
        }
        let u = uniform_choices(&[1, 1, 1], &[2, 2, 2], &mut rng);
        assert!(u.iter().all(|&x| x == 1 || x == 2));
    }
}
