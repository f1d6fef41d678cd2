//! Issue 100's property over 2 000 random cases (`tests/common/raster_cases.rs`): planners and
//! the common scorer agree about the raster at cells of 0.02–0.6 m and robots 0.05–1.5 m wide.

/// The full sample; `tests/it` runs the first 120 of the same cases.
#[test]
fn planners_and_the_scorer_agree_on_two_thousand_random_rasters() {
    let (ran, failures) = crate::common::raster_cases::failures(0..2_200);
    assert!(ran >= 2_000, "only {ran} of 2 200 cases drew a map");
    assert!(failures.is_empty(), "{} of {ran} cases failed:\n{}", failures.len(), failures.join("\n"));
}
