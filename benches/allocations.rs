//! Heap allocations of the thesis GA per evaluation, counted by a wrapping global allocator:
//! the reference run (Table A.1 row e, Elite, 100 individuals, 2000 iterations, f2, one thread,
//! no observers) and a tournament run with `Init_I` = 1000, 200 iterations.
//!
//! `cargo bench --bench allocations` prints the counts; it times nothing.

mod common;

use common::{architecture_a, thesis1_ga};
use covga::planner::Budget;
use covga::thesis::params::{Selection, ThesisParams};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicU64, Ordering};

/// The system allocator, counting allocations and the bytes they asked for.
struct Counting;

static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);
static BYTES: AtomicU64 = AtomicU64::new(0);

// SAFETY: every call is passed on unchanged to the system allocator.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        BYTES.fetch_add(layout.size() as u64, Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        BYTES.fetch_add(new_size as u64, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn count(name: &str, params: ThesisParams, iterations: u32) {
    let mut ga = thesis1_ga(params);
    let budget = Budget::iterations(iterations);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("pool");
    let (a0, b0) = (ALLOCATIONS.load(Ordering::Relaxed), BYTES.load(Ordering::Relaxed));
    let outcome = pool.install(|| ga.run(&budget, None, &mut []).expect("run"));
    let (a, b) = (ALLOCATIONS.load(Ordering::Relaxed) - a0, BYTES.load(Ordering::Relaxed) - b0);
    let e = outcome.evaluations as f64;
    println!(
        "{name}: {} evaluations, {a} allocations ({:.2} per evaluation), {:.1} MiB asked ({:.0} bytes per evaluation)",
        outcome.evaluations,
        a as f64 / e,
        b as f64 / (1 << 20) as f64,
        b as f64 / e
    );
}

fn main() {
    // `cargo bench` passes `--bench`; any other run (e.g. `cargo test --benches`) also counts.
    let row_e = ThesisParams::thesis_elite();
    count("reference run (row e, Elite, 2000 iterations)", row_e, 2000);
    let tournament = architecture_a(Selection::tournament(3));
    count("tournament, Init_I 1000, 200 iterations", tournament, 200);
}
