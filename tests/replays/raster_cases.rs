//! Issue 100's property over 2 500 random cases (`tests/common/raster_cases.rs`): planners and
//! the common scorer agree about the raster at cells of 0.02–0.6 m and robots 0.05–1.5 m wide.

use crate::common::raster_cases::{Kind, assert_cases};

/// The full sample; `tests/it` runs the first 120 of the same cases. Every plan is executable
/// and no case is refused. The ceilings are the counts measured over these cases where the issue
/// is still open:
///
/// - 111 plans short of 0.8 of the cells the reach counts. 106 of them cover at least 0.8 of
///   the cells a straight axis-parallel move can sweep (`common::sweepable`): the reach counts
///   every cell within half a width of a position, and for robots of 0.7–1.5 m in rooms of a
///   few metres the corners' quarter discs and the lane ends' half discs, which no move's swept
///   line reaches, are a large share.
/// - 5 plans short of that too: robots that fit at their start only in a band about 0.3 m long
///   and thinner than any split cell (747, 1240, 1597), which the band's route drives end to
///   end (`lanes::band`); a spiral of a 1.4 m robot in a 3 m window (547, 0.77); a cell-order
///   plan over 40 sweepable cells of 0.18 m (851, 0.70).
#[test]
fn planners_and_the_scorer_agree_on_two_thousand_random_rasters() {
    assert_cases(
        0..2_500,
        2_000,
        &[(Kind::NotExecutable, 0), (Kind::ShortCoverage, 111), (Kind::ShortOfSweepable, 5), (Kind::WrongRefusal, 0)],
    );
}
