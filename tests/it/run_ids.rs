//! Run ids are stable: every shipped grid expands to the run ids recorded in
//! `tests/fixtures/grid-ids.txt` (the hash of its sorted run ids, as `study.json` records it).
//! An id is the hash of the run's canonical experiment, so renaming or moving a key must not
//! change it: a change that does would force every committed study to re-run. A change that
//! means to alter runs (a new default, say) re-records the fixture with
//! `COVGA_RECORD_IDS=1 cargo test --test run_ids` and re-runs the affected studies.

use crate::common::repo;
use covga::study::grid::Study;
use covga::study::runner::grid_hash;
use std::path::{Path, PathBuf};

/// `name hash runs` per shipped grid, sorted by name.
fn shipped_grid_ids() -> String {
    let mut names: Vec<PathBuf> = std::fs::read_dir(repo().join("grids"))
        .expect("grids/")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    names.sort();
    let mut out = String::new();
    for path in names {
        let study = Study::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let name = path.file_name().unwrap().to_string_lossy();
        out.push_str(&format!("{name} {} {}\n", grid_hash(&study), study.runs.len()));
    }
    out
}

#[test]
fn shipped_grids_keep_their_run_ids() {
    let fixture: &Path = &repo().join("tests/fixtures/grid-ids.txt");
    let today = shipped_grid_ids();
    if std::env::var_os("COVGA_RECORD_IDS").is_some() {
        std::fs::write(fixture, &today).expect("write the fixture");
    }
    let recorded = std::fs::read_to_string(fixture).expect("tests/fixtures/grid-ids.txt");
    assert_eq!(today, recorded, "a shipped grid's run ids changed (left: today, right: recorded)");
}
