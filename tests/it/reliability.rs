//! The reliability suite: every bad input found in review, as one table of cases (command,
//! input files, expected exit code, a fragment of the message) checked the same way: exit 2,
//! one error line naming the file or key, no panic, and nothing written. Plus warnings for
//! ignored keys, and a study killed at several moments that resumes to the same results.

use crate::common::covga_in;
use std::path::Path;
use std::process::{Command, Stdio};

mod bad_input;
mod interrupts;

mod fourth_pass;
mod fourth_pass_rest;
mod goal_and_bound;
mod map_memory;
mod one_raster;
mod report_inputs;
mod third_pass;

/// A small valid experiment (map 1, Elite, 20 individuals, 3 iterations).
const SMALL: &str =
    "seed = 3\n[map]\nsource = \"thesis-1\"\n[thesis]\npop_min = 20\ninit_actions = 20\n[budget]\niterations = 3\n";

/// A small valid grid over two C_len values.
const GRID: &str = "[base]\n[base.thesis]\npop_min = 20\ninit_actions = 20\n[base.budget]\niterations = 3\n[axes]\n\"thesis.c_len\" = [0.1, 0.4]\n";

/// Thesis map 1 as a bare image, for cases that set its resolution.
const THESIS_1_PGM: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/experiments/maps/thesis-1.pgm");

/// D14: a path of a million points is refused at once with the bound and a way out, and a
/// tenth of it (a dense log of lanes) is scored with a figure that draws only what shows.
#[test]
fn a_path_of_a_million_points_is_refused_and_a_dense_log_is_scored() {
    let dir = tempfile::tempdir().unwrap();
    let lanes = |n: usize| {
        let mut text = String::from("x_m,y_m\n");
        for i in 0..n {
            let (lane, t) = (i * 14 / n, (i % (n / 14)) as f64 / (n / 14) as f64);
            let x = 1.5 + 8.0 * if lane % 2 == 0 { t } else { 1.0 - t };
            text.push_str(&format!("{x:.6},{:.6}\n", 1.5 + 0.6 * lane as f64));
        }
        text
    };
    std::fs::write(dir.path().join("million.csv"), lanes(1_000_000)).unwrap();
    let started = std::time::Instant::now();
    let args = |f: &str, out: &str| ["eval", "--path", f, "--out", out].map(String::from).to_vec();
    let o = covga_in(dir.path(), &args("million.csv", "OUT"));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("would pose the camera") && err.contains("at most 200000 poses are scored"), "{err}");
    assert!(started.elapsed().as_secs() < 5, "refused after {:?}", started.elapsed());
    assert!(!dir.path().join("OUT").exists());
    std::fs::write(dir.path().join("log.csv"), lanes(60_000)).unwrap();
    let o = covga_in(dir.path(), &args("log.csv", "scored"));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let svg = std::fs::metadata(dir.path().join("scored/path.svg")).unwrap().len();
    assert!(svg < 4 << 20, "path.svg of {svg} bytes for a path one figure pixel wide");
}

/// The peak resident set size of the largest child process waited for so far, in bytes
/// (`getrusage(RUSAGE_CHILDREN)`; Linux reports kilobytes).
fn children_peak_rss_bytes() -> u64 {
    // SAFETY: `getrusage` only writes the zeroed struct it is given.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let rc = unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut usage) };
    assert_eq!(rc, 0, "getrusage failed");
    u64::try_from(usage.ru_maxrss).unwrap_or(0) * 1024
}

/// Every file below `dir` with its size.
fn listing(dir: &Path) -> Vec<(String, u64)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p.clone());
            }
            out.push((p.strip_prefix(dir).unwrap().display().to_string(), e.metadata().map_or(0, |m| m.len())));
        }
    }
    out.sort();
    out
}

#[test]
fn keys_the_selection_ignores_are_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let text = SMALL.replace("[thesis]\n", "[thesis]\ninit_individuals = 500\nkeep = 4\n");
    std::fs::write(dir.path().join("e.toml"), text).unwrap();
    let o = covga_in(dir.path(), &["run", "e.toml", "--out", "o", "--quiet"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    for key in ["thesis.init_individuals", "thesis.keep"] {
        assert!(
            err.contains(&format!("warning: e.toml: `{key}` is ignored: thesis.selection = \"elite\" does not use it")),
            "{err}"
        );
    }
    assert!(!err.contains("pop_min"), "read keys are not warned about: {err}");
}

/// Output keys a planner never reads are named in a warning (the diversity interval outside
/// the thesis GA); the run goes on. Every budget key is read by every iterative planner: the
/// executor's stop rules are the same for all.
#[test]
fn budget_and_output_keys_a_planner_does_not_read_are_warned_about() {
    let cases: &[(&str, &[&str], &[&str])] = &[
        (
            "planner = \"random_search\"\n[budget]\nevaluations = 200\niterations = 5\nstall_iterations = 3\n[output]\ndiversity_every = 5\n",
            &["output.diversity_every"],
            &["budget.evaluations", "budget.iterations", "budget.stall_iterations"],
        ),
        (
            "planner = \"waypoint\"\n[waypoint]\ngenerations = 3\n[budget]\nstall_iterations = 3\n",
            &[],
            &["waypoint.generations", "budget.stall_iterations"],
        ),
        (
            "planner = \"thesis\"\n[budget]\niterations = 2\nstall_iterations = 3\n[output]\ndiversity_every = 5\n",
            &[],
            &[],
        ),
    ];
    for (text, ignored, read) in cases {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("e.toml"), text).unwrap();
        let o = covga_in(dir.path(), &["run", "e.toml", "--out", "o", "--quiet"].map(String::from));
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{text}: {err}");
        for key in *ignored {
            assert!(err.contains(&format!("warning: e.toml: `{key}` is ignored")), "{key}: {err}");
        }
        for key in *read {
            assert!(!err.contains(&format!("`{key}` is ignored")), "{key} is read: {err}");
        }
        if ignored.is_empty() {
            assert!(!err.contains("is ignored"), "{text}: {err}");
        }
    }
}

/// A 12-run grid, stopped after two runs by the runner's abort switch (so the study is known to
/// be unfinished whatever the machine's speed), then killed with SIGKILL at several moments
/// (chosen by a fixed-seed generator, so the schedule is the same every time, while where the
/// runs are when it strikes is not, mid-write included), then resumed: the results equal an
/// uninterrupted study's. A kill that comes after the study's end finds nothing to do.
#[test]
fn a_study_killed_at_several_moments_resumes_to_the_same_results() {
    let dir = tempfile::tempdir().unwrap();
    let grid = "seed = 9\nseeds = 3\n[base]\n[base.thesis]\npop_min = 20\ninit_actions = 20\n[base.budget]\niterations = 400\n[axes]\n\"thesis.c_len\" = [0.1, 0.4]\n\"thesis.p_mi\" = [0.0, 0.1]\n";
    std::fs::write(dir.path().join("g.toml"), grid).unwrap();
    let args = |out: &str, jobs: &str| -> Vec<String> {
        ["grid", "g.toml", "--out", out, "--jobs", jobs].iter().map(|s| s.to_string()).collect()
    };
    let reference = covga_in(dir.path(), &args("reference", "2"));
    assert!(reference.status.success(), "{}", String::from_utf8_lossy(&reference.stderr));
    let mut state: u64 = 0x5EED;
    let mut next = || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z ^ (z >> 27)
    };
    let aborted = crate::common::command()
        .current_dir(dir.path())
        .args(args("killed", "1"))
        .args(["--abort-after-runs", "2"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .unwrap();
    assert!(!aborted.success());
    let recorded = || std::fs::read_to_string(dir.path().join("killed/runs.csv")).map_or(0, |t| t.lines().count() - 1);
    assert_eq!(recorded(), 2, "the abort switch stopped the study after two runs");
    for _ in 0..4 {
        let delay_ms = 10 + next() % 150;
        let jobs = if next() % 2 == 0 { "1" } else { "2" };
        let mut child = crate::common::command()
            .current_dir(dir.path())
            .args(args("killed", jobs))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(std::time::Duration::from_millis(delay_ms));
        let _ = child.kill();
        let _ = child.wait();
    }
    assert!(recorded() >= 2, "no recorded run was lost by a kill");
    let resumed = covga_in(dir.path(), &args("killed", "2"));
    assert!(resumed.status.success(), "{}", String::from_utf8_lossy(&resumed.stderr));
    let rows = |study: &str| {
        let text = std::fs::read_to_string(dir.path().join(study).join("runs.csv")).unwrap();
        let mut lines = text.lines();
        let wall = lines.next().unwrap().split(',').position(|h| h == "wall_s").unwrap();
        let mut rows: Vec<String> = lines
            .map(|l| l.split(',').enumerate().filter(|(i, _)| *i != wall).map(|(_, v)| v).collect::<Vec<_>>().join(","))
            .collect();
        rows.sort();
        rows
    };
    assert_eq!(rows("killed").len(), 12);
    assert_eq!(rows("killed"), rows("reference"));
}

/// Two processes writing one folder: a second `covga run --out D` while the first runs, and a
/// shard beside a whole-study grid, are refused with exit 2 naming the process that holds it;
/// the first finishes unharmed. Two shards of one study may write the folder together.
#[test]
fn a_folder_in_use_by_another_covga_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let long = "seed = 3\n[map]\nsource = \"thesis-1\"\n[thesis]\npop_min = 40\ninit_actions = 30\n[budget]\niterations = 1000000\nwall_clock_s = 4\n";
    std::fs::write(dir.path().join("long.toml"), long).unwrap();
    std::fs::write(dir.path().join("short.toml"), SMALL).unwrap();
    let spawn = |args: &[&str]| {
        crate::common::command()
            .current_dir(dir.path())
            .args(args)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    };
    let wait_for_lock = |folder: &str| {
        let lock = dir.path().join(folder).join(".covga.lock");
        let started = std::time::Instant::now();
        while !std::fs::read_to_string(&lock).is_ok_and(|t| !t.trim().is_empty()) {
            assert!(started.elapsed().as_secs_f64() < 10.0, "no lock in {folder}");
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
    };
    let first = spawn(&["run", "long.toml", "--quiet", "--out", "D"]);
    wait_for_lock("D");
    let second = covga_in(dir.path(), &["run", "long.toml", "--quiet", "--out", "D"].map(String::from));
    let err = String::from_utf8_lossy(&second.stderr);
    assert_eq!(second.status.code(), Some(2), "{err}");
    assert!(err.contains(&format!("D: in use by process {}", first.id())), "{err}");
    let out = first.wait_with_output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(dir.path().join("D/summary.json").exists());
    // A whole-study grid holds its folder: a shard beside it is refused.
    let grid = "[base]\n[base.thesis]\npop_min = 40\ninit_actions = 30\n[base.budget]\niterations = 1000000\nwall_clock_s = 2\n[axes]\n\"thesis.c_len\" = [0.1, 0.4]\n";
    std::fs::write(dir.path().join("g.toml"), grid).unwrap();
    let whole = spawn(&["grid", "g.toml", "--jobs", "1", "--out", "S"]);
    wait_for_lock("S");
    let shard = covga_in(dir.path(), &["grid", "g.toml", "--shard", "0/2", "--out", "S"].map(String::from));
    let err = String::from_utf8_lossy(&shard.stderr);
    assert_eq!(shard.status.code(), Some(2), "{err}");
    assert!(err.contains("in use by process"), "{err}");
    let out = whole.wait_with_output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    // Two shards of one study, at once, into one folder.
    let a = spawn(&["grid", "g.toml", "--jobs", "1", "--shard", "0/2", "--out", "T"]);
    wait_for_lock("T");
    let b = covga_in(dir.path(), &["grid", "g.toml", "--jobs", "1", "--shard", "1/2", "--out", "T"].map(String::from));
    assert!(b.status.success(), "{}", String::from_utf8_lossy(&b.stderr));
    assert!(a.wait_with_output().unwrap().status.success());
}

/// A path file that is a FIFO nobody writes to is refused at once instead of blocking.
#[cfg(unix)]
#[test]
fn a_fifo_as_path_file_is_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("p.csv");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let started = std::time::Instant::now();
    let o = covga_in(dir.path(), &["eval", "--map", "thesis-1", "--path", "p.csv", "--out", "OUT"].map(String::from));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("p.csv: is not a regular file"), "{err}");
    assert!(started.elapsed().as_secs_f64() < 5.0);
    assert!(!dir.path().join("OUT").exists());
}

/// A 20 m square hall at 0.1 m holding 144 pillars (0.3 m square, 1.6 m apart): hundreds of
/// cells, thousands of candidate sweeps, seconds of transit to prepare.
fn pillar_hall(dir: &Path) {
    let n = 200;
    let mut px = vec![254u8; n * n];
    for i in 0..12 {
        for j in 0..12 {
            let (x0, y0) = (12 + i * 16, 12 + j * 16);
            for y in y0..y0 + 3 {
                for x in x0..x0 + 3 {
                    px[y * n + x] = 0;
                }
            }
        }
    }
    let mut pgm = format!("P5\n{n} {n}\n255\n").into_bytes();
    pgm.extend(px);
    std::fs::write(dir.join("hall.pgm"), pgm).unwrap();
}

const HALL: &str = "[map]\nsource = \"hall.pgm\"\nresolution = 0.1\n[stations]\nstart = [0.5, 0.5]\n";

#[test]
fn cell_order_preparation_stops_at_the_wall_clock() {
    let dir = tempfile::tempdir().unwrap();
    pillar_hall(dir.path());
    let e = format!("planner = \"cell_order\"\n{HALL}[budget]\nevaluations = 1\nwall_clock_s = 0.001\n");
    std::fs::write(dir.path().join("e.toml"), e).unwrap();
    let started = std::time::Instant::now();
    let o = covga_in(dir.path(), &["run", "e.toml", "--out", "OUT"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("the wall clock (budget.wall_clock_s = 0.001 s) ran out while"), "{err}");
    assert!(started.elapsed().as_secs_f64() < 5.0, "{:?}", started.elapsed());
    assert!(!dir.path().join("OUT").exists());
}

#[test]
fn a_dry_run_plans_no_seed_and_the_run_checks_it() {
    let dir = tempfile::tempdir().unwrap();
    pillar_hall(dir.path());
    // A genome limit far below the seed's length: only planning the seed finds it.
    let base = HALL.replace("[map]", "[base.map]").replace("[stations]", "[base.stations]");
    let g = format!(
        "[base]\nplanner = \"thesis\"\n{base}[base.thesis]\nseed_population = [\"cell_order\"]\nmax_genome_len = 60\n\
         [base.budget]\niterations = 0\n[axes]\n\"thesis.c_len\" = [0.1, 0.2]\n"
    );
    std::fs::write(dir.path().join("g.toml"), g).unwrap();
    let args = |more: &[&str]| {
        ["grid", "g.toml", "--out", "OUT"].iter().chain(more).map(|s| s.to_string()).collect::<Vec<_>>()
    };
    let dry = covga_in(dir.path(), &args(&["--dry-run"]));
    assert!(dry.status.success(), "{dry:?}");
    assert!(String::from_utf8_lossy(&dry.stdout).contains("seed plans and cell counts are checked when it runs"));
    let run = covga_in(dir.path(), &args(&[]));
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert!(err.contains("`thesis.seed_population` the cell_order seed is a genome of"), "{err}");
    assert!(!dir.path().join("OUT").exists());
}
