//! Balling's maximin fitness (000 §III-A.5, eq. 4): for organism `i` with objective vector
//! `f^i` (minimised), `fitness_i = max_{j≠i} min_k (f^i_k − f^j_k)`. Negative means
//! non-dominated, positive dominated, zero weakly dominated or duplicated; lower is better.

/// Maximin fitness of every member of `objectives` (each a vector of the same length).
pub fn maximin(objectives: &[[f64; 2]]) -> Vec<f64> {
    let n = objectives.len();
    (0..n)
        .map(|i| {
            (0..n)
                .filter(|&j| j != i)
                .map(|j| (objectives[i][0] - objectives[j][0]).min(objectives[i][1] - objectives[j][1]))
                .fold(f64::NEG_INFINITY, f64::max)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hand_worked_three_points() {
        // a = (1, 4), b = (2, 2), c = (3, 3): c is dominated by b.
        // a: max(min(1−2, 4−2), min(1−3, 4−3)) = max(−1, −2) = −1
        // b: max(min(2−1, 2−4), min(2−3, 2−3)) = max(−2, −1) = −1
        // c: max(min(3−1, 3−4), min(3−2, 3−2)) = max(−1, 1) = 1
        assert_eq!(maximin(&[[1.0, 4.0], [2.0, 2.0], [3.0, 3.0]]), vec![-1.0, -1.0, 1.0]);
        // Duplicates get 0.
        assert_eq!(maximin(&[[1.0, 1.0], [1.0, 1.0]]), vec![0.0, 0.0]);
    }
}
