//! The README against the binary: every `covga` line of its shell blocks names a subcommand and
//! flags that exist; every grid whose run count it quotes expands to that count; every
//! experiment file it runs is valid; every `eval` whose inputs exist runs; and the figures it
//! quotes for the coverage completion are what `eval` prints today.

use std::collections::HashMap;
use std::path::Path;
use std::process::Output;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn covga(args: &[&str]) -> Output {
    crate::common::covga_in(root(), args)
}

fn readme() -> String {
    std::fs::read_to_string(root().join("README.md")).expect("README.md")
}

/// The `covga …` lines of the README's `sh` blocks: (command tokens, trailing comment).
fn commands(text: &str) -> Vec<(Vec<String>, String)> {
    let mut out = Vec::new();
    let mut in_sh = false;
    for line in text.lines() {
        if line.starts_with("```") {
            in_sh = line.trim() == "```sh";
            continue;
        }
        if !in_sh || !line.starts_with("covga ") {
            continue;
        }
        let (command, comment) = match line.find(" #") {
            Some(k) => (&line[..k], line[k + 2..].trim()),
            None => (line, ""),
        };
        out.push((command.split_whitespace().map(String::from).collect(), comment.to_string()));
    }
    out
}

/// The whole numbers in `text`, with thin spaces and spaces between digit groups read as one
/// number (`6 912` → 6912).
fn numbers(text: &str) -> Vec<u64> {
    let mut out = Vec::new();
    let mut digits = String::new();
    let chars: Vec<char> = text.chars().collect();
    for (i, &c) in chars.iter().enumerate() {
        // A space followed by exactly three digits separates groups of one number.
        let group_gap = (c == ' ' || c == '\u{2009}')
            && chars.get(i + 1..i + 4).is_some_and(|g| g.iter().all(char::is_ascii_digit))
            && !chars.get(i + 4).is_some_and(char::is_ascii_digit);
        if c.is_ascii_digit() {
            digits.push(c);
        } else if !digits.is_empty() && !group_gap {
            out.push(digits.parse().unwrap());
            digits.clear();
        }
    }
    if !digits.is_empty() {
        out.push(digits.parse().unwrap());
    }
    out
}

/// `(runs, configurations)` of a grid by its dry run.
fn dry_run(grid: &str) -> (u64, u64) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("study");
    let o = covga(&["grid", grid, "--dry-run", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{grid}: {}", String::from_utf8_lossy(&o.stderr));
    let first = String::from_utf8_lossy(&o.stdout).lines().next().unwrap_or_default().to_string();
    // `grids/x.toml: 36 runs (12 configurations x replicates)`
    let n = numbers(first.split_once(": ").map_or("", |p| p.1));
    assert!(n.len() >= 2, "{grid}: unexpected dry-run line `{first}`");
    (n[0], n[1])
}

#[test]
fn every_readme_command_uses_flags_that_exist() {
    let text = readme();
    let cmds = commands(&text);
    assert!(cmds.len() >= 15, "found only {} covga commands in the README", cmds.len());
    let mut helps: HashMap<String, String> = HashMap::new();
    let mut problems = Vec::new();
    for (tokens, _) in &cmds {
        let sub = &tokens[1];
        let help = helps.entry(sub.clone()).or_insert_with(|| {
            let o = covga(&[sub, "--help"]);
            if o.status.success() { String::from_utf8_lossy(&o.stdout).into_owned() } else { String::new() }
        });
        if help.is_empty() {
            problems.push(format!("`{}`: no subcommand `{sub}`", tokens.join(" ")));
            continue;
        }
        for flag in tokens.iter().filter(|t| t.starts_with("--")) {
            let name = flag.split('=').next().unwrap();
            if !help.contains(&format!("{name} ")) && !help.lines().any(|l| l.trim_end().ends_with(name)) {
                problems.push(format!("`{}`: `{sub}` has no flag {name}", tokens.join(" ")));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// Run counts quoted beside grid commands (`# 36 short runs`, `# 54432 runs (18144
/// configurations × 3 seeds)`) and in the sentence on 003 Table 4.3's grids.
#[test]
fn quoted_grid_sizes_are_what_the_grids_expand_to() {
    let text = readme();
    let mut checked = 0;
    for (tokens, comment) in commands(&text) {
        if tokens[1] != "grid" || !comment.contains("runs") || !root().join(&tokens[2]).exists() {
            continue;
        }
        let quoted = numbers(comment.split("runs").next().unwrap());
        let (runs, configurations) = dry_run(&tokens[2]);
        assert_eq!(quoted.last(), Some(&runs), "{}: `{comment}`", tokens[2]);
        if let Some(rest) = comment.split_once("runs (").map(|p| p.1)
            && rest.contains("configurations")
        {
            assert_eq!(numbers(rest).first(), Some(&configurations), "{}: `{comment}`", tokens[2]);
        }
        checked += 1;
    }
    // `grids/thesis-{elite,turn,prws,rrws}.toml` reproduce 003 Table 4.3 (864 / … runs)
    let flat = text.replace('\n', " ");
    let at = flat.find("`grids/thesis-{").expect("the Table 4.3 grids sentence");
    let names: Vec<&str> = flat[at + 15..].split('}').next().unwrap().split(',').collect();
    let counts = numbers(flat[at..].split("runs)").next().unwrap().split_once('(').unwrap().1);
    assert_eq!(names.len(), counts.len(), "{names:?} vs {counts:?}");
    for (name, count) in names.iter().zip(&counts) {
        assert_eq!(dry_run(&format!("grids/thesis-{name}.toml")).0, *count, "grids/thesis-{name}.toml");
        checked += 1;
    }
    assert!(checked >= 6, "checked only {checked} quoted grid sizes");
}

/// The experiment files the README runs are valid as they stand.
#[test]
fn readme_experiment_files_are_valid() {
    use covga::experiment::file::ExperimentFile;
    let mut checked = 0;
    for (tokens, _) in commands(&readme()) {
        if tokens[1] != "run" || tokens.len() < 3 || !root().join(&tokens[2]).exists() {
            continue;
        }
        let path = root().join(&tokens[2]);
        let file = ExperimentFile::read(&path).unwrap_or_else(|e| panic!("{}: {e}", tokens[2]));
        file.validate(&tokens[2], root(), "readme").unwrap_or_else(|e| panic!("{}: {e}", tokens[2]));
        checked += 1;
    }
    assert!(checked >= 7, "checked only {checked} experiment files");
}

/// The `eval` lines whose inputs are in the project run as written.
#[test]
fn readme_eval_commands_run() {
    let mut ran = 0;
    for (tokens, _) in commands(&readme()) {
        let inputs_exist = tokens
            .windows(2)
            .filter(|w| w[0] == "--map" || w[0] == "--path")
            .all(|w| !w[1].contains('.') || root().join(&w[1]).exists());
        if tokens[1] != "eval" || !inputs_exist {
            continue;
        }
        let dir = tempfile::tempdir().unwrap();
        let mut args: Vec<&str> = tokens[1..].iter().map(String::as_str).collect();
        args.extend(["--out", dir.path().to_str().unwrap()]);
        let o = covga(&args);
        assert!(o.status.success(), "`{}`: {}", tokens.join(" "), String::from_utf8_lossy(&o.stderr));
        ran += 1;
    }
    assert!(ran >= 3, "ran only {ran} eval commands");
}

/// The completion pass's figures in the README: unchanged on thesis-1, 0.936 → 0.974 on office.
#[test]
fn the_completion_figures_are_what_eval_prints() {
    let reach = |map: &str, complete: bool| {
        let dir = tempfile::tempdir().unwrap();
        let mut args =
            vec!["eval", "--map", map, "--start", "1.3,1.3", "--json", "--out", dir.path().to_str().unwrap()];
        if !complete {
            args.push("--no-complete");
        }
        let o = covga(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        v["common"]["cov_final_reach"].as_f64().unwrap()
    };
    let flat = readme().replace('\n', " ");
    let (t1, t1_plain) = (reach("thesis-1", true), reach("thesis-1", false));
    assert_eq!(format!("{t1:.3}"), format!("{t1_plain:.3}"));
    let thesis_1 = format!("(`cov_final_reach` {t1:.3} either way)");
    let office =
        format!("raises the boustrophedon's from {:.3} to {:.3}", reach("office", false), reach("office", true));
    for claim in [thesis_1, office] {
        assert!(flat.contains(&claim), "the README should say `{claim}`");
    }
}

/// The central-fleet example's figures and the area division's makespan beside them.
#[test]
fn the_central_fleet_figures_are_what_the_example_gives() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("central");
    let o = covga(&["run", "experiments/fleet-thesis1-hetero-central.toml", "--quiet", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let f = |k: &str| summary["fleet"][k].as_f64().unwrap_or_else(|| panic!("no fleet.{k}"));
    let central = format!(
        "union {:.1} %, overlap {:.1} %, makespan {:.0} s, balance {:.2}",
        100.0 * f("union_free"),
        100.0 * f("overlap_fraction"),
        f("makespan_s"),
        f("balance")
    );
    let divided = dir.path().join("divided");
    let o = covga(&[
        "eval",
        "--fleet",
        "experiments/fleets/thesis1-hetero.toml",
        "--divide",
        "--json",
        "--out",
        divided.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let division = format!("against {:.0} s by area division", v["fleet"]["makespan_s"].as_f64().unwrap());
    let flat = readme().replace('\n', " ");
    for claim in [central, division] {
        assert!(flat.contains(&claim), "the README should say `{claim}`");
    }
}

/// `eval --help` names every preset, and `covga maps` writes nowhere unless told where.
#[test]
fn eval_help_names_every_preset_and_maps_needs_a_folder() {
    let help = String::from_utf8_lossy(&covga(&["eval", "--help"]).stdout).into_owned();
    for name in covga::map::presets::PRESET_NAMES {
        assert!(help.contains(name), "eval --help does not name the preset {name}");
    }
    let dir = tempfile::tempdir().unwrap();
    let o = crate::common::command().current_dir(dir.path()).arg("maps").output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "covga maps without --out wrote files");
}

/// Every test command of the README's quickstart (`cargo test …`, `bash scripts/…tests.sh`) is a
/// line of `.ci/run`, and every `cargo test` line of `.ci/run` is in the quickstart: what a
/// newcomer runs is what CI runs.
#[test]
fn the_quickstart_test_commands_are_what_ci_runs() {
    let text = readme();
    let quickstart = text.split("## Quickstart").nth(1).expect("a Quickstart section");
    let block = quickstart.split("```sh").nth(1).and_then(|b| b.split("```").next()).expect("its sh block");
    let wanted: Vec<&str> = block
        .lines()
        .map(|l| l.split('#').next().unwrap_or("").trim())
        .filter(|c| c.starts_with("cargo test") || (c.starts_with("bash scripts/") && c.ends_with("tests.sh")))
        .collect();
    assert!(wanted.iter().filter(|c| c.starts_with("cargo test")).count() >= 1, "no cargo test in {block}");
    let ci = std::fs::read_to_string(root().join(".ci/run")).expect(".ci/run");
    let ci_lines: Vec<&str> = ci.lines().map(str::trim).collect();
    for command in &wanted {
        assert!(ci_lines.contains(command), "the README's `{command}` is not a line of .ci/run");
    }
    for line in ci_lines.iter().filter(|l| l.starts_with("cargo test")) {
        assert!(wanted.contains(line), ".ci/run's `{line}` is not in the README's quickstart");
    }
}
