//! The cell-order planner's speed targets on `experiments/maps/basement.yaml` (skipped with a
//! message where the map is not beside the checkout): the set-up (decomposition, candidate
//! sweeps, transit matrix, leg times) and one evaluation of a tour, whose inverse is the
//! evaluations per second of the GA; and the set-up on a generated 20 m hall of pillars
//! (`covga maps generate --kind hall --seed 0 --width 20 --height 20`: 121 cells, 1 936
//! candidate sweeps, most of its time the transit matrix). Run on one core for the issue's
//! figures:
//!
//! `RAYON_NUM_THREADS=1 cargo bench --bench cell_order`

use covga::cell_order::config::CellOrderSection;
use covga::cell_order::search::nearest_neighbour;
use covga::cell_order::{Preparation, prepare};
use covga::experiment::file::ExperimentFile;
use covga::experiment::registry::PlannerKind;
use covga::map::generate::{PlanKind, PlanSpec, generate};
use criterion::{Criterion, criterion_group, criterion_main};
use std::path::Path;
use std::time::Duration;

/// The set-up on the 20 m hall of pillars, generated in memory (no file needed).
fn hall(c: &mut Criterion) {
    let spec =
        PlanSpec { kind: PlanKind::Hall, width_m: 20.0, height_m: 20.0, resolution: 0.05, noisy: false, seed: 0 };
    let hall = generate(&spec).expect("a hall");
    let file =
        ExperimentFile { planner: PlannerKind::named("cell_order").expect("a planner"), ..ExperimentFile::default() };
    let mut exp = file.validate("bench", Path::new("."), "bench").expect("valid");
    exp.scenario.map = hall.map;
    (exp.scenario.start, exp.scenario.end) = (hall.start, hall.start);
    let section = CellOrderSection::default();
    let how = Preparation::of(&section);
    let mut group = c.benchmark_group("cell_order");
    group.sample_size(10).warm_up_time(Duration::from_secs(1)).measurement_time(Duration::from_secs(60));
    group.bench_function("setup_hall_20m", |b| {
        b.iter(|| prepare(&exp.scenario, how).expect("prepared").instance.cells())
    });
    group.finish();
}

fn bench(c: &mut Criterion) {
    let map = Path::new("experiments/maps/basement.yaml");
    if !map.exists() {
        eprintln!("cell_order bench: {} is missing (run from the repository root); nothing to measure", map.display());
        return;
    }
    let mut file =
        ExperimentFile { planner: PlannerKind::named("cell_order").expect("a planner"), ..ExperimentFile::default() };
    file.map.source = map.display().to_string();
    file.stations.start = [0.0, 0.0];
    let exp = file.validate("bench", Path::new("."), "bench").expect("valid");
    let section = CellOrderSection::default();
    let how = Preparation::of(&section);
    let mut group = c.benchmark_group("cell_order");
    group.sample_size(10).warm_up_time(Duration::from_secs(1)).measurement_time(Duration::from_secs(30));
    group.bench_function("setup_basement", |b| {
        b.iter(|| prepare(&exp.scenario, how).expect("prepared").instance.cells())
    });
    let prepared = prepare(&exp.scenario, how).expect("prepared");
    let tour = nearest_neighbour(&prepared.instance);
    group.measurement_time(Duration::from_secs(5));
    group.bench_function("evaluate_tour_basement", |b| b.iter(|| prepared.instance.time(&tour)));
    group.finish();
}

criterion_group!(benches, bench, hall);
criterion_main!(benches);
