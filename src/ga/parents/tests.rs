//! Tests of the parent-selection registry and its schemes.

use super::*;
use crate::ga::rng::{Purpose, stream};
use crate::ga::selection::{best_k, cumulative, proportionate_probabilities, rank_probabilities, spin, tournament};

const FITNESS: [f64; 7] = [0.3, 0.9, 0.1, 0.5, 0.7, 0.5, 0.0];
const PARAMS: DrawParams = DrawParams { tournament_size: 3, pressure: 1.7, best_parents: 3 };

#[test]
fn names_are_unique_and_found() {
    for (i, s) in SCHEMES.iter().enumerate() {
        assert!(SCHEMES[..i].iter().all(|t| t.name() != s.name()), "{} twice", s.name());
        assert_eq!(scheme(s.name()).map(|t| t.name()), Some(s.name()));
    }
    assert!(scheme("roulette").is_none());
}

/// Each registered scheme draws exactly as the operator it wraps, from the same stream: the
/// GAs that moved onto the registry kept their results bit for bit.
#[test]
fn each_scheme_draws_as_its_operator() {
    type Reference = fn(&[f64], &mut rand_chacha::ChaCha8Rng) -> usize;
    let cases: [(&str, Reference); 4] = [
        ("tournament", |f, rng| tournament(f, PARAMS.tournament_size, rng)),
        ("prws", |f, rng| spin(&cumulative(&proportionate_probabilities(f)), rng)),
        ("rrws", |f, rng| spin(&cumulative(&rank_probabilities(f, PARAMS.pressure)), rng)),
        ("best", |f, rng| {
            use rand::Rng;
            let best = best_k(f, PARAMS.best_parents);
            best[rng.random_range(0..best.len())]
        }),
    ];
    for (name, reference) in cases {
        let mut draw = scheme(name).unwrap().prepare(&FITNESS, &PARAMS);
        let (mut a, mut b) = (stream(3, Purpose::Main, &[]), stream(3, Purpose::Main, &[]));
        for k in 0..500 {
            assert_eq!(draw.pick(&mut a), reference(&FITNESS, &mut b), "{name}, draw {k}");
        }
    }
}

/// Every scheme favours the fitter: over many draws the best member is picked more often than
/// the worst, and never an index outside the population.
#[test]
fn every_scheme_prefers_the_fitter() {
    for s in SCHEMES {
        let mut draw = s.prepare(&FITNESS, &PARAMS);
        let mut rng = stream(8, Purpose::Main, &[]);
        let mut counts = [0usize; FITNESS.len()];
        for _ in 0..7000 {
            counts[draw.pick(&mut rng)] += 1;
        }
        assert!(counts[1] > counts[6], "{}: {counts:?}", s.name());
    }
}

#[test]
fn draws_compare_by_the_parameters_their_scheme_reads() {
    let a = ParentDraw::named("prws", PARAMS).unwrap();
    let b = ParentDraw::named("prws", DrawParams { tournament_size: 9, ..PARAMS }).unwrap();
    assert_eq!(a, b);
    let c = ParentDraw::named("tournament", PARAMS).unwrap();
    let d = ParentDraw::named("tournament", DrawParams { tournament_size: 9, ..PARAMS }).unwrap();
    assert_ne!(c, d);
    assert_ne!(a, c);
}
