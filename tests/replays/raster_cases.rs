//! Issue 100's property over 2 500 random cases (`tests/common/raster_cases.rs`): planners and
//! the common scorer agree about the raster at cells of 0.02–0.6 m and robots 0.05–1.5 m wide.

use crate::common::raster_cases::{Kind, assert_cases};

/// The full sample; `tests/it` runs the first 120 of the same cases. Every plan is executable.
/// The ceilings are the counts measured over these cases where the issue is still open: plans
/// short of 0.8 of the reachable cells (mostly robots over 0.9 m on cells under 5 cm in small
/// windows of real scans, where the centres reach the cells but the lanes and the spiral leave
/// them), and refusals of robots that fit at their start only in a band no split of the cells
/// (up to 8 × 8) puts a centre in.
#[test]
fn planners_and_the_scorer_agree_on_two_thousand_random_rasters() {
    assert_cases(0..2_500, 2_000, &[(Kind::NotExecutable, 0), (Kind::ShortCoverage, 107), (Kind::WrongRefusal, 4)]);
}
