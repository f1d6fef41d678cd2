//! The grids and experiments the repository ships: every one dry-runs or validates and reads nothing
//! outside the repository; a grid with a renamed key keeps its run ids, and `covga migrate` rewrites it.

use super::*;

/// Whether the file `file` names a path that leaves the repository `root` (a quoted string
/// starting `../` that is no file beside `file` and, read from the root, lies outside it):
/// a fresh clone does not have it, and every shipped file must run from a clean clone.
fn reads_outside_the_repository(root: &Path, file: &Path, text: &str) -> bool {
    let code = text.lines().map(|l| l.split('#').next().unwrap_or(""));
    code.flat_map(|l| l.split('"').skip(1).step_by(2).map(str::to_string).collect::<Vec<_>>())
        .filter(|quoted| quoted.starts_with("../"))
        .any(|quoted| !file.parent().unwrap().join(&quoted).exists() && !lexical(&root.join(&quoted)).starts_with(root))
}

/// `p` with `..` taken lexically (no file system reads).
fn lexical(p: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in p.components() {
        match c {
            std::path::Component::ParentDir => {
                out.pop();
            }
            std::path::Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

/// A fresh clone runs every shipped file: each grid dry-runs, each experiment validates, and
/// none names a file outside the repository.
#[test]
fn every_shipped_grid_dry_runs_and_every_shipped_experiment_validates() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut checked = 0;
    let mut grids: Vec<PathBuf> = std::fs::read_dir(root.join("grids"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    grids.sort();
    for g in &grids {
        let text = std::fs::read_to_string(g).unwrap();
        assert!(!reads_outside_the_repository(root, g, &text), "{}: names a file outside the repository", g.display());
        let o = crate::common::grid_dry_run(g);
        assert!(o.status.success(), "{}: {}", g.display(), String::from_utf8_lossy(&o.stderr));
        checked += 1;
    }
    let mut experiments: Vec<PathBuf> = ["experiments", "experiments/fleets"]
        .iter()
        .flat_map(|d| std::fs::read_dir(root.join(d)).unwrap().map(|e| e.unwrap().path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    experiments.sort();
    for e in &experiments {
        let text = std::fs::read_to_string(e).unwrap();
        assert!(!reads_outside_the_repository(root, e, &text), "{}: names a file outside the repository", e.display());
        let file = covga::experiment::file::ExperimentFile::parse(&text, &e.display().to_string())
            .unwrap_or_else(|err| panic!("{err}"));
        file.validate(&e.display().to_string(), root, "t").unwrap_or_else(|err| panic!("{err}"));
        checked += 1;
    }
    assert!(checked >= 25, "only {checked} shipped files checked");
}

#[test]
fn a_path_that_leaves_the_repository_is_found() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let grid = root.join("grids/x.toml");
    let cases = [
        ("\"map.source\" = [\"../shared/maps/basement.yaml\"]", true),
        ("base = \"../experiments/thesis-map1-elite.toml\"", false),
        ("source = \"experiments/maps/basement.yaml\"", false),
        ("# source = \"../shared/maps/basement.yaml\"", false),
    ];
    for (text, leaves) in cases {
        assert_eq!(reads_outside_the_repository(root, &grid, text), leaves, "{text}");
    }
}

/// A grid that spells a moved key the old way (`thesis.projection`, now `scorer.projection`)
/// runs the same runs under the same ids as one that spells it the new way, with a warning
/// naming the new key, and its column takes the new name in the same place.
#[test]
fn a_grid_with_a_renamed_key_keeps_its_run_ids_and_warns() {
    let dir = tempfile::tempdir().unwrap();
    let grid = |key: &str, base: &str| {
        format!(
            "seed = 3\n[base]\n{base}pop_min = 10\ninit_individuals = 20\ninit_actions = 10\n[base.budget]\n\
             iterations = 2\n[axes]\n\"thesis.c_len\" = [0.1, 0.4]\n\"{key}\" = [\"f1\", \"f2\"]\n"
        )
    };
    let mut plans = Vec::new();
    for (name, key, base) in [
        ("old", "thesis.projection", "[base.thesis]\nprojection = \"f1\"\n"),
        ("new", "scorer.projection", "[base.scorer]\nprojection = \"f1\"\n[base.thesis]\n"),
    ] {
        let g = dir.path().join(format!("{name}.toml"));
        std::fs::write(&g, grid(key, base)).unwrap();
        let o = covga(&["grid", g.to_str().unwrap(), "--dry-run"]);
        ok(&o);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(name == "old", err.contains("`thesis.projection` is now `scorer.projection`"), "{name}: {err}");
        let study = covga::study::grid::Study::load(&g).unwrap();
        assert_eq!(study.columns, ["thesis.c_len", "scorer.projection"]);
        let ids: Vec<String> = study.runs.iter().map(|r| r.id.clone()).collect();
        plans.push((covga::study::runner::grid_hash(&study), ids));
    }
    assert_eq!(plans[0], plans[1], "both spellings give the same runs and ids");
}

/// `covga migrate` rewrites old key names in experiment and grid files, keeping comments and
/// the runs a grid makes; `--check` says whether any file still needs it; a file whose two
/// spellings disagree is refused and nothing is written.
#[test]
fn migrate_rewrites_old_keys_and_keeps_the_runs() {
    let dir = tempfile::tempdir().unwrap();
    let grid = dir.path().join("g.toml");
    let old_grid = "# a study\nseed = 3\n[base]\n[base.thesis]\nprojection = \"f1\"\npop_min = 10\n[base.waypoint]\nscale = 0.15\n\
                    [base.budget]\niterations = 2\n[axes]\n\"thesis.c_len\" = [0.1, 0.4]\n\"thesis.projection\" = [\"f1\", \"f2\"]\n";
    std::fs::write(&grid, old_grid).unwrap();
    let exp = dir.path().join("e.toml");
    std::fs::write(&exp, "planner = \"thesis\"\n[thesis]\nprojection = \"f1\"   # the mean\n").unwrap();
    let before = covga::study::grid::Study::load(&grid).unwrap();
    let (g, e) = (grid.to_str().unwrap(), exp.to_str().unwrap());
    let check = covga(&["migrate", g, e, "--check"]);
    assert_eq!(check.status.code(), Some(1), "{}", String::from_utf8_lossy(&check.stderr));
    assert_eq!(std::fs::read_to_string(&grid).unwrap(), old_grid, "--check writes nothing");
    let o = covga(&["migrate", g, e]);
    ok(&o);
    assert!(String::from_utf8_lossy(&o.stdout).contains("`thesis.projection` -> `scorer.projection`"));
    let text = std::fs::read_to_string(&grid).unwrap();
    assert!(
        text.starts_with("# a study\n")
            && text.contains("\"scorer.projection\" = [")
            && text.contains("[base.scorer.camera]"),
        "{text}"
    );
    let after = covga::study::grid::Study::load(&grid).unwrap();
    assert!(after.warnings.is_empty(), "{:?}", after.warnings);
    assert_eq!(covga::study::runner::grid_hash(&after), covga::study::runner::grid_hash(&before));
    assert_eq!(after.columns, before.columns);
    assert!(std::fs::read_to_string(&exp).unwrap().contains("[scorer]\nprojection = \"f1\"   # the mean"));
    ok(&covga(&["migrate", g, e, "--check"]));
    // Two spellings that disagree: refused (exit 2), and the other file is not written either.
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "[thesis]\nprojection = \"f1\"\n[scorer]\nprojection = \"f2\"\n").unwrap();
    std::fs::write(&exp, "[thesis]\nprojection = \"f1\"\n").unwrap();
    let o = covga(&["migrate", e, bad.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("disagree"));
    assert_eq!(std::fs::read_to_string(&exp).unwrap(), "[thesis]\nprojection = \"f1\"\n");
}
