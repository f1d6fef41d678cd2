//! End-to-end tests of `covga report --compare` on a committed study's runs.csv
//! (`results/init-dist`, 384 runs): the comparison files, their reproducibility, and a
//! comparison that cannot be made refused before anything is written.

use crate::common::covga;
use std::path::Path;

/// A committed study's `runs.csv` (or its `runs.csv.xz`, decompressed).
fn committed_runs(folder: &Path) -> Vec<u8> {
    let plain = folder.join("runs.csv");
    if plain.exists() {
        return std::fs::read(plain).unwrap();
    }
    let packed = std::fs::read(folder.join("runs.csv.xz")).unwrap();
    let mut out = Vec::new();
    lzma_rs::xz_decompress(&mut std::io::Cursor::new(packed), &mut out).unwrap();
    out
}

/// A study folder holding a committed study's runs.csv and study.json.
fn committed_study(folder: &Path) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(folder.join("study.json"), dir.path().join("study.json")).unwrap();
    std::fs::write(dir.path().join("runs.csv"), committed_runs(folder)).unwrap();
    dir
}

/// [`committed_study`] with the study's grid file and what its reports recorded of the run
/// folders (`report/run-folders.csv`, and report folder `report`'s own): each plan's times to
/// coverage, which a comparison of plans of unequal coverage reads.
fn committed_study_with_record(folder: &Path, report: &str) -> tempfile::TempDir {
    let dir = committed_study(folder);
    if folder.join("grid.toml").exists() {
        std::fs::copy(folder.join("grid.toml"), dir.path().join("grid.toml")).unwrap();
    }
    for r in ["report", report] {
        let record = folder.join(r).join("run-folders.csv");
        if record.exists() {
            std::fs::create_dir_all(dir.path().join(r)).unwrap();
            std::fs::copy(&record, dir.path().join(r).join("run-folders.csv")).unwrap();
        }
    }
    dir
}

/// A study folder holding the committed runs.csv and study.json of `results/init-dist`.
fn study() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for f in ["runs.csv", "study.json"] {
        std::fs::copy(Path::new("results/init-dist").join(f), dir.path().join(f)).unwrap();
    }
    dir
}

#[test]
fn a_comparison_is_written_beside_the_report_and_remade_byte_for_byte() {
    let dir = study();
    let d = dir.path().to_str().unwrap();
    let o = covga(&["report", d, "--compare", "thesis.init_dist_max=3.0"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(dir.path().join("report/compare-thesis.init_dist_max.md")).unwrap();
    let csv = std::fs::read(dir.path().join("report/compare-thesis.init_dist_max.csv")).unwrap();
    for part in
        ["## Executable plans", "## `cov_final_reach`", "## `time_s`", "Holm–Bonferroni over the", "paired by seed"]
    {
        assert!(md.contains(part), "{part}");
    }
    // One row per stratum and metric (the other parameters crossed) × 3, and per value the
    // pooled rows of the three and of the time's margin.
    let rows = csv.iter().filter(|&&b| b == b'\n').count() - 1;
    assert_eq!((rows - 2 * 4) % 3, 0, "{rows}");
    assert!(rows >= 3 * 64, "{rows}");
    // 192 strata of five seeds on two floor plans: pooled first, then stratum by stratum.
    assert!(md.contains("## `cov_final_reach`, pooled over the floor plans\n"), "the pooled section");
    assert!(md.contains("The pooled unit is the floor plan (2 units from 192 strata)"), "the unit and why");
    assert!(md.find("pooled over the floor plans").unwrap() < md.find("## `cov_final_reach`\n").unwrap());
    let again = covga(&["report", d, "--compare", "thesis.init_dist_max=3.0"]);
    assert!(again.status.success());
    assert_eq!(std::fs::read(dir.path().join("report/compare-thesis.init_dist_max.csv")).unwrap(), csv);
}

#[test]
fn every_plan_is_compared_beside_the_executable_plans() {
    let dir = study();
    let d = dir.path().to_str().unwrap();
    let o = covga(&[
        "report",
        d,
        "--compare",
        "thesis.init_dist_max=3.0",
        "--compare-every-plan",
        "thesis.init_dist_max=3.0",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let read = |f: &str| std::fs::read_to_string(dir.path().join("report").join(f)).unwrap();
    let (executable, every) =
        (read("compare-thesis.init_dist_max.md"), read("compare-thesis.init_dist_max-every-plan.md"));
    assert!(every.starts_with("# `thesis.init_dist_max`: each value against `3.0`, every plan\n"));
    // Every pooled pair counts: 192 strata × 5 seeds, against the few where both plans are
    // executable.
    let pooled_pairs = |md: &str| -> usize {
        let line = md
            .lines()
            .skip_while(|l| !l.starts_with("## `cov_final_reach`, pooled"))
            .find(|l| l.starts_with("| 10.0 |"))
            .unwrap();
        line.split('|').nth(3).unwrap().trim().parse().unwrap()
    };
    assert_eq!(pooled_pairs(&every), 960);
    assert!(pooled_pairs(&executable) < 100, "{}", pooled_pairs(&executable));
}

/// `--design` writes what each comparison can show beside it: the seed-bound study's five seeds
/// per setting cannot show anything setting by setting, nor can its four floor plans pooled.
#[test]
fn the_design_file_says_what_a_comparison_can_show() {
    let dir = committed_study(Path::new("results/thesis-seed-bound"));
    let d = dir.path().to_str().unwrap();
    let o = covga(&["report", d, "--compare", "thesis.seed_bound=none", "--design"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("design-thesis.seed_bound.md"));
    let md = std::fs::read_to_string(dir.path().join("report/design-thesis.seed_bound.md")).unwrap();
    for row in [
        "| `time_s`, stratum by stratum | 8 | 5 | 0.0625 | 0.5000 | **no** | 9 |",
        "| `time_s`, pooled | 1 | 4 | 0.1250 | 0.1250 | **no** | 6 |",
        "| `time_s` | dominate | 4 |",
    ] {
        assert!(md.contains(row), "{row}\n{md}");
    }
    let o = covga(&["report", d, "--design"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--design"), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn a_comparison_that_cannot_be_made_exits_2_and_writes_nothing() {
    let dir = study();
    let d = dir.path().to_str().unwrap();
    for (arg, message) in [
        ("thesis.nope=3", "not a swept parameter"),
        ("thesis.init_dist_max=7", "no run has that value; values: 3.0, 10.0, 50.0"),
        ("thesis.init_dist_max", "expected KEY=BASELINE"),
    ] {
        let o = covga(&["report", d, "--compare", arg]);
        assert_eq!(o.status.code(), Some(2), "{arg}");
        assert!(String::from_utf8_lossy(&o.stderr).contains(message), "{arg}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(!dir.path().join("report").exists(), "{arg}: a report folder was written");
    }
}

/// The committed comparison files are what `covga report` writes from the committed runs: each
/// study's `compare-*` files (the forest plots' PNGs included) re-made from its `runs.csv` and
/// `study.json` alone, byte for byte.
#[test]
fn committed_comparisons_are_remade_byte_for_byte() {
    // (study, report folder and the arguments that name and filter it, --compare, --compare-every-plan)
    type Study<'a> = (&'a str, (&'a str, &'a [&'a str]), &'a [&'a str], &'a [&'a str]);
    let studies: [Study; 4] = [
        ("results/init-dist", ("report", &[]), &["thesis.init_dist_max=3.0"], &["thesis.init_dist_max=3.0"]),
        ("results/thesis-seed-bound", ("report", &[]), &["thesis.seed_bound=none"], &[]),
        (
            "results/thesis-real-maps",
            ("report", &[]),
            &["thesis.moves=straight", "thesis.seed_population=[]", "thesis.selection=elite"],
            &[],
        ),
        (
            "results/cell-order",
            ("report-controls", &["--name", "controls", "--where", "planner=cell_order"]),
            &[
                "cell_order.solver=nearest|boustrophedon",
                "cell_order.solver=nearest",
                "cell_order.solver=boustrophedon",
                "cell_order.solver=ils",
            ],
            &[],
        ),
    ];
    for (folder, (report, naming), compare, every) in studies {
        let dir = committed_study_with_record(Path::new(folder), report);
        let mut args = vec!["report".to_string(), dir.path().to_str().unwrap().to_string()];
        args.extend(naming.iter().map(|a| a.to_string()));
        for c in compare {
            args.extend(["--compare".to_string(), c.to_string()]);
        }
        for c in every {
            args.extend(["--compare-every-plan".to_string(), c.to_string()]);
        }
        let o = covga(&args.iter().map(String::as_str).collect::<Vec<_>>());
        assert!(o.status.success(), "{folder}: {}", String::from_utf8_lossy(&o.stderr));
        let mut compared = 0;
        for entry in std::fs::read_dir(dir.path().join(report)).unwrap().flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            // The forest plot's SVG is not committed (its PNG is, and is compared too).
            if !name.starts_with("compare-") || name.ends_with(".svg") {
                continue;
            }
            let committed = std::fs::read(Path::new(folder).join(report).join(&name))
                .unwrap_or_else(|e| panic!("{folder}/{report}/{name} is not committed: {e}"));
            assert!(
                std::fs::read(entry.path()).unwrap() == committed,
                "{folder}/{report}/{name} differs from covga report's"
            );
            compared += usize::from(!name.ends_with(".png"));
        }
        assert_eq!(compared, 2 * (compare.len() + every.len()), "{folder}");
    }
}

/// The committed `plans.md` and `plans.csv` of the seeded thesis studies are what `covga report
/// --plans` writes from the committed runs.csv and the plans.csv it recorded when the run
/// folders were there (the folders themselves are not committed), byte for byte.
#[test]
fn committed_plans_are_remade_byte_for_byte() {
    for folder in ["results/thesis-real-maps", "results/thesis-seed-bound"] {
        let folder = Path::new(folder);
        let dir = committed_study(folder);
        std::fs::create_dir(dir.path().join("report")).unwrap();
        std::fs::copy(folder.join("report/plans.csv"), dir.path().join("report/plans.csv")).unwrap();
        let d = dir.path().to_str().unwrap();
        let reference = "results/thesis-real-maps/seeds.csv";
        let o = covga(&["report", d, "--by", "map.source", "--plans", "--reference", reference]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        for file in ["plans.md", "plans.csv"] {
            assert!(
                std::fs::read(dir.path().join("report").join(file)).unwrap()
                    == std::fs::read(folder.join("report").join(file)).unwrap(),
                "{}/report/{file} differs from covga report's",
                folder.display()
            );
        }
    }
}

/// `results/thesis-table-4-3`'s seed-to-seed tables are what `covga report --seed-to-seed`
/// writes from the committed runs, byte for byte.
#[test]
fn the_seed_to_seed_tables_are_remade_byte_for_byte() {
    let folder = Path::new("results/thesis-table-4-3");
    let dir = committed_study(folder);
    let d = dir.path().to_str().unwrap();
    let args =
        ["report", d, "--name", "seed-to-seed", "--by", "map.source", "--by", "thesis.c_child", "--seed-to-seed"];
    let o = covga(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let made = std::fs::read_to_string(dir.path().join("report-seed-to-seed/seed-to-seed.md")).unwrap();
    let committed = std::fs::read_to_string(folder.join("report-seed-to-seed/seed-to-seed.md")).unwrap();
    assert!(made == committed, "report-seed-to-seed/seed-to-seed.md differs from covga report's");
    for part in ["| 0 vs 1 |", "## 003 Tables A.1/A.2 beside this study", "| thesis-2 | 6.28 | f2 | rrws |"] {
        assert!(made.contains(part), "{part}");
    }
}

/// The condensed analysis of variance of `results/thesis-table-4-3` is what `covga report
/// --anova-condensed` writes from the committed runs, byte for byte; so is the table of feasible
/// runs by `P_mA` its README's new finding reads (`covga report --measure` on runs.csv columns).
#[test]
fn the_condensed_anova_and_the_c_child_table_are_remade() {
    let folder = Path::new("results/thesis-table-4-3");
    let dir = committed_study(folder);
    let d = dir.path().to_str().unwrap();
    let o = covga(&["report", d, "--by", "thesis.selection", "--anova-condensed"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let made = std::fs::read_to_string(dir.path().join("report/anova-condensed.md")).unwrap();
    let committed = std::fs::read_to_string(folder.join("report/anova-condensed.md")).unwrap();
    assert!(made == committed, "results/thesis-table-4-3/report/anova-condensed.md differs from covga report's");
    assert_eq!(made.matches("| term | df |").count(), 4, "the four condensed tables");
    let readme = std::fs::read_to_string(folder.join("README.md")).unwrap();
    let line = readme.lines().find(|l| l.starts_with("covga report") && l.contains("--measure")).expect("the command");
    let args: Vec<&str> = line.split("   #").next().unwrap().split_whitespace().skip(3).collect();
    let o = covga(&[&["report", d], args.as_slice()].concat());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let file = "report-c-child-0/measures.md";
    let made = std::fs::read_to_string(dir.path().join(file)).unwrap();
    assert!(made == std::fs::read_to_string(folder.join(file)).unwrap(), "{file} differs from covga report's");
    assert!(made.contains("| thesis.p_ma=0.1 | 1008 |"), "{made}");
}

/// `results/olson-ring`'s table of the waypoint planner's own figures is what `covga report
/// --measure` writes from the committed runs.csv and the measures.csv it recorded when the run
/// folders were there, byte for byte; without that file, a figure read from the run folders is
/// refused with exit 2 and the file named.
#[test]
fn the_waypoint_measures_are_remade_byte_for_byte() {
    let folder = Path::new("results/olson-ring");
    let dir = committed_study(folder);
    let d = dir.path().to_str().unwrap();
    let text = std::fs::read_to_string(folder.join("README.md")).unwrap();
    // The command the README gives, from `covga report` on, its study folder left out.
    let command = text.lines().skip_while(|l| !l.starts_with("covga report")).take_while(|l| !l.starts_with("```"));
    let args: Vec<String> = command
        .flat_map(|l| l.trim_end_matches('\\').split_whitespace().map(str::to_string).collect::<Vec<_>>())
        .skip(3)
        .collect();
    assert!(args.iter().any(|a| a == "--measure"), "the README's report command: {args:?}");
    let mut full = vec!["report".to_string(), d.to_string()];
    full.extend(args);
    let full: Vec<&str> = full.iter().map(String::as_str).collect();
    let refused = covga(&full);
    assert_eq!(refused.status.code(), Some(2), "{}", String::from_utf8_lossy(&refused.stderr));
    assert!(String::from_utf8_lossy(&refused.stderr).contains("measures.csv"));
    assert!(!dir.path().join("report").exists(), "a refused report leaves no report folder");
    std::fs::create_dir(dir.path().join("report")).unwrap();
    std::fs::copy(folder.join("report/measures.csv"), dir.path().join("report/measures.csv")).unwrap();
    let o = covga(&full);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for file in ["measures.md", "measures.csv"] {
        assert!(
            std::fs::read(dir.path().join("report").join(file)).unwrap()
                == std::fs::read(folder.join("report").join(file)).unwrap(),
            "results/olson-ring/report/{file} differs from covga report's"
        );
    }
}
