//! Pareto fronts and the 2-D hypervolume, for two objectives that are both maximised
//! (003 §4.1.2: `t_final` and `cov_final`; 000's objectives after sign changes).

/// Indices of the non-dominated points (maximising both coordinates); duplicates of a front
/// point are all kept. Sorted by the first coordinate, descending.
pub fn non_dominated(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| points[b].0.total_cmp(&points[a].0).then(points[b].1.total_cmp(&points[a].1)));
    let mut front = Vec::new();
    let mut best_y = f64::NEG_INFINITY;
    let mut last: Option<(f64, f64)> = None;
    for i in order {
        let p = points[i];
        if p.1 > best_y || last == Some(p) {
            front.push(i);
            best_y = best_y.max(p.1);
            last = Some(p);
        }
    }
    front
}

/// Whether `a` dominates `b` (at least as good in both, better in one).
pub fn dominates(a: (f64, f64), b: (f64, f64)) -> bool {
    a.0 >= b.0 && a.1 >= b.1 && (a.0 > b.0 || a.1 > b.1)
}

/// Area dominated by `points` and bounded below by `reference` (both maximised).
pub fn hypervolume_2d(points: &[(f64, f64)], reference: (f64, f64)) -> f64 {
    let front = non_dominated(points);
    let mut area = 0.0;
    let mut y_prev = reference.1;
    // Front sorted by x descending, so y ascends.
    for &i in &front {
        let (x, y) = points[i];
        if x > reference.0 && y > y_prev {
            area += (x - reference.0) * (y - y_prev);
            y_prev = y;
        }
    }
    area
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn front_and_hypervolume_by_hand() {
        let pts = [(0.9, 0.5), (0.5, 0.9), (0.6, 0.6), (0.4, 0.4), (0.7, 0.8)];
        let mut f = non_dominated(&pts);
        f.sort();
        assert_eq!(f, vec![0, 1, 4]);
        // Staircase: 0.9·0.5 + 0.7·(0.8−0.5) + 0.5·(0.9−0.8) = 0.45 + 0.21 + 0.05.
        assert!((hypervolume_2d(&pts, (0.0, 0.0)) - 0.71).abs() < 1e-12);
        assert!(dominates((0.7, 0.8), (0.6, 0.6)));
        assert!(!dominates((0.9, 0.5), (0.5, 0.9)));
    }

    #[test]
    fn dominance_by_cases() {
        let cases = [
            ((0.5, 0.5), (0.5, 0.5), false, "equal points"),
            ((0.6, 0.5), (0.5, 0.5), true, "better first, equal second"),
            ((0.5, 0.6), (0.5, 0.5), true, "equal first, better second"),
            ((0.6, 0.6), (0.5, 0.5), true, "better in both"),
            ((0.6, 0.4), (0.5, 0.5), false, "a trade-off"),
            ((0.4, 0.5), (0.5, 0.5), false, "worse first"),
            ((0.5, 0.4), (0.5, 0.5), false, "worse second"),
        ];
        for (a, b, want, what) in cases {
            assert_eq!(dominates(a, b), want, "{what}: {a:?} over {b:?}");
        }
    }

    #[test]
    fn front_drops_a_point_tied_on_one_coordinate_and_keeps_exact_duplicates() {
        // (0.6, 0.5) ties (0.9, 0.5) on the second coordinate and loses on the first.
        assert_eq!(non_dominated(&[(0.6, 0.5), (0.9, 0.5)]), vec![1]);
        assert_eq!(non_dominated(&[(0.9, 0.5), (0.9, 0.5), (0.5, 0.9)]), vec![0, 1, 2]);
    }

    #[test]
    fn hypervolume_with_a_reference_point_off_the_origin() {
        // Reference (0.2, 0.1): the staircase of (0.9, 0.5) and (0.5, 0.9) is
        // 0.7·0.4 + 0.3·0.4 = 0.40; (0.1, 0.95) lies left of the reference and adds nothing.
        let pts = [(0.9, 0.5), (0.5, 0.9), (0.1, 0.95)];
        assert!((hypervolume_2d(&pts, (0.2, 0.1)) - 0.40).abs() < 1e-12, "{}", hypervolume_2d(&pts, (0.2, 0.1)));
        assert_eq!(hypervolume_2d(&[(0.1, 0.95)], (0.2, 0.1)), 0.0);
    }
}
