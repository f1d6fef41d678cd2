//! Counting 64 lanes at once: for a list of 64-bit masks, the number of masks that have each
//! lane set, kept as a bit-sliced binary number, and the sums over the lanes that the
//! population diversity (003 eqs. 3.17–3.19) reads off it.
//!
//! The masks are added by a carry-save adder tree (Harley–Seal): eight masks at a time reduce
//! to one carry of weight 8 without a data-dependent branch, so the cost per mask is a few
//! logic operations instead of a ripple carry whose length the branch predictor cannot guess.

/// The most bit-sliced levels a count can need (counts below `2^48`).
const LEVELS: usize = 48;

/// A carry-save adder: `(carry, sum)` of three masks, lane by lane.
#[inline(always)]
fn csa(a: u64, b: u64, c: u64) -> (u64, u64) {
    let u = a ^ b;
    ((a & b) | (u & c), u ^ c)
}

/// Adds `carry` at level `from` of the bit-sliced counter; returns the levels in use.
#[inline(always)]
fn ripple(levels: &mut [u64; LEVELS], mut carry: u64, from: usize, used: usize) -> usize {
    let mut q = from;
    while carry != 0 {
        let old = levels[q];
        levels[q] = old ^ carry;
        carry &= old;
        q += 1;
    }
    used.max(q)
}

/// `(Σ_lanes c, Σ_lanes c²)` where `c` is, per lane, the number of `masks` with the lane set.
#[inline(always)]
pub fn lane_count_sums(masks: &[u64]) -> (u64, u64) {
    let mut levels = [0u64; LEVELS];
    let (mut ones, mut twos, mut fours) = (0u64, 0u64, 0u64);
    let mut used = 3;
    let mut chunks = masks.chunks_exact(8);
    for m in &mut chunks {
        let (twos_a, o) = csa(ones, m[0], m[1]);
        let (twos_b, o) = csa(o, m[2], m[3]);
        let (fours_a, t) = csa(twos, twos_a, twos_b);
        let (twos_a, o) = csa(o, m[4], m[5]);
        let (twos_b, o) = csa(o, m[6], m[7]);
        let (fours_b, t) = csa(t, twos_a, twos_b);
        let (eights, f) = csa(fours, fours_a, fours_b);
        (ones, twos, fours) = (o, t, f);
        used = ripple(&mut levels, eights, 3, used);
    }
    for &m in chunks.remainder() {
        let c1 = ones & m;
        ones ^= m;
        let c2 = twos & c1;
        twos ^= c1;
        let c4 = fours & c2;
        fours ^= c2;
        used = ripple(&mut levels, c4, 3, used);
    }
    // Levels 0–2 may be zero (fewer than four masks); they then add nothing below.
    (levels[0], levels[1], levels[2]) = (ones, twos, fours);
    let (mut s1, mut s2) = (0u64, 0u64);
    for q in 0..used {
        let ones_q = u64::from(levels[q].count_ones());
        s1 += ones_q << q;
        s2 += ones_q << (2 * q);
        for r in q + 1..used {
            s2 += u64::from((levels[q] & levels[r]).count_ones()) << (q + r + 1);
        }
    }
    (s1, s2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Lane by lane, the plain way.
    fn by_lanes(masks: &[u64]) -> (u64, u64) {
        (0..64)
            .map(|l| masks.iter().filter(|m| (*m >> l) & 1 == 1).count() as u64)
            .fold((0, 0), |(s1, s2), c| (s1 + c, s2 + c * c))
    }

    #[test]
    fn hand_computed_counts() {
        assert_eq!(lane_count_sums(&[]), (0, 0));
        // Lane 0 in three masks, lane 1 in one: Σc = 4, Σc² = 9 + 1.
        assert_eq!(lane_count_sums(&[0b01, 0b11, 0b01]), (4, 10));
        // All 64 lanes in 1 000 masks: 64 000 and 64 · 10⁶ (the ripple above the adder tree).
        assert_eq!(lane_count_sums(&vec![u64::MAX; 1000]), (64_000, 64_000_000));
    }

    proptest! {
        #[test]
        fn equals_counting_lane_by_lane(masks in proptest::collection::vec(any::<u64>(), 0..300), sparse in any::<u64>()) {
            prop_assert_eq!(lane_count_sums(&masks), by_lanes(&masks));
            let thin: Vec<u64> = masks.iter().map(|m| m & sparse).collect();
            prop_assert_eq!(lane_count_sums(&thin), by_lanes(&thin));
        }
    }
}
