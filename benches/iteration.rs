//! One iteration of each architecture of the thesis GA on one thread, in the middle of a run:
//! Elite families (architecture b, Table A.1 row e) with incremental and with full evaluation
//! of children, and tournament, PRWS and RRWS (architecture a, `Init_I` 1000, `keep` 10,
//! `select` 20, as in the Table 4.3 grid). Thesis-1, f2, no diversity measured.
//!
//! Each sample starts from a run advanced [`WARM_ITERATIONS`] iterations (outside the timer)
//! and times the next iterations of that run (the same number in every sample). The throughput is in evaluations, so criterion's
//! rate is children evaluated per second.
//!
//! `cargo bench --bench iteration`

mod common;

use common::{architecture_a, thesis1_ga};
use covga::thesis::individual::EvaluationMode;
use covga::thesis::params::{Selection, ThesisParams};
use covga::thesis::run::{GaState, ThesisGa};
use criterion::{Criterion, SamplingMode, Throughput, criterion_group, criterion_main};
use std::time::{Duration, Instant};

/// Iterations a run is advanced before its iterations are timed (past the initial population's
/// fast improvements, when genomes have their typical length).
const WARM_ITERATIONS: u32 = 200;

/// Advances `state` by `iterations` iterations of `ga` (iteration budget `iter_max`).
fn advance(ga: &ThesisGa, state: &mut GaState, iterations: u32, iter_max: u32) {
    let mut scratches = ga.new_scratches();
    for _ in 0..iterations {
        let effective = ga.effective(state, state.iteration + 1, iter_max);
        ga.step(state, effective, &mut scratches, false);
    }
}

/// A run of `ga` advanced [`WARM_ITERATIONS`] iterations.
fn warm(ga: &ThesisGa) -> GaState {
    let mut state = ga.init(false);
    advance(ga, &mut state, WARM_ITERATIONS, u32::MAX);
    state
}

fn iteration(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("pool");
    let row_e = ThesisParams::thesis_elite();
    let cases = [
        ("elite_row_e/incremental", row_e),
        ("elite_row_e/full", ThesisParams { evaluation: EvaluationMode::Full, ..row_e }),
        ("tournament_3", architecture_a(Selection::tournament(3))),
        ("prws", architecture_a(Selection::prws())),
        ("rrws_2", architecture_a(Selection::rrws(2.0))),
    ];
    let mut group = c.benchmark_group("iteration");
    // Every sample times the same number of iterations from the same point of the run.
    group.sampling_mode(SamplingMode::Flat);
    group.sample_size(20).measurement_time(Duration::from_secs(10)).warm_up_time(Duration::from_secs(1));
    for (name, params) in cases {
        let ga = thesis1_ga(params);
        // Evaluations per iteration, counted over 100 iterations after the warm-up.
        let per_iteration = pool.install(|| {
            let mut state = warm(&ga);
            let before = state.evaluations;
            advance(&ga, &mut state, 100, u32::MAX);
            (state.evaluations - before).div_ceil(100)
        });
        group.throughput(Throughput::Elements(per_iteration));
        group.bench_function(name, |b| {
            b.iter_custom(|iters| {
                pool.install(|| {
                    let mut state = warm(&ga);
                    let start = Instant::now();
                    advance(&ga, &mut state, iters as u32, u32::MAX);
                    start.elapsed()
                })
            })
        });
    }
    group.finish();
}

criterion_group!(benches, iteration);
criterion_main!(benches);
