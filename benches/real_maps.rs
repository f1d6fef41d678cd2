//! The thesis GA on the real floor plans, straight against routed moves (the real-map speed
//! work): the reference experiment of `benches/README.md` ("Routed moves on basement") on
//! `experiments/maps/basement.yaml` and on the office preset, each for 4 000 evaluations on one
//! thread. The ratio routed ÷ straight is the per-evaluation cost of routing; the maps' set-up
//! (the router's landmarks, reachability) is inside each run, as users meet it. Basement is
//! skipped with a message where the map is not beside the checkout.
//!
//! `cargo bench --bench real_maps`

use covga::coverage::Footprint;
use covga::coverage::fitness::Projection;
use covga::geom::Point;
use covga::map::GridMap;
use covga::map::presets::preset;
use covga::map::ros::{BareImage, load_map};
use covga::planner::Budget;
use covga::thesis::individual::InitParams;
use covga::thesis::params::{Selection, ThesisParams};
use covga::thesis::run::ThesisGa;
use covga::thesis::scenario::{Moves, ThesisScenario};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

/// Evaluations per measured run.
const EVALUATIONS: u64 = 4_000;

fn run(map: &GridMap, start: Point, moves: Moves) -> f64 {
    let robot = Footprint { width: 0.6, speed: 0.2, rot_speed: 0.0 };
    let scenario = ThesisScenario::new(map.clone(), robot, start, start, Projection::F2).with_moves(moves);
    let params = ThesisParams {
        selection: Selection::Elite,
        pop_min: 100,
        init: InitParams { actions: 150, dist_max: 6.0 },
        max_genome_len: 600,
        ..ThesisParams::thesis_elite()
    };
    let mut ga = ThesisGa { scenario, params, seed: 1, seeds: (Vec::new(), 0) };
    let budget = Budget { evaluations: Some(EVALUATIONS), ..Budget::iterations(1_000_000) };
    ga.run(&budget, None, &mut []).expect("run").best.fitness()
}

fn bench(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("pool");
    let mut maps = vec![("office", preset("office").expect("preset"), Point::new(2.0, 2.0))];
    let basement = Path::new("experiments/maps/basement.yaml");
    match load_map(&basement.display().to_string(), &BareImage::default()) {
        Ok(map) => maps.insert(0, ("basement", map, Point::new(0.0, 0.0))),
        Err(e) => eprintln!("real_maps bench: {} ({e}); basement not measured", basement.display()),
    }
    let mut group = c.benchmark_group("real_maps");
    group.sample_size(10).warm_up_time(Duration::from_secs(1)).measurement_time(Duration::from_secs(20));
    for (name, map, start) in &maps {
        for (label, moves) in [("straight", Moves::Straight), ("routed", Moves::Routed)] {
            group.bench_function(format!("{name}_{label}_{EVALUATIONS}_evaluations"), |b| {
                b.iter(|| pool.install(|| black_box(run(map, *start, moves))))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
