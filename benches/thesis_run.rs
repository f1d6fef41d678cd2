//! The reference run of the thesis GA on one thread: thesis-1, Elite, 100 individuals, 50
//! initial actions, 2000 iterations, f2 (003 Table 4.4 reports 269 s per Elite run), with the
//! default operators (Table A.1 row e: C_child 2) and with Table A.1 row a's (C_child 0);
//! and iterations per second of a tournament run with Init_I = 1000.
//!
//! `cargo bench --bench thesis_run`

mod common;

use common::{architecture_a, thesis1_ga};
use covga::planner::Budget;
use covga::thesis::crossover::ChildMode;
use covga::thesis::params::{Selection, ThesisParams};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::time::Duration;

fn run(params: ThesisParams, iterations: u32) -> f64 {
    let mut ga = thesis1_ga(params);
    let budget = Budget::iterations(iterations);
    ga.run(&budget, None, &mut []).expect("run").best.fitness()
}

fn reference(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("pool");
    let mut group = c.benchmark_group("thesis_run");
    group.sample_size(10).measurement_time(Duration::from_secs(30)).warm_up_time(Duration::from_secs(1));
    let row_e = ThesisParams::thesis_elite();
    let row_a = ThesisParams { c_len: 0.6, c_child: ChildMode::Changing, p_ma: 0.01, p_mi: 0.1, ..row_e };
    group.bench_function("elite_2000_iterations/row_e_default", |b| b.iter(|| pool.install(|| run(row_e, 2000))));
    group.bench_function("elite_2000_iterations/row_a", |b| b.iter(|| pool.install(|| run(row_a, 2000))));
    let tournament = architecture_a(Selection::tournament(3));
    group.throughput(Throughput::Elements(200));
    group.bench_function("tournament_init1000/200_iterations", |b| b.iter(|| pool.install(|| run(tournament, 200))));
    group.finish();
}

criterion_group!(benches, reference);
criterion_main!(benches);
