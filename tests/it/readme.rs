//! The README and the book (`docs/src/`) against the binary: every `covga` line of their shell
//! blocks names a subcommand and flags that exist; every grid whose run count they quote
//! expands to that count; every experiment file they run is valid; every `eval` whose inputs
//! exist runs; the commands of the README and of "Getting started" run as written, in order;
//! the figures they quote are what the program prints today; and every link and anchor
//! resolves (the book is built by `mdbook build docs` in CI; this check also covers reading the
//! pages in the repository).

mod links;

use std::collections::HashMap;
use std::path::{Path, PathBuf};
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

/// The README and every page of the book, as (path from the repository root, text).
fn pages() -> Vec<(PathBuf, String)> {
    let mut files = vec![root().join("README.md")];
    files.extend(crate::common::files_with_extension(&root().join("docs/src"), "md"));
    files
        .into_iter()
        .map(|f| {
            let text = std::fs::read_to_string(&f).unwrap();
            (f.strip_prefix(root()).unwrap().to_path_buf(), text)
        })
        .collect()
}

/// The README and the book as one text (the claims below may be on any page).
fn all_text() -> String {
    pages().into_iter().map(|(_, t)| t).collect::<Vec<_>>().join("\n")
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
    let o = crate::common::grid_dry_run(Path::new(grid));
    assert!(o.status.success(), "{grid}: {}", String::from_utf8_lossy(&o.stderr));
    let first = String::from_utf8_lossy(&o.stdout).lines().next().unwrap_or_default().to_string();
    // `grids/x.toml: 36 runs (12 configurations x replicates)`
    let n = numbers(first.split_once(": ").map_or("", |p| p.1));
    assert!(n.len() >= 2, "{grid}: unexpected dry-run line `{first}`");
    (n[0], n[1])
}

#[test]
fn every_command_of_the_readme_and_the_book_uses_flags_that_exist() {
    let text = all_text();
    let cmds = commands(&text);
    assert!(cmds.len() >= 40, "found only {} covga commands in the README and the book", cmds.len());
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
    let text = all_text();
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

/// The experiment files the README and the book run are valid as they stand, and so is the
/// README's TOML example.
#[test]
fn experiment_files_of_the_readme_and_the_book_are_valid() {
    use covga::experiment::file::ExperimentFile;
    let mut checked = 0;
    let text = readme();
    let example = text.split("```toml\n").nth(1).and_then(|b| b.split("```").next()).expect("the README's TOML");
    let file = ExperimentFile::parse(example, "README.md").unwrap_or_else(|e| panic!("{e}"));
    file.validate("README.md", root(), "readme").unwrap_or_else(|e| panic!("the README's TOML: {e}"));
    for (tokens, _) in commands(&all_text()) {
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
fn eval_commands_of_the_readme_and_the_book_run() {
    let mut ran = 0;
    for (tokens, _) in commands(&all_text()) {
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

/// The completion pass's figures in the book: unchanged on thesis-1, 0.936 → 0.974 on office.
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
    let flat = all_text().replace('\n', " ");
    let (t1, t1_plain) = (reach("thesis-1", true), reach("thesis-1", false));
    assert_eq!(format!("{t1:.3}"), format!("{t1_plain:.3}"));
    let thesis_1 = format!("(`cov_final_reach` {t1:.3} either way)");
    let office =
        format!("raises the boustrophedon's from {:.3} to {:.3}", reach("office", false), reach("office", true));
    for claim in [thesis_1, office] {
        assert!(flat.contains(&claim), "the book should say `{claim}`");
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
    let flat = all_text().replace('\n', " ");
    for claim in [central, division] {
        assert!(flat.contains(&claim), "the book should say `{claim}`");
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

/// The README's quickstart has one test command, `bash scripts/test.sh`, and it is a line of
/// `.ci/run`, which runs no test suite of its own: what a newcomer runs is what CI runs. The
/// script runs every test target (`--tests`: the unit tests and each binary under `tests/`),
/// the Python tests and the Slurm test.
#[test]
fn the_quickstart_test_command_is_what_ci_runs() {
    let text = readme();
    let quickstart = text.split("## Quickstart").nth(1).expect("a Quickstart section");
    let block = quickstart.split("```sh").nth(1).and_then(|b| b.split("```").next()).expect("its sh block");
    let commands: Vec<&str> =
        block.lines().map(|l| l.split('#').next().unwrap_or("").trim()).filter(|c| !c.is_empty()).collect();
    let tests: Vec<&str> =
        commands.iter().copied().filter(|c| c.starts_with("cargo test") || c.starts_with("bash scripts/")).collect();
    assert_eq!(tests, ["bash scripts/test.sh"], "the quickstart's test commands");
    assert_eq!(commands.len(), 3, "install, run and test: {commands:?}");
    let ci = std::fs::read_to_string(root().join(".ci/run")).expect(".ci/run");
    let ci_lines: Vec<&str> = ci.lines().map(str::trim).collect();
    assert!(ci_lines.contains(&"bash scripts/test.sh"), ".ci/run does not run bash scripts/test.sh");
    assert!(!ci.contains("cargo test"), ".ci/run runs a test suite of its own instead of through scripts/test.sh");
    let script = std::fs::read_to_string(root().join("scripts/test.sh")).expect("scripts/test.sh");
    let binaries: Vec<String> = std::fs::read_dir(root().join("tests"))
        .unwrap()
        .flatten()
        .filter(|e| e.path().join("main.rs").exists())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    assert!(binaries.len() >= 2, "test binaries under tests/: {binaries:?}");
    assert!(
        script.contains("cargo test --release --workspace --tests\n"),
        "scripts/test.sh does not run every test binary"
    );
    for binary in binaries {
        let manifest = std::fs::read_to_string(root().join("Cargo.toml")).unwrap();
        assert!(
            !manifest.contains(&format!("path = \"tests/{binary}/main.rs\"\ntest = false")),
            "tests/{binary} is left out"
        );
    }
    for suite in ["scripts/python-tests.sh", "tests/slurm/smoke-array.sh"] {
        assert!(script.contains(suite), "scripts/test.sh does not run {suite}");
    }
}

/// What a newcomer runs first: every `covga` command of the README and of "Getting started",
/// in the order written, from a folder that has the repository's experiments and grids (so that
/// `out/` lands in a temporary folder), each ending with success.
#[test]
fn the_readme_and_getting_started_commands_run_in_order() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["experiments", "grids"] {
        std::os::unix::fs::symlink(root().join(name), dir.path().join(name)).unwrap();
    }
    let mut ran = 0;
    for page in ["README.md", "docs/src/getting-started/install.md", "docs/src/getting-started/your-floor-plan.md"] {
        let text = std::fs::read_to_string(root().join(page)).unwrap();
        for (tokens, _) in commands(&text) {
            let args: Vec<&str> = tokens[1..].iter().map(String::as_str).collect();
            let o = crate::common::covga_in(dir.path(), &args);
            assert!(o.status.success(), "{page}: `{}`: {}", tokens.join(" "), String::from_utf8_lossy(&o.stderr));
            ran += 1;
        }
    }
    assert!(ran >= 8, "ran only {ran} commands");
    assert!(dir.path().join("out/smoke/report/summary.md").is_file(), "the first report was written");
}

/// Every relative link and image of the README and the book points to a file of the
/// repository, every `#anchor` to a heading or an `<a id>` of its page, and every page of the
/// book is in its table of contents.
#[test]
fn every_link_and_anchor_resolves() {
    let pages = pages();
    let mut problems = Vec::new();
    let mut checked = 0;
    for (page, text) in &pages {
        for link in links::links(text) {
            checked += 1;
            if let Err(p) = links::resolve(root(), page, &link) {
                problems.push(format!("{}: `{link}`: {p}", page.display()));
            }
        }
    }
    assert!(checked >= 150, "only {checked} links checked");
    let summary = std::fs::read_to_string(root().join("docs/src/SUMMARY.md")).unwrap();
    let listed: Vec<String> = links::links(&summary).into_iter().map(|l| format!("docs/src/{l}")).collect();
    for (page, _) in &pages {
        let name = page.display().to_string();
        if name.starts_with("docs/src/") && name != "docs/src/SUMMARY.md" && !listed.contains(&name) {
            problems.push(format!("{name} is not in docs/src/SUMMARY.md"));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// The routed office run's figures in the book: its reachable coverage with routed moves, an
/// executable plan, and with straight moves the coverage and a plan that is not executable.
#[test]
fn the_routed_office_figures_are_what_the_runs_give() {
    let dir = tempfile::tempdir().unwrap();
    let routed = std::fs::read_to_string(root().join("experiments/thesis-office-routed.toml")).unwrap();
    assert!(routed.contains("moves = \"routed\""), "the example sets routed moves");
    let score = |name: &str, text: &str| {
        let file = dir.path().join(format!("{name}.toml"));
        std::fs::write(&file, text).unwrap();
        let out = dir.path().join(name);
        let o = covga(&["run", file.to_str().unwrap(), "--quiet", "--out", out.to_str().unwrap()]);
        assert!(o.status.success(), "{name}: {}", String::from_utf8_lossy(&o.stderr));
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
        (summary["score"]["cov_final_reach"].as_f64().unwrap(), summary["score"]["executable"].as_bool().unwrap())
    };
    let (routed_reach, routed_ok) = score("routed", &routed);
    let (straight_reach, straight_ok) =
        score("straight", &routed.replace("moves = \"routed\"", "moves = \"straight\""));
    assert!(routed_ok && !straight_ok, "routed plans are executable, straight ones here are not");
    let claim = format!(
        "covers {routed_reach:.3} of its reachable cells with an executable plan, where the same \
         file with straight moves covers {straight_reach:.3} and its plan is not executable"
    );
    let flat = all_text().replace('\n', " ");
    assert!(flat.contains(&claim), "the book should say `{claim}`");
}
