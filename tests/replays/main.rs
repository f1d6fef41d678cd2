//! The heavy replays, a test binary of their own so that CI runs and times them as a step of
//! their own: every committed study's cheapest rows re-run (`committed_results`), every
//! committed summary re-made (`report_remake`), the fuzzing corpus replayed (`fuzz_corpus`)
//! and every key a planner does not read varied (`unread_keys`). The fast tests are
//! `tests/it`.

#[path = "../common/mod.rs"]
mod common;

/// One test per study folder (`test name => "folder"`), each calling `$run("folder")`, so the
/// test harness runs the studies side by side; and `$list`, the folders that have a test.
macro_rules! per_study_tests {
    ($run:ident, $list:ident: $($test:ident => $folder:literal),* $(,)?) => {
        $(
            #[test]
            fn $test() {
                $run($folder);
            }
        )*
        /// The study folders that have a test of their own.
        const $list: &[&str] = &[$($folder),*];
    };
}

mod committed_bounds;
mod committed_results;
mod fuzz_corpus;
mod raster_cases;
mod report_remake;
mod unread_keys;
