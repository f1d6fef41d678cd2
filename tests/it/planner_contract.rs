//! The contract every planner keeps, checked for every kind of the registry
//! (`PlannerKind::built_in`, the list `PLANNERS`), so that a planner added there is covered without an edit here: the
//! same file and seed give the same files; the evaluation budget is kept to within one step
//! (one generation, or one batch, of the planner's own); the history counts iterations 0..n
//! with evaluations that never fall and end at the summary's; the returned plan is what the
//! common scorer says of it (`covga eval` of its `best_path.csv`); and a key of a section the
//! planner does not read is named in a warning.

use crate::common::run_text;
use covga::experiment::file::ExperimentFile;
use covga::experiment::ignored::why_ignored;
use covga::experiment::registry::PlannerKind;
use std::path::Path;

/// The evaluation budget of every contract run.
const BUDGET: u64 = 900;

/// A small run of `kind` on map 2 of the thesis.
fn experiment(kind: PlannerKind) -> String {
    format!(
        "planner = \"{}\"\nseed = 4\n[map]\nsource = \"thesis-2\"\n[stations]\nstart = [1.3, 1.3]\n\
         [thesis]\npop_min = 20\ninit_individuals = 20\ninit_actions = 20\n\
         [waypoint]\npopulation = 20\n\
         [cell_order]\npopulation = 20\n\
         [budget]\nevaluations = {BUDGET}\n",
        kind.name()
    )
}

/// Runs `text` into a fresh folder; returns the folder.
fn run(text: &str) -> tempfile::TempDir {
    let tmp = tempfile::tempdir().unwrap();
    run_text(text, Path::new("."), tmp.path());
    tmp
}

/// The run's summary without its timings.
fn summary(dir: &Path) -> serde_json::Value {
    let mut s = crate::common::summary(dir);
    for timing in ["wall_s", "precompute_s"] {
        s.as_object_mut().unwrap().remove(timing);
    }
    s
}

/// `(iteration, evaluations)` of each row of `history.csv`.
fn history(dir: &Path) -> Vec<(u64, u64)> {
    let mut rows = csv::Reader::from_path(dir.join("history.csv")).unwrap();
    let head = rows.headers().unwrap().clone();
    let col = |name: &str| head.iter().position(|h| h == name).unwrap();
    let (it, ev) = (col("iteration"), col("evaluations"));
    rows.records().map(|r| r.unwrap()).map(|r| (r[it].parse().unwrap(), r[ev].parse().unwrap())).collect()
}

#[test]
fn every_planner_keeps_the_contract() {
    for kind in PlannerKind::built_in() {
        let name = kind.name();
        let text = experiment(kind);
        let (a, b) = (run(&text), run(&text));
        // Deterministic for a seed.
        let s = summary(a.path());
        assert_eq!(s, summary(b.path()), "{name}: two runs of one seed differ");
        for file in ["best_path.csv", "history.csv"] {
            let read = |d: &tempfile::TempDir| std::fs::read(d.path().join(file)).unwrap();
            assert_eq!(read(&a), read(&b), "{name}: {file} differs between two runs of one seed");
        }
        // Records 0..n, evaluations never falling, ending at the summary's.
        let rows = history(a.path());
        assert!(!rows.is_empty(), "{name}: no history");
        for (k, w) in rows.iter().enumerate() {
            assert_eq!(w.0, k as u64, "{name}: history row {k} is iteration {}", w.0);
        }
        assert!(rows.windows(2).all(|w| w[0].1 <= w[1].1), "{name}: evaluations fall: {rows:?}");
        let evaluations = s["evaluations"].as_u64().unwrap();
        assert_eq!(rows.last().unwrap().1, evaluations, "{name}: the history ends elsewhere than the summary");
        // The summary's iterations are the last record's, the initial population being 0.
        let last = rows.last().unwrap().0;
        assert_eq!(s["iterations"].as_u64().unwrap(), last, "{name}: iterations");
        // The budget, to within one step of the planner's own.
        let step = rows.windows(2).map(|w| w[1].1 - w[0].1).max().unwrap_or(rows[0].1);
        assert!(
            evaluations <= BUDGET + step,
            "{name}: {evaluations} evaluations of a budget of {BUDGET} (step {step})"
        );
        // The returned plan is what the common scorer says of it.
        let eval = crate::common::command()
            .args(["eval", "--map", "thesis-2", "--start", "1.3,1.3", "--json", "--path"])
            .arg(a.path().join("best_path.csv"))
            .output()
            .unwrap();
        assert!(eval.status.success(), "{name}: {}", String::from_utf8_lossy(&eval.stderr));
        let eval: serde_json::Value = serde_json::from_slice(&eval.stdout).unwrap();
        for key in ["executable", "cov_final_free", "cov_final_reach", "obstacle_cells", "length_m", "time_s"] {
            assert_eq!(s["score"][key], eval["common"][key], "{name}: score.{key}");
        }
        // The time-to-coverage curve rises to the scorer's reachable coverage at the plan's
        // makespan, and the summary's times are read off it.
        let curve: Vec<(f64, f64)> = std::fs::read_to_string(a.path().join("coverage_curve.csv"))
            .unwrap()
            .lines()
            .skip(1)
            .map(|l| {
                let (t, c) = l.split_once(',').unwrap();
                (t.parse().unwrap(), c.parse().unwrap())
            })
            .collect();
        assert!(curve.windows(2).all(|w| w[0].0 < w[1].0 && w[0].1 <= w[1].1), "{name}: {curve:?}");
        let (end_t, end_c) = *curve.last().unwrap();
        let makespan = s["score"]["makespan_s"].as_f64().unwrap();
        assert!(
            (end_t - makespan).abs() <= 1e-6 * makespan.max(1.0),
            "{name}: curve ends at {end_t} s, makespan {makespan}"
        );
        // (serde_json reads floats to within an ulp, the CSV exactly.)
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1.0);
        let cov = s["score"]["cov_final_reach"].as_f64().unwrap();
        assert!(close(end_c, cov), "{name}: the curve ends at {end_c}, the scorer says {cov}");
        for (key, level) in [("time_to_80_s", 0.8), ("time_to_90_s", 0.9), ("time_to_95_s", 0.95)] {
            let first = curve.iter().find(|p| p.1 >= level - 1e-12).map(|p| p.0);
            let read = s["coverage_curve"][key].as_f64();
            assert_eq!(read.is_some(), first.is_some(), "{name}: {key} {read:?} vs {first:?}");
            assert!(read.zip(first).is_none_or(|(a, b)| close(a, b)), "{name}: {key} {read:?} vs {first:?}");
        }
    }
}

#[test]
fn every_planner_names_the_sections_it_does_not_read() {
    let sections = ["thesis.pop_min", "waypoint.population", "pattern.angle_deg", "cell_order.population"];
    for kind in PlannerKind::built_in() {
        let file = ExperimentFile::parse(&experiment(kind), "c.toml").unwrap();
        let read: Vec<&str> = sections.iter().copied().filter(|k| why_ignored(&file, k).is_none()).collect();
        // A planner reads its own section, and random search the thesis's genome keys.
        assert!(read.len() <= 1, "{}: reads {read:?}", kind.name());
    }
}

/// Every planner that iterates reads the budget through the one executor: an iteration limit
/// stops it there, a stall limit of one stops it at the first iteration with no better best.
#[test]
fn every_iterative_planner_stops_on_the_budgets_iterations_and_stalls() {
    for kind in PlannerKind::built_in() {
        let name = kind.name();
        let cases = [
            ("evaluations = 200000\niterations = 3\n".to_string(), "iterations"),
            ("evaluations = 200000\niterations = 100000\nstall_iterations = 1\n".to_string(), "stall"),
        ];
        for (budget, stop) in cases {
            let text = experiment(kind).replace(&format!("evaluations = {BUDGET}\n"), &budget);
            let s = summary(run(&text).path());
            if s["stop"] == "completed" {
                continue; // a planner that plans in one step
            }
            assert_eq!(s["stop"], stop, "{name}: {budget}");
            let iterations = s["iterations"].as_u64().unwrap();
            assert!(if stop == "iterations" { iterations == 3 } else { iterations < 100_000 }, "{name}: {iterations}");
        }
    }
}
