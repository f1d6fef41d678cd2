//! The reference run of the thesis GA (thesis-1, Elite, 100 individuals, 50 initial actions,
//! 2000 iterations, f2) with its time and result; `cargo run --release --example reference_run`.

use covga::coverage::Footprint;
use covga::coverage::fitness::Projection;
use covga::ga::observer::Recorder;
use covga::geom::Point;
use covga::map::presets::preset;
use covga::planner::Budget;
use covga::thesis::params::ThesisParams;
use covga::thesis::run::ThesisGa;
use covga::thesis::scenario::ThesisScenario;

fn main() {
    let iterations: u32 = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(2000);
    let s = Point::new(1.3, 1.3);
    let scenario = ThesisScenario::new(preset("thesis-1").expect("preset"), Footprint::default(), s, s, Projection::F2);
    let seed: u64 = std::env::args().nth(2).and_then(|s| s.parse().ok()).unwrap_or(1);
    let projection = if std::env::args().nth(3).as_deref() == Some("f1") { Projection::F1 } else { Projection::F2 };
    let scenario = ThesisScenario { projection, ..scenario };
    let mut params = ThesisParams::thesis_elite();
    let env = |k: &str| std::env::var(k).ok().and_then(|v| v.parse::<f64>().ok());
    if let Some(v) = env("C_LEN") {
        params.c_len = v;
    }
    if let Some(v) = env("DIST") {
        params.init.dist_max = v;
    }
    if let Some(v) = env("P_MA") {
        params.p_ma = v;
    }
    if let Some(v) = env("P_MI") {
        params.p_mi = v;
    }
    if let Some(v) = env("C_CHILD") {
        params.c_child = covga::thesis::crossover::ChildMode::from_index(v as u8).expect("0..2");
    }
    let mut ga = ThesisGa { scenario, params, seed, seeds: (Vec::new(), 0) };
    let mut rec = Recorder::default();
    let budget = Budget::iterations(iterations);
    // NO_OBSERVER=1: no observer, hence no diversity measured (as in `cargo bench --bench thesis_run`).
    let out = if std::env::var_os("NO_OBSERVER").is_some() {
        ga.run(&budget, None, &mut [])
    } else {
        ga.run(&budget, None, &mut [&mut rec])
    }
    .expect("run");
    let b = &out.best.score;
    println!(
        "iterations {} evaluations {} wall {:.3} s cov_final {:.4} t_final {:.4} f {:.4} len {} div {:.0}",
        out.iterations,
        out.evaluations,
        out.wall_s,
        b.cov_final,
        b.t_final,
        b.fitness,
        out.best.len(),
        rec.history.last().and_then(|h| h.diversity).unwrap_or(0.0)
    );
}
