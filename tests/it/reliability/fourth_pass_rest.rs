//! The rest of the fourth hardening pass's smaller findings (item 9): one case per finding,
//! each failing on the code before it.

use std::path::Path;
use std::process::Output;

use crate::common::covga_in as run;

fn ok(o: &Output) -> String {
    assert!(o.status.success(), "{}\n{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The error output of a command that ended with exit code `code`.
fn refused(o: &Output, code: i32) -> String {
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(code), "{err}");
    err
}

fn write(dir: &Path, name: &str, text: &str) {
    let path = dir.join(name);
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, text).unwrap();
}

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

