//! `thesis.selection = "nsga2"`: Pareto selection over 003's two objectives, end to end.

use crate::common::{run_text, summary};
use covga::experiment::file::ExperimentFile;
use covga::ga::pareto::dominates;
use std::path::Path;

fn run(text: &str, dir: &Path) -> serde_json::Value {
    run_text(text, Path::new("."), dir);
    summary(dir)
}

/// A numeric column of a CSV file by name.
fn column(path: &Path, name: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let k = lines.next().unwrap().split(',').position(|h| h == name).unwrap_or_else(|| panic!("no {name}"));
    lines.map(|l| l.split(',').nth(k).unwrap().parse().unwrap()).collect()
}

const NSGA2: &str = "seed = 3\nplanner = \"thesis\"\n[thesis]\nselection = \"nsga2\"\npop_min = 40\ninit_actions = 30\n\
                     [budget]\niterations = 150\n";

#[test]
fn nsga2_reports_its_front_its_knee_and_a_growing_hypervolume() {
    let tmp = tempfile::tempdir().unwrap();
    let s = run(NSGA2, tmp.path());
    let front: Vec<(f64, f64)> =
        s["front"].as_array().unwrap().iter().map(|r| (r[0].as_f64().unwrap(), r[1].as_f64().unwrap())).collect();
    assert!(front.len() >= 2, "{front:?}");
    for a in &front {
        assert!(front.iter().all(|b| !dominates(*b, *a)), "{a:?} is dominated on the front");
    }
    // The plan is a member of the front: the knee.
    let plan = (s["cov_final"].as_f64().unwrap(), s["t_final"].as_f64().unwrap());
    assert!(front.contains(&plan), "{plan:?} not on {front:?}");
    // 003's constraint: no obstacle cell swept by the footprint's rectangles. The body rule of
    // `executable` is stricter (vertices, turns and end caps), and 003's penalty does not see it.
    assert_eq!(s["score"]["obstacle_sweeps"], 0);
    let hv = column(&tmp.path().join("history.csv"), "hypervolume");
    assert_eq!(hv.len(), 151);
    assert!(hv[150] > hv[0] && hv[150] <= 1.0, "{} -> {}", hv[0], hv[150]);
    let population = column(&tmp.path().join("population.csv"), "obstacle_cells");
    assert_eq!(population.len(), 40);
}

#[test]
fn nsga2_is_reproducible_on_any_number_of_threads() {
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap().install(|| run(NSGA2, a.path()));
    let two = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap().install(|| run(NSGA2, b.path()));
    let strip = |mut v: serde_json::Value| {
        v.as_object_mut().unwrap().remove("wall_s");
        v
    };
    assert_eq!(strip(one), strip(two));
    for f in ["history.csv", "best_path.csv", "population.csv", "best_genome.csv"] {
        assert_eq!(std::fs::read(a.path().join(f)).unwrap(), std::fs::read(b.path().join(f)).unwrap(), "{f}");
    }
}

#[test]
fn elite_runs_write_no_pareto_columns() {
    let tmp = tempfile::tempdir().unwrap();
    let s = run(&NSGA2.replace("nsga2", "elite"), tmp.path());
    assert!(s.get("front").is_none());
    let header = std::fs::read_to_string(tmp.path().join("history.csv")).unwrap();
    assert!(!header.lines().next().unwrap().contains("hypervolume"));
}

#[test]
fn nsga2_refuses_a_ramp() {
    let text = NSGA2.replace("[budget]", "[thesis.control]\nkind = \"ramp\"\nmin = 1.0\nmax = 2.0\n[budget]");
    let e = ExperimentFile::parse(&text, "t").unwrap().validate("t", Path::new("."), "t").unwrap_err();
    assert!(e.to_string().contains("thesis.control.kind"), "{e}");
}
