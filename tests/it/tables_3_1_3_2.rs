//! 003 Tables 3.1 and 3.2 rebuilt from geometry, not from their own numbers: the hand-made
//! boustrophedon and spiral of §3.2.2 on map 1 (lanes 0.6 m apart, start and end at the
//! station (1.3, 1.3) m, straight back to it), with and without a 1 m square obstacle placed at
//! the centre of the map under the path and kept in `A_pix` (spec R29), under f1 and f2 and
//! `R_rot` 0 and 2π, scored by `covga eval` with the real rasteriser.
//!
//! The boustrophedon reproduces all eight rows of Table 3.1 (cov_final and t_final within 0.01,
//! f within 2 %), and the obstacle changes its counts exactly as the thesis's do (44 traversals
//! = 25 cells + 19 crossings). The spiral reproduces the two rows of Table 3.2 without the
//! obstacle and without a rotation cost; the other six rows are explained below with numbers.

/// What `covga eval` reports for one scenario.
#[derive(Debug)]
struct Eval {
    unique: u64,
    swept: u64,
    crossings: u64,
    obstacle: u64,
    area: u64,
    turn_rad: f64,
    cov: f64,
    t: f64,
    f: f64,
}

fn eval(pattern: &str, obstacle: bool, projection: &str, rot: &str) -> Eval {
    let dir = tempfile::tempdir().unwrap();
    let mut args = vec!["eval", "--map", "thesis-1", "--pattern", pattern, "--start", "1.3,1.3"];
    args.extend(["--width", "0.6", "--speed", "0.2", "--rot-speed", rot, "--projection", projection, "--json"]);
    if obstacle {
        args.extend(["--obstacle", "5.0,5.0,6.0,6.0", "--obstacle-in-area"]);
    }
    args.extend(["--out", dir.path().to_str().unwrap()]);
    let out = crate::common::command().args(&args).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let n = |k: &str| v[k].as_f64().unwrap_or_else(|| panic!("{k} in {v}"));
    Eval {
        unique: n("unique_cells") as u64,
        swept: n("cells_swept") as u64,
        crossings: n("crossings") as u64,
        obstacle: n("obstacle_cells") as u64,
        area: n("area_cells") as u64,
        turn_rad: n("total_turn_rad"),
        cov: n("cov_final"),
        t: n("t_final"),
        f: n("f_obstacle"),
    }
}

/// One printed row: obstacle, projection, R_rot, f_obstacle, cov_final, t_final.
type Row = (bool, &'static str, &'static str, f64, f64, f64);

const TABLE_3_1: [Row; 8] = [
    (false, "f1", "0", 0.922019, 0.96, 0.884038),
    (false, "f1", "6.28319", 0.91871, 0.96, 0.87742),
    (false, "f2", "0", 0.848677, 0.96, 0.884038),
    (false, "f2", "6.28319", 0.842323, 0.96, 0.87742),
    (true, "f1", "0", 0.010444, 0.947654, 0.890487),
    (true, "f1", "6.28319", 0.0104053, 0.947654, 0.883685),
    (true, "f2", "0", 0.00958948, 0.947654, 0.890487),
    (true, "f2", "6.28319", 0.00951623, 0.947654, 0.883685),
];

const TABLE_3_2: [Row; 8] = [
    (false, "f1", "0", 0.953991, 0.973827, 0.934154),
    (false, "f1", "6.28319", 0.950108, 0.973827, 0.92639),
    (false, "f2", "0", 0.909705, 0.973827, 0.934154),
    (false, "f2", "6.28319", 0.902144, 0.973827, 0.92639),
    (true, "f1", "0", 0.013216, 0.962469, 0.940637),
    (true, "f1", "6.28319", 0.0131625, 0.962469, 0.932929),
    (true, "f2", "0", 0.0125741, 0.962469, 0.940637),
    (true, "f2", "6.28319", 0.0124711, 0.962469, 0.932929),
];

fn matches(e: &Eval, &(_, _, _, f, cov, t): &Row) -> bool {
    (e.cov - cov).abs() <= 0.01 && (e.t - t).abs() <= 0.01 && (e.f / f - 1.0).abs() <= 0.02
}

#[test]
fn table_3_1_boustrophedon_all_eight_rows_from_the_path() {
    for row in &TABLE_3_1 {
        let e = eval("thesis-boustrophedon", row.0, row.1, row.2);
        assert!(matches(&e, row), "row {row:?}: got {e:?}");
        assert_eq!(e.area, 2025, "the obstacle stays in A_pix (R29)");
    }
    // The counts behind the rows, pinned: a change of the rasteriser moves them.
    let free = eval("thesis-boustrophedon", false, "f1", "0");
    let blocked = eval("thesis-boustrophedon", true, "f1", "0");
    assert_eq!((free.unique, free.swept, free.crossings, free.obstacle), (1964, 2226, 262, 0));
    assert_eq!((blocked.unique, blocked.swept, blocked.crossings, blocked.obstacle), (1939, 2182, 243, 44));
    // The thesis's own decomposition (spec §16.1: 1944 → 1919 unique, 255 → 236 crossings,
    // obj_pix 44): 44 traversals of the obstacle = 25 cells once + 19 crossings of the return
    // diagonal, and cov_pix drops by exactly obj_pix (Listing 3.1).
    assert_eq!(free.unique - blocked.unique, 1944 - 1919);
    assert_eq!(free.crossings - blocked.crossings, 255 - 236);
    assert_eq!(free.swept - blocked.swept, blocked.obstacle);
}

#[test]
fn table_3_2_spiral_rows_and_the_explained_mismatches() {
    let mut matched = Vec::new();
    for (k, row) in TABLE_3_2.iter().enumerate() {
        let e = eval("thesis-spiral", row.0, row.1, row.2);
        if matches(&e, row) {
            matched.push(k);
        }
        // Every row: coverage within 0.01, and the projection f(t, cov) before the obstacle
        // penalty within 2 % once each side's own obj_pix is divided out.
        assert!((e.cov - row.4).abs() <= 0.01, "row {row:?}: {e:?}");
        let penalty = |obj: u64| if obj == 0 { 1.0 } else { 2.0 * obj as f64 };
        let printed_obj = if row.0 { 36 } else { 0 };
        assert!((e.f * penalty(e.obstacle) / (row.3 * penalty(printed_obj)) - 1.0).abs() <= 0.02, "row {row:?}: {e:?}");
    }
    assert_eq!(matched, vec![0, 2], "rows without the obstacle and without rotation cost match");
    let free = eval("thesis-spiral", false, "f1", "0");
    let blocked = eval("thesis-spiral", true, "f1", "0");
    assert_eq!((free.unique, free.swept, free.crossings, free.obstacle), (1963, 2121, 158, 0));
    assert_eq!((blocked.unique, blocked.swept, blocked.crossings, blocked.obstacle), (1941, 2087, 146, 34));
    // Why the other rows miss:
    // 1. With the obstacle our spiral sweeps it 34 times, the printed row says 36; f_obstacle
    //    divides by 2·obj_pix, so f is 36/34 − 1 = 5.9 % high before anything else. The thesis's
    //    row is itself inconsistent (spec R27: its cov_pix drops by 39 = 2111 − 2072, not by
    //    the 36 it prints); ours drops by exactly obj_pix, as Listing 3.1 demands.
    assert_eq!(free.swept - blocked.swept, blocked.obstacle);
    // 2. Our spiral crosses 158 cells against the thesis's 139 (its cov_pix − unique), so its
    //    t_final is lower by 0.0086 at R_rot = 0 ...
    assert!((free.t - 0.934154) < -0.008 && (free.t - 0.934154) > -0.01);
    // 3. ... and it turns 46.3 rad in all (28 right angles and the return), while the thesis's
    //    R_rot = 2π row implies T_rot = 5.90 s, i.e. 37.1 rad: the extra 9.2 rad cost 4.4 more
    //    cells of time and push t_final just past the tolerance (0.0104 low).
    assert!((free.turn_rad - 46.34).abs() < 0.01);
    let turning = eval("thesis-spiral", false, "f1", "6.28319");
    assert!((turning.t - 0.92639).abs() > 0.01 && (turning.t - 0.92639).abs() < 0.011, "{turning:?}");
}
