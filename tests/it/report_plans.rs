//! End-to-end tests of `covga report --plans --reference`: a small seeded and unseeded thesis
//! study set against the boustrophedon plans it is seeded with, the per-run figures read from
//! the run folders (checked against the folders here), the report re-made byte for byte once
//! the folders are gone, and the input that cannot be reported refused before anything is written.

use crate::common::covga;
use std::path::Path;

const STUDY: &str = r#"
seed = 11
seeds = 2
[base]
planner = "thesis"
[base.thesis]
pop_min = 12
max_genome_len = 300
[base.budget]
iterations = 1000000
evaluations = 400
[axes]
"map.source" = ["thesis-1", "thesis-2"]
"thesis.seed_population" = [[], ["boustrophedon"]]
"thesis.selection" = ["elite", "nsga2"]
"#;

const REFERENCE: &str = r#"
seed = 11
seeds = 1
[base]
planner = "boustrophedon"
[axes]
"map.source" = ["thesis-1", "thesis-2"]
"#;

/// The study and its reference plans, run into `dir` (`study/`, `reference/`).
fn studies(dir: &Path) {
    for (name, text) in [("study", STUDY), ("reference", REFERENCE)] {
        let file = dir.join(format!("{name}.toml"));
        std::fs::write(&file, text).unwrap();
        let out = dir.join(name);
        let o = covga(&["grid", file.to_str().unwrap(), "--jobs", "2", "--out", out.to_str().unwrap()]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
}

fn rows(text: &str) -> Vec<Vec<String>> {
    text.lines().map(|l| l.split(',').map(String::from).collect()).collect()
}

#[test]
fn plans_are_read_from_the_run_folders_and_remade_without_them() {
    let tmp = tempfile::tempdir().unwrap();
    studies(tmp.path());
    let study = tmp.path().join("study");
    let reference = tmp.path().join("reference/runs.csv");
    let args = ["report", study.to_str().unwrap(), "--plans", "--reference", reference.to_str().unwrap()];
    let o = covga(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(study.join("report/plans.md")).unwrap();
    let csv = std::fs::read_to_string(study.join("report/plans.csv")).unwrap();
    let table = rows(&csv);
    assert_eq!(table.len(), 1 + 16, "a row per run");
    // Each run's population figures, recomputed here from its population.csv.
    for row in &table[1..] {
        let pop = std::fs::read_to_string(study.join("runs").join(&row[0]).join("population.csv")).unwrap();
        let members: Vec<(f64, f64, f64)> = rows(&pop)[1..]
            .iter()
            .map(|m| (m[1].parse().unwrap(), m[2].parse().unwrap(), m[7].parse().unwrap()))
            .collect();
        assert_eq!(row[1].parse::<usize>().unwrap(), members.len());
        let clear: Vec<(f64, f64)> = members.iter().filter(|m| m.2 == 0.0).map(|m| (m.0, m.1)).collect();
        // Area above (0, 0) of the staircase of the points no other point dominates.
        let mut sorted = clear.clone();
        sorted.sort_by(|a, b| b.0.total_cmp(&a.0).then(b.1.total_cmp(&a.1)));
        let (mut area, mut top) = (0.0, 0.0);
        for (c, t) in sorted {
            if t > top {
                area += c * (t - top);
                top = t;
            }
        }
        let hv: f64 = row[3].parse().unwrap();
        assert!((hv - area).abs() < 1e-12, "run {}: {hv} vs {area}", row[0]);
        assert!(row[5].parse::<f64>().unwrap() > 0.0, "the initial population's best coverage");
    }
    for part in [
        "## Findings",
        "## Every configuration",
        "## Each run against its map's reference plan",
        "| thesis-1 | the reference plan |",
        "**`thesis.selection` = `nsga2`**",
        "of 16 runs are at least as good on both coverage and time_s",
    ] {
        assert!(md.contains(part), "{part}\n{md}");
    }
    // The folders gone, the report reads back its plans.csv: the same two files.
    std::fs::remove_dir_all(study.join("runs")).unwrap();
    let o = covga(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::read_to_string(study.join("report/plans.md")).unwrap(), md);
    assert_eq!(std::fs::read_to_string(study.join("report/plans.csv")).unwrap(), csv);
    // A reference without a plan for one of the maps, and --reference without --plans, are
    // refused (exit 2) with the report left as it was.
    let partial = tmp.path().join("partial.csv");
    let text = std::fs::read_to_string(&reference).unwrap();
    let kept: Vec<&str> = text.lines().filter(|l| !l.contains("thesis-2")).collect();
    std::fs::write(&partial, kept.join("\n") + "\n").unwrap();
    std::fs::write(study.join("report/plans.md"), "kept").unwrap();
    let o = covga(&["report", study.to_str().unwrap(), "--plans", "--reference", partial.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("no plan for map thesis-2"), "{err}");
    assert_eq!(std::fs::read_to_string(study.join("report/plans.md")).unwrap(), "kept");
    let o = covga(&["report", study.to_str().unwrap(), "--reference", reference.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn a_fleet_study_is_not_read_as_plans_of_one_robot() {
    let tmp = tempfile::tempdir().unwrap();
    for f in ["runs.csv", "study.json"] {
        std::fs::copy(Path::new("results/fleets").join(f), tmp.path().join(f)).unwrap();
    }
    for flag in ["--plans", "--seed-to-seed"] {
        let o = covga(&["report", tmp.path().to_str().unwrap(), flag]);
        assert_eq!(o.status.code(), Some(2), "{flag}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("this is a fleet study"), "{flag}: {err}");
    }
}
