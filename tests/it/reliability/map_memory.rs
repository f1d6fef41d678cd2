//! Issue 100, item 6: memory for maps. `eval` estimates what a map and a width need before it
//! allocates anything large (a narrow robot on coarse cells is planned on a refined raster that
//! grows with the square of the split; a large map is scored cell by cell) and refuses with
//! exit 2, naming the flag, the estimate and the limit, instead of aborting in an allocation.

use std::path::Path;
use std::process::{Command, Output};
use std::time::{Duration, Instant};

/// `covga ARGS` in `dir` under an address-space limit of `kib` KiB (`ulimit -v`), so that a
/// large allocation fails instead of being made; with the time it took.
fn covga_limited(dir: &Path, kib: u64, args: &[&str]) -> (Output, Duration) {
    let begun = Instant::now();
    let o = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {kib} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_covga"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("sh runs");
    (o, begun.elapsed())
}

/// The error output of a run refused with exit 2 within a few seconds, having written nothing.
fn refused_quickly(dir: &Path, (o, took): (Output, Duration)) -> String {
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{err}\n{}", String::from_utf8_lossy(&o.stdout));
    assert!(took < Duration::from_secs(20), "refused after {took:?}: {err}");
    assert!(!err.contains("panicked") && !err.contains("memory allocation"), "{err}");
    assert!(!dir.join("out").exists(), "a refused eval wrote out/");
    err
}

#[test]
fn a_narrow_robot_on_coarse_cells_is_refused_before_its_raster_is_allocated() {
    let dir = tempfile::tempdir().unwrap();
    // 0.004 m on thesis-1's 0.2 m cells: planned on 11 000 × 11 000 cells, about 15 GB; the
    // limit is the address space `ulimit -v` leaves.
    let err = refused_quickly(dir.path(), covga_limited(dir.path(), 2_000_000, &["eval", "--width", "0.004"]));
    for part in ["--width = 0.004 m", "11000 × 11000", "memory limit of", "ulimit -v", "--max-memory"] {
        assert!(err.contains(part), "no `{part}` in: {err}");
    }
    // --max-memory sets the limit, whatever the machine has.
    let o = crate::common::covga_in(dir.path(), &["eval", "--width", "0.004", "--max-memory", "1G"]);
    let err = refused_quickly(dir.path(), (o, Duration::ZERO));
    assert!(err.contains("memory limit of 1.0 GB (set by --max-memory"), "{err}");
    // 0.001 m would split each cell 800 × 800: past the cap on a map's cells whatever the
    // memory, with the least width that fits.
    let err = refused_quickly(dir.path(), covga_limited(dir.path(), 2_000_000, &["eval", "--width", "0.001"]));
    for part in ["--width = 0.001 m", "44000 × 44000", "268435456", "at least 0.0027 m"] {
        assert!(err.contains(part), "no `{part}` in: {err}");
    }
    // The least width named is accepted by the cap (and then by the memory it is given).
    let o = crate::common::covga_in(dir.path(), &["eval", "--width", "0.0027", "--max-memory", "1M"]);
    let err = refused_quickly(dir.path(), (o, Duration::ZERO));
    assert!(err.contains("memory limit of 1.0 MB") && !err.contains("268435456"), "{err}");
}

#[test]
fn a_large_map_is_refused_naming_the_map_and_a_path_alone_plans_nothing() {
    let dir = tempfile::tempdir().unwrap();
    // An all-free 4 000 × 4 000 image (16 million cells, 16 MB): scoring it needs gigabytes.
    let n = 4000;
    let mut pgm = format!("P5\n{n} {n}\n255\n").into_bytes();
    pgm.resize(pgm.len() + n * n, 255);
    std::fs::write(dir.path().join("free.pgm"), pgm).unwrap();
    let args = ["eval", "--map", "free.pgm", "--resolution", "0.05", "--start", "1,1", "--max-memory", "1G"];
    let err = refused_quickly(dir.path(), covga_limited(dir.path(), 3_000_000, &args));
    for part in ["--map:", "map `free` of 4000 × 4000 cells", "memory limit of 1.0 GB", "smaller map"] {
        assert!(err.contains(part), "no `{part}` in: {err}");
    }
    // A path scored with a narrow robot plans nothing: thesis-1 is scored as it is.
    std::fs::write(dir.path().join("p.csv"), "x_m,y_m\n1.3,1.3\n4,1.3\n").unwrap();
    let o = crate::common::covga_in(dir.path(), &["eval", "--width", "0.004", "--path", "p.csv", "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn a_run_of_a_routing_planner_for_a_narrow_robot_is_refused_before_planning() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("b.toml"), "planner = \"boustrophedon\"\nrobot.width = 0.004\n").unwrap();
    std::fs::write(dir.path().join("c.toml"), "planner = \"cell_order\"\nrobot.width = 0.001\n").unwrap();
    let err = refused_quickly(dir.path(), covga_limited(dir.path(), 2_000_000, &["run", "b.toml", "--quiet"]));
    for part in ["`robot.width`", "11000 × 11000 cells", "memory limit of", "--max-memory"] {
        assert!(err.contains(part), "no `{part}` in: {err}");
    }
    let err = refused_quickly(dir.path(), covga_limited(dir.path(), 2_000_000, &["run", "c.toml", "--quiet"]));
    for part in ["robot.width = 0.001 m", "268435456", "give robot.width of at least 0.0027 m"] {
        assert!(err.contains(part), "no `{part}` in: {err}");
    }
}
