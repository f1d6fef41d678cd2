//! End-to-end tests of `covga eval` and `covga maps`: metrics, pictures and bad input.

use crate::common::covga;
use std::path::Path;
use std::process::Output;

fn json_of(out: &Output) -> serde_json::Value {
    assert!(out.status.success(), "stderr: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("valid JSON")
}

fn num(v: &serde_json::Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key} missing in {v}"))
}

#[test]
fn patterns_meet_the_thesis_reference_quality() {
    let dir = tempfile::tempdir().unwrap();
    for (map, pattern, min_cov, min_t) in [
        ("thesis-1", "boustrophedon", 0.93, 0.85),
        ("thesis-1", "spiral", 0.93, 0.85),
        ("thesis-2", "boustrophedon", 0.85, 0.0),
        ("thesis-2", "spiral", 0.85, 0.0),
    ] {
        let out_dir = dir.path().join(format!("{map}-{pattern}"));
        let out = covga(&["eval", "--map", map, "--pattern", pattern, "--json", "--out", out_dir.to_str().unwrap()]);
        let v = json_of(&out);
        assert!(num(&v, "cov_final") >= min_cov, "{map} {pattern}: {v}");
        assert!(num(&v, "t_final") >= min_t, "{map} {pattern}: {v}");
        assert_eq!(num(&v, "obstacle_cells"), 0.0);
        for f in ["path.png", "path.svg", "path.csv", "metrics.json", "coverage_curve.csv"] {
            assert!(out_dir.join(f).metadata().unwrap().len() > 100, "{f}");
        }
        // The curve ends at the plan's time and reachable coverage; the bound lies below the
        // time: the length bound of the covered reachable area (0.6 m at 0.2 m/s), turning free.
        let curve = std::fs::read_to_string(out_dir.join("coverage_curve.csv")).unwrap();
        let last: Vec<f64> = curve.lines().last().unwrap().split(',').map(|x| x.parse().unwrap()).collect();
        let common = &v["common"];
        assert!((last[0] - num(common, "time_s")).abs() < 1e-6 * last[0], "{curve}");
        assert!((last[1] - num(common, "cov_final_reach")).abs() < 1e-9, "{curve}");
        let bound = num(&v, "time_lower_bound_s");
        let resolution = covga::map::presets::preset(map).unwrap().resolution();
        let area = num(common, "unique_reach_cells") * resolution * resolution;
        let expected = covga::coverage::bound::area_time_s(area, &[(0.6, 0.2)], resolution);
        assert!((bound - expected).abs() < 1e-6 * bound && bound < num(common, "time_s"), "{bound}");
        assert_eq!(num(&v, "turning_bound_s"), 0.0);
        let to_80 = v["coverage_curve"]["time_to_80_s"].as_f64().unwrap();
        assert!(to_80 > 0.0 && to_80 < last[0], "{to_80}");
        // The written path scores the same when read back.
        let again = covga(&[
            "eval",
            "--map",
            map,
            "--path",
            out_dir.join("path.csv").to_str().unwrap(),
            "--json",
            "--out",
            out_dir.join("again").to_str().unwrap(),
        ]);
        let w = json_of(&again);
        assert_eq!(v["cells_swept"], w["cells_swept"]);
        assert_eq!(v["crossings"], w["crossings"]);
    }
}

#[test]
fn table_output_lists_every_metric() {
    let dir = tempfile::tempdir().unwrap();
    let out = covga(&[
        "eval",
        "--map",
        "thesis-1",
        "--pattern",
        "spiral",
        "--rot-speed",
        "6.28",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    for key in [
        "cells swept",
        "unique cells",
        "crossings",
        "obstacle cells",
        "length [m]",
        "total turn",
        "T_rot",
        "cov_final",
        "t_final",
        "f1",
        "f2",
        "f_obstacle",
        "× the bound",
    ] {
        assert!(text.contains(key), "{key} missing:\n{text}");
    }
}

#[test]
fn shipped_map_files_equal_the_presets() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["thesis-1", "thesis-2", "office"] {
        let shipped = Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments/maps").join(format!("{name}.yaml"));
        let a = covga(&["eval", "--map", name, "--json", "--out", dir.path().join("a").to_str().unwrap()]);
        let b = covga(&[
            "eval",
            "--map",
            shipped.to_str().unwrap(),
            "--json",
            "--out",
            dir.path().join("b").to_str().unwrap(),
        ]);
        let (a, b) = (json_of(&a), json_of(&b));
        for key in ["cells_swept", "crossings", "area_cells", "unique_cells"] {
            assert_eq!(a[key], b[key], "{name} {key}");
        }
    }
}

fn expect_input_error(args: &[&str], needle: &str) {
    let out = covga(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(err.contains(needle), "{args:?}: expected `{needle}` in: {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(err.trim().lines().count(), 1, "one error line: {err}");
}

#[test]
fn bad_input_gives_one_clear_error_and_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let d = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let out = d("out");
    let write = |name: &str, bytes: &[u8]| std::fs::write(dir.path().join(name), bytes).unwrap();
    write("ok.pgm", b"P5\n4 4\n255\n\xfe\xfe\xfe\xfe\xfe\xfe\xfe\xfe\xfe\xfe\xfe\xfe\xfe\xfe\xfe\xfe");
    write("black.pgm", b"P5\n2 2\n255\n\x00\x00\x00\x00");
    write("notimage.pgm", b"hello");
    let yaml = |image: &str, extra: &str| {
        format!(
            "image: {image}\nresolution: 0.5\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n{extra}"
        )
    };
    write("mode.yaml", yaml("ok.pgm", "mode: fuzzy\n").as_bytes());
    write("malformed.yaml", b"image: [unclosed\n");
    write("mismatch.yaml", yaml("notimage.pgm", "").as_bytes());
    write("missing_image.yaml", yaml("nowhere.pgm", "").as_bytes());
    write("black.yaml", yaml("black.pgm", "").as_bytes());
    write("ok.yaml", yaml("ok.pgm", "").as_bytes());
    write("badheader.csv", b"x,y\n1,2\n");
    write("nonnum.csv", b"x_m,y_m\n1.3,1.3\n2.0,two\n");
    write("nonfinite.csv", b"x_m,y_m\n1.3,1.3\nNaN,2\n");
    write("inwall.csv", b"x_m,y_m\n0.5,0.5\n2,2\n");
    let cases: Vec<(Vec<String>, &str)> = vec![
        (vec!["--map".into(), d("nowhere.yaml")], "nowhere.yaml"),
        (vec!["--map".into(), d("malformed.yaml")], "malformed.yaml"),
        (vec!["--map".into(), d("mode.yaml")], "fuzzy"),
        (vec!["--map".into(), d("mismatch.yaml")], "cannot decode map image"),
        (vec!["--map".into(), d("missing_image.yaml")], "nowhere.pgm"),
        (vec!["--map".into(), d("black.yaml")], "no free cell"),
        (vec!["--map".into(), d("ok.pgm")], "--resolution"),
        (vec!["--map".into(), "thesis-9".into()], "unknown map `thesis-9`"),
        (vec!["--start".into(), "20,20".into()], "outside map"),
        (vec!["--start".into(), "0.5,0.5".into()], "inside an obstacle"),
        (vec!["--end".into(), "5.5,5.5".into(), "--map".into(), "thesis-2".into()], "inside an obstacle"),
        (vec!["--start".into(), "1.3".into()], "X,Y"),
        (vec!["--path".into(), d("badheader.csv")], "expected columns x_m,y_m"),
        (vec!["--path".into(), d("nonnum.csv")], "nonnum.csv:3: `y_m` = `two`"),
        (vec!["--path".into(), d("nonfinite.csv")], "nonfinite.csv:3: `x_m` = `NaN`"),
        (vec!["--path".into(), d("inwall.csv")], "inside an obstacle"),
        (vec!["--path".into(), d("absent.csv")], "absent.csv"),
        (vec!["--width=-1".into()], "--width"),
        (vec!["--width".into(), "60".into()], "--width = 60 m is wider than the map's shorter side (11 m)"),
        (vec!["--width".into(), "1e300".into()], "--width = 1e300 m is wider"),
        (vec!["--obstacle".into(), "5,5,6".into()], "--obstacle 5,5,6: expected four numbers"),
        (vec!["--obstacle".into(), "6,5,5,6".into()], "X0 < X1 and Y0 < Y1"),
        (vec!["--obstacle".into(), "5,5,x,6".into()], "`x` is not a number"),
        (vec!["--obstacle".into(), "-1,-1,12,12".into()], "no free cell"),
        (vec!["--obstacle-in-area".into()], "--obstacle"),
        (vec!["--pattern".into(), "thesis-spiral".into(), "--map".into(), "thesis-2".into()], "one rectangle"),
        (vec!["--pattern".into(), "thesis-spiral".into(), "--end".into(), "2,2".into()], "same station"),
    ];
    for (args, needle) in cases {
        let mut all = vec!["eval".to_string(), "--out".into(), out.clone()];
        all.extend(args);
        expect_input_error(&all.iter().map(String::as_str).collect::<Vec<_>>(), needle);
    }
    // A valid tiny image map with a resolution works.
    let ok = covga(&["eval", "--map", &d("ok.yaml"), "--start", "1,1", "--width", "0.5", "--json", "--out", &out]);
    assert!(ok.status.success(), "{}", String::from_utf8_lossy(&ok.stderr));
}

/// The real SLAM map shipped with the project (`experiments/maps/basement.yaml`, Apache-2.0):
/// both patterns finish, report the pockets a 0.6 m robot cannot reach,
/// and cover at least 90 % of the cells it can.
#[test]
fn patterns_finish_on_a_slam_map_and_report_its_pockets() {
    let map = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments/maps/basement.yaml");
    let dir = tempfile::tempdir().unwrap();
    for pattern in ["boustrophedon", "spiral"] {
        let out = covga(&[
            "eval",
            "--map",
            map.to_str().unwrap(),
            "--pattern",
            pattern,
            "--start",
            "0,0",
            "--json",
            "--out",
            dir.path().join(pattern).to_str().unwrap(),
        ]);
        let v = json_of(&out);
        assert!(v["pockets"].as_u64().unwrap() > 0, "{pattern}: {v}");
        assert!(v["pocket_area_m2"].as_f64().unwrap() > 1.0);
        let reach = v["common"]["cov_final_reach"].as_f64().unwrap();
        assert!(reach >= 0.90, "{pattern}: cov_final over reachable cells {reach}");
        assert_eq!(v["obstacle_cells"], 0, "{pattern}");
        assert!(v["common"]["reachable_cells"].as_u64().unwrap() < v["common"]["free_cells"].as_u64().unwrap());
    }
}

#[test]
fn a_fleet_plan_is_scored_per_robot_and_bad_fleets_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let d = |name: &str| dir.path().join(name).display().to_string();
    std::fs::write(
        d("fleet.toml"),
        "[robot]\nspeed = 0.2\n[[robots]]\nname = \"small\"\nwidth = 0.4\nstart = [2.0, 3.0]\n\
         [[robots]]\nname = \"large\"\nwidth = 0.8\nspeed = 0.4\nstart = [4.0, 3.0]\n",
    )
    .unwrap();
    std::fs::write(d("plan.csv"), "x_m,y_m,agent\n2,3,0\n6,3,0\n4,3,1\n8,3,1\n").unwrap();
    let out = covga(&["eval", "--path", &d("plan.csv"), "--fleet", &d("fleet.toml"), "--json", "--out", &d("out")]);
    let v = json_of(&out);
    let f = &v["fleet"];
    assert_eq!(f["robots"], serde_json::json!(["small", "large"]));
    // Hand-counted in fleet::metrics: 40 and 80 cells, 20 shared, union 100.
    assert_eq!((num(f, "union_cells"), num(f, "overlap_cells")), (100.0, 20.0));
    assert_eq!((num(f, "makespan_s"), num(f, "balance")), (20.0, 2.0));
    assert!((num(f, "t_final") - 0.5).abs() < 1e-9);
    let metrics: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("out/metrics.json")).unwrap()).unwrap();
    assert_eq!(metrics["fleet"], *f);

    std::fs::write(d("inside.toml"), "[[robots]]\nname = \"a\"\n[[robots]]\nname = \"b\"\nstart = [0.5, 3.0]\n")
        .unwrap();
    expect_input_error(
        &["eval", "--path", &d("plan.csv"), "--fleet", &d("inside.toml"), "--out", &d("o2")],
        "robots[1].start (robot \"b\")",
    );
    std::fs::write(d("one.toml"), "[[robots]]\nname = \"a\"\n").unwrap();
    expect_input_error(
        &["eval", "--path", &d("plan.csv"), "--fleet", &d("one.toml"), "--out", &d("o3")],
        "2 paths for a fleet of 1 robots",
    );
    expect_input_error(&["eval", "--path", &d("plan.csv"), "--fleet", &d("missing.toml")], "missing.toml");
    // The `robot` column names each agent's robot of the fleet, in order.
    std::fs::write(d("named.csv"), "x_m,y_m,agent,robot\n2,3,0,small\n6,3,0,small\n4,3,1,large\n8,3,1,large\n")
        .unwrap();
    json_of(&covga(&["eval", "--path", &d("named.csv"), "--fleet", &d("fleet.toml"), "--json", "--out", &d("o4")]));
    std::fs::write(d("swapped.csv"), "x_m,y_m,agent,robot\n2,3,0,large\n6,3,0,large\n4,3,1,small\n8,3,1,small\n")
        .unwrap();
    expect_input_error(
        &["eval", "--path", &d("swapped.csv"), "--fleet", &d("fleet.toml"), "--out", &d("o5")],
        "agent 0 names robot `large`, but robot 0 of",
    );
    std::fs::write(d("unknown.csv"), "x_m,y_m,agent,robot\n2,3,0,small\n6,3,0,small\n4,3,1,nobody\n8,3,1,nobody\n")
        .unwrap();
    expect_input_error(
        &["eval", "--path", &d("unknown.csv"), "--fleet", &d("fleet.toml"), "--out", &d("o6")],
        "agent 1 names robot `nobody`",
    );
    std::fs::write(d("mixed.csv"), "x_m,y_m,agent,robot\n2,3,0,small\n6,3,0,large\n").unwrap();
    expect_input_error(
        &["eval", "--path", &d("mixed.csv"), "--fleet", &d("fleet.toml"), "--out", &d("o7")],
        "mixed.csv:3: `robot` = `large` where agent 0's earlier rows name `small`",
    );
}

#[test]
fn area_division_plans_one_region_per_robot() {
    let dir = tempfile::tempdir().unwrap();
    let d = |name: &str| dir.path().join(name).display().to_string();
    std::fs::write(
        d("fleet.toml"),
        "[[robots]]\nname = \"a\"\nwidth = 0.4\nspeed = 0.2\nstart = [1.3, 1.3]\n\
         [[robots]]\nname = \"b\"\nwidth = 0.6\nspeed = 0.3\nstart = [9.7, 1.3]\n\
         [[robots]]\nname = \"c\"\nwidth = 0.9\nspeed = 0.5\nstart = [5.5, 9.5]\n",
    )
    .unwrap();
    let v = json_of(&covga(&["eval", "--fleet", &d("fleet.toml"), "--divide", "--json", "--out", &d("out")]));
    let f = &v["fleet"];
    assert_eq!(f["robots"].as_array().map(Vec::len), Some(3));
    assert!(num(f, "union_reach") > 0.97, "{f}");
    assert!(num(f, "overlap_fraction") < 0.2, "{f}");
    assert!(v["source"].as_str().unwrap().starts_with("area division"));
    let csv = std::fs::read_to_string(dir.path().join("out/path.csv")).unwrap();
    assert!(csv.starts_with("agent,robot,index,x_m,y_m\n"), "{}", &csv[..40]);
    let robots: std::collections::BTreeSet<&str> = csv.lines().skip(1).filter_map(|l| l.split(',').nth(1)).collect();
    assert_eq!(robots, ["a", "b", "c"].into_iter().collect(), "one path per robot in path.csv");
    // The file scores again as a fleet plan.
    let again = json_of(&covga(&[
        "eval",
        "--path",
        &dir.path().join("out/path.csv").display().to_string(),
        "--fleet",
        &d("fleet.toml"),
        "--json",
        "--out",
        &d("again"),
    ]));
    assert_eq!(again["fleet"]["union_cells"], f["union_cells"]);
    assert!(dir.path().join("out/path.png").exists());

    std::fs::write(d("shared.toml"), "[[robots]]\nname = \"a\"\n[[robots]]\nname = \"b\"\n").unwrap();
    expect_input_error(&["eval", "--fleet", &d("shared.toml"), "--divide", "--out", &d("o2")], "distinct start");
    expect_input_error(&["eval", "--fleet", &d("fleet.toml"), "--out", &d("o3")], "--path FILE");
}

/// Two 5 m rooms at 0.1 m with a closed wall at x = 5 m: an end station behind the wall is
/// refused before planning (exit 2), instead of a plan that drives through the wall.
#[test]
fn an_end_behind_a_closed_wall_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let (cols, rows) = (100usize, 60usize);
    let mut pgm = format!("P5\n{cols} {rows}\n255\n").into_bytes();
    for _ in 0..rows {
        pgm.extend((0..cols).map(|c| if c == 50 { 0u8 } else { 254 }));
    }
    std::fs::write(dir.path().join("rooms.pgm"), pgm).unwrap();
    std::fs::write(
        dir.path().join("rooms.yaml"),
        "image: rooms.pgm\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
    )
    .unwrap();
    let map = dir.path().join("rooms.yaml");
    let map = map.to_str().unwrap();
    expect_input_error(
        &["eval", "--map", map, "--pattern", "boustrophedon", "--start", "2,3", "--end", "8,3"],
        "--end: (8, 3) m cannot be reached from the start (2, 3) m",
    );
    let exp = dir.path().join("rooms.toml");
    std::fs::write(
        &exp,
        format!(
            "planner = \"boustrophedon\"\n[map]\nsource = {map:?}\n[stations]\nstart = [2.0, 3.0]\nend = [8.0, 3.0]\n"
        ),
    )
    .unwrap();
    expect_input_error(&["run", exp.to_str().unwrap(), "--quiet"], "stations.end");
    // In the start's room the same end is fine.
    let ok = covga(&[
        "eval",
        "--map",
        map,
        "--pattern",
        "boustrophedon",
        "--start",
        "2,3",
        "--end",
        "4,3",
        "--json",
        "--out",
        dir.path().join("ok").to_str().unwrap(),
    ]);
    let s = json_of(&ok);
    assert_eq!(s["common"]["obstacle_cells"], 0);
    assert_eq!(s["common"]["executable"], true);
}

/// A heterogeneous fleet's headline sweeps each robot at its own width: the area division's
/// plan sweeps no obstacle cell in the headline, as in its fleet block.
#[test]
fn the_fleet_headline_scores_each_robot_at_its_own_width() {
    let dir = tempfile::tempdir().unwrap();
    let fleet = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments/fleets/thesis1-hetero.toml");
    let out = covga(&[
        "eval",
        "--map",
        "thesis-1",
        "--fleet",
        fleet.to_str().unwrap(),
        "--divide",
        "--json",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    let s = json_of(&out);
    assert_eq!(s["fleet"]["obstacle_cells"], 0, "{s}");
    assert_eq!(s["common"]["obstacle_cells"], 0, "{s}");
    assert_eq!(s["common"]["executable"], true);
    assert_eq!(s["obstacle_cells"], 0, "the headline metrics");
}

/// `covga eval --help` names every preset map.
#[test]
fn eval_help_lists_every_preset() {
    let o = crate::common::command().args(["eval", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&o.stdout);
    for name in covga::map::presets::PRESET_NAMES {
        assert!(help.contains(name), "{name} missing from:\n{help}");
    }
}

/// A robot so narrow that a pattern would need lanes without end is refused at once, naming
/// the key and the narrowest width allowed, in `eval` and in `run`.
#[test]
fn a_robot_too_narrow_for_lanes_is_refused_at_once() {
    let started = std::time::Instant::now();
    let o = crate::common::command().args(["eval", "--map", "thesis-1", "--width", "1e-12"]).output().unwrap();
    assert_eq!(o.status.code(), Some(2), "{o:?}");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("--width") && err.contains("at least 1.556e-4 m"), "{err}");
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("narrow.toml");
    std::fs::write(&file, "planner = \"boustrophedon\"\n[robot]\nwidth = 1e-6\n[stations]\nstart = [1.3, 1.3]\n")
        .unwrap();
    let o = crate::common::command()
        .args(["run", file.to_str().unwrap(), "--out", dir.path().join("out").to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{o:?}");
    assert!(String::from_utf8_lossy(&o.stderr).contains("`robot.width`"), "{o:?}");
    assert!(!dir.path().join("out").join("best_path.csv").exists(), "nothing half written");
    assert!(started.elapsed().as_secs_f64() < 5.0);
}

/// `covga maps` writes only where it is told: without `--out` it refuses (exit 2) and writes
/// nothing.
#[test]
fn maps_needs_an_out_folder() {
    let dir = tempfile::tempdir().unwrap();
    let o = crate::common::command().arg("maps").current_dir(dir.path()).output().unwrap();
    assert_eq!(o.status.code(), Some(2), "{o:?}");
    assert!(String::from_utf8_lossy(&o.stderr).contains("--out"), "{o:?}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "nothing written");
}

/// A map smaller than the default camera's narrowest hallway (1.5 m) is scored: the hallway is
/// the map's longer side there (it was refused before, naming `waypoint.hallway`).
#[test]
fn a_map_smaller_than_the_default_hallway_is_scored() {
    let dir = tempfile::tempdir().unwrap();
    let mut pgm = String::from("P2\n12 8\n255\n");
    for _ in 0..8 {
        pgm.push_str(&["254"; 12].join(" "));
        pgm.push('\n');
    }
    let map = dir.path().join("small.pgm");
    std::fs::write(&map, pgm).unwrap();
    let o = covga(&[
        "eval",
        "--map",
        map.to_str().unwrap(),
        "--resolution",
        "0.1",
        "--width",
        "0.3",
        "--start",
        "0.5,0.4",
        "--json",
        "--out",
        dir.path().join("out").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["common"]["executable"], true, "{v}");
    assert!(v["common"]["cam_open_free"].as_f64().unwrap() > 0.0, "{v}");
}

/// `covga maps generate` writes a seeded floor plan as ROS files and prints a start station
/// that `covga eval` accepts; the same seed writes the same bytes; a bad kind or size is
/// refused (exit 2) with nothing written.
#[test]
fn maps_generate_writes_a_plan_that_eval_scores_from_the_printed_start() {
    let dir = tempfile::tempdir().unwrap();
    let covga = |args: &[&str]| crate::common::command().args(args).current_dir(dir.path()).output().unwrap();
    let o = covga(&["maps", "generate", "--kind", "house", "--seed", "5", "--noisy", "--out", "a"]);
    assert!(o.status.success(), "{o:?}");
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    let start = out.lines().find_map(|l| l.strip_prefix("start = [")).expect("a start station").trim_end_matches(']');
    let start = start.replace(' ', "");
    let e =
        covga(&["eval", "--map", "a/house-5-noisy.yaml", "--pattern", "boustrophedon", "--start", &start, "--json"]);
    assert!(e.status.success(), "{e:?}");
    let json: serde_json::Value = serde_json::from_slice(&e.stdout).unwrap();
    assert_eq!(json["common"]["executable"], true, "{json}");
    let again = covga(&["maps", "generate", "--kind", "house", "--seed", "5", "--noisy", "--out", "b"]);
    assert!(again.status.success());
    let read = |p: &str| std::fs::read(dir.path().join(p)).unwrap();
    assert_eq!(read("a/house-5-noisy.pgm"), read("b/house-5-noisy.pgm"));
    for (args, want) in [
        (&["maps", "generate", "--kind", "castle", "--out", "c"][..], "castle"),
        (&["maps", "generate", "--kind", "hall", "--width", "3", "--out", "c"][..], "width = 3 m"),
    ] {
        let o = covga(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {o:?}");
        assert!(String::from_utf8_lossy(&o.stderr).contains(want), "{args:?}: {o:?}");
    }
    assert!(!dir.path().join("c").exists(), "nothing written for a refused plan");
}
