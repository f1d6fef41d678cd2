//! End-to-end tests of `covga run`: outputs, determinism across thread counts, improvement
//! over the initial population, retrain, and bad experiment files.

use crate::common::covga_threads;
use std::path::{Path, PathBuf};

mod fleets;
mod records;

/// A small experiment (map 1, Elite, 40 individuals, 200 iterations) as TOML text.
fn small(extra: &str) -> String {
    format!(
        "seed = 7\n[map]\nsource = \"thesis-1\"\n[thesis]\npop_min = 40\ninit_actions = 30\n{extra}\n[budget]\niterations = 200\n"
    )
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// A numeric column of history.csv by name.
fn column(hist: &str, name: &str) -> Vec<f64> {
    let mut lines = hist.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let k = header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no column {name} in {header:?}"));
    lines.map(|l| l.split(',').nth(k).unwrap().parse().unwrap()).collect()
}

/// summary.json without its timing field.
fn summary_without_time(dir: &Path) -> serde_json::Value {
    let mut v: serde_json::Value = serde_json::from_str(&read(&dir.join("summary.json"))).unwrap();
    v.as_object_mut().unwrap().remove("wall_s");
    v
}

#[test]
fn run_writes_every_result_file_and_improves() {
    let dir = tempfile::tempdir().unwrap();
    let exp = write(dir.path(), "e.toml", &small(""));
    let out = dir.path().join("out");
    let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], "2");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in [
        "config.toml",
        "best_path.csv",
        "best_genome.csv",
        "population.csv",
        "history.csv",
        "summary.json",
        "path.png",
        "path.svg",
        "history.png",
        "history.svg",
    ] {
        assert!(out.join(f).metadata().map(|m| m.len() > 50).unwrap_or(false), "{f}");
    }
    let s: serde_json::Value = serde_json::from_str(&read(&out.join("summary.json"))).unwrap();
    for key in ["cov_final", "t_final", "fitness", "evaluations", "iterations", "seed", "wall_s"] {
        assert!(s.get(key).is_some(), "{key}");
    }
    assert_eq!(s["iterations"], 200);
    assert_eq!(s["seed"], 7);
    // history.csv: header + iteration 0 + 200 iterations; the best at the end beats the start.
    let hist = read(&out.join("history.csv"));
    let best_f = column(&hist, "best_fitness");
    assert_eq!(best_f.len(), 201);
    assert!(best_f[200] > best_f[0], "best f {} should beat the initial best {}", best_f[200], best_f[0]);
    assert_eq!(s["planner"], "thesis");
    assert_eq!(s["score"]["cov_final_free"], s["cov_final"], "the common scorer agrees with the GA on map 1");
    // population.csv: the final population (Elite keeps pop_min), its fittest is the best.
    let population = read(&out.join("population.csv"));
    let fitness = column(&population, "fitness");
    assert_eq!(fitness.len(), 40);
    let fittest = fitness.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    assert_eq!(Some(fittest), s["fitness"].as_f64());
    assert_eq!(column(&population, "genome_len").iter().filter(|&&g| g >= 3.0).count(), 40);
    // The best path is scored identically by `covga eval`.
    let ev = covga_threads(
        &[
            "eval",
            "--map",
            "thesis-1",
            "--path",
            out.join("best_path.csv").to_str().unwrap(),
            "--projection",
            "f2",
            "--json",
            "--out",
            dir.path().join("ev").to_str().unwrap(),
        ],
        "1",
    );
    let v: serde_json::Value = serde_json::from_slice(&ev.stdout).unwrap();
    assert!((v["cov_final"].as_f64().unwrap() - s["cov_final"].as_f64().unwrap()).abs() < 1e-12);
    assert!((v["t_final"].as_f64().unwrap() - s["t_final"].as_f64().unwrap()).abs() < 1e-12);
}

#[test]
fn same_seed_same_bytes_with_one_or_two_threads() {
    let dir = tempfile::tempdir().unwrap();
    for (name, extra) in [
        ("elite", String::new()),
        ("tournament", "selection = \"tournament\"\ninit_individuals = 80\ntournament_size = 3\nkeep = 2\nselect = 10\np_mi = 0.05\np_ma = 0.1\n".to_string()),
        ("rrws-adaptive", "selection = \"rrws\"\ninit_individuals = 60\nkeep = 2\nselect = 10\n[thesis.control]\nkind = \"adaptive\"\n".to_string()),
    ] {
        let exp = write(dir.path(), &format!("{name}.toml"), &small(&extra));
        let a = dir.path().join(format!("{name}-1"));
        let b = dir.path().join(format!("{name}-2"));
        for (out, threads) in [(&a, "1"), (&b, "2")] {
            let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], threads);
            assert!(o.status.success(), "{name}: {}", String::from_utf8_lossy(&o.stderr));
        }
        for f in ["config.toml", "best_path.csv", "best_genome.csv", "history.csv", "path.svg", "history.svg"] {
            assert_eq!(read(&a.join(f)), read(&b.join(f)), "{name}: {f} differs between 1 and 2 threads");
        }
        assert_eq!(summary_without_time(&a), summary_without_time(&b), "{name}");
    }
}

/// Incremental evaluation is a speed-up only: every result file is byte-identical with the
/// full evaluation of every child, for both architectures, with mutations and
/// re-initialisations, with the rotation cost, and across a retrain.
#[test]
fn incremental_and_full_evaluation_give_identical_files() {
    let dir = tempfile::tempdir().unwrap();
    for (name, extra, tail) in [
        ("elite", "c_child = 2\np_ma = 0.3\n", ""),
        (
            "tournament",
            "selection = \"tournament\"\ninit_individuals = 80\nkeep = 2\nselect = 10\np_mi = 0.05\np_ma = 0.3\nc_child = 1\n",
            "",
        ),
        (
            "prws-rot",
            "selection = \"prws\"\ninit_individuals = 60\nkeep = 2\nselect = 10\np_ma = 0.2\n",
            "[robot]\nrot_speed = 0.5\n",
        ),
        ("elite-retrain", "p_ma = 0.1\n", "[retrain]\nat_iteration = 60\n"),
    ] {
        let mut outs = Vec::new();
        for mode in ["incremental", "full"] {
            let text = small(&format!("{extra}evaluation = \"{mode}\"\n")) + tail;
            let exp = write(dir.path(), &format!("{name}-{mode}.toml"), &text);
            let out = dir.path().join(format!("{name}-{mode}"));
            let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], "2");
            assert!(o.status.success(), "{name}: {}", String::from_utf8_lossy(&o.stderr));
            outs.push(out);
        }
        for f in ["best_path.csv", "best_genome.csv", "history.csv", "path.svg", "history.svg"] {
            assert_eq!(read(&outs[0].join(f)), read(&outs[1].join(f)), "{name}: {f} differs between the evaluations");
        }
        assert_eq!(summary_without_time(&outs[0]), summary_without_time(&outs[1]), "{name}");
    }
}

/// `output.diversity_every` thins the diversity column of history.csv and changes nothing
/// else: the other columns, the plan and every other result file are those of a run that
/// measures it every iteration (the population does not depend on it), for Elite and for
/// RRWS; 0 is refused with the key named.
#[test]
fn diversity_every_only_thins_the_diversity_column() {
    let dir = tempfile::tempdir().unwrap();
    for (name, extra) in [("elite", "c_child = 2\n"), ("rrws", "selection = \"rrws\"\ninit_individuals = 60\n")] {
        let mut outs = Vec::new();
        for every in [None, Some(7)] {
            let tail = every.map_or(String::new(), |e| format!("[output]\ndiversity_every = {e}\n"));
            let exp = write(dir.path(), &format!("{name}-{}.toml", every.unwrap_or(1)), &(small(extra) + &tail));
            let out = dir.path().join(format!("{name}-{}", every.unwrap_or(1)));
            let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], "1");
            assert!(o.status.success(), "{name}: {}", String::from_utf8_lossy(&o.stderr));
            outs.push(out);
        }
        for f in ["best_path.csv", "best_genome.csv", "path.svg"] {
            assert_eq!(read(&outs[0].join(f)), read(&outs[1].join(f)), "{name}: {f}");
        }
        assert_eq!(summary_without_time(&outs[0]), summary_without_time(&outs[1]), "{name}");
        let (every_row, thinned) = (read(&outs[0].join("history.csv")), read(&outs[1].join("history.csv")));
        let header: Vec<&str> = every_row.lines().next().unwrap().split(',').collect();
        let d = header.iter().position(|h| *h == "diversity").unwrap();
        let (mut measured, mut rows) = (0, 0);
        for (a, b) in every_row.lines().zip(thinned.lines()).skip(1) {
            let (a, b): (Vec<&str>, Vec<&str>) = (a.split(',').collect(), b.split(',').collect());
            let iteration: u32 = a[header.iter().position(|h| *h == "iteration").unwrap()].parse().unwrap();
            for (k, (x, y)) in a.iter().zip(&b).enumerate() {
                if k == d && !iteration.is_multiple_of(7) {
                    assert!(
                        y.is_empty() && !x.is_empty(),
                        "{name}: iteration {iteration} has no diversity when thinned"
                    );
                } else {
                    assert_eq!(x, y, "{name}: column {} of iteration {iteration}", header[k]);
                }
            }
            measured += usize::from(iteration.is_multiple_of(7));
            rows += 1;
        }
        assert_eq!((rows, measured), (201, 29), "{name}: rows and diversity measurements");
    }
    let exp = write(dir.path(), "zero.toml", &(small("") + "[output]\ndiversity_every = 0\n"));
    let o = covga_threads(
        &["run", exp.to_str().unwrap(), "--out", dir.path().join("zero").to_str().unwrap(), "--quiet"],
        "1",
    );
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("output.diversity_every") && err.contains("at least 1"), "{err}");
    assert!(!dir.path().join("zero").exists(), "nothing written for a refused file");
}

#[test]
fn retrain_marks_the_region_and_recovers() {
    let dir = tempfile::tempdir().unwrap();
    let text = small("").replace("iterations = 200", "iterations = 1100") + "[retrain]\nat_iteration = 100\n";
    let exp = write(dir.path(), "r.toml", &text);
    let out = dir.path().join("out");
    let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], "2");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.join("path_before_retrain.png").exists());
    let s: serde_json::Value = serde_json::from_str(&read(&out.join("summary.json"))).unwrap();
    assert_eq!(s["metrics"]["area_cells"], 1400, "A_pix after marking the 5 m corner (spec §16.4)");
    let hist = read(&out.join("history.csv"));
    let best_t = column(&hist, "best_t_final");
    // The switch after iteration 100 turns covered cells into crossings: t_final drops.
    assert!(best_t[101] < best_t[100], "t_final should drop at the switch: {} -> {}", best_t[100], best_t[101]);
    // ... and the population re-optimises: within 1000 iterations the best t_final regains at
    // least 90 % of its value before the switch.
    let regained = best_t[101..=1100].iter().copied().fold(f64::NEG_INFINITY, f64::max);
    assert!(regained >= 0.9 * best_t[100], "best t_final {} after the switch, {} before", regained, best_t[100]);
}

#[test]
fn a_population_that_cannot_fit_is_refused_before_it_is_allocated() {
    let text = "[thesis]\npop_min = 1000000\ninit_actions = 100000\nmax_genome_len = 1000000\n";
    let started = std::time::Instant::now();
    expect_error(text, "`thesis.pop_min` would need up to about");
    assert!(started.elapsed().as_secs() < 10, "refused at once");
}

fn expect_error(text: &str, needle: &str) {
    let dir = tempfile::tempdir().unwrap();
    let exp = write(dir.path(), "bad.toml", text);
    let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", dir.path().join("o").to_str().unwrap()], "1");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{text}: {err}");
    assert!(err.contains(needle) && err.contains("bad.toml"), "expected `{needle}` in: {err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(!dir.path().join("o").exists(), "no results for a bad file");
}

#[test]
fn bad_experiment_files_are_rejected_with_exit_2() {
    expect_error(&small("colour = 3"), "unknown field `colour`");
    expect_error(&small("p_c = 1.5"), "`thesis.p_c` = 1.5 is out of range");
    // One robot rule in run and eval: it must fit on the map; huge numbers stay short.
    let robot = |w: &str| small("").replacen("[thesis]", &format!("[robot]\nwidth = {w}\n[thesis]"), 1);
    expect_error(&robot("60.0"), "`robot.width` = 60 m is wider than the map's shorter side (11 m)");
    expect_error(&robot("1e300"), "`robot.width` = 1e300 m is wider than the map's shorter side");
    expect_error(
        &small("selection = \"tournament\"\ntournament_size = 500\ninit_individuals = 100\nselect = 5"),
        "`thesis.tournament_size` = 500 is out of range [1, 40]",
    );
    expect_error(&small("").replace("thesis-1", "maps/nowhere.yaml"), "nowhere.yaml");
    expect_error(&small("c_child = 3"), "`thesis.c_child`");
    expect_error(&small("").replace("[map]", "[stations]\nstart = [0.5, 0.5]\n[map]"), "inside an obstacle");
    expect_error("seed = \"x\"\n", "bad.toml:1");
}

#[test]
fn missing_experiment_file_is_an_input_error() {
    let o = covga_threads(&["run", "no/such/experiment.toml"], "1");
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("no/such/experiment.toml"));
}

#[test]
fn parameter_control_schedules_show_in_the_history() {
    let dir = tempfile::tempdir().unwrap();
    // Tournament size ramps from 1 to 7 (eq. 3.25).
    let ramp = small(
        "selection = \"tournament\"\ninit_individuals = 60\nkeep = 2\nselect = 10\n[thesis.control]\nkind = \"ramp\"\nmin = 1.0\nmax = 7.0\n",
    );
    let exp = write(dir.path(), "ramp.toml", &ramp);
    let out = dir.path().join("ramp");
    let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], "2");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let sp = column(&read(&out.join("history.csv")), "sp");
    assert_eq!(sp[1], 1.0);
    assert_eq!(*sp.last().unwrap(), 7.0);
    assert!(sp.windows(2).skip(1).all(|w| w[1] >= w[0]));
    // Mühlenbein: P_mA rises from ~0 to 1 while P_c falls (eqs. 2.1–2.2).
    let exp = write(dir.path(), "mu.toml", &small("[thesis.control]\nkind = \"muhlenbein\"\n"));
    let out = dir.path().join("mu");
    let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], "2");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let hist = read(&out.join("history.csv"));
    let (pm, pc) = (column(&hist, "p_ma"), column(&hist, "p_c"));
    assert!(pm[1] < 0.001 && (pm[200] - 1.0).abs() < 1e-12 && pc[200].abs() < 1e-12);
}

#[test]
fn every_planner_runs_alone_and_random_search_is_deterministic() {
    let dir = tempfile::tempdir().unwrap();
    for (planner, extra) in [("random_search", "evaluations = 2000\n"), ("spiral", ""), ("boustrophedon", "")] {
        let text = format!(
            "seed = 3\nplanner = \"{planner}\"\n[map]\nsource = \"thesis-2\"\n[thesis]\npop_min = 40\ninit_actions = 30\n[budget]\n{extra}"
        );
        let exp = write(dir.path(), &format!("{planner}.toml"), &text);
        let (a, b) = (dir.path().join(format!("{planner}-1")), dir.path().join(format!("{planner}-2")));
        for (out, threads) in [(&a, "1"), (&b, "2")] {
            let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], threads);
            assert!(o.status.success(), "{planner}: {}", String::from_utf8_lossy(&o.stderr));
        }
        for f in ["config.toml", "best_path.csv", "history.csv", "path.svg"] {
            assert_eq!(read(&a.join(f)), read(&b.join(f)), "{planner}: {f} differs between 1 and 2 threads");
        }
        assert_eq!(summary_without_time(&a), summary_without_time(&b), "{planner}");
        let s = summary_without_time(&a);
        assert_eq!(s["planner"], planner);
        assert!(s["score"]["cov_final_reach"].as_f64().unwrap() > 0.1, "{planner}: {s}");
    }
    // Random search spends its evaluation budget and no more than one batch beyond it.
    let s = summary_without_time(&dir.path().join("random_search-1"));
    let e = s["evaluations"].as_u64().unwrap();
    assert!((2000..2000 + 80).contains(&e), "{e}");
    assert_eq!(s["stop"], "evaluations");
    // Patterns on thesis-2 report their pockets (none: the disc leaves no pocket a 0.6 m robot
    // cannot reach), meet their own constraints and are executable.
    let s = summary_without_time(&dir.path().join("spiral-1"));
    assert_eq!(s["pockets"], 0);
    assert_eq!(s["planner_feasible"], true);
    assert_eq!(s["score"]["executable"], true);
}

/// The budget's other stops: no better best for `stall_iterations`, and the wall clock; the
/// reason is in summary.json and the iterations stop early.
#[test]
fn stall_and_wall_clock_stops_are_reported() {
    let dir = tempfile::tempdir().unwrap();
    let base = "seed = 2\n[map]\nsource = \"thesis-1\"\n[thesis]\npop_min = 20\ninit_actions = 20\n";
    for (name, budget, stop) in [
        ("stall", "[budget]\niterations = 100000\nstall_iterations = 5\n", "stall"),
        ("clock", "[budget]\niterations = 100000000\nwall_clock_s = 0.5\n", "wall_clock"),
    ] {
        let exp = write(dir.path(), &format!("{name}.toml"), &format!("{base}{budget}"));
        let out = dir.path().join(name);
        let started = std::time::Instant::now();
        let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], "1");
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let s = summary_without_time(&out);
        assert_eq!(s["stop"], stop, "{name}");
        let iterations = s["iterations"].as_u64().unwrap();
        assert!(iterations < 100_000, "{name}: {iterations}");
        if name == "stall" {
            // The best did not improve over the last 5 iterations of the history.
            let best = column(&read(&out.join("history.csv")), "best_fitness");
            let n = best.len();
            assert!(n >= 6 && best[n - 1] <= best[n - 6], "{:?}", &best[n.saturating_sub(6)..]);
        } else {
            assert!(started.elapsed().as_secs_f64() < 30.0);
        }
    }
}

#[test]
fn short_genomes_keep_crossing_unless_the_literal_rule_is_asked_for() {
    // 50 m initial moves (003 §3.3.1 read literally) clamp every viewpoint to the map edge and
    // leave genomes of ~10 actions; with C_len = 0.8 eq. 3.21's CP_1 range is empty for them,
    // and under Elite with P_mI = 0 the literal rule stops every evaluation.
    let dir = tempfile::tempdir().unwrap();
    let evaluations_late = |rule: &str| {
        let text = small(&format!("init_dist_max = 50.0\nc_len = 0.8\np_mi = 0.0\nshort_genomes = \"{rule}\"\n"));
        let exp = write(dir.path(), &format!("{rule}.toml"), &text);
        let out = dir.path().join(rule);
        let o = covga_threads(&["run", exp.to_str().unwrap(), "--out", out.to_str().unwrap(), "--quiet"], "2");
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let evals = column(&read(&out.join("history.csv")), "evaluations");
        evals[200] - evals[100]
    };
    assert_eq!(evaluations_late("literal"), 0.0, "the literal rule freezes this population");
    assert!(evaluations_late("clamp") > 1000.0, "clamped, short genomes still cross");
}

/// A file that never ends (`/dev/zero`, or a map that names it) is read only up to its kind's
/// limit and refused with exit 2, quickly and without growing.
#[test]
fn endless_input_files_are_refused_at_their_limit() {
    if !Path::new("/dev/zero").exists() {
        return;
    }
    let started = std::time::Instant::now();
    let o = covga_threads(&["run", "/dev/zero"], "1");
    assert_eq!(o.status.code(), Some(2), "{o:?}");
    assert!(String::from_utf8_lossy(&o.stderr).contains("larger than 16 MiB"), "{o:?}");
    let dir = tempfile::tempdir().unwrap();
    let yaml = write(
        dir.path(),
        "zero.yaml",
        "image: /dev/zero\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
    );
    let exp = write(dir.path(), "e.toml", &format!("[map]\nsource = \"{}\"\n", yaml.display()));
    let o = covga_threads(&["run", exp.to_str().unwrap()], "1");
    assert_eq!(o.status.code(), Some(2), "{o:?}");
    assert!(String::from_utf8_lossy(&o.stderr).contains("larger than 128 MiB"), "{o:?}");
    assert!(started.elapsed().as_secs_f64() < 5.0, "{:?}", started.elapsed());
}

/// Out-of-range values are refused with the real bound, not "> 0" (table of key, value, bound).
#[test]
fn range_messages_name_the_real_bound() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        ("[robot]\nwidth = 5e-324\n", "robot.width", "a finite number > 0 metres"),
        ("[robot]\nspeed = 1e-300\n", "robot.speed", "a finite number >= 1e-9 m/s"),
        ("[thesis]\ninit_dist_max = 1e18\n", "thesis.init_dist_max", "[1e-9, 1e6] metres"),
    ];
    for (k, (text, key, bound)) in cases.iter().enumerate() {
        let file = write(dir.path(), &format!("e{k}.toml"), text);
        let o = covga_threads(
            &["run", file.to_str().unwrap(), "--out", dir.path().join(format!("o{k}")).to_str().unwrap()],
            "1",
        );
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{key}: {err}");
        assert!(err.contains(key) && err.contains(bound), "{key}: {err}");
    }
}

/// One rule for relative map paths: read from the working directory, whether a run file or a
/// grid's base file (in a folder of its own) names them; the run's `config.toml` keeps the
/// path as written, so it runs again from the same directory.
#[test]
fn relative_map_paths_are_read_from_the_working_directory() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("maps")).unwrap();
    std::fs::create_dir_all(dir.path().join("experiments")).unwrap();
    let mut pgm = b"P5\n30 20\n255\n".to_vec();
    pgm.extend(std::iter::repeat_n(254u8, 600));
    std::fs::write(dir.path().join("maps/room.pgm"), pgm).unwrap();
    let text = "planner = \"boustrophedon\"\n[map]\nsource = \"maps/room.pgm\"\nresolution = 0.2\n[stations]\nstart = [1.0, 1.0]\n";
    write(&dir.path().join("experiments"), "e.toml", text);
    write(dir.path(), "g.toml", "base = \"experiments/e.toml\"\n[axes]\n\"robot.width\" = [0.4, 0.6]\n");
    let at_root =
        |args: &[&str]| crate::common::command().current_dir(dir.path()).args(args).output().expect("covga runs");
    for args in [
        vec!["run", "experiments/e.toml", "--out", "r1", "--quiet"],
        vec!["run", "r1/config.toml", "--out", "r2", "--quiet"],
        vec!["grid", "g.toml", "--out", "study", "--jobs", "1"],
    ] {
        let o = at_root(&args);
        assert!(o.status.success(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
        // A run's own config.toml sets every key, read or not: run again it warns of none.
        if args[1] == "r1/config.toml" {
            assert!(
                !String::from_utf8_lossy(&o.stderr).contains("is ignored"),
                "{}",
                String::from_utf8_lossy(&o.stderr)
            );
        }
    }
    // The same file edited by hand is the user's own: its unread keys are warned about.
    let edited =
        std::fs::read_to_string(dir.path().join("r1/config.toml")).unwrap().replacen("seed = ", "seed = 7\n# ", 1);
    write(dir.path(), "edited.toml", &edited);
    let o = at_root(&["run", "edited.toml", "--out", "r4", "--quiet"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        // A section none of whose keys its planner reads is named once, not key by key.
        String::from_utf8_lossy(&o.stderr).contains("`thesis` is ignored")
            && !String::from_utf8_lossy(&o.stderr).contains("`thesis.c_len` is ignored"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // From inside the run file's folder the same path names nothing, and the message says which.
    let o = crate::common::command()
        .current_dir(dir.path().join("experiments"))
        .args(["run", "e.toml", "--out", "r3"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("maps/room.pgm"), "{}", String::from_utf8_lossy(&o.stderr));
}
