//! The set-up the thesis benches share: the GA on thesis map 1 and the architecture (a)
//! parameters of the Table 4.3 grid. Each bench uses part of it.
#![allow(dead_code)]

use covga::coverage::Footprint;
use covga::coverage::fitness::Projection;
use covga::geom::Point;
use covga::map::presets::preset;
use covga::thesis::crossover::ChildMode;
use covga::thesis::params::{Selection, ThesisParams};
use covga::thesis::run::ThesisGa;
use covga::thesis::scenario::ThesisScenario;

/// The thesis GA on thesis map 1, start and end at (1.3, 1.3), f2, seed 1.
pub fn thesis1_ga(params: ThesisParams) -> ThesisGa {
    let s = Point::new(1.3, 1.3);
    let scenario = ThesisScenario::new(preset("thesis-1").expect("preset"), Footprint::default(), s, s, Projection::F2);
    ThesisGa { scenario, params, seed: 1, seeds: (Vec::new(), 0) }
}

/// Architecture (a) with `selection`, as in the Table 4.3 grid: `Init_I` 1000, `keep` 10,
/// `select` 20, `C_len` 0.4, `C_child` 0, `P_mA` 0.1, `P_mI` 0.1; the rest as row (e).
pub fn architecture_a(selection: Selection) -> ThesisParams {
    ThesisParams {
        selection,
        init_individuals: 1000,
        keep: 10,
        select: 20,
        c_len: 0.4,
        c_child: ChildMode::Changing,
        p_ma: 0.1,
        p_mi: 0.1,
        ..ThesisParams::thesis_elite()
    }
}
