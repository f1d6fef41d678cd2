//! End-to-end tests of `covga report --compare` on a committed study's runs.csv
//! (`results/init-dist`, 384 runs): the comparison files, their reproducibility, and a
//! comparison that cannot be made refused before anything is written.

use std::path::Path;
use std::process::{Command, Output};

fn covga(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_covga")).args(args).output().expect("covga runs")
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
    // One row per stratum and metric: 128 strata (the other parameters crossed) × 3.
    let rows = csv.iter().filter(|&&b| b == b'\n').count() - 1;
    assert_eq!(rows % 3, 0);
    assert!(rows >= 3 * 64, "{rows}");
    // 192 strata of five seeds: pooled first, then stratum by stratum.
    assert!(md.contains("## `cov_final_reach`, pooled over the strata\n"), "the pooled section");
    assert!(md.find("pooled over the strata").unwrap() < md.find("## `cov_final_reach`\n").unwrap());
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
