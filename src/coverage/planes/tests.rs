use super::*;
use proptest::prelude::*;

fn counts(v: &VisitPlanes) -> Vec<(u32, u32)> {
    let mut c = Vec::new();
    v.for_each_count(|cell, k| c.push((cell, k)));
    c
}

#[test]
fn visits_carry_into_new_planes_and_borrow_back() {
    let mut v = VisitPlanes::default();
    v.reset(2);
    assert_eq!(v.add(0, 0b11), 0b11, "cells 0 and 1 were unvisited");
    assert_eq!(v.planes(), 1);
    assert_eq!(v.add(0, 0b01), 0, "cell 0 goes to 2: a carry into a new plane");
    assert_eq!(v.planes(), 2);
    assert_eq!(v.add(0, 0b01), 0);
    assert_eq!(v.add(1, 0b10), 0b10);
    assert_eq!(counts(&v), [(0, 3), (1, 1), (65, 1)]);
    // Cell 0 holds 3 = 0b11, cell 1 holds 1, cell 65 (word 1, bit 1) holds 1.
    assert_eq!([v.word(0, 0), v.word(1, 0), v.word(0, 1), v.word(1, 1), v.word(2, 0)], [0b11, 0b01, 0b10, 0, 0]);
    // Word-major: word 0's planes, then word 1's.
    assert_eq!(v.plane_data(), [0b11, 0b01, 0b10, 0]);
    // 3 → 2 borrows nothing past plane 0 and leaves cell 0 visited; cell 1 is left unvisited.
    assert_eq!(v.remove(0, 0b11), 0b10);
    assert_eq!(counts(&v), [(0, 2), (65, 1)]);
    assert_eq!(v.remove(0, 0b01), 0, "2 → 1 borrows from plane 1");
    assert_eq!(v.remove(0, 0b01), 0b01);
    assert_eq!(counts(&v), [(65, 1)]);
    assert_eq!(v.planes(), 2, "planes stay once made");
    let mut copy = VisitPlanes::default();
    copy.copy_from(&v);
    assert_eq!(copy, v);
    assert_eq!(VisitPlanes::from_counts(2, &[(0, 3), (1, 1), (65, 1)]).plane_data(), [0b11, 0b01, 0b10, 0]);
}

fn mask() -> impl Strategy<Value = u64> {
    prop_oneof![Just(u64::MAX), Just(1u64), Just(0u64), Just(0x8000_0000_0000_0001), any::<u64>()]
}

proptest! {
    /// An edit gives the map that adding or removing its masks one by one gives, and counts
    /// the countable cells those report; both agree with a count per cell. A new plane in
    /// the middle of an edit is included, and so are counts of 256 and more (`heavy` adds
    /// up to 299 visits to the cells of one mask first), whose nine planes take the loop
    /// that is not unrolled.
    #[test]
    fn an_edit_equals_its_masks_one_by_one_and_a_count_per_cell(
        words in 1usize..4,
        heavy in (0usize..300, 0usize..4, mask()),
        edits in proptest::collection::vec((0usize..4, mask(), any::<bool>()), 0..80),
        countable in proptest::collection::vec(mask(), 4),
    ) {
        let (repeat, heavy_word, heavy_mask) = heavy;
        let heavy = std::iter::repeat_n(((heavy_word % words) as u32, heavy_mask), repeat);
        let masks: Vec<(u32, u64)> = heavy.chain(edits.iter().map(|&(i, m, _)| ((i % words) as u32, m))).collect();
        let removed: Vec<(u32, u64)> =
            masks[repeat..].iter().zip(&edits).filter(|(_, e)| e.2).map(|(m, _)| *m).rev().collect();
        let countable = &countable[..words];
        let mut model = vec![0u32; words * 64];
        let (mut edited, mut single) = (VisitPlanes::default(), VisitPlanes::default());
        edited.reset(words);
        single.reset(words);
        let mut fresh_countable = 0;
        for &(i, m) in &masks {
            let i = i as usize;
            let fresh = (0..64).filter(|b| m >> b & 1 == 1 && model[i * 64 + b] == 0).fold(0, |f, b| f | 1 << b);
            (0..64).filter(|b| m >> b & 1 == 1).for_each(|b| model[i * 64 + b] += 1);
            prop_assert_eq!(single.add(i, m), fresh);
            fresh_countable += u64::from((fresh & countable[i]).count_ones());
        }
        prop_assert_eq!(edited.edit::<true>(&masks, countable), fresh_countable);
        prop_assert_eq!(&edited, &single);
        let mut left_countable = 0;
        for &(i, m) in &removed {
            let i = i as usize;
            (0..64).filter(|b| m >> b & 1 == 1).for_each(|b| model[i * 64 + b] -= 1);
            let left = (0..64).filter(|b| m >> b & 1 == 1 && model[i * 64 + b] == 0).fold(0, |f, b| f | 1 << b);
            prop_assert_eq!(single.remove(i, m), left);
            left_countable += u64::from((left & countable[i]).count_ones());
        }
        prop_assert_eq!(edited.edit::<false>(&removed, countable), left_countable);
        prop_assert_eq!(&edited, &single);
        let want: Vec<(u32, u32)> = model.iter().enumerate().filter(|c| *c.1 > 0).map(|(c, &k)| (c as u32, k)).collect();
        prop_assert_eq!(counts(&edited), want);
    }
}
