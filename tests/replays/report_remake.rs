//! Every committed `summary.md` under `results/` is what `covga report` writes from the
//! committed `runs.csv` and `study.json`, with the study's own arguments: a summary edited by
//! hand, or one the report no longer writes, fails here.
//!
//! A committed study keeps no run folders (histories and paths, up to 30 GB). What the report
//! read from them for its tables — each run's final diversity for 003 §5.1's claims, each
//! plan's times to coverage — it recorded in `run-folders.csv` beside the summary, committed
//! with it and read back here, so those tables must come out the same. Left out of the
//! comparison, and only that: the figure lines and the note that the folders are missing (the
//! figures cannot be redrawn without them), and, for a study that commits no record, the
//! tables the record would give (the time-to-coverage section, the claims' diversity rows).

use std::path::Path;

/// Study, the committed summary's path in it, and the `covga report` arguments that made it
/// (the README's commands; `scripts/thesis-figures.sh` for Table 4.3's figure reports).
const REPORTS: &[(&str, &str, &[&str])] = &[
    ("ablation", "report/summary.md", &["--by", "map.source"]),
    ("smoke", "report/summary.md", &[]),
    ("figures-gallery", "report/summary.md", &["--by", "planner", "--by", "cell_order.solver"]),
    ("init-dist", "report/summary.md", &["--by", "thesis.init_dist_max"]),
    ("fleets", "summary.md", &[]),
    ("thesis-real-maps", "report/summary.md", &["--by", "map.source"]),
    (
        "cell-order",
        "report-basement/summary.md",
        &[
            "--name",
            "basement",
            "--where",
            "map.source=experiments/maps/basement.yaml",
            "--where",
            "robot.rot_speed=0.52",
            "--where",
            "planner=cell_order",
            "--by",
            "cell_order.solver",
            "--by",
            "cell_order.seed_directions",
        ],
    ),
    (
        "quota-completion",
        "report/summary.md",
        &["--by", "cell_order.solver", "--by", "cell_order.completion", "--compare", "cell_order.completion=boundary"],
    ),
    (
        "merged-lanes",
        "report/summary.md",
        &["--by", "cell_order.solver", "--by", "cell_order.merge_gap_m", "--compare", "cell_order.merge_gap_m=0"],
    ),
    (
        "lane-layouts",
        "report/summary.md",
        &[
            "--by",
            "cell_order.solver",
            "--by",
            "cell_order.offer_split_lanes",
            "--compare",
            "cell_order.offer_split_lanes=false",
        ],
    ),
    (
        "quota-search",
        "report/summary.md",
        &["--by", "cell_order.solver", "--by", "cell_order.completion", "--compare", "cell_order.completion=quota"],
    ),
    ("thesis-table-4-3", "report/summary.md", &["--by", "thesis.selection"]),
    (
        "thesis-table-4-3",
        "report-fig-4-2/summary.md",
        &[
            "--name",
            "fig-4-2",
            "--where",
            "map.source=thesis-1",
            "--where",
            "robot.rot_speed=0",
            "--by",
            "thesis.selection",
            "--by",
            "scorer.projection",
        ],
    ),
    (
        "thesis-table-4-3",
        "report-fig-4-3-ts/summary.md",
        &[
            "--name",
            "fig-4-3-ts",
            "--where",
            "map.source=thesis-1",
            "--where",
            "robot.rot_speed=0",
            "--where",
            "thesis.selection=tournament",
            "--by",
            "thesis.tournament_size",
            "--by",
            "scorer.projection",
        ],
    ),
    (
        "thesis-table-4-3",
        "report-fig-4-3-sp/summary.md",
        &[
            "--name",
            "fig-4-3-sp",
            "--where",
            "map.source=thesis-1",
            "--where",
            "robot.rot_speed=0",
            "--where",
            "thesis.selection=rrws",
            "--by",
            "thesis.selection_pressure",
            "--by",
            "scorer.projection",
        ],
    ),
    (
        "thesis-table-4-3",
        "report-fig-4-4/summary.md",
        &[
            "--name",
            "fig-4-4",
            "--where",
            "map.source=thesis-1",
            "--where",
            "robot.rot_speed=0",
            "--by",
            "thesis.c_len",
            "--by",
            "thesis.c_child",
        ],
    ),
    (
        "thesis-table-4-3",
        "report-fig-4-5/summary.md",
        &[
            "--name",
            "fig-4-5",
            "--where",
            "map.source=thesis-1",
            "--where",
            "robot.rot_speed=0",
            "--by",
            "thesis.p_mi",
            "--by",
            "thesis.p_ma",
        ],
    ),
    (
        "thesis-table-4-3",
        "report-tables-a1-a2/summary.md",
        &[
            "--name",
            "tables-a1-a2",
            "--by",
            "map.source",
            "--by",
            "robot.rot_speed",
            "--by",
            "thesis.selection",
            "--by",
            "scorer.projection",
        ],
    ),
];

/// A study folder holding a committed study's runs.csv (decompressed), study.json and grid.toml
/// (which gives the time-to-coverage table each run's area bound).
fn committed_study(folder: &Path) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for file in ["study.json", "grid.toml"] {
        std::fs::copy(folder.join(file), dir.path().join(file)).unwrap();
    }
    let plain = folder.join("runs.csv");
    let text = if plain.exists() {
        std::fs::read(&plain).unwrap()
    } else {
        let bytes = std::fs::read(folder.join("runs.csv.xz")).unwrap();
        let mut out = Vec::new();
        lzma_rs::xz_decompress(&mut std::io::Cursor::new(bytes), &mut out).unwrap();
        out
    };
    std::fs::write(dir.path().join("runs.csv"), text).unwrap();
    dir
}

/// `text` without what the report draws from run folders and, without a `record`, the tables
/// it reads from them (module docs), the study folder's path written as `folder`.
fn without_run_folders(text: &str, tmp: &str, folder: &str, record: bool) -> String {
    let text = text.replace(tmp, folder);
    let mut out = Vec::new();
    let mut skipping_paragraph = false;
    let mut in_curves = false;
    for line in text.lines() {
        if line.starts_with("## ") {
            in_curves = !record && line == "## Time to coverage";
        }
        if in_curves {
            continue;
        }
        if line.starts_with("**No `runs/` folder") || line.starts_with("![") {
            skipping_paragraph = true;
            continue;
        }
        if skipping_paragraph && line.is_empty() {
            skipping_paragraph = false;
            continue;
        }
        if !record && (line.contains("with a history for the diversity") || line.contains("| final diversity,")) {
            continue;
        }
        out.push(line);
    }
    out.join("\n")
}

/// Every committed summary of study folder `study` re-made and compared.
fn remake_study(study: &str) {
    let mut failures = Vec::new();
    {
        let folder = Path::new("results").join(study);
        let dir = committed_study(&folder);
        let tmp = dir.path().to_str().unwrap();
        // The study's record of its run folders (`report/run-folders.csv`; a report of some of
        // the runs reads it there too).
        let record = folder.join("report").join("run-folders.csv");
        let recorded = record.exists();
        if recorded {
            std::fs::create_dir(dir.path().join("report")).unwrap();
            std::fs::copy(&record, dir.path().join("report/run-folders.csv")).unwrap();
        }
        for (_, file, args) in REPORTS.iter().filter(|r| r.0 == study) {
            // A report folder's own record (a filtered report's) is read before the study's.
            let own = folder.join(file).with_file_name("run-folders.csv");
            if own.exists() {
                let made_folder = dir.path().join(Path::new(file).parent().unwrap());
                std::fs::create_dir_all(&made_folder).unwrap();
                std::fs::copy(&own, made_folder.join("run-folders.csv")).unwrap();
            }
            let o = crate::common::command().arg("report").arg(tmp).args(*args).output().unwrap();
            assert!(o.status.success(), "{study} {args:?}: {}", String::from_utf8_lossy(&o.stderr));
            // The fleet report writes report/summary.md; the study commits it at its top.
            let made_file = if file.starts_with("report") { file.to_string() } else { format!("report/{file}") };
            let made = std::fs::read_to_string(dir.path().join(made_file)).unwrap();
            let committed = std::fs::read_to_string(folder.join(file)).unwrap();
            let out_folder = format!("out/{study}");
            let strict = recorded || own.exists();
            let (a, b) = (
                without_run_folders(&made, tmp, &out_folder, strict),
                without_run_folders(&committed, tmp, &out_folder, strict),
            );
            assert!(b.lines().count() > 10, "{study}/{file}: nothing left to compare");
            if a != b {
                let first = a.lines().zip(b.lines()).position(|(x, y)| x != y).unwrap_or(0);
                failures.push(format!(
                    "results/{study}/{file} differs from covga report's at line {first} of the compared text:\n  made:      {}\n  committed: {}",
                    a.lines().nth(first).unwrap_or(""),
                    b.lines().nth(first).unwrap_or("")
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

per_study_tests! {
    remake_study, REMADE:
    ablation => "ablation",
    smoke => "smoke",
    figures_gallery => "figures-gallery",
    init_dist => "init-dist",
    fleets => "fleets",
    thesis_real_maps => "thesis-real-maps",
    cell_order => "cell-order",
    quota_completion => "quota-completion",
    merged_lanes => "merged-lanes",
    lane_layouts => "lane-layouts",
    quota_search => "quota-search",
    thesis_table_4_3 => "thesis-table-4-3",
}

/// A study added to [`REPORTS`] without a test of its own fails here.
#[test]
fn every_listed_study_has_a_remake_test() {
    let mut studies: Vec<&str> = REPORTS.iter().map(|r| r.0).collect();
    studies.dedup();
    assert_eq!(studies, REMADE, "studies of REPORTS (left) and those with a test (right)");
}

/// Every `summary.md` under `results/` is one of [`REPORTS`]: a summary added without a way
/// to re-make it fails.
#[test]
fn every_summary_under_results_is_listed() {
    fn walk(dir: &Path, found: &mut Vec<String>) {
        for e in std::fs::read_dir(dir).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                walk(&p, found);
            } else if p.file_name().is_some_and(|n| n == "summary.md") {
                found.push(p.strip_prefix("results").unwrap().to_string_lossy().replace('\\', "/"));
            }
        }
    }
    let mut found = Vec::new();
    walk(Path::new("results"), &mut found);
    found.sort();
    let mut listed: Vec<String> = REPORTS.iter().map(|(s, f, _)| format!("{s}/{f}")).collect();
    listed.sort();
    assert_eq!(found, listed, "summaries under results/ (left) and those this test re-makes (right)");
}
