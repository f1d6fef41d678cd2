//! The Rust side of the Python package's speed targets: the calls `covga.score` and
//! `covga.thesis.evaluate` make, on the inputs `python/benchmarks/bindings.py` times from
//! Python (a 1000-point path along the thesis-1 boustrophedon; 1000 random genomes of 50
//! actions). The ratio of the two is the cost of the bindings.

use covga::coverage::Footprint;
use covga::coverage::fitness::Projection;
use covga::coverage::score::Scorer;
use covga::geom::Point;
use covga::map::presets::preset;
use covga::patterns::{self, Pattern};
use covga::thesis::batch::evaluate_batch;
use covga::thesis::scenario::ThesisScenario;
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rand::{Rng, SeedableRng};
use std::hint::black_box;

/// `n` points at equal arc-length steps along `path` (its ends included).
fn resample(path: &[Point], n: usize) -> Vec<Point> {
    let lengths: Vec<f64> = path.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
    let total: f64 = lengths.iter().sum();
    let mut out = Vec::with_capacity(n);
    let (mut seg, mut before) = (0, 0.0);
    for k in 0..n {
        let s = total * k as f64 / (n - 1) as f64;
        while seg + 1 < lengths.len() && before + lengths[seg] < s {
            before += lengths[seg];
            seg += 1;
        }
        let t = if lengths[seg] > 0.0 { ((s - before) / lengths[seg]).clamp(0.0, 1.0) } else { 0.0 };
        out.push(path[seg] + (path[seg + 1] - path[seg]) * t);
    }
    out
}

fn bindings(c: &mut Criterion) {
    let map = preset("thesis-1").expect("preset");
    let start = Point::new(1.3, 1.3);
    let robot = Footprint { width: 0.6, speed: 0.2, rot_speed: 0.0 };
    let planned = patterns::plan(&map, Pattern::Boustrophedon { angle_deg: 0.0 }, 0.6, start, start, true)
        .expect("a boustrophedon on thesis-1");
    let path = resample(&planned.points, 1000);
    let camera = covga::planner::sections::CameraSection::default().spec("camera", &map).expect("camera");
    let mut group = c.benchmark_group("bindings");
    group.bench_function("score_1000_points", |b| {
        b.iter(|| {
            let plan = vec![black_box(path.clone())];
            Scorer::for_widths(&map, robot, &[0.6], Projection::F1, &camera, &[start]).score_agents(&plan, &[robot])
        })
    });
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
    let genomes: Vec<Vec<(f64, f64)>> = (0..1000)
        .map(|_| (0..50).map(|_| (rng.random_range(0.0..360.0), rng.random_range(0.0..=3.0))).collect())
        .collect();
    group.throughput(Throughput::Elements(genomes.len() as u64));
    group.bench_function("thesis_evaluate_1000x50", |b| {
        b.iter(|| {
            let scenario = ThesisScenario::new(map.clone(), robot, start, start, Projection::F2);
            evaluate_batch(&scenario, black_box(&genomes)).expect("valid genomes")
        })
    });
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30);
    targets = bindings
}
criterion_main!(benches);
