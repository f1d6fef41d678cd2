//! Unit tests of the time-to-coverage section: series, labels, bound ratios, curves.
use super::*;

/// Every `--by` group is a series; the planner joins it where the study has several.
#[test]
fn each_group_is_a_series_with_its_planner() {
    for (group, planner, one, series) in [
        ("planner=cell_order, cell_order.solver=ga", "cell_order", false, "planner=cell_order, cell_order.solver=ga"),
        ("cell_order.solver=ga", "cell_order", false, "planner=cell_order, cell_order.solver=ga"),
        ("map.source=office", "spiral", false, "spiral"),
        ("thesis.selection=elite", "thesis", true, "thesis.selection=elite"),
    ] {
        assert_eq!(series_label(group, planner, one), series, "{group}");
    }
}

#[test]
fn legend_labels_keep_what_tells_the_series_apart() {
    let labels: Vec<String> = [
        "planner=cell_order, cell_order.solver=ga, cell_order.seed_directions=true",
        "planner=cell_order, cell_order.solver=nearest, cell_order.seed_directions=",
    ]
    .map(String::from)
    .to_vec();
    assert_eq!(distinct_parts(&labels), ["solver=ga, seed_directions=true", "solver=nearest"]);
    assert_eq!(distinct_parts(&["planner=thesis".to_string()]), ["planner=thesis"]);
    // The panel names the map: a series told apart by its map alone is the panel's runs.
    let by_map = ["map.source=office".to_string(), "map.source=thesis-2".to_string()];
    assert_eq!(distinct_parts(&by_map), ["executable runs", "executable runs"]);
    let both = ["map.source=office, thesis.moves=routed".to_string()];
    assert_eq!(distinct_parts(&both), ["moves=routed"]);
}

#[test]
fn a_level_shows_the_median_time_and_its_median_ratio_to_the_bound() {
    let times = vec![[Some(80.0), Some(100.0), None], [Some(40.0), None, None], [None, None, None]];
    let b = |full: f64| Some(LEVELS.map(|l| l * full));
    let se = Series {
        label: "a".into(),
        times,
        bounds: vec![b(100.0), b(50.0), None],
        curves: Vec::new(),
        colour: 0,
        first: "r".into(),
    };
    // 80 s over 0.8 × 100 s and 40 s over 0.8 × 50 s; the third run reaches no level.
    assert_eq!(bound_ratios(&se, 0), vec![1.0, 1.0]);
    assert_eq!(level_cell(&[80.0, 40.0], &bound_ratios(&se, 0)), "60 (1.00×)");
    assert_eq!(level_cell(&[100.0], &bound_ratios(&se, 1)), "100 (1.11×)");
    assert_eq!(level_cell(&[], &bound_ratios(&se, 2)), "–");
    // A run that reaches the level without a bound: no ratio for anyone.
    let se = Series { bounds: vec![b(100.0), None, None], ..se };
    assert!(bound_ratios(&se, 0).is_empty());
    assert_eq!(level_cell(&[80.0, 40.0], &[]), "60");
}

#[test]
fn curves_are_read_and_sampled_as_steps() {
    let read_curve = |f: &std::path::Path| CoverageCurve::parse_csv(&std::fs::read_to_string(f).ok()?);
    let dir = std::env::temp_dir().join(format!("covga-curves-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("coverage_curve.csv");
    std::fs::write(&file, "time_s,coverage_reach\n0,0\n10,0.5\n20,0.9\n30,0.95\n").unwrap();
    let c = read_curve(&file).unwrap();
    assert_eq!(c.points().len(), 4);
    let at = |t| c.coverage_at(t);
    assert_eq!((at(9.9), at(10.0), at(25.0), at(99.0)), (0.0, 0.5, 0.9, 0.95));
    assert_eq!((c.time_to(0.8), c.time_to(0.95), c.time_to(0.96)), (Some(20.0), Some(30.0), None));
    for bad in ["x,y\n0,0\n", "time_s,coverage_reach\n0,0\n10,x\n", "time_s,coverage_reach\n0,0.5\n10,0.4\n"] {
        std::fs::write(&file, bad).unwrap();
        assert!(read_curve(&file).is_none(), "{bad:?} is not a curve");
    }
    let slower = CoverageCurve::parse_csv("time_s,coverage_reach\n0,0\n20,0.5\n40,0.9\n60,0.95\n").unwrap();
    let series = [Series {
        label: "a".into(),
        times: Vec::new(),
        bounds: Vec::new(),
        curves: vec![c, slower],
        colour: 3,
        first: "r".into(),
    }];
    let drawn = summarise(&series, &AreaBounds::none("no grid file".into()));
    assert_eq!((drawn[0].colour, drawn[0].bound.len()), (3, 0), "the report's colour; no bound without one");
    assert_eq!(drawn[0].curve.len(), SAMPLES + 1);
    // At the end of the longer plan both runs have reached 0.95.
    let last = drawn[0].curve.last().unwrap();
    assert_eq!((last.0, last.1), (60.0, 0.95));
    std::fs::remove_dir_all(&dir).unwrap();
}
