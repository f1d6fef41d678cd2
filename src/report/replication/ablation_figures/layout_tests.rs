//! The box and convergence figures' layout on four study shapes (the thesis GA alone, mixed
//! planners, one run per group, many maps): no text outside the canvas, no tick label repeated
//! along an axis, every group named.

use super::*;
use crate::plot::layout::problems;

/// `(map, [(group, values)])` of each shape.
type Shape = Vec<(String, Vec<(String, Vec<f64>)>)>;

fn shapes() -> Vec<(&'static str, Shape)> {
    let seeds = |base: f64, step: f64, n: usize| (0..n).map(|k| base + step * k as f64).collect::<Vec<f64>>();
    let thesis = vec![
        (
            "thesis-1".to_string(),
            vec![("elite".to_string(), seeds(0.62, 0.01, 10)), ("nsga2".into(), seeds(0.6, 0.012, 10))],
        ),
        (
            "thesis-2".to_string(),
            vec![("elite".to_string(), seeds(0.55, 0.01, 10)), ("nsga2".into(), seeds(0.57, 0.01, 10))],
        ),
    ];
    let mixed = vec![(
        "office-1".to_string(),
        vec![
            ("boustrophedon".to_string(), vec![0.943]),
            ("spiral".into(), vec![0.966]),
            ("cell_order-ga".into(), vec![0.9012, 0.9013, 0.9015]),
            ("cell_order-ils".into(), vec![0.9011, 0.9014, 0.9016]),
        ],
    )];
    let one_run =
        vec![("basement".to_string(), vec![("nearest".to_string(), vec![0.90]), ("boustrophedon".into(), vec![0.91])])];
    let many = (0..6)
        .map(|m| {
            (
                format!("experiments/maps/generated/house-{m}-noisy.yaml"),
                vec![("ils".to_string(), seeds(0.9, 0.001, 5))],
            )
        })
        .collect();
    vec![("thesis", thesis), ("mixed", mixed), ("one run", one_run), ("many maps", many)]
}

#[test]
fn box_plots_keep_every_text_on_the_canvas_and_every_tick_distinct() {
    let mut found = Vec::new();
    for (name, shape) in shapes() {
        let panels: Vec<(String, Vec<BoxSeries>)> = shape
            .iter()
            .map(|(map, groups)| {
                let boxes = groups
                    .iter()
                    .map(|(label, values)| BoxSeries {
                        label: label.clone(),
                        values: values.clone(),
                        excluded: Vec::new(),
                    })
                    .collect();
                (map.clone(), boxes)
            })
            .collect();
        let figure = BoxFigure { metric: "coverage of the reachable cells".into(), panels };
        let groups: Vec<&str> = shape.iter().flat_map(|(_, g)| g.iter().map(|(l, _)| l.as_str())).collect();
        for p in problems(&figure, &groups).unwrap() {
            found.push(format!("{name}: {p}"));
        }
        // A group of one run is drawn as a point, and its label says so.
        if shape.iter().any(|(_, g)| g.iter().any(|(_, v)| v.len() == 1)) {
            let texts = crate::plot::layout::drawn_texts(&figure).unwrap();
            if !texts.iter().any(|t| t.text.contains("(1 run)")) {
                found.push(format!("{name}: a one-run group is not labelled as such"));
            }
        }
    }
    assert!(found.is_empty(), "{}", found.join("\n"));
}

#[test]
fn convergence_figures_keep_every_text_on_the_canvas_and_every_tick_distinct() {
    let mut found = Vec::new();
    for (name, shape) in shapes() {
        let panels: Vec<(String, Vec<Curve>)> = shape
            .iter()
            .map(|(map, groups)| {
                let curves = groups
                    .iter()
                    .map(|(label, values)| {
                        let top = values.iter().copied().fold(0.0, f64::max);
                        let points = (0..20)
                            .map(|k| (k as f64 * 150.0, top * 0.9, top * (0.9 + 0.005 * k as f64).min(1.0), top))
                            .collect();
                        Curve { label: label.clone(), runs: values.len(), points, scored: Some(top) }
                    })
                    .collect();
                (map.clone(), curves)
            })
            .collect();
        let figure = ConvergenceFigure { panels };
        let groups: Vec<&str> = shape.iter().flat_map(|(_, g)| g.iter().map(|(l, _)| l.as_str())).collect();
        for p in problems(&figure, &groups).unwrap() {
            found.push(format!("{name}: {p}"));
        }
    }
    assert!(found.is_empty(), "{}", found.join("\n"));
}

#[test]
fn planner_path_grids_keep_every_text_on_the_canvas() {
    use crate::coverage::CoverageGrid;
    use crate::geom::Point;
    let map = crate::map::presets::preset("thesis-1").unwrap();
    let grid = CoverageGrid::new(&map);
    let path = vec![Point::new(1.0, 1.0), Point::new(8.0, 1.0), Point::new(8.0, 8.0)];
    let panel = |planner: &str, map_name: &str| PathFigure {
        map: &map,
        grid: &grid,
        paths: vec![path.clone()],
        width: 0.6,
        robots: Vec::new(),
        title: format!("{planner}, {map_name}: 1234 s, 90.1 % of the reachable cells"),
    };
    let mut found = Vec::new();
    for (name, shape) in shapes() {
        let rows: Vec<Vec<Option<PathFigure>>> = shape
            .iter()
            .map(|(map_name, groups)| groups.iter().map(|(g, _)| Some(panel(g, map_name))).collect())
            .collect();
        // One planner of the first map without an executable plan: its cell says so.
        let mut rows = rows;
        let mut missing: Vec<Vec<Option<String>>> = rows.iter().map(|r| vec![None; r.len()]).collect();
        rows[0][0] = None;
        missing[0][0] = Some("waypoint-camera: no executable plan of 10 runs".into());
        let figure = PlannerPathsFigure { rows, missing };
        for p in problems(&figure, &["1234 s", "no executable plan of 10 runs"]).unwrap() {
            found.push(format!("planner paths {name}: {p}"));
        }
    }
    assert!(found.is_empty(), "{}", found.join("\n"));
}
