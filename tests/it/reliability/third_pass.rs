//! The third hardening pass: one case per finding, each failing on the code before it.

use std::path::Path;
use std::process::{Command, Output, Stdio};

use crate::common::covga_in as run;

fn ok(o: &Output) -> String {
    assert!(o.status.success(), "{}\n{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The one error line of a refusal with exit code `code`.
fn refused(o: &Output, code: i32) -> String {
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(code), "{err}");
    err
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))).unwrap()
}

fn write(dir: &Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).unwrap();
}

/// Item 1 and 2: on a generated pillar hall whose cells are coarser than half the robot's
/// width, every routing planner covers the reachable hall with a plan the body rule accepts
/// (before: 0.4 % coverage at 0.5 m cells; walls touched at 0.45 m).
#[test]
fn coarse_maps_are_planned_on_a_refined_raster_and_respect_the_body_rule() {
    let dir = tempfile::tempdir().unwrap();
    for res in ["0.45", "0.5"] {
        let maps = format!("m{res}");
        ok(&run(
            dir.path(),
            &["maps", "generate", "--kind", "hall", "--seed", "0", "--resolution", res, "--out", &maps],
        ));
        let map = format!("{maps}/hall-0.yaml");
        for pattern in ["boustrophedon", "spiral"] {
            let out = format!("e-{res}-{pattern}");
            let args = ["eval", "--map", &map, "--pattern", pattern, "--start", "13,9", "--json", "--out", &out];
            let report: serde_json::Value = serde_json::from_str(&ok(&run(dir.path(), &args))).unwrap();
            let common = &report["common"];
            assert_eq!(common["executable"], true, "{pattern} at {res} m: {common}");
            let cov = common["cov_final_reach"].as_f64().unwrap();
            assert!(cov > 0.85, "{pattern} at {res} m covers {cov} of the reachable cells");
        }
        let exp = format!(
            "seed = 1\nplanner = \"cell_order\"\n[map]\nsource = \"{map}\"\n[stations]\nstart = [13, 9]\n[budget]\niterations = 3\n"
        );
        write(dir.path(), "c.toml", &exp);
        let out = format!("c-{res}");
        ok(&run(dir.path(), &["run", "c.toml", "--quiet", "--out", &out]));
        let score = &json(&dir.path().join(&out).join("summary.json"))["score"];
        assert_eq!(score["executable"], true, "cell_order at {res} m: {score}");
        assert!(score["cov_final_reach"].as_f64().unwrap() > 0.85, "cell_order at {res} m: {score}");
    }
}

/// Item 3: a resource limit below what a run needs is the limit it is checked against, and
/// the message names it (before: checked against MemAvailable, then aborted by the allocator).
#[cfg(unix)]
#[test]
fn the_memory_check_reads_the_address_space_limit() {
    let dir = tempfile::tempdir().unwrap();
    let big = "seed = 3\n[map]\nsource = \"thesis-1\"\n[thesis]\npop_min = 2000\ninit_actions = 2000\nmax_genome_len = 20000\n[budget]\niterations = 1\n";
    write(dir.path(), "big.toml", big);
    let script = format!("ulimit -v 1000000 && exec '{}' run big.toml --out OUT", env!("CARGO_BIN_EXE_covga"));
    let o = Command::new("sh").current_dir(dir.path()).args(["-c", &script]).output().unwrap();
    let err = refused(&o, 2);
    assert!(err.contains("`thesis.pop_min` would need up to about") && err.contains("RLIMIT_AS (ulimit -v)"), "{err}");
    assert!(!dir.path().join("OUT").exists());
}

/// Item 4: a coverage goal no plan reaches is `null` in `summary.json`, and `--measure`
/// counts the nulls instead of taking the ranking penalty's median (before: 1.02e12 s).
#[test]
fn a_coverage_goal_not_reached_has_no_time() {
    let dir = tempfile::tempdir().unwrap();
    ok(&run(
        dir.path(),
        &["maps", "generate", "--kind", "hall", "--seed", "1", "--width", "10", "--height", "8", "--out", "m"],
    ));
    let grid = "seeds = 2\n[base]\nplanner = \"cell_order\"\n[base.map]\nsource = \"m/hall-1.yaml\"\n[base.stations]\nstart = [6, 5]\n[base.cell_order]\ncoverage_goal = 1.0\n[base.budget]\niterations = 5\n[axes]\n\"cell_order.solver\" = [\"ga\"]\n";
    write(dir.path(), "g.toml", grid);
    ok(&run(dir.path(), &["grid", "g.toml", "--out", "S"]));
    for run_dir in std::fs::read_dir(dir.path().join("S/runs")).unwrap().flatten() {
        let summary = json(&run_dir.path().join("summary.json"));
        assert!(summary["time_to_goal_s"].is_null(), "{}", summary["time_to_goal_s"]);
        assert!(summary["finalists_time_to_goal_s"].as_array().unwrap().iter().all(|t| t.is_null()));
    }
    ok(&run(dir.path(), &["report", "S", "--measure", "time_to_goal_s", "--measure", "coverage_curve.time_to_95_s"]));
    let md = std::fs::read_to_string(dir.path().join("S/report/measures.md")).unwrap();
    assert!(md.contains("| no value (2 null) |"), "{md}");
    assert!(md.contains("counted apart"), "{md}");
}

/// Item 5: SIGINT and SIGTERM end a run cleanly (nothing left, exit 130), and after SIGKILL
/// the same command reclaims the folder its killed run left (before: "holds files of another run").
#[cfg(unix)]
#[test]
fn a_signal_leaves_a_run_that_can_be_run_again() {
    let dir = tempfile::tempdir().unwrap();
    let long = "seed = 3\n[map]\nsource = \"thesis-1\"\n[thesis]\npop_min = 20\ninit_actions = 20\n[budget]\niterations = 1000000\nwall_clock_s = 30\n";
    write(dir.path(), "long.toml", long);
    let start = |out: &str| {
        let child = crate::common::command()
            .current_dir(dir.path())
            .args(["run", "long.toml", "--quiet", "--out", out])
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let partial = dir.path().join(out).join(".history.csv.partial");
        let begun = std::time::Instant::now();
        while !partial.exists() {
            assert!(begun.elapsed().as_secs() < 10, "the run did not start");
            std::thread::sleep(std::time::Duration::from_millis(10));
        }
        child
    };
    for (signal, out) in [(libc::SIGINT, "I"), (libc::SIGTERM, "T")] {
        let child = start(out);
        // SAFETY: a signal to the child this test started.
        assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, signal) }, 0);
        let o = child.wait_with_output().unwrap();
        let err = refused(&o, 130);
        assert!(err.contains("interrupted") && err.contains("nothing was written"), "{err}");
        assert!(!dir.path().join(out).exists(), "signal {signal}: the folder it made is gone");
    }
    let mut child = start("K");
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(dir.path().join("K/.history.csv.partial").exists());
    let short = long.replace("iterations = 1000000", "iterations = 2");
    write(dir.path(), "long.toml", &short);
    ok(&run(dir.path(), &["run", "long.toml", "--quiet", "--out", "K"]));
    assert!(dir.path().join("K/summary.json").exists() && !dir.path().join("K/.history.csv.partial").exists());
}

/// Item 6: where `budget.evaluations` limits a run, `summary.json` says how far past the
/// limit the run went and how far the planner can go.
#[test]
fn summary_json_states_the_evaluation_bound() {
    let dir = tempfile::tempdir().unwrap();
    for planner in ["thesis", "random_search", "cell_order", "boustrophedon"] {
        let exp = format!(
            "seed = 3\nplanner = \"{planner}\"\n[map]\nsource = \"thesis-1\"\n[budget]\nevaluations = 503\niterations = 100000\n"
        );
        write(dir.path(), "e.toml", &exp);
        ok(&run(dir.path(), &["run", "e.toml", "--quiet", "--out", planner]));
        let s = json(&dir.path().join(planner).join("summary.json"));
        let b = &s["evaluation_budget"];
        assert_eq!(b["limit"], 503, "{planner}: {b}");
        let spent = s["evaluations"].as_u64().unwrap();
        assert_eq!(b["past_limit"].as_u64().unwrap(), spent.saturating_sub(503), "{planner}");
        assert!(b["rule"].as_str().is_some_and(|r| r.contains("limit")), "{planner}: {b}");
    }
}

/// A finished study of the thesis GA and random search over two seeds, both planners in one
/// stratum (the map): `planner` is a compared axis.
fn two_planner_study(dir: &Path) {
    let grid = "seeds = 2\n[base]\n[base.thesis]\npop_min = 20\ninit_actions = 20\n[base.budget]\niterations = 3\nevaluations = 400\n[axes]\nplanner = [\"thesis\", \"random_search\"]\n[[conditional]]\nwhen = { planner = \"thesis\" }\naxes = { \"thesis.c_len\" = [0.1, 0.4] }\n";
    write(dir, "g.toml", grid);
    ok(&run(dir, &["grid", "g.toml", "--out", "S"]));
}

/// Item 7: what the report reads is checked, and compares as `--where` does.
#[test]
fn report_inputs_are_checked_and_keys_compare_alike() {
    let dir = tempfile::tempdir().unwrap();
    two_planner_study(dir.path());
    let runs = std::fs::read_to_string(dir.path().join("S/runs.csv")).unwrap();
    let header: Vec<&str> = runs.lines().next().unwrap().split(',').collect();
    let edited = |column: &str, value: &str| {
        let c = header.iter().position(|h| *h == column).unwrap();
        let mut lines: Vec<String> = runs.lines().map(str::to_string).collect();
        let mut cells: Vec<String> = lines[1].split(',').map(str::to_string).collect();
        cells[c] = value.to_string();
        lines[1] = cells.join(",");
        lines.join("\n") + "\n"
    };
    // A yes/no column holds true or false, whatever else is typed.
    for bad in ["TRUE", "1", "maybe", ""] {
        write(dir.path(), "S/runs.csv", &edited("executable", bad));
        let err = refused(&run(dir.path(), &["report", "S"]), 2);
        assert!(err.contains(&format!("`executable` = `{bad}` (line 2): allowed `true` or `false`")), "{bad}: {err}");
    }
    write(dir.path(), "S/runs.csv", &runs);
    // A reference plan with a negative or undefined time.
    for bad in ["-5", "nan"] {
        write(dir.path(), "ref.csv", &edited("time_s", bad));
        let err = refused(&run(dir.path(), &["report", "S", "--plans", "--reference", "ref.csv"]), 2);
        assert!(err.contains("ref.csv") && err.contains("`time_s`"), "{bad}: {err}");
    }
    // Numbers compare as numbers, and `planner` is an axis like any other.
    ok(&run(dir.path(), &["report", "S", "--where", "planner=thesis", "--compare", "thesis.c_len=0.10"]));
    assert!(dir.path().join("S/report/compare-thesis.c_len.md").exists());
    ok(&run(dir.path(), &["report", "S", "--compare", "planner=random_search"]));
    let md = std::fs::read_to_string(dir.path().join("S/report/compare-planner.md")).unwrap();
    assert!(md.contains("thesis"), "{md}");
    let err = refused(&run(dir.path(), &["report", "S", "--compare", "thesis.c_len=0.3"]), 2);
    assert!(err.ends_with("values: 0.1, 0.4 (and runs that do not set it)\n"), "{err}");
    // One key given twice keeps either value.
    ok(&run(dir.path(), &["report", "S", "--where", "thesis.c_len=0.1", "--where", "thesis.c_len=0.4"]));
    let summary = std::fs::read_to_string(dir.path().join("S/report/summary.md")).unwrap();
    assert!(summary.contains("thesis.c_len = 0.1 or 0.4"), "{summary}");
    // Seed to seed needs two replicates.
    let err = refused(&run(dir.path(), &["report", "S", "--seed-to-seed", "--where", "replicate=0", "--name", "x"]), 2);
    assert!(err.contains("--seed-to-seed compares replicates, and the runs hold only replicate 0"), "{err}");
    assert!(!dir.path().join("S/report-x").exists());
}

/// Item 8: failed runs can be retried, and every report file names them.
#[test]
fn failed_runs_are_retried_on_request_and_named_in_every_report_file() {
    let dir = tempfile::tempdir().unwrap();
    // Area division finds robot b's end outside its region while planning.
    let grid = "[base]\nplanner = \"thesis\"\n[base.thesis]\npop_min = 10\ninit_actions = 10\n[base.budget]\niterations = 2\n[[base.robots]]\nname = \"a\"\nstart = [1.3, 1.3]\n[[base.robots]]\nname = \"b\"\nstart = [9.7, 9.5]\nend = [1.6, 1.3]\n[axes]\n\"fleet.mode\" = [\"central\", \"divide\"]\n";
    write(dir.path(), "g.toml", grid);
    refused(&run(dir.path(), &["grid", "g.toml", "--out", "S"]), 2);
    let again = run(dir.path(), &["grid", "g.toml", "--out", "S", "--retry-failed"]);
    refused(&again, 2);
    assert!(String::from_utf8_lossy(&again.stdout).contains("1 already recorded, 1 run now"), "{again:?}");
    let runs = std::fs::read_to_string(dir.path().join("S/runs.csv")).unwrap();
    assert_eq!(runs.lines().count(), 3, "the retried run is recorded once: {runs}");
    // A study of single-robot runs with one failed run: measures.md says so.
    let single = "seeds = 2\n[base]\n[base.thesis]\npop_min = 20\ninit_actions = 20\n[base.budget]\niterations = 2\n[axes]\n\"thesis.c_len\" = [0.1, 0.4]\n";
    write(dir.path(), "s.toml", single);
    ok(&run(dir.path(), &["grid", "s.toml", "--out", "T"]));
    let text = std::fs::read_to_string(dir.path().join("T/runs.csv")).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let stop = header.iter().position(|h| *h == "stop").unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let mut cells: Vec<String> = lines[1].split(',').map(str::to_string).collect();
    cells[stop] = "failed".into();
    lines[1] = cells.join(",");
    write(dir.path(), "T/runs.csv", &(lines.join("\n") + "\n"));
    ok(&run(dir.path(), &["report", "T", "--measure", "evaluations"]));
    let md = std::fs::read_to_string(dir.path().join("T/report/measures.md")).unwrap();
    assert!(md.contains("**1 recorded runs failed while running**"), "{md}");
}

/// Item 9: `covga migrate` keeps what it does not own: comments, line ends, permissions and
/// links; a read-only file is refused; `--check` follows a grid's base file and refuses a
/// table-valued axis it cannot migrate.
#[cfg(unix)]
#[test]
fn migrate_keeps_comments_line_ends_modes_and_links() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(d, "e.toml", "[thesis]\n# the thesis's projection\nprojection = \"f1\"\npop_min = 20\n");
    std::fs::set_permissions(d.join("e.toml"), std::fs::Permissions::from_mode(0o600)).unwrap();
    std::os::unix::fs::symlink("e.toml", d.join("link.toml")).unwrap();
    write(d, "crlf.toml", "[thesis]\r\nprojection = \"f1\"\r\n");
    ok(&run(d, &["migrate", "link.toml", "crlf.toml"]));
    let e = std::fs::read_to_string(d.join("e.toml")).unwrap();
    assert!(e.contains("# the thesis's projection\nprojection = \"f1\"") && e.contains("[scorer]"), "{e}");
    assert_eq!(std::fs::metadata(d.join("e.toml")).unwrap().permissions().mode() & 0o777, 0o600);
    assert!(std::fs::symlink_metadata(d.join("link.toml")).unwrap().file_type().is_symlink());
    let crlf = std::fs::read_to_string(d.join("crlf.toml")).unwrap();
    assert!(crlf.contains("[scorer]\r\n") && !crlf.replace("\r\n", "").contains('\n'), "{crlf:?}");
    write(d, "ro.toml", "[thesis]\nprojection = \"f1\"\n");
    std::fs::set_permissions(d.join("ro.toml"), std::fs::Permissions::from_mode(0o400)).unwrap();
    let err = refused(&run(d, &["migrate", "ro.toml"]), 2);
    assert!(err.contains("ro.toml: the file is read-only"), "{err}");
    assert_eq!(std::fs::read_to_string(d.join("ro.toml")).unwrap(), "[thesis]\nprojection = \"f1\"\n");
    let err = refused(&run(d, &["migrate", "missing.toml"]), 2);
    assert!(err.contains("missing.toml: cannot read"), "{err}");
    write(d, "b.toml", "[thesis]\nprojection = \"f2\"\n");
    write(d, "g.toml", "base = \"b.toml\"\n[axes]\n\"robot.speed\" = [0.2, 0.3]\n");
    let check = run(d, &["migrate", "--check", "g.toml"]);
    refused(&check, 1);
    assert!(String::from_utf8_lossy(&check.stdout).contains("b.toml: `thesis.projection` -> `scorer.projection`"));
    write(d, "t.toml", "[base]\n[axes]\n\"thesis\" = [{ projection = \"f1\" }, { projection = \"f2\" }]\n");
    let err = refused(&run(d, &["migrate", "--check", "t.toml"]), 2);
    assert!(err.contains("`axes.\"thesis\"` holds tables with keys that moved section"), "{err}");
}

/// Item 10: nothing a grid or experiment sets is dropped without a word.
#[test]
fn grid_output_budget_keys_and_shard_counts_are_not_silently_ignored() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let grid = "[base]\n[base.thesis]\npop_min = 20\ninit_actions = 20\n[base.budget]\niterations = 3\n[base.output]\ndiversity_every = 2\nBOGUS[axes]\n\"thesis.c_len\" = [0.1, 0.4]\n";
    write(d, "g.toml", &grid.replace("BOGUS", "bogus = 1\n"));
    let err = refused(&run(d, &["grid", "g.toml", "--out", "S"]), 2);
    assert!(err.contains("`base.output` unknown field `bogus`"), "{err}");
    write(d, "g.toml", &grid.replace("BOGUS", ""));
    ok(&run(d, &["grid", "g.toml", "--out", "S"]));
    for run_dir in std::fs::read_dir(d.join("S/runs")).unwrap().flatten() {
        let history = std::fs::read_to_string(run_dir.path().join("history.csv")).unwrap();
        let diversity: Vec<bool> = history.lines().skip(1).map(|l| !l.split(',').nth(7).unwrap().is_empty()).collect();
        assert_eq!(diversity, [true, false, true, false], "{history}");
    }
    write(d, "p.toml", "planner = \"boustrophedon\"\n[budget]\nwall_clock_s = 1\n");
    let err = String::from_utf8_lossy(&ok_output(run(d, &["run", "p.toml", "--quiet", "--out", "P"]))).into_owned();
    assert!(err.contains("`budget.wall_clock_s` is ignored: planner = \"boustrophedon\" plans once"), "{err}");
    ok(&run(d, &["grid", "g.toml", "--shard", "0/2", "--out", "H"]));
    let err = refused(&run(d, &["grid", "g.toml", "--shard", "1/3", "--out", "H"]), 2);
    assert!(err.contains("holds shards of 2, and this is shard 1/3"), "{err}");
}

/// The stderr of a successful command.
fn ok_output(o: Output) -> Vec<u8> {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o.stderr
}

/// Item 12: the robot and its time model are said where a plan is scored; Python's scorer
/// takes f2 as files do (checked in pytest).
#[test]
fn the_robot_and_time_model_are_said_in_every_summary() {
    let dir = tempfile::tempdir().unwrap();
    let out = ok(&run(dir.path(), &["eval", "--map", "thesis-1", "--pattern", "boustrophedon", "--out", "E"]));
    assert!(
        out.contains(
            "robot                      0.6 m wide; time_s = length / 0.2 m/s (rot_speed = 0: turning is free"
        ),
        "{out}"
    );
    assert!(out.contains("f_obstacle") && out.contains("(F2)"), "one default projection: {out}");
    write(dir.path(), "e.toml", "planner = \"boustrophedon\"\n[robot]\nrot_speed = 0.5\n");
    let out = ok(&run(dir.path(), &["run", "e.toml", "--out", "R"]));
    assert!(out.contains("robot: 0.6 m wide; time_s = length / 0.2 m/s + turning / 0.5 rad/s"), "{out}");
    let s = json(&dir.path().join("R/summary.json"));
    assert_eq!(s["time_model"], "0.6 m wide; time_s = length / 0.2 m/s + turning / 0.5 rad/s");
}

/// Item 13: messages say each thing once, as the experiment file's do.
#[test]
fn messages_name_the_missing_resolution_and_a_busy_folder_once() {
    let dir = tempfile::tempdir().unwrap();
    let pgm = concat!(env!("CARGO_MANIFEST_DIR"), "/experiments/maps/thesis-1.pgm");
    let err = refused(&run(dir.path(), &["eval", "--map", pgm, "--pattern", "boustrophedon", "--out", "E"]), 2);
    assert!(err.contains("the resolution is missing: the bare image") && err.contains("--resolution 0.05"), "{err}");
    assert!(!err.contains("= missing"), "{err}");
    let grid = "[base]\n[base.thesis]\npop_min = 40\ninit_actions = 30\n[base.budget]\niterations = 1000000\nwall_clock_s = 3\n[axes]\n\"thesis.c_len\" = [0.1, 0.4]\n";
    write(dir.path(), "g.toml", grid);
    let whole = crate::common::command()
        .current_dir(dir.path())
        .args(["grid", "g.toml", "--jobs", "1", "--out", "sh"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let lock = dir.path().join("sh/.covga.lock");
    let begun = std::time::Instant::now();
    while !std::fs::read_to_string(&lock).is_ok_and(|t| !t.trim().is_empty()) {
        assert!(begun.elapsed().as_secs() < 10, "no lock");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let err = refused(&run(dir.path(), &["grid", "g.toml", "--shard", "0/2", "--out", "sh"]), 2);
    assert!(err.contains("sh: in use") && !err.contains("sh: sh:"), "{err}");
    let mut whole = whole;
    whole.kill().unwrap();
    whole.wait().unwrap();
}
