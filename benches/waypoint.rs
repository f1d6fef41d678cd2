//! The waypoint planner's speed targets: precomputation (waypoints, graph, per-edge views) on
//! the office preset, and 1000 generations of 100 organisms, single agent; and 100
//! generations on the floor-plan scale of 000 (`experiments/olson-ring.toml`: the 60 m × 40 m
//! `office-ring` preset with the authors' camera).
//!
//! `cargo bench --bench waypoint`

use covga::experiment::file::ExperimentFile;
use covga::experiment::registry::PlannerKind;
use covga::ga::observer::{GenerationRecord, Observers};
use covga::map::presets::preset;
use covga::planner::Budget;
use covga::waypoint::config::WaypointConfig;
use covga::waypoint::run::run;
use covga::waypoint::world::World;
use criterion::{Criterion, criterion_group, criterion_main};
use std::path::Path;
use std::time::Duration;

fn bench(c: &mut Criterion) {
    let file =
        ExperimentFile { planner: PlannerKind::named("waypoint").expect("a planner"), ..ExperimentFile::default() };
    let mut file = file;
    file.map.source = "office".into();
    file.stations.start = [2.0, 2.0];
    file.sections.get_mut(&covga::waypoint::config::WAYPOINT_SECTION).l_init = 200;
    let exp = file.validate("bench", Path::new("."), "bench").expect("valid");
    let plan = exp.planner.downcast_ref::<WaypointConfig>().expect("a waypoint experiment").clone();
    let map = preset("office").expect("preset");
    let mut group = c.benchmark_group("waypoint");
    group.sample_size(10).warm_up_time(Duration::from_secs(1)).measurement_time(Duration::from_secs(20));
    group.bench_function("precompute_office", |b| {
        b.iter(|| World::build(&map, &plan.world, 1).expect("world").graph.points.len())
    });
    let world = World::build(&map, &plan.world, 1).expect("world");
    group.measurement_time(Duration::from_secs(60));
    group.bench_function("ga_1000_generations_100_organisms", |b| {
        b.iter(|| {
            run(&world, &plan.ga, 1, &Budget::iterations(u32::MAX), &mut Observers::none(), &mut |_, _, _| {
                GenerationRecord::default()
            })
            .expect("no interrupt")
            .best
        })
    });
    let ring = ExperimentFile::read(Path::new("experiments/olson-ring.toml")).expect("olson-ring.toml");
    let ring = ring.validate("olson-ring", Path::new("experiments"), "olson-ring").expect("valid");
    let mut ring_plan = ring.planner.downcast_ref::<WaypointConfig>().expect("a waypoint experiment").clone();
    ring_plan.ga.generations = 100;
    let ring_world = World::build(&ring.scenario.map, &ring_plan.world, 1).expect("world");
    group.measurement_time(Duration::from_secs(30));
    group.bench_function("ring_floor_100_generations", |b| {
        b.iter(|| {
            run(&ring_world, &ring_plan.ga, 1, &Budget::iterations(u32::MAX), &mut Observers::none(), &mut |_, _, _| {
                GenerationRecord::default()
            })
            .expect("no interrupt")
            .best
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
