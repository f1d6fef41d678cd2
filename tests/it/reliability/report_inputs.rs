//! Item 8 of the fourth hardening pass: what `covga report` reads. Hand-edited `runs.csv`
//! values and reference plans are refused naming the file, run, line and column; a figure some
//! runs of a study of several planners do not record is counted apart.

use std::path::Path;
use std::process::Output;

use crate::common::covga_in as run;

fn ok(o: &Output) -> String {
    assert!(o.status.success(), "{}\n{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn refused(o: &Output) -> String {
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{err}");
    err
}

/// A finished study of the thesis GA over two C_len values and two replicates, in `dir/S`.
fn study(dir: &Path) -> String {
    let grid = "seeds = 2\n[base]\n[base.thesis]\npop_min = 20\ninit_actions = 20\n[base.budget]\niterations = 3\n[axes]\n\"thesis.c_len\" = [0.1, 0.4]\n";
    std::fs::write(dir.join("g.toml"), grid).unwrap();
    ok(&run(dir, &["grid", "g.toml", "--out", "S"]));
    std::fs::read_to_string(dir.join("S/runs.csv")).unwrap()
}

/// `runs` with `column` of its first run set to `value`, and that run's id.
fn edited(runs: &str, column: &str, value: &str) -> (String, String) {
    let header: Vec<&str> = runs.lines().next().unwrap().split(',').collect();
    let c = header.iter().position(|h| *h == column).unwrap_or_else(|| panic!("no column {column}"));
    let mut lines: Vec<String> = runs.lines().map(str::to_string).collect();
    let mut cells: Vec<String> = lines[1].split(',').map(str::to_string).collect();
    cells[c] = value.to_string();
    lines[1] = cells.join(",");
    (lines.join("\n") + "\n", cells[0].clone())
}

#[test]
fn hand_edited_runs_values_are_refused_with_file_run_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let runs = study(dir.path());
    for (column, value, needle) in [
        ("time_s", "abc", "expected a number"),
        ("wall_s", "-1", "allowed [0, inf]"),
        ("wall_s", "nan", "must be a finite number"),
        ("t_final", "2", "allowed [0, 1]"),
        ("unique_cells", "2.5", "expected a whole number"),
        ("replicate", "abc", "expected a whole number"),
        ("replicate", "2", "runs replicates 0 to 1 (seeds = 2)"),
        ("thesis.c_len", "0.2", "not a value"),
    ] {
        let (text, id) = edited(&runs, column, value);
        std::fs::write(dir.path().join("S/runs.csv"), text).unwrap();
        let err = refused(&run(dir.path(), &["report", "S"]));
        let named = format!("run {id} has `{column}` = ");
        assert!(
            err.contains("runs.csv") && err.contains(&named) && err.contains("(line 2)") && err.contains(needle),
            "{column} = {value}: {err}"
        );
    }
}

#[test]
fn a_reference_plan_without_a_time_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let runs = study(dir.path());
    for value in ["0", "abc", ""] {
        let (text, _) = edited(&runs, "time_s", value);
        // One plan of the map: the header and the edited first run.
        let reference: Vec<&str> = text.lines().take(2).collect();
        std::fs::write(dir.path().join("ref.csv"), reference.join("\n") + "\n").unwrap();
        let o = run(dir.path(), &["report", "S", "--plans", "--reference", "ref.csv"]);
        let err = refused(&o);
        assert!(err.contains("ref.csv") && err.contains("`time_s`") && err.contains("(line 2)"), "{value}: {err}");
        let out = String::from_utf8_lossy(&o.stdout);
        assert!(!out.contains("inf") && !out.contains("NaN"), "{value}: {out}");
    }
}

/// A coverage goal's time, recorded by the cell-order planner only, in a study that also runs
/// the spiral: the spiral's runs are counted as missing, not a failure of the report.
#[test]
fn a_measure_some_planners_do_not_record_is_counted_as_missing() {
    let dir = tempfile::tempdir().unwrap();
    let grid = "[base]\n[base.cell_order]\nsolver = \"nearest\"\ncoverage_goal = 0.9\n[axes]\nplanner = [\"spiral\", \"cell_order\"]\n";
    std::fs::write(dir.path().join("g.toml"), grid).unwrap();
    ok(&run(dir.path(), &["grid", "g.toml", "--out", "S"]));
    ok(&run(dir.path(), &["report", "S", "--by", "planner", "--measure", "time_to_goal_s"]));
    let md = std::fs::read_to_string(dir.path().join("S/report/measures.md")).unwrap();
    let spiral = md.lines().find(|l| l.contains("planner=spiral")).unwrap_or_else(|| panic!("{md}"));
    assert!(spiral.contains("no value (1 missing)"), "{md}");
    let cell_order = md.lines().find(|l| l.contains("planner=cell_order")).unwrap_or_else(|| panic!("{md}"));
    assert!(!cell_order.contains("missing"), "{md}");
    let err = refused(&run(dir.path(), &["report", "S", "--measure", "no_such_figure", "--name", "x"]));
    assert!(err.contains("--measure no_such_figure: no run of S records it"), "{err}");
}
