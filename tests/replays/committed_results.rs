//! Committed results re-run exactly: for every study under `results/` (a folder with
//! `study.json` and `runs.csv` or `runs.csv.xz`), the grid file it names still expands to the
//! same runs, and the cheapest committed rows of each planner, each map not re-run by an
//! earlier folder and each swept value ([`cheap_rows`]), run again with today's code, give the
//! committed rows in every column but the timings.
//!
//! Every committed study reads its maps from the repository (presets or `experiments/maps/`),
//! so a fresh clone re-runs them all; a row whose map file is missing fails. When a change
//! alters a result, this test fails until the affected study is re-run and
//! re-committed in the same change.

use crate::common::repo;
use covga::study::grid::Study;
use covga::study::records::{RunsTable, TIMING_COLUMNS, row};
use covga::study::runner::{MapCache, experiment_of, grid_hash};
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Committed rows whose recorded run took longer than this are not re-run (seconds).
const MAX_ROW_SECONDS: f64 = 25.0;

/// The same for the rows picked to cover each value of a swept key (seconds).
const MAX_VALUE_ROW_SECONDS: f64 = 6.0;

/// The committed `runs.csv` of a study folder (or its `runs.csv.xz`, decompressed here).
fn committed_runs(dir: &Path) -> RunsTable {
    let plain = dir.join("runs.csv");
    let text = if plain.exists() {
        std::fs::read_to_string(&plain).expect("read runs.csv")
    } else {
        let packed = dir.join("runs.csv.xz");
        let bytes = std::fs::read(&packed).unwrap_or_else(|e| panic!("{}: {e}", packed.display()));
        let mut out = Vec::new();
        lzma_rs::xz_decompress(&mut std::io::Cursor::new(bytes), &mut out)
            .unwrap_or_else(|e| panic!("{}: {e:?}", packed.display()));
        String::from_utf8(out).expect("utf-8")
    };
    RunsTable::parse(&text).unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
}

/// Whether a run's map is a file that is not in this checkout.
fn map_missing(source: &str) -> bool {
    (source.contains('/') || source.contains('.')) && !repo().join(source).exists()
}

/// The study folders under `results/`.
fn study_dirs() -> Vec<PathBuf> {
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(repo().join("results"))
        .expect("results/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.join("study.json").exists())
        .collect();
    dirs.sort();
    dirs
}

/// Run ids to re-run: the cheapest committed row (smallest `wall_s` under
/// [`MAX_ROW_SECONDS`]) of each planner and of each map, so that every planner and every map
/// kind of the study is re-run at least once; and the cheapest row under
/// [`MAX_VALUE_ROW_SECONDS`] of each value of each swept key (`columns`), so that an option a
/// study sweeps (routed moves, a seeded population, a selection scheme) is re-run too. A map
/// an earlier study folder re-ran (`seen_maps`) gets no row of its own, nor does a value of a
/// key that only names the map (`map.*`, `stations.*`): studies that sweep options over the
/// same floor plans re-run each option, not each plan again. The maps of the rows picked join
/// `seen_maps`.
fn cheap_rows(table: &RunsTable, columns: &[String], seen_maps: &mut BTreeSet<String>) -> Vec<String> {
    let col = |n: &str| table.col(n).unwrap_or_else(|| panic!("runs.csv has no {n} column"));
    // The metric `planner` column, not a swept `planner` key of the same name before it.
    let planner = table.header.iter().rposition(|h| h == "planner").expect("a planner column");
    let (id, map, wall) = (col("run_id"), col("map"), col("wall_s"));
    // A swept key's column is the first of that name (a metric column can share it).
    let swept: Vec<(usize, bool)> =
        columns.iter().map(|c| (col(c), c.starts_with("map.") || c.starts_with("stations."))).collect();
    let mut best: BTreeMap<(u8, String), (f64, String)> = BTreeMap::new();
    for r in &table.rows {
        let secs: f64 = r[wall].parse().unwrap_or(f64::INFINITY);
        if secs > MAX_ROW_SECONDS {
            continue;
        }
        let known = seen_maps.contains(&r[map]);
        let mut slots = vec![(0, r[planner].clone())];
        if !known {
            slots.push((1, r[map].clone()));
        }
        if secs <= MAX_VALUE_ROW_SECONDS {
            let values = swept.iter().filter(|&&(c, of_map)| !(r[c].is_empty() || (known && of_map)));
            slots.extend(values.map(|&(c, _)| (2, format!("{}={}", table.header[c], r[c]))));
        }
        for key in slots {
            let slot = best.entry(key).or_insert((secs, r[id].clone()));
            if (secs, &r[id]) < (slot.0, &slot.1) {
                *slot = (secs, r[id].clone());
            }
        }
    }
    let mut picked: Vec<String> = best.into_values().map(|(_, id)| id).collect();
    picked.sort();
    picked.dedup();
    for r in table.rows.iter().filter(|r| picked.binary_search(&r[id]).is_ok()) {
        seen_maps.insert(r[map].clone());
    }
    picked
}

#[test]
fn committed_study_rows_re_run_exactly() {
    let dirs = study_dirs();
    assert!(dirs.len() >= 4, "expected the committed studies under results/, found {dirs:?}");
    let scratch = tempfile::tempdir().expect("tempdir");
    let mut failures = Vec::new();
    let mut checked = 0;
    let mut seen_maps = BTreeSet::new();
    for dir in dirs {
        let name = dir.file_name().unwrap().to_string_lossy().into_owned();
        let meta: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("study.json")).unwrap()).unwrap();
        let grid_file = repo().join(meta["grid_file"].as_str().expect("study.json names its grid file"));
        let study = Study::load(&grid_file).unwrap_or_else(|e| panic!("{name}: {e}"));
        if grid_hash(&study) != meta["grid_hash"].as_str().unwrap_or_default() {
            failures.push(format!("{name}: {} no longer expands to the committed runs", grid_file.display()));
            continue;
        }
        let table = committed_runs(&dir);
        let today = covga::study::records::header(&study.columns);
        if table.header != today {
            failures.push(format!("{name}: runs.csv's columns differ from today's"));
            continue;
        }
        let committed = table.by_id();
        // The metric `planner` column, not a swept `planner` key of the same name before it.
        let metric_planner = table.header.iter().rposition(|h| h == "planner").expect("a planner column");
        let maps = MapCache::default();
        for id in cheap_rows(&table, &study.columns, &mut seen_maps) {
            let run = study.runs.iter().find(|r| r.id == id).unwrap_or_else(|| panic!("{name}: no run {id}"));
            assert!(
                !map_missing(&run.file.map.source),
                "{name} {id}: its map {} is not in this checkout, which must re-run every committed study",
                run.file.map.source
            );
            let exp = experiment_of(&study, run, &maps).unwrap_or_else(|e| panic!("{name} {id}: {e}"));
            let out = scratch.path().join(&name).join(&id);
            let summary = covga::experiment::output::run_experiment(&exp, &out, false, &mut [])
                .unwrap_or_else(|e| panic!("{name} {id}: {e}"));
            let fresh = row(&study.columns, run, &summary);
            let old = committed[&id];
            for ((h, a), b) in table.header.iter().zip(old).zip(&fresh) {
                if !TIMING_COLUMNS.contains(&h.as_str()) && a != b {
                    failures.push(format!(
                        "{name} {id} ({}, {}): {h} committed {a}, today {b}",
                        fresh[metric_planner],
                        fresh[table.col("map").unwrap()]
                    ));
                }
            }
            eprintln!("{name} {id}: re-run ({}, {})", fresh[metric_planner], fresh[table.col("map").unwrap()]);
            checked += 1;
        }
    }
    assert!(failures.is_empty(), "{} differences over {checked} re-run rows:\n{}", failures.len(), failures.join("\n"));
    assert!(checked >= 12, "only {checked} rows re-run");
}
