//! `thesis.seed_population`: the initial population seeded with a pattern's plan.

use covga::experiment::file::ExperimentFile;
use covga::experiment::output::run_experiment;
use std::path::Path;

fn summary(text: &str) -> serde_json::Value {
    let tmp = tempfile::tempdir().unwrap();
    let exp = ExperimentFile::parse(text, "test").unwrap().validate("test", Path::new("."), "t").unwrap();
    run_experiment(&exp, tmp.path(), false, &mut []).unwrap();
    serde_json::from_str(&std::fs::read_to_string(tmp.path().join("summary.json")).unwrap()).unwrap()
}

fn refused(text: &str) -> String {
    match ExperimentFile::parse(text, "test").and_then(|f| f.validate("test", Path::new("."), "t")) {
        Ok(_) => panic!("accepted: {text}"),
        Err(e) => e.to_string(),
    }
}

const SEEDED: &str = "seed = 4\nplanner = \"thesis\"\n[map]\nsource = \"thesis-2\"\n[robot]\nrot_speed = 0.5\n\
                      [thesis]\npop_min = 40\ninit_actions = 30\nmax_genome_len = 400\n\
                      seed_population = [\"boustrophedon\"]\n[pattern]\nangle_deg = 90.0\n[budget]\niterations = 150\n";

#[test]
fn an_elite_run_seeded_with_a_pattern_ends_at_least_as_fit_as_the_pattern() {
    let pattern = summary(&SEEDED.replace("planner = \"thesis\"", "planner = \"boustrophedon\""));
    let seeded = summary(SEEDED);
    let (p, s) = (pattern["objectives"]["fitness"].as_f64().unwrap(), seeded["fitness"].as_f64().unwrap());
    // Elite keeps the seed genome unless a fitter member replaces it; the seed scores as the
    // pattern up to a few cells of overlap (see `thesis::seeding`'s tests).
    assert!(s >= p * (1.0 - 1e-3), "seeded GA {s} below its seed {p}");
    // 003's constraint: no obstacle cell swept by the footprint's rectangles. The body rule of
    // `executable` is stricter (vertices, turns and end caps), and 003's penalty does not see it.
    assert_eq!(seeded["score"]["obstacle_sweeps"], 0);
    // Without the seed, the same short run stays far below the pattern.
    let unseeded = summary(&SEEDED.replace("seed_population = [\"boustrophedon\"]\n", ""));
    assert!(unseeded["fitness"].as_f64().unwrap() < p, "{unseeded}");
}

#[test]
fn seeding_checks_its_keys() {
    let cases = [
        ("seed_share = 0.0\n", "thesis.seed_share` = 0 is out of range (0, 1]"),
        ("seed_share = 1.5\n", "(0, 1]"),
        ("max_genome_len = 40\n", "raise it to at least"),
    ];
    for (extra, message) in cases {
        let text = SEEDED.replace("max_genome_len = 400\n", "").replace("[pattern]", &format!("{extra}[pattern]"));
        let e = refused(&text);
        assert!(e.contains(message) && e.contains("thesis."), "{e}");
    }
    let e = refused(&SEEDED.replace("[\"boustrophedon\"]", "[\"spiral\", \"spiral\"]"));
    assert!(e.contains("listed twice"), "{e}");
    let e = refused(&SEEDED.replace("seed_population = [\"boustrophedon\"]\n", "seed_share = 0.2\n"));
    assert!(e.contains("thesis.seed_share") && e.contains("names no pattern"), "{e}");
    let fleet = format!("{SEEDED}[[robots]]\nname = \"a\"\n[[robots]]\nname = \"b\"\nstart = [9.7, 1.3]\n");
    let e = refused(&fleet);
    assert!(e.contains("thesis.seed_population") && e.contains("fleet"), "{e}");
}

/// The cell-order seed: the cell-order planner's local-optimum tour (no GA), written as a
/// genome. An Elite run seeded with it ends at least as fit as that plan, scored on its own.
#[test]
fn an_elite_run_seeded_with_the_cell_order_plan_ends_at_least_as_fit_as_the_plan() {
    let text = SEEDED.replace("[\"boustrophedon\"]", "[\"cell_order\"]").replace("[pattern]\nangle_deg = 90.0\n", "");
    let exp = ExperimentFile::parse(&text, "test").unwrap().validate("test", Path::new("."), "t").unwrap();
    let s = &exp.scenario;
    let plan = covga::cell_order::local_optimum_plan(s, &Default::default()).unwrap();
    let grid = covga::coverage::CoverageGrid::new(&s.map);
    let metrics = s.robot.measure(&grid, &mut covga::coverage::SweepScratch::new(&grid), &plan);
    let alone = covga::coverage::fitness::score(&metrics, &s.robot, s.map.resolution(), s.projection);
    assert_eq!(metrics.obstacle_cells, 0, "the cell-order plan is wall-free");
    let seeded = summary(&text);
    let f = seeded["fitness"].as_f64().unwrap();
    assert!(f >= alone.fitness * (1.0 - 1e-3), "seeded GA {f} below its seed {}", alone.fitness);
    // 003's constraint: no obstacle cell swept by the footprint's rectangles. The body rule of
    // `executable` is stricter (vertices, turns and end caps), and 003's penalty does not see it.
    assert_eq!(seeded["score"]["obstacle_sweeps"], 0);
    // Two patterns seed together, one member each at least.
    let both = summary(&text.replace("[\"cell_order\"]", "[\"boustrophedon\", \"cell_order\"]"));
    assert!(both["fitness"].as_f64().unwrap() >= alone.fitness * (1.0 - 1e-3), "{both}");
}

#[test]
fn the_cell_order_seed_checks_its_section() {
    let text = SEEDED.replace("[\"boustrophedon\"]", "[\"cell_order\"]");
    let e = refused(&format!("{text}[cell_order]\ndirections = []\n"));
    assert!(e.contains("cell_order.directions"), "{e}");
    let e = refused(&text.replace("max_genome_len = 400\n", "max_genome_len = 40\n"));
    assert!(e.contains("cell_order seed") && e.contains("raise it to at least"), "{e}");
}

/// `thesis.seed_bound = "dominate"`: a seeded NSGA-II or Elite run reports a plan at least as
/// good as its seed on both of 003's objectives (NSGA-II's front holds only such plans) and
/// says which seed objectives bounded it; without the bound, the same runs' plans cover less
/// than the seed.
#[test]
fn a_seed_bounded_run_reports_a_plan_at_least_as_good_as_its_seed_on_both_objectives() {
    for selection in ["nsga2", "elite"] {
        let bounded = SEEDED
            .replace("[thesis]\n", &format!("[thesis]\nselection = \"{selection}\"\nseed_bound = \"dominate\"\n"));
        for seed in [4, 5, 6] {
            let s = summary(&bounded.replace("seed = 4", &format!("seed = {seed}")));
            let bound = s["seed_bound"].as_array().unwrap_or_else(|| panic!("no seed_bound in {s}"));
            let seeds: Vec<(f64, f64)> =
                bound.iter().map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap())).collect();
            assert_eq!(seeds.len(), 1, "one seed plan, listed once: {seeds:?}");
            let at_least_seed = |cov: f64, t: f64| seeds.iter().any(|&(c, tt)| cov >= c && t >= tt);
            let plan = (s["cov_final"].as_f64().unwrap(), s["t_final"].as_f64().unwrap());
            assert!(at_least_seed(plan.0, plan.1), "{selection} seed {seed}: plan {plan:?} behind {seeds:?}");
            for row in s["front"].as_array().into_iter().flatten() {
                let (c, t) = (row[0].as_f64().unwrap(), row[1].as_f64().unwrap());
                assert!(at_least_seed(c, t), "{selection} seed {seed}: front point ({c}, {t}) behind {seeds:?}");
            }
            assert_eq!(s["score"]["obstacle_sweeps"], 0, "003's constraint (the body rule is stricter)");
        }
        // Unbounded, the plan of seed 5's run covers less than the seed plan (0.958).
        let free = summary(&bounded.replace("seed = 4", "seed = 5").replace("seed_bound = \"dominate\"\n", ""));
        assert!(free.get("seed_bound").is_none());
        assert!(free["cov_final"].as_f64().unwrap() < 0.958, "{selection}: {}", free["cov_final"]);
    }
}

#[test]
fn the_seed_bound_needs_nsga2_or_elite_and_seeds() {
    let e = refused(&SEEDED.replace("[thesis]\n", "[thesis]\nselection = \"prws\"\nseed_bound = \"dominate\"\n"));
    assert!(e.contains("thesis.seed_bound") && e.contains("nsga2") && e.contains("elite"), "{e}");
    let unseeded = SEEDED
        .replace("[thesis]\n", "[thesis]\nselection = \"nsga2\"\nseed_bound = \"dominate\"\n")
        .replace("seed_population = [\"boustrophedon\"]\n", "");
    let e = refused(&unseeded);
    assert!(e.contains("thesis.seed_bound") && e.contains("names no pattern"), "{e}");
    let e = refused(&SEEDED.replace("[thesis]\n", "[thesis]\nseed_bound = \"always\"\n"));
    assert!(e.contains("`always`") && e.contains("`none` or `dominate`"), "{e}");
}
