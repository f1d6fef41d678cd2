use super::*;
use crate::experiment::registry::PlannerKind;
use crate::study::estimate::BranchTime;

/// Thesis runs with 10 and 40 iterations, two seeds each, and a boustrophedon (one replicate: it
/// draws nothing) under each budget: 6 runs.
const GRID: &str =
    "seeds = 2\n[base]\n[axes]\n\"planner\" = [\"thesis\", \"boustrophedon\"]\n\"budget.iterations\" = [10, 40]\n";

fn study() -> Study {
    Study::parse(GRID, Path::new("g.toml")).unwrap()
}

fn iterations(r: &RunSpec) -> u32 {
    r.file.budget.iterations
}

#[test]
fn orders_are_found_by_their_names() {
    assert_eq!(RunOrder::from_name("longest-first"), Some(RunOrder::LongestFirst));
    assert_eq!(RunOrder::from_name("seeds"), Some(RunOrder::Seeds));
    assert_eq!(RunOrder::from_name("Seeds"), None);
}

#[test]
fn seeds_order_is_replicate_then_id() {
    let s = study();
    let mut runs: Vec<&RunSpec> = s.runs.iter().collect();
    sort_runs(&mut runs, RunOrder::Seeds, |_| unreachable!("the seeds order reads no cost"));
    let keys: Vec<(u32, &str)> = runs.iter().map(|r| (r.replicate, r.id.as_str())).collect();
    let mut sorted = keys.clone();
    sorted.sort();
    assert_eq!(keys, sorted);
}

#[test]
fn longest_first_by_cost_then_seeds() {
    let s = study();
    let mut runs: Vec<&RunSpec> = s.runs.iter().collect();
    // Equal costs keep the seeds order.
    sort_runs(&mut runs, RunOrder::LongestFirst, |_| 1.0);
    let mut seeds = runs.clone();
    sort_runs(&mut seeds, RunOrder::Seeds, |_| 0.0);
    assert_eq!(runs.iter().map(|r| &r.id).collect::<Vec<_>>(), seeds.iter().map(|r| &r.id).collect::<Vec<_>>());
    sort_runs(&mut runs, RunOrder::LongestFirst, |r| f64::from(iterations(r)));
    let got: Vec<(u32, u32)> = runs.iter().map(|r| (iterations(r), r.replicate)).collect();
    assert_eq!(got, [(40, 0), (40, 0), (40, 1), (10, 0), (10, 0), (10, 1)]);
}

/// Tasks taken in order by the worker free first.
#[test]
fn list_schedule_by_hand() {
    let table: [(&[f64], usize, f64); 6] = [
        (&[], 3, 0.0),
        (&[5.0], 4, 5.0),
        (&[3.0, 3.0, 2.0, 2.0, 2.0], 2, 7.0),
        (&[2.0, 2.0, 2.0, 3.0, 3.0], 2, 7.0),
        (&[1.0, 1.0, 1.0, 1.0, 4.0], 2, 6.0),
        (&[4.0, 1.0, 1.0, 1.0, 1.0], 2, 4.0),
    ];
    for (times, jobs, want) in table {
        assert_eq!(list_schedule(times, jobs), want, "{times:?} on {jobs}");
    }
}

#[test]
fn estimates_come_from_records_then_calibration_then_budget() {
    let s = study();
    let runs: Vec<&RunSpec> = s.runs.iter().collect();
    let dir = tempfile::tempdir().unwrap();
    let maps = MapCache::default();
    // Nothing recorded: the budget figure, evaluations or iterations times map cells.
    let e = estimates(&s, &runs, dir.path(), &maps);
    assert_eq!(e.source, EstimateSource::Budget);
    let named = |name: &str| PlannerKind::named(name).unwrap();
    let (boustrophedon, thesis) = (named("boustrophedon"), named("thesis"));
    let by_kind = |kind: PlannerKind, it: u32| {
        let r = runs.iter().find(|r| r.file.planner == kind && iterations(r) == it).unwrap();
        e.cost[&r.id]
    };
    let cells = by_kind(boustrophedon, 10);
    assert!(cells > 100.0);
    assert_eq!(by_kind(boustrophedon, 40), cells, "a pattern plans once");
    assert_eq!(by_kind(thesis, 10), 10.0 * cells);
    assert_eq!(by_kind(thesis, 40), 40.0 * cells);
    // One run recorded: its configuration (both replicates) takes its time, the others the
    // mean of all records.
    let first = runs[0];
    std::fs::write(dir.path().join("runs.csv"), format!("run_id,wall_s\n{},6\n", first.id)).unwrap();
    let e = estimates(&s, &runs, dir.path(), &maps);
    assert_eq!(e.source, EstimateSource::Records);
    for r in &runs {
        assert_eq!(e.cost[&r.id], 6.0);
    }
    // A shard file and a calibration: configurations take their own mean, then their branch's
    // (recorded before calibrated), then the mean of all.
    let twin = runs.iter().find(|r| r.config_id == first.config_id && r.id != first.id).unwrap();
    std::fs::write(dir.path().join("runs-shard-1-of-2.csv"), format!("run_id,wall_s\n{},2\n", twin.id)).unwrap();
    let times = [BranchTime { branch: first.branch.clone(), runs: 6, seconds_per_run: 100.0, samples: 5 }];
    std::fs::write(dir.path().join(CALIBRATION_FILE), calibration_csv(&times)).unwrap();
    assert_eq!(read_calibration(&dir.path().join(CALIBRATION_FILE))[0].seconds_per_run, 100.0);
    let e = estimates(&s, &runs, dir.path(), &maps);
    assert_eq!(e.cost[&first.id], 4.0);
    assert_eq!(e.cost[&twin.id], 4.0);
    // Every run of this grid is in the one branch without conditionals: the recorded mean.
    assert!(runs.iter().all(|r| r.branch == first.branch));
    assert!(runs.iter().all(|r| e.cost[&r.id] == 4.0));
}

#[test]
fn a_calibration_alone_gives_the_estimates() {
    let s = study();
    let runs: Vec<&RunSpec> = s.runs.iter().collect();
    let dir = tempfile::tempdir().unwrap();
    let times = [BranchTime { branch: runs[0].branch.clone(), runs: 6, seconds_per_run: 12.5, samples: 5 }];
    std::fs::write(dir.path().join(CALIBRATION_FILE), calibration_csv(&times)).unwrap();
    let e = estimates(&s, &runs, dir.path(), &MapCache::default());
    assert_eq!(e.source, EstimateSource::Records);
    assert!(runs.iter().all(|r| e.cost[&r.id] == 12.5));
    assert!(read_calibration(&dir.path().join("absent.csv")).is_empty());
}

/// A branch with no record is ranked by its budget at the recorded seconds per unit of work:
/// a boustrophedon (free cells) beside a thesis run of 10 iterations (10 × free cells) that
/// took 5 s gets 0.5 s.
#[test]
fn an_unrecorded_branch_takes_its_budget_at_the_recorded_rate() {
    let grid = "seeds = 2\n[base]\n[axes]\n\"planner\" = [\"thesis\", \"boustrophedon\"]\n[[conditional]]\nwhen = { \"planner\" = \"thesis\" }\naxes = { \"budget.iterations\" = [10, 40] }\n";
    let s = Study::parse(grid, Path::new("g.toml")).unwrap();
    let runs: Vec<&RunSpec> = s.runs.iter().collect();
    let thesis = PlannerKind::named("thesis").unwrap();
    let thesis10 = runs.iter().find(|r| r.file.planner == thesis && iterations(r) == 10).unwrap();
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("runs.csv"), format!("run_id,wall_s\n{},5\n", thesis10.id)).unwrap();
    let e = estimates(&s, &runs, dir.path(), &MapCache::default());
    for r in &runs {
        let want = if r.file.planner == thesis { 5.0 } else { 0.5 };
        assert!((e.cost[&r.id] - want).abs() < 1e-12, "{} {}", r.branch, e.cost[&r.id]);
    }
}
