use super::*;
use crate::ga::rng::{Purpose, stream};
use crate::thesis::genome::{decode, random_genome};
use ShortGenomes::{Clamp, Literal};
use proptest::prelude::*;

#[test]
fn worked_example_of_section_3_3_2_1() {
    // G_len = 30, C_len = 0.5 → absShare = 15, CP1 ∈ {2..14}, CP2 ∈ {CP1+1 ..= CP1+15}.
    assert_eq!(abs_share(30, 0.5), 15);
    let mut rng = stream(1, Purpose::Main, &[]);
    let (mut seen_lo, mut seen_hi) = (usize::MAX, 0);
    for _ in 0..5000 {
        let (a0, a1) = draw_block(30, 0.5, Literal, &mut rng).unwrap();
        let (cp1, cp2) = (a0 + 1, a1 + 1);
        assert!((2..=14).contains(&cp1), "{cp1}");
        assert!(cp2 > cp1 && cp2 <= cp1 + 15);
        seen_lo = seen_lo.min(cp1);
        seen_hi = seen_hi.max(cp1);
    }
    assert_eq!((seen_lo, seen_hi), (2, 14));
    // CP1 = 3, CP2 = 8 shares positions 3..7 (five genes) = 0-based 2..7.
    let a: Vec<Action> = (0..30).map(|i| Action::new(i as f64, 1.0)).collect();
    let b: Vec<Action> = (0..30).map(|i| Action::new(100.0 + i as f64, 1.0)).collect();
    let mut child = vec![Action::new(0.0, 9.0); 40];
    splice_into(&mut child, &a, (2, 7), &b, (2, 7));
    assert_eq!(child.len(), 30, "what the buffer held before is gone");
    let angles: Vec<f64> = child.iter().map(|x| x.alpha_deg()).collect();
    assert_eq!(&angles[..9], &[0.0, 1.0, 102.0, 103.0, 104.0, 105.0, 106.0, 7.0, 8.0]);
}

#[test]
fn too_short_parents_do_not_cross() {
    let mut rng = stream(2, Purpose::Main, &[]);
    assert!(draw_block(3, 0.2, Literal, &mut rng).is_none());
    assert!(draw_block(4, 0.2, Literal, &mut rng).is_some());
    assert!(draw_block(10, 0.8, Literal, &mut rng).is_none());
    assert!(draw_block(3, 0.2, Clamp, &mut rng).is_none(), "no gene between the first and the connector");
}

#[test]
fn clamped_share_table() {
    // (n, C_len, literal absShare, literal can cross, clamped share)
    for (n, c_len, literal, crosses, clamped) in [
        (3, 0.5, 1, false, None),
        (4, 0.2, 1, true, Some(1)),
        (5, 0.2, 1, true, Some(2)),
        (10, 0.8, 8, false, Some(7)),
        (10, 0.1, 1, true, Some(2)),
        (13, 0.8, 10, true, Some(10)),
        (30, 0.5, 15, true, Some(15)),
        (300, 0.2, 60, true, Some(60)),
    ] {
        assert_eq!(abs_share(n, c_len), literal, "n = {n}, C_len = {c_len}");
        assert_eq!(Literal.share(n, c_len).is_some(), crosses, "n = {n}, C_len = {c_len}");
        assert_eq!(Clamp.share(n, c_len), clamped, "n = {n}, C_len = {c_len}");
    }
}

#[test]
fn clamped_blocks_of_short_parents_span_every_allowed_cut() {
    // n = 10, C_len = 0.8: literally no crossover; clamped to absShare = 7, so CP_1 = 2 and
    // CP_2 ∈ {3, …, 9}: blocks [1, CP_2 − 1) of 1 to 7 genes, never the connector (8) or E.
    let mut rng = stream(7, Purpose::Main, &[]);
    let mut lengths = std::collections::BTreeSet::new();
    for _ in 0..2000 {
        let (a0, a1) = draw_block(10, 0.8, Clamp, &mut rng).unwrap();
        assert_eq!(a0, 1);
        assert!(a1 <= 8);
        lengths.insert(a1 - a0);
    }
    assert_eq!(lengths.into_iter().collect::<Vec<_>>(), (1..=7).collect::<Vec<_>>());
    // C_len·n < 2 (n = 9, C_len = 0.2): literal blocks are one gene, clamped ones one or two.
    let mut seen = std::collections::BTreeSet::new();
    for _ in 0..2000 {
        let (a0, a1) = draw_block(9, 0.2, Literal, &mut rng).unwrap();
        assert_eq!(a1 - a0, 1);
        let (a0, a1) = draw_block(9, 0.2, Clamp, &mut rng).unwrap();
        seen.insert(a1 - a0);
    }
    assert_eq!(seen.into_iter().collect::<Vec<_>>(), vec![1, 2]);
}

#[test]
fn short_parents_cross_and_change_length_only_when_clamped() {
    let (ga, pa) = parent(21, 9);
    let (gb, pb) = parent(22, 10);
    let (a, b) = (Parent { genome: &ga, points: &pa, stable: 0 }, Parent { genome: &gb, points: &pb, stable: 0 });
    let mut rng = stream(8, Purpose::Individual, &[]);
    assert!(crossover(a, b, 0.8, Literal, ChildMode::Changing, 300, &frame(), &mut rng).is_none());
    let mut lengths = std::collections::BTreeSet::new();
    for _ in 0..200 {
        let kids = crossover(a, b, 0.8, Clamp, ChildMode::Changing, 300, &frame(), &mut rng).expect("clamped");
        assert_eq!(kids[0].len() + kids[1].len(), 19, "genes are exchanged, not made or lost");
        lengths.insert(kids[0].len());
        // Small C_len: literal one-gene blocks keep the lengths.
        let kids = crossover(a, b, 0.15, Literal, ChildMode::Changing, 300, &frame(), &mut rng).unwrap();
        assert_eq!((kids[0].len(), kids[1].len()), (9, 10));
    }
    assert!(lengths.len() > 3, "clamped children take several lengths: {lengths:?}");
}

fn frame() -> Frame {
    Frame { start: Point::new(1.3, 1.3), end: Point::new(1.3, 1.3), min: Point::origin(), max: Point::new(11.0, 11.0) }
}

fn parent(seed: u64, n: usize) -> (Vec<Action>, Vec<Point>) {
    let mut rng = stream(seed, Purpose::Main, &[]);
    let mut g = Vec::new();
    random_genome(&mut rng, n - 2, 3.0, &mut g);
    let mut p = Vec::new();
    decode(&mut g, &frame(), &mut p);
    (g, p)
}

fn close(p: Point, q: Point) -> bool {
    (p - q).norm() < 1e-6
}

#[test]
fn preserving_child_keeps_absolute_positions() {
    let (ga, pa) = parent(3, 20);
    let (gb, pb) = parent(4, 16);
    let (a, b) = (Parent { genome: &ga, points: &pa, stable: 0 }, Parent { genome: &gb, points: &pb, stable: 0 });
    let mut child = preserving_child(a, (4, 9), b, (3, 6));
    let mut pts = Vec::new();
    decode(&mut child, &frame(), &mut pts);
    // Prefix 0..=3 from A, then B's viewpoints 3..=6, then A's from 10 on.
    for i in 0..4 {
        assert!(close(pts[i], pa[i]));
    }
    for (k, j) in (3..=6).enumerate() {
        assert!(close(pts[4 + k], pb[j]), "block viewpoint {j}");
    }
    for (k, j) in (10..20).enumerate() {
        assert!(close(pts[8 + k], pa[j]), "suffix viewpoint {j}");
    }
}

#[test]
fn changing_child_keeps_relative_moves_and_the_receiver_suffix() {
    // Short moves from the map centre never leave the map, so nothing is clamped.
    let centre = Frame { start: Point::new(5.5, 5.5), end: Point::new(5.5, 5.5), ..frame() };
    let make = |seed: u64, n: usize| {
        let mut rng = stream(seed, Purpose::Main, &[]);
        let mut g = Vec::new();
        random_genome(&mut rng, n - 2, 0.25, &mut g);
        let mut p = Vec::new();
        decode(&mut g, &centre, &mut p);
        (g, p)
    };
    let ((ga, pa), (gb, pb)) = (make(5, 20), make(6, 16));
    let (a, b) = (Parent { genome: &ga, points: &pa, stable: 0 }, Parent { genome: &gb, points: &pb, stable: 0 });
    let mut child = changing_child(a, (4, 9), b, (3, 6), &centre);
    let mut pts = Vec::new();
    decode(&mut child, &centre, &mut pts);
    for i in 0..=4 {
        assert!(close(pts[i], pa[i]));
    }
    // The inserted block keeps B's relative moves from wherever A left off.
    for (k, j) in (3..6).enumerate() {
        assert!(((pts[5 + k] - pts[4 + k]) - (pb[j + 1] - pb[j])).norm() < 1e-9);
    }
    // Child gene 7 was A's gene 9; from viewpoint 8 on the child follows A from 10.
    for (k, j) in (10..20).enumerate() {
        assert!(close(pts[8 + k], pa[j]), "suffix viewpoint {j}");
    }
}

/// The children of one crossover, by value: which interpretations come out, in which
/// order, for each `C_child` (003 Figs. 3.6–3.7): changing A←B, changing B←A, then
/// preserving A←B, preserving B←A, each from the same two drawn blocks.
#[test]
fn children_by_mode_are_the_named_interpretations_in_order() {
    let (ga, pa) = parent(11, 24);
    let (gb, pb) = parent(12, 18);
    let (a, b) = (Parent { genome: &ga, points: &pa, stable: 0 }, Parent { genome: &gb, points: &pb, stable: 0 });
    for (mode, seed) in [(ChildMode::Changing, 1), (ChildMode::Preserving, 2), (ChildMode::Both, 3)] {
        let mut rng = stream(seed, Purpose::Individual, &[]);
        let mut replay = rng.clone();
        let kids = crossover(a, b, 0.3, Literal, mode, 1000, &frame(), &mut rng).expect("long parents always cross");
        let (ba, bb) =
            (draw_block(24, 0.3, Literal, &mut replay).unwrap(), draw_block(18, 0.3, Literal, &mut replay).unwrap());
        let changing = [changing_child(a, ba, b, bb, &frame()), changing_child(b, bb, a, ba, &frame())];
        let preserving = [preserving_child(a, ba, b, bb), preserving_child(b, bb, a, ba)];
        let expected: Vec<Vec<Action>> = match mode {
            ChildMode::Changing => changing.to_vec(),
            ChildMode::Preserving => preserving.to_vec(),
            ChildMode::Both => changing.into_iter().chain(preserving).collect(),
        };
        assert_eq!(kids, expected, "{mode:?}");
        // Each child is its receiver's genome with the donor's block: lengths add up.
        let (la, lb) = (ba.1 - ba.0, bb.1 - bb.0);
        assert_eq!(kids[0].len(), 24 - la + lb);
        assert_eq!(kids[1].len(), 18 - lb + la);
        assert_ne!(kids[0], kids[1], "the second child is not a copy of the first");
    }
    // The two interpretations of one cut differ (the inserted genes are re-aimed in one
    // and keep their relative moves in the other).
    let mut rng = stream(3, Purpose::Individual, &[]);
    let both = crossover(a, b, 0.3, Literal, ChildMode::Both, 1000, &frame(), &mut rng).unwrap();
    assert_ne!(both[0], both[2]);
    assert_ne!(both[1], both[3]);
}

#[test]
fn a_child_of_exactly_max_len_is_accepted() {
    // absShare = 1 for these lengths and C_len: blocks are one gene, children keep their
    // receivers' lengths (24 and 18).
    let (ga, pa) = parent(13, 24);
    let (gb, pb) = parent(14, 18);
    let (a, b) = (Parent { genome: &ga, points: &pa, stable: 0 }, Parent { genome: &gb, points: &pb, stable: 0 });
    assert_eq!((abs_share(24, 0.04), abs_share(18, 0.04)), (1, 1));
    let mut rng = stream(5, Purpose::Individual, &[]);
    let kids = crossover(a, b, 0.04, Literal, ChildMode::Changing, 24, &frame(), &mut rng).expect("24 ≤ max_len = 24");
    assert_eq!((kids[0].len(), kids[1].len()), (24, 18));
    // The same with the longer parent second: its child is the one at the cap.
    let mut rng = stream(5, Purpose::Individual, &[]);
    let kids = crossover(b, a, 0.04, Literal, ChildMode::Changing, 24, &frame(), &mut rng).expect("24 ≤ max_len = 24");
    assert_eq!((kids[0].len(), kids[1].len()), (18, 24));
    let mut rng = stream(5, Purpose::Individual, &[]);
    assert!(
        crossover(a, b, 0.04, Literal, ChildMode::Changing, 23, &frame(), &mut rng).is_none(),
        "24 > 23 on every redraw"
    );
    let mut rng = stream(5, Purpose::Individual, &[]);
    assert!(crossover(b, a, 0.04, Literal, ChildMode::Changing, 23, &frame(), &mut rng).is_none());
}

/// R14 as a model: crossover takes the first of up to ten block draws (one for each parent,
/// from the same stream) whose two children both fit in `max_len`, and gives up after ten.
#[test]
fn the_first_draw_that_fits_max_len_is_taken() {
    let (ga, pa) = parent(21, 30);
    let (gb, pb) = parent(22, 24);
    let (a, b) = (Parent { genome: &ga, points: &pa, stable: 0 }, Parent { genome: &gb, points: &pb, stable: 0 });
    let (mut taken, mut refused) = (0, 0);
    for seed in 0..60 {
        for max_len in [27, 29, 30, 32] {
            let mut model = stream(seed, Purpose::Individual, &[]);
            let mut expected = None;
            for _ in 0..10 {
                let (ba, bb) =
                    (draw_block(30, 0.3, Clamp, &mut model).unwrap(), draw_block(24, 0.3, Clamp, &mut model).unwrap());
                let (la, lb) = (ba.1 - ba.0, bb.1 - bb.0);
                if 30 - la + lb <= max_len && 24 - lb + la <= max_len {
                    expected = Some((30 - la + lb, 24 - lb + la));
                    break;
                }
            }
            let mut rng = stream(seed, Purpose::Individual, &[]);
            let kids = crossover(a, b, 0.3, Clamp, ChildMode::Changing, max_len, &frame(), &mut rng);
            assert_eq!(kids.map(|k| (k[0].len(), k[1].len())), expected, "seed {seed}, max_len {max_len}");
            if expected.is_some() { taken += 1 } else { refused += 1 }
        }
    }
    assert!(taken > 0 && refused > 0, "both outcomes occur: {taken} taken, {refused} refused");
}

#[test]
fn a_block_ending_at_the_last_free_gene_leaves_the_connector_alone() {
    // CP_2 = n − 1 (0-based end n − 2): the receiver's genes from a1 on are its last free
    // gene and the connector; neither is re-aimed (there is no receiver viewpoint after
    // the block to aim at but the end station, which the connector reaches anyway).
    let (ga, pa) = parent(15, 20);
    let (gb, pb) = parent(16, 16);
    let (a, b) = (Parent { genome: &ga, points: &pa, stable: 0 }, Parent { genome: &gb, points: &pb, stable: 0 });
    for (a0, b0, b1) in [(17, 3, 6), (15, 10, 12)] {
        let k = a0 + (b1 - b0);
        let changing = changing_child(a, (a0, 18), b, (b0, b1), &frame());
        assert_eq!(&changing[k..], &ga[18..], "changing child, block {a0}..18");
        let preserving = preserving_child(a, (a0, 18), b, (b0, b1));
        assert_eq!(&preserving[k..], &ga[18..], "preserving child, block {a0}..18");
        assert_eq!(&preserving[a0..k], &gb[b0..b1]);
    }
}

#[test]
fn short_genome_rules_are_named_as_in_experiment_files() {
    assert_eq!((Clamp.name(), Literal.name()), ("clamp", "literal"));
}

proptest! {
    /// Parents long enough for a block always cross when the cap allows any child: no
    /// silent "no crossover".
    #[test]
    fn long_enough_parents_always_cross(seed in 0u64..10_000, na in 6usize..80, nb in 6usize..80, c_len in 0.0..0.5f64, mode in 0u8..3) {
        prop_assume!(na >= abs_share(na, c_len) + 3 && nb >= abs_share(nb, c_len) + 3);
        let (ga, pa) = parent(seed, na);
        let (gb, pb) = parent(seed + 1, nb);
        let (a, b) = (Parent { genome: &ga, points: &pa, stable: 0 }, Parent { genome: &gb, points: &pb, stable: 0 });
        let mut rng = stream(seed, Purpose::Individual, &[]);
        let kids = crossover(a, b, c_len, Literal, ChildMode::from_index(mode).unwrap(), 1000, &frame(), &mut rng);
        prop_assert!(kids.is_some());
    }

    /// Clamped, every pair of parents with four genes or more crosses, whatever `C_len`,
    /// and a clamped draw equals the literal one wherever the literal one exists.
    #[test]
    fn clamped_parents_always_cross_and_agree_with_the_literal_rule(seed in 0u64..10_000, na in 4usize..40, nb in 4usize..40, c_len in 0.0..1.0f64, mode in 0u8..3) {
        let (ga, pa) = parent(seed, na);
        let (gb, pb) = parent(seed + 1, nb);
        let (a, b) = (Parent { genome: &ga, points: &pa, stable: 0 }, Parent { genome: &gb, points: &pb, stable: 0 });
        let mode = ChildMode::from_index(mode).unwrap();
        let mut rng = stream(seed, Purpose::Individual, &[]);
        prop_assert!(crossover(a, b, c_len, Clamp, mode, 1000, &frame(), &mut rng).is_some());
        let long = |n: usize| abs_share(n, c_len) >= 2 && Literal.share(n, c_len).is_some();
        if long(na) && long(nb) {
            let mut r1 = stream(seed, Purpose::Individual, &[]);
            let mut r2 = r1.clone();
            prop_assert_eq!(
                crossover(a, b, c_len, Clamp, mode, 1000, &frame(), &mut r1),
                crossover(a, b, c_len, Literal, mode, 1000, &frame(), &mut r2)
            );
        }
    }

    /// Children of parents that pass their stable prefixes (decoded from the end of the
    /// shared genes) equal children of parents that pass none (decoded from S).
    #[test]
    fn children_from_stable_prefixes_equal_children_decoded_from_s(seed in 0u64..10_000, na in 4usize..60, nb in 4usize..60, c_len in 0.0..0.6f64, mode in 0u8..3, dist in 1.0..20.0f64) {
        let decoded = |seed: u64, n: usize| {
            let mut rng = stream(seed, Purpose::Main, &[]);
            let mut g = Vec::new();
            random_genome(&mut rng, n - 2, dist, &mut g);
            let mut p = Vec::new();
            let stable = decode(&mut g, &frame(), &mut p);
            (g, p, stable)
        };
        let (ga, pa, sa) = decoded(seed, na);
        let (gb, pb, sb) = decoded(seed + 1, nb);
        let mode = ChildMode::from_index(mode).unwrap();
        let kids = |sa: usize, sb: usize| {
            let (a, b) = (Parent { genome: &ga, points: &pa, stable: sa }, Parent { genome: &gb, points: &pb, stable: sb });
            crossover(a, b, c_len, Clamp, mode, 1000, &frame(), &mut stream(seed, Purpose::Individual, &[]))
        };
        prop_assert_eq!(kids(sa, sb), kids(0, 0));
    }

    #[test]
    fn children_keep_stations_stay_on_the_map_and_respect_the_cap(seed in 0u64..10_000, na in 3usize..80, nb in 3usize..80, c_len in 0.0..1.0f64, mode in 0u8..3, clamp in any::<bool>()) {
        let short = if clamp { Clamp } else { Literal };
        let (ga, pa) = parent(seed, na);
        let (gb, pb) = parent(seed + 1, nb);
        let (a, b) = (Parent { genome: &ga, points: &pa, stable: 0 }, Parent { genome: &gb, points: &pb, stable: 0 });
        let mode = ChildMode::from_index(mode).unwrap();
        let mut rng = stream(seed, Purpose::Individual, &[]);
        if let Some(kids) = crossover(a, b, c_len, short, mode, 100, &frame(), &mut rng) {
            prop_assert_eq!(kids.len(), mode.children());
            for mut k in kids {
                prop_assert!(k.len() >= 3 && k.len() <= 100);
                let mut pts = Vec::new();
                decode(&mut k, &frame(), &mut pts);
                prop_assert_eq!(pts[0], frame().start);
                prop_assert_eq!(*pts.last().unwrap(), frame().end);
                for p in &pts {
                    prop_assert!(p.x >= 0.0 && p.x <= 11.0 && p.y >= 0.0 && p.y <= 11.0);
                }
            }
        }
    }
}
