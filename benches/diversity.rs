//! Population diversity (003 eqs. 3.17–3.19): the pair-distance sum of 100 and of 1 000 visit
//! maps on thesis-1, each swept from a random 40-move path of moves up to 3 m from the station
//! (the shape of an initial population), as every generation of a recorded run computes it.
//!
//! `kept_pair_sum` is the sum kept from call to call ([`kept_pair_distance_sum`]) on 100 maps
//! of which 4 are replaced per call, the churn of a recorded Elite run after its first 200
//! iterations.
//!
//! `cargo bench --bench diversity`

use covga::coverage::CoverageGrid;
use covga::coverage::bits::BitLayers;
use covga::coverage::planes::VisitPlanes;
use covga::geom::Point;
use covga::map::presets::preset;
use covga::thesis::diversity::{DiversityScratch, kept_pair_distance_sum, pair_distance_sum_by};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rand::{Rng, SeedableRng};
use std::hint::black_box;

fn population(layers: &BitLayers, n: usize, rng: &mut impl Rng) -> Vec<VisitPlanes> {
    (0..n)
        .map(|_| {
            let mut p = Point::new(1.3, 1.3);
            let mut path = vec![p];
            for _ in 0..40 {
                let (a, d) = (rng.random_range(0.0..std::f64::consts::TAU), rng.random_range(0.0..3.0));
                p = Point::new((p.x + d * a.cos()).clamp(0.3, 10.7), (p.y + d * a.sin()).clamp(0.3, 10.7));
                path.push(p);
            }
            let mut visits = VisitPlanes::default();
            layers.sweep(&mut visits, &path, 0.6);
            visits
        })
        .collect()
}

fn diversity(c: &mut Criterion) {
    let grid = CoverageGrid::new(&preset("thesis-1").expect("preset"));
    let layers = BitLayers::new(&grid);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    let mut group = c.benchmark_group("diversity");
    for n in [100, 1000] {
        let pop = population(&layers, n, &mut rng);
        let mut scratch = DiversityScratch::default();
        group.throughput(Throughput::Elements(n as u64));
        group.bench_function(format!("pair_distance_sum/{n}_maps"), |b| {
            b.iter(|| black_box(pair_distance_sum_by(pop.len(), |i| &pop[i], &mut scratch)))
        });
    }
    // Two populations 4 members apart, measured in turn: each call sees 4 leave and 4 join.
    let pop = population(&layers, 104, &mut rng);
    let (first, second): (Vec<&VisitPlanes>, Vec<&VisitPlanes>) =
        (pop[..100].iter().collect(), pop[..96].iter().chain(&pop[100..]).collect());
    let mut scratch = DiversityScratch::default();
    let mut turn = false;
    group.throughput(Throughput::Elements(100));
    group.bench_function("kept_pair_sum/100_maps_4_changed", |b| {
        b.iter(|| {
            turn = !turn;
            let now = if turn { &first } else { &second };
            black_box(kept_pair_distance_sum(100, |i| now[i], &mut scratch, 0))
        })
    });
    group.finish();
}

criterion_group!(benches, diversity);
criterion_main!(benches);
