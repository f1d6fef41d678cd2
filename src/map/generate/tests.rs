//! Tests of the floor-plan generator.

use super::*;
use crate::map::clearance::Clearance;
use crate::map::reach::Reach;

fn spec(kind: PlanKind, seed: u64, noisy: bool) -> PlanSpec {
    PlanSpec { kind, width_m: 24.0, height_m: 16.0, resolution: 0.05, noisy, seed }
}

/// Every kind, clean or noisy, over ten seeds: the start station fits a 0.6 m robot, and the
/// robot reaches and sweeps nearly all the free floor (rooms joined by doors it fits through).
#[test]
fn a_robot_reaches_nearly_every_room_of_every_plan() {
    for (kind, name) in PlanKind::ALL {
        for noisy in [false, true] {
            for seed in 0..10 {
                let g = generate(&spec(kind, seed, noisy)).unwrap();
                let clear = Clearance::new(&g.map, 0.6);
                assert!(clear.fits(g.start), "{name} {seed} {noisy}: the start {:?} does not fit", g.start);
                let reach = Reach::new(&clear, &[g.start]);
                let share = reach.coverable_count() as f64 / g.map.free_count() as f64;
                assert!(share > 0.85, "{name} {seed} noisy {noisy}: {share:.3} of the free cells coverable");
            }
        }
    }
}

#[test]
fn the_same_spec_and_seed_give_the_same_map_and_other_seeds_others() {
    for (kind, _) in PlanKind::ALL {
        let a = generate(&spec(kind, 3, true)).unwrap().map;
        assert_eq!(a, generate(&spec(kind, 3, true)).unwrap().map);
        assert_ne!(a.cells(), generate(&spec(kind, 4, true)).unwrap().map.cells());
        assert_eq!(a.name(), format!("{}-3-noisy", kind.name()));
    }
}

/// Noise makes what SLAM maps have: unknown space outside the building (solid in a clean plan),
/// and less free floor than the clean plan of the same seed.
#[test]
fn noise_adds_unknown_outside_and_ragged_walls() {
    for (kind, name) in PlanKind::ALL {
        let count = |m: &GridMap, s: CellState| m.cells().iter().filter(|&&c| c == s).count();
        let (clean, noisy) =
            (generate(&spec(kind, 1, false)).unwrap().map, generate(&spec(kind, 1, true)).unwrap().map);
        assert_eq!(count(&clean, CellState::Unknown), 0, "{name}");
        assert!(count(&noisy, CellState::Unknown) > 0, "{name}");
        // The same rooms, doors and furniture, with ragged faces and specks taken from the floor.
        assert!(noisy.free_count() < clean.free_count(), "{name}");
    }
}

#[test]
fn specs_out_of_range_are_refused_with_the_reason() {
    let cases: &[(f64, f64, f64, &str)] = &[
        (5.0, 10.0, 0.05, "width = 5 m"),
        (10.0, 250.0, 0.05, "height = 250 m"),
        (10.0, 10.0, 0.001, "resolution = 0.001"),
        (200.0, 200.0, 0.02, "2^26"),
        (f64::NAN, 10.0, 0.05, "width = NaN"),
    ];
    for &(w, h, res, want) in cases {
        let s = PlanSpec { width_m: w, height_m: h, resolution: res, ..spec(PlanKind::Office, 0, false) };
        let err = generate(&s).unwrap_err();
        assert!(err.contains(want), "{w} × {h} at {res}: {err}");
    }
}

/// A hall of 40 m × 40 m holds about 600 pillars (the kind of map the cell-order planner's
/// set-up is measured on), every one standing free.
#[test]
fn a_large_hall_has_about_six_hundred_pillars() {
    for seed in 0..3 {
        let s = PlanSpec { width_m: 40.0, height_m: 40.0, ..spec(PlanKind::Hall, seed, false) };
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let (_, _, pillars) = hall(Rect::new(1.15, 1.15, 40.85, 40.85), &mut rng);
        assert!((450..=800).contains(&pillars.len()), "seed {seed}: {} pillars", pillars.len());
        let g = generate(&s).unwrap();
        assert!(Clearance::new(&g.map, 0.6).fits(g.start), "seed {seed}");
    }
}

#[test]
fn a_noisy_plan_has_the_clean_plan_of_its_seed_as_twin() {
    for (source, twin) in [
        ("maps/house-1-noisy.yaml", "maps/house-1.yaml"),
        ("maps/house-1.yaml", "maps/house-1.yaml"),
        ("office-3-noisy", "office-3"),
        ("office", "office"),
    ] {
        assert_eq!(clean_twin(source), twin);
    }
    let g = generate(&spec(PlanKind::House, 4, true)).unwrap();
    assert_eq!(clean_twin(g.map.name()), generate(&spec(PlanKind::House, 4, false)).unwrap().map.name());
}
