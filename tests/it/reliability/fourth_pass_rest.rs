//! The rest of the fourth hardening pass's smaller findings (item 9): one case per finding,
//! each failing on the code before it.

use crate::common::covga_in as run;

use super::fourth_pass::{ok, refused, write};

/// A conditional's `when` that tests an old value (`"elite"`) matches the runs that read it under
/// its new spelling, and `migrate` gives it the new spelling with the axis it tests (both were
/// refused as matching no run).
#[test]
fn migrate_renames_the_values_a_when_table_tests() {
    let dir = tempfile::tempdir().unwrap();
    let grid = "[base]\nplanner = \"cell_order\"\n[base.cell_order]\nsolver = \"ga\"\n[base.budget]\niterations = 2\n\
                [axes]\n\"cell_order.selection\" = [\"elite\", \"tournament\"]\n\
                [[conditional]]\nwhen = {\"cell_order.selection\" = \"elite\"}\naxes = {\"cell_order.select\" = [10, 20]}\n";
    write(dir.path(), "g.toml", grid);
    let before = ok(&run(dir.path(), &["grid", "g.toml", "--dry-run", "--out", "S"]));
    let out = ok(&run(dir.path(), &["migrate", "g.toml"]));
    assert!(out.contains("`cell_order.selection = \"elite\"` -> `cell_order.selection = \"best\"`"), "{out}");
    let text = std::fs::read_to_string(dir.path().join("g.toml")).unwrap();
    assert!(text.contains("when = {\"cell_order.selection\" = \"best\"}"), "{text}");
    assert!(text.contains("\"cell_order.best_parents\" = [10, 20]"), "{text}");
    let after = ok(&run(dir.path(), &["grid", "g.toml", "--dry-run", "--out", "S"]));
    assert_eq!(after, before, "the migrated grid has the runs it had");
}

/// A fleet's evaluation names each robot's time model (not the command line's default robot)
/// and divides the makespan, not the sum of the robots' times, by the makespan's bound.
#[test]
fn a_fleet_evaluation_names_each_robots_time_model_and_bounds_its_makespan() {
    let dir = tempfile::tempdir().unwrap();
    let robots = "[[robots]]\nname = \"small\"\nwidth = 0.4\nspeed = 0.2\nstart = [1.3, 1.3]\n\
                  [[robots]]\nname = \"large\"\nwidth = 0.9\nspeed = 0.5\nrot_speed = 0.5\nstart = [5.5, 9.5]\n";
    write(dir.path(), "fleet.toml", robots);
    let table = ok(&run(dir.path(), &["eval", "--map", "thesis-1", "--fleet", "fleet.toml", "--divide", "--out", "E"]));
    let row =
        |name: &str| table.lines().find(|l| l.trim_start().starts_with(name)).unwrap_or_else(|| panic!("{table}"));
    assert!(row("robot ").contains("2 robots, each with its own time model"), "{table}");
    assert!(!table.contains("0.6 m wide"), "the command line's default robot is no fleet robot's: {table}");
    assert!(row("robot small").contains("0.4 m wide; time_s = length / 0.2 m/s (rot_speed = 0"), "{table}");
    assert!(row("robot large").contains("0.9 m wide; time_s = length / 0.5 m/s + turning / 0.5 rad/s"), "{table}");
    let metrics: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("E/metrics.json")).unwrap()).unwrap();
    let (makespan, bound) =
        (metrics["fleet"]["makespan_s"].as_f64().unwrap(), metrics["time_lower_bound_s"].as_f64().unwrap());
    assert!(metrics["common"]["time_s"].as_f64().unwrap() > makespan * 1.2, "two robots' times sum past the makespan");
    let line = row("× the bound");
    assert!(line.starts_with(&format!("× the bound                {:.2}, the makespan", makespan / bound)), "{line}");
    assert!(row("time [s]").contains("summed over 2 paths; makespan"), "{table}");
}

/// `covga run` of a fleet names each robot's time model, on screen and in `summary.json`.
#[test]
fn a_fleet_run_names_each_robots_time_model() {
    let dir = tempfile::tempdir().unwrap();
    let file = "planner = \"thesis\"\n[fleet]\nmode = \"divide\"\n\
                [[robots]]\nname = \"small\"\nwidth = 0.4\nspeed = 0.2\nstart = [1.3, 1.3]\n\
                [[robots]]\nname = \"large\"\nwidth = 0.9\nspeed = 0.5\nstart = [5.5, 9.5]\n";
    write(dir.path(), "f.toml", file);
    let out = ok(&run(dir.path(), &["run", "f.toml", "--out", "o"]));
    assert!(!out.contains("robot: 0.6 m wide"), "{out}");
    assert!(out.contains("  small: 0.4 m wide; time_s = length / 0.2 m/s"), "{out}");
    assert!(out.contains("  large: 0.9 m wide; time_s = length / 0.5 m/s"), "{out}");
    let summary = crate::common::summary(&dir.path().join("o"));
    let model = summary["time_model"].as_str().unwrap();
    assert!(model.starts_with("per robot: small: 0.4 m wide") && model.contains("; large: 0.9 m wide"), "{model}");
}

/// An instance whose arcs weigh past a GTSPLIB solver's 32-bit weights (a robot crawling at a
/// micrometre a second) is refused, naming the speeds, and nothing is written.
#[test]
fn gtsp_refuses_weights_past_32_bits() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "c.toml", "planner = \"cell_order\"\nrobot.speed = 1e-6\n");
    let err = refused(&run(dir.path(), &["gtsp", "c.toml", "--out", "x.gtsp", "--nodes", "x.csv"]), 2);
    assert!(err.contains("c.toml: at robot.speed = 0.000001 m/s") && err.contains("2147483647 ms"), "{err}");
    assert!(!dir.path().join("x.gtsp").exists() && !dir.path().join("x.csv").exists());
    // A real robot's instance is written as before.
    write(dir.path(), "r.toml", "planner = \"cell_order\"\nrobot.speed = 0.2\n");
    ok(&run(dir.path(), &["gtsp", "r.toml", "--out", "r.gtsp"]));
}

/// A map of one cell: smaller than one pixel of the default camera it is refused for its size
/// (no camera key named: the user set none); one pixel or more across it is scored.
#[test]
fn a_one_cell_map_is_refused_for_its_size_or_scored() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "one.pgm", "P2\n1 1\n255\n254\n");
    let eval = |resolution: &str| {
        let half = (resolution.parse::<f64>().unwrap() / 2.0).to_string();
        let start = format!("{half},{half}");
        let width = (resolution.parse::<f64>().unwrap() / 3.0).to_string();
        run(
            dir.path(),
            &[
                "eval",
                "--map",
                "one.pgm",
                "--resolution",
                resolution,
                "--start",
                &start,
                "--width",
                &width,
                "--out",
                "E",
            ],
        )
    };
    let err = refused(&eval("0.1"), 2);
    assert!(err.contains("map `one.pgm` is 0.1 m across") && err.contains("0.15 m"), "{err}");
    assert!(!err.contains("scorer.camera"), "{err}");
    assert!(ok(&eval("0.2")).contains("reachable cells            1 of 1 free"));
}

/// A whole-study run in a folder holding a shard of the study is refused (it would run the
/// shard's runs again into a second runs file); merged first, the study resumes from them.
#[test]
fn a_whole_study_run_is_refused_beside_an_unmerged_shard() {
    let dir = tempfile::tempdir().unwrap();
    let grid = "seeds = 2\n[base]\n[base.thesis]\npop_min = 20\ninit_actions = 20\n[base.budget]\niterations = 3\n\
                [axes]\n\"thesis.c_len\" = [0.1, 0.4]\n";
    write(dir.path(), "g.toml", grid);
    ok(&run(dir.path(), &["grid", "g.toml", "--shard", "0/2", "--out", "S"]));
    let err = refused(&run(dir.path(), &["grid", "g.toml", "--out", "S"]), 2);
    assert!(err.contains("runs-shard-0-of-2.csv: records 2 runs of shard 0/2"), "{err}");
    assert!(err.contains("--shard K/2") && err.contains("covga merge S"), "{err}");
    assert!(!dir.path().join("S/runs.csv").exists(), "nothing written");
    ok(&run(dir.path(), &["merge", "S", "--allow-partial"]));
    let o = run(dir.path(), &["grid", "g.toml", "--out", "S"]);
    assert!(ok(&o).contains("4 runs: 2 already recorded, 2 run now"), "{}", String::from_utf8_lossy(&o.stdout));
}

/// The reverse: a shard in a folder whose `runs.csv` a whole-study run wrote runs none of the
/// runs that file records (it ran them all again before), and the merge unites the two.
#[test]
fn a_shard_beside_a_whole_study_runs_file_runs_only_what_it_lacks() {
    let dir = tempfile::tempdir().unwrap();
    let grid = "seeds = 2\n[base]\n[base.thesis]\npop_min = 20\ninit_actions = 20\n[base.budget]\niterations = 3\n\
                [axes]\n\"thesis.c_len\" = [0.1, 0.4]\n";
    write(dir.path(), "g.toml", grid);
    ok(&run(dir.path(), &["grid", "g.toml", "--out", "W"]));
    let whole = std::fs::read_to_string(dir.path().join("W/runs.csv")).unwrap();
    let o = run(dir.path(), &["grid", "g.toml", "--shard", "1/2", "--out", "W"]);
    assert!(
        ok(&o).contains("2 runs in shard 1/2: 2 already recorded, 0 run now"),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    ok(&run(dir.path(), &["merge", "W", "--allow-partial"]));
    assert_eq!(std::fs::read_to_string(dir.path().join("W/runs.csv")).unwrap(), whole, "the merge keeps each run once");
}

/// A grid of a pattern planner with a budget warns that the budget is ignored, as `covga run`
/// does for such a file.
#[test]
fn a_pattern_grid_with_a_budget_is_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let grid = "[base]\nplanner = \"spiral\"\n[base.budget]\niterations = 5\n[axes]\n\"robot.width\" = [0.5, 0.6]\n";
    write(dir.path(), "g.toml", grid);
    let o = run(dir.path(), &["grid", "g.toml", "--dry-run", "--out", "S"]);
    ok(&o);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("warning: g.toml: `budget.iterations` is ignored by 2 of 2 runs: planner = \"spiral\" plans once"),
        "{err}"
    );
    // A grid whose every run reads its budget is not warned.
    write(dir.path(), "t.toml", &grid.replace("spiral", "thesis"));
    let o = run(dir.path(), &["grid", "t.toml", "--dry-run", "--out", "T"]);
    assert!(!String::from_utf8_lossy(&o.stderr).contains("is ignored"), "{o:?}");
}

/// The book's sentence on how far each planner passes `budget.evaluations` quotes what the
/// planners do today, measured as it says.
#[test]
fn the_books_overshoot_figures_are_what_the_planners_spend() {
    let root = crate::common::repo();
    let page = std::fs::read_to_string(root.join("docs/src/guide/planners.md")).unwrap();
    let page = page.split_whitespace().collect::<Vec<_>>().join(" ");
    let at = page.find("Measured with `evaluations = ").expect("the measured overshoots");
    let sentence = &page[at..at + page[at..].find(". ").unwrap()];
    let number = |text: &str| -> u64 {
        let digits: String =
            text.chars().skip_while(|c| !c.is_ascii_digit()).take_while(char::is_ascii_digit).collect();
        digits.parse().unwrap_or_else(|_| panic!("no number in `{text}`"))
    };
    let (setup, figures) = sentence.split_once("): ").expect("`(...): planner N, ...`");
    assert!(setup.contains("on thesis-1"), "{sentence}");
    let limit = number(&setup[setup.find("evaluations = ").unwrap()..]);
    let iterations = number(&setup[setup.find("iterations = ").unwrap()..]);
    // The figures end where a parenthesis or the sentence does.
    let quoted: Vec<(String, u64)> = figures
        .split(" (")
        .next()
        .unwrap()
        .split(", ")
        .map(|f| {
            let (name, n) = f.rsplit_once(' ').unwrap();
            (name.replace(' ', "_"), number(n))
        })
        .collect();
    let names: Vec<&str> = quoted.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["cell_order", "random_search", "thesis"], "{sentence}");
    for (planner, figure) in quoted {
        let out = tempfile::tempdir().unwrap();
        let text = format!("planner = \"{planner}\"\n[budget]\nevaluations = {limit}\niterations = {iterations}\n");
        crate::common::run_text(&text, &root, out.path());
        let spent = crate::common::summary(out.path())["evaluations"].as_u64().unwrap();
        assert_eq!(figure, spent, "{planner}: the book says {figure}, the planner spends {spent}: {sentence}");
    }
}
