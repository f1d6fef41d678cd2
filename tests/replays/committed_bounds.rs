//! The lower bound of `docs/src/concepts/lower-bound.md` holds for every committed plan: no
//! executable run of any committed study under `results/` reaches its final reachable
//! coverage sooner than the bound allows for that coverage (its robots, its map's cells and
//! free-space diameter, as `covga report` reads them from the study's grid file). The bound is
//! recomputed here from the committed `runs.csv`, so a change to the bound that makes it claim
//! more than the committed plans achieve fails this test.

use crate::common::repo;
use covga::report::analysis::bound::AreaBounds;
use covga::study::records::RunsTable;
use std::path::Path;

/// The committed `runs.csv` of a study folder, or its `runs.csv.xz` decompressed.
fn committed_runs(dir: &Path) -> RunsTable {
    let plain = dir.join("runs.csv");
    let text = if plain.exists() {
        std::fs::read_to_string(&plain).expect("read runs.csv")
    } else {
        let bytes = std::fs::read(dir.join("runs.csv.xz")).expect("read runs.csv.xz");
        let mut out = Vec::new();
        lzma_rs::xz_decompress(&mut std::io::Cursor::new(bytes), &mut out).expect("xz");
        String::from_utf8(out).expect("utf-8")
    };
    RunsTable::parse(&text).unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
}

/// Each executable run's mission time (a fleet's makespan) over its bound at the coverage it
/// reached, for the study in `results/<study>`.
fn ratios(study: &str) -> Vec<(String, f64)> {
    let dir = repo().join("results").join(study);
    let t = committed_runs(&dir);
    let bounds = AreaBounds::of(&dir, &t);
    assert!(bounds.missing.is_none(), "{study}: no bound: {:?}", bounds.missing);
    let col = |n: &str| t.col(n).unwrap_or_else(|| panic!("{study}: no {n} column"));
    let (id, exec, cov, span) = (col("run_id"), col("executable"), col("cov_final_reach"), col("makespan_s"));
    t.rows
        .iter()
        .filter(|r| r[exec] == "true")
        .filter_map(|r| {
            let (level, time): (f64, f64) = (r[cov].parse().ok()?, r[span].parse().ok()?);
            let bound = bounds.to_level_s(&r[id], level).expect("a bound for every run");
            (bound > 0.0).then(|| (r[id].clone(), time / bound))
        })
        .collect()
}

/// The studies with a grid file the bound can read its robots and maps from.
const STUDIES: &[&str] = &[
    "ablation",
    "cell-order",
    "figures-gallery",
    "fleets",
    "init-dist",
    "lane-layouts",
    "merged-lanes",
    "olson-ring",
    "quota-completion",
    "quota-search",
    "smoke",
    "thesis-real-maps",
    "thesis-seed-bound",
    "thesis-table-4-3",
];

#[test]
fn every_committed_study_is_checked() {
    let mut with_runs: Vec<String> = std::fs::read_dir(repo().join("results"))
        .expect("results/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.join("grid.toml").exists() && (p.join("runs.csv").exists() || p.join("runs.csv.xz").exists()))
        .map(|p| p.file_name().expect("a name").to_string_lossy().into_owned())
        .collect();
    with_runs.sort();
    assert_eq!(with_runs, STUDIES, "a committed study the bound test does not check, or one gone");
}

#[test]
fn no_committed_executable_run_beats_its_bound() {
    let mut all = Vec::new();
    for study in STUDIES {
        let r = ratios(study);
        let below: Vec<_> = r.iter().filter(|(_, x)| *x < 1.0 - 1e-9).collect();
        assert!(below.is_empty(), "{study}: runs faster than their bound: {below:?}");
        let mut x: Vec<f64> = r.iter().map(|(_, x)| *x).collect();
        x.sort_by(f64::total_cmp);
        if let (Some(least), Some(median)) = (x.first(), x.get(x.len() / 2)) {
            eprintln!("{study}: {} executable runs, time over bound least {least:.3}, median {median:.3}", x.len());
        }
        all.extend(r.into_iter().map(|(_, x)| x));
    }
    assert!(all.len() > 9_000, "{} runs checked", all.len());
    all.sort_by(f64::total_cmp);
    eprintln!(
        "{} executable runs; time over bound: least {:.3}, median {:.3}; bound over time median {:.3}",
        all.len(),
        all[0],
        all[all.len() / 2],
        1.0 / all[all.len() / 2]
    );
}
