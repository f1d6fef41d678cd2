//! Committed results re-run exactly: for every study under `results/` (a folder with
//! `study.json` and `runs.csv` or `runs.csv.xz`), the grid file it names still expands to the
//! same runs, and the committed rows listed for it in `tests/replays/rows.csv` run again with
//! today's code give the committed rows in every column but the timings.
//!
//! Each study is a test of its own ([`replay!`]), so the test harness runs them side by side.
//! The rows are the cheapest committed rows of each planner, each map not re-run by an earlier
//! folder and each swept value ([`cheap_rows`]); the selection is written down in
//! `rows.csv` and checked against the committed studies
//! ([`the_committed_replay_rows_are_the_selection`]), so that no study's test depends on
//! which other study ran first. After a study is re-run and re-committed, write the list anew
//! with `COVGA_WRITE_REPLAY_ROWS=1 cargo test --release --test replays committed_results::the_`.
//!
//! Every committed study reads its maps from the repository (presets or `experiments/maps/`),
//! so a fresh clone re-runs them all; a row whose map file is missing fails. When a change
//! alters a result, this test fails until the affected study is re-run and
//! re-committed in the same change.

use crate::common::repo;
use covga::study::grid::Study;
use covga::study::records::{RunsTable, TIMING_COLUMNS, row};
use covga::study::runner::{MapCache, experiment_of, grid_hash};
use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

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

/// One row of `tests/replays/rows.csv`: a committed run to re-run, with what names it.
#[derive(Debug, Clone, PartialEq)]
struct ReplayRow {
    study: String,
    run_id: String,
    planner: String,
    map: String,
    wall_s: String,
}

/// The committed list of rows to re-run.
const ROWS_FILE: &str = "tests/replays/rows.csv";

/// The header of [`ROWS_FILE`].
const ROWS_HEADER: &str = "study,run_id,planner,map,wall_s";

/// A study folder's grid, checked to expand to the runs it committed, and its runs; loaded
/// once per test process (the selection and the study's own test both read it, and the
/// largest grids expand to tens of thousands of runs).
fn committed_study(name: &str) -> Arc<(Study, RunsTable)> {
    type Slots = Mutex<HashMap<String, Arc<OnceLock<Arc<(Study, RunsTable)>>>>>;
    static LOADED: OnceLock<Slots> = OnceLock::new();
    let slot = LOADED.get_or_init(Slots::default).lock().expect("studies").entry(name.to_string()).or_default().clone();
    slot.get_or_init(|| Arc::new(load_committed_study(name))).clone()
}

/// [`committed_study`], read from disk.
fn load_committed_study(name: &str) -> (Study, RunsTable) {
    let dir = repo().join("results").join(name);
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("study.json")).unwrap()).unwrap();
    let grid_file = repo().join(meta["grid_file"].as_str().expect("study.json names its grid file"));
    let study = Study::load(&grid_file).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(
        grid_hash(&study),
        meta["grid_hash"].as_str().unwrap_or_default(),
        "{name}: {} no longer expands to the committed runs",
        grid_file.display()
    );
    let table = committed_runs(&dir);
    assert_eq!(
        table.header,
        covga::study::records::header(&study.columns),
        "{name}: runs.csv's columns differ from today's"
    );
    (study, table)
}

/// The rows [`cheap_rows`] picks, study folder by study folder in name order.
fn selected_rows() -> Vec<ReplayRow> {
    let mut seen_maps = BTreeSet::new();
    let mut out = Vec::new();
    for dir in study_dirs() {
        let name = dir.file_name().unwrap().to_string_lossy().into_owned();
        let loaded = committed_study(&name);
        let (study, table) = (&loaded.0, &loaded.1);
        let committed = table.by_id();
        let planner = table.header.iter().rposition(|h| h == "planner").expect("a planner column");
        let (map, wall) = (table.col("map").unwrap(), table.col("wall_s").unwrap());
        for id in cheap_rows(table, &study.columns, &mut seen_maps) {
            let r = committed[&id];
            out.push(ReplayRow {
                study: name.clone(),
                run_id: id.clone(),
                planner: r[planner].clone(),
                map: r[map].clone(),
                wall_s: r[wall].clone(),
            });
        }
    }
    out
}

/// [`ROWS_FILE`] as written.
fn committed_rows() -> Vec<ReplayRow> {
    let text = std::fs::read_to_string(repo().join(ROWS_FILE)).expect("tests/replays/rows.csv");
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    assert_eq!(reader.headers().unwrap().iter().collect::<Vec<_>>().join(","), ROWS_HEADER);
    reader
        .records()
        .map(|r| {
            let r = r.expect("a rows.csv record");
            ReplayRow {
                study: r[0].to_string(),
                run_id: r[1].to_string(),
                planner: r[2].to_string(),
                map: r[3].to_string(),
                wall_s: r[4].to_string(),
            }
        })
        .collect()
}

/// `rows` as the CSV text of [`ROWS_FILE`].
fn rows_csv(rows: &[ReplayRow]) -> String {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(ROWS_HEADER.split(',')).unwrap();
    for r in rows {
        w.write_record([&r.study, &r.run_id, &r.planner, &r.map, &r.wall_s]).unwrap();
    }
    String::from_utf8(w.into_inner().unwrap()).unwrap()
}

#[test]
fn the_committed_replay_rows_are_the_selection() {
    let selected = selected_rows();
    if std::env::var_os("COVGA_WRITE_REPLAY_ROWS").is_some() {
        std::fs::write(repo().join(ROWS_FILE), rows_csv(&selected)).unwrap();
    }
    let committed = committed_rows();
    assert!(
        committed == selected,
        "{ROWS_FILE} is not the selection of today's committed studies; write it anew (module docs):\n{}",
        rows_csv(&selected)
    );
    assert!(committed.len() >= 12, "only {} rows re-run", committed.len());
}

/// Re-runs the rows of [`ROWS_FILE`] listed for study folder `name` and compares them with its
/// committed rows.
fn replay_study(name: &str) {
    let rows: Vec<ReplayRow> = committed_rows().into_iter().filter(|r| r.study == name).collect();
    assert!(!rows.is_empty(), "{ROWS_FILE} lists no row of {name}");
    let loaded = committed_study(name);
    let (study, table) = (&loaded.0, &loaded.1);
    let committed = table.by_id();
    let metric_planner = table.header.iter().rposition(|h| h == "planner").expect("a planner column");
    let scratch = tempfile::tempdir().expect("tempdir");
    let maps = MapCache::default();
    let mut failures = Vec::new();
    for ReplayRow { run_id: id, .. } in &rows {
        let run = study.runs.iter().find(|r| &r.id == id).unwrap_or_else(|| panic!("{name}: no run {id}"));
        assert!(
            !map_missing(&run.file.map.source),
            "{name} {id}: its map {} is not in this checkout, which must re-run every committed study",
            run.file.map.source
        );
        let exp = experiment_of(study, run, &maps).unwrap_or_else(|e| panic!("{name} {id}: {e}"));
        let out = scratch.path().join(id);
        let summary = covga::experiment::output::run_experiment(&exp, &out, false, &mut [])
            .unwrap_or_else(|e| panic!("{name} {id}: {e}"));
        let fresh = row(&study.columns, run, &summary);
        let old = committed.get(id).unwrap_or_else(|| panic!("{name}: runs.csv has no {id}"));
        for ((h, a), b) in table.header.iter().zip(old.iter()).zip(&fresh) {
            if !TIMING_COLUMNS.contains(&h.as_str()) && a != b {
                failures.push(format!(
                    "{name} {id} ({}, {}): {h} committed {a}, today {b}",
                    fresh[metric_planner],
                    fresh[table.col("map").unwrap()]
                ));
            }
        }
        eprintln!("{name} {id}: re-run ({}, {})", fresh[metric_planner], fresh[table.col("map").unwrap()]);
    }
    assert!(
        failures.is_empty(),
        "{} differences over {} re-run rows:\n{}",
        failures.len(),
        rows.len(),
        failures.join("\n")
    );
}

per_study_tests! {
    replay_study, REPLAYED:
    ablation => "ablation",
    cell_order => "cell-order",
    figures_gallery => "figures-gallery",
    fleets => "fleets",
    init_dist => "init-dist",
    lane_layouts => "lane-layouts",
    merged_lanes => "merged-lanes",
    olson_ring => "olson-ring",
    quota_completion => "quota-completion",
    quota_search => "quota-search",
    smoke => "smoke",
    thesis_real_maps => "thesis-real-maps",
    thesis_seed_bound => "thesis-seed-bound",
    thesis_table_4_3 => "thesis-table-4-3",
}

/// A study folder added under `results/` without a test of its own fails here.
#[test]
fn every_committed_study_has_a_replay_test() {
    let dirs: Vec<String> =
        study_dirs().iter().map(|d| d.file_name().unwrap().to_string_lossy().into_owned()).collect();
    assert_eq!(dirs, REPLAYED, "study folders under results/ (left) and those with a replay test (right)");
}
