//! `covga init`: the recommended experiment file for a floor plan, written whole or not at
//! all, that `covga run` runs; bad flags refused with exit 2, naming the flag and what is
//! allowed.

use crate::common::covga_in as run;
use std::path::Path;
use std::process::Output;

fn ok(o: &Output) -> String {
    assert!(o.status.success(), "{}\n{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The error of a command refused with exit code 2; nothing is left in `dir` but `keep`.
fn refused(o: &Output, dir: &Path, keep: &[&str]) -> String {
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    let mut left: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    left.sort();
    assert_eq!(left, keep, "{err}");
    err
}

/// The written file loads and runs with `covga run` (its budget made tiny), and plans an
/// executable plan on the map it names.
#[test]
fn the_written_file_runs() {
    let dir = tempfile::tempdir().unwrap();
    let out =
        ok(&run(dir.path(), &["init", "--map", "office", "--start", "1.3,1.3", "--width", "0.5", "--out", "o.toml"]));
    assert!(out.contains("wrote o.toml (run it with `covga run o.toml`)"), "{out}");
    let text = std::fs::read_to_string(dir.path().join("o.toml")).unwrap();
    assert!(
        text.contains("width = 0.5") && text.contains("start = [1.3, 1.3]") && text.contains("#   covga run o.toml")
    );
    let tiny = text.replace("evaluations = 20000", "evaluations = 300");
    assert_ne!(tiny, text, "the budget line is where the test expects it");
    std::fs::write(dir.path().join("tiny.toml"), tiny).unwrap();
    let o = run(dir.path(), &["run", "tiny.toml", "--out", "r"]);
    let printed = ok(&o);
    assert!(printed.contains("cell_order on office") && printed.contains("executable: yes"), "{printed}");
    assert!(!String::from_utf8_lossy(&o.stderr).contains("warning"), "the file sets no key its planner ignores: {o:?}");
}

/// A bare image needs its scale, and its thresholds are written as given.
#[test]
fn a_bare_image_is_written_with_its_scale() {
    let dir = tempfile::tempdir().unwrap();
    let image = crate::common::repo().join("experiments/maps/office.pgm");
    let image = image.to_str().unwrap();
    let err = refused(&run(dir.path(), &["init", "--map", image, "--start", "12.5,7"]), dir.path(), &[]);
    assert!(err.contains("--resolution") || err.contains("resolution"), "{err}");
    let args = ["init", "--map", image, "--resolution", "0.1", "--free-threshold", "250", "--start", "12.5,7"];
    ok(&run(dir.path(), &args));
    let text = std::fs::read_to_string(dir.path().join("office.toml")).unwrap();
    assert!(text.contains("resolution = 0.1") && text.contains("free_threshold = 250"), "{text}");
}

/// Bad flags: exit 2, the flag and what is allowed named, nothing written; an existing file
/// is never overwritten.
#[test]
fn bad_flags_are_refused_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let init = |extra: &[&str]| {
        let mut args = vec!["init", "--map", "thesis-1", "--out", "e.toml"];
        args.extend_from_slice(extra);
        run(dir.path(), &args)
    };
    for (extra, said) in [
        (&["--start", "1.3,1.3", "--width", "0"][..], "--width 0: `robot.width` = 0 is out of range: allowed"),
        (&["--start", "1.3,1.3", "--speed", "-1"][..], "--speed -1: `robot.speed`"),
        (&["--start", "1.3,1.3", "--rot-speed", "-0.5"][..], "--rot-speed -0.5: `robot.rot_speed`"),
        (&["--start", "1.3,1.3", "--speed", "inf"][..], "--speed inf is not a finite number"),
        (&["--start", "50,1.3"][..], "--start 50,1.3: `stations.start`"),
        (&["--start", "1.3"][..], "--start: `1.3` is not X,Y"),
    ] {
        let err = refused(&init(extra), dir.path(), &[]);
        assert!(err.starts_with(&format!("error: {said}")), "{extra:?}: {err}");
    }
    let err = refused(
        &run(dir.path(), &["init", "--map", "no-such-map.yaml", "--start", "1,1", "--out", "e.toml"]),
        dir.path(),
        &[],
    );
    assert!(err.starts_with("error: --map no-such-map.yaml: "), "{err}");
    std::fs::write(dir.path().join("e.toml"), "mine\n").unwrap();
    let err = refused(&init(&["--start", "1.3,1.3"]), dir.path(), &["e.toml"]);
    assert!(err.contains("--out e.toml: the file exists") && err.contains("never overwrites"), "{err}");
    assert_eq!(std::fs::read_to_string(dir.path().join("e.toml")).unwrap(), "mine\n");
}
