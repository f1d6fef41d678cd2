//! Test support: inputs placed ulp by ulp so that a scan's own arithmetic lands exactly on a
//! boundary (the half-open ends of spec §3.3), where only an exact comparison decides.

/// The `x` within 64 ulps of `start` (positive) for which `f(x) == target` exactly; `f` is
/// increasing or decreasing in `x`.
pub(crate) fn solve(f: impl Fn(f64) -> f64, increasing: bool, target: f64, start: f64) -> Option<f64> {
    let mut x = start;
    for _ in 0..64 {
        let y = f(x);
        if y == target {
            return Some(x);
        }
        x = f64::from_bits(if (y < target) == increasing { x.to_bits() + 1 } else { x.to_bits() - 1 });
    }
    None
}
