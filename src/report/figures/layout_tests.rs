//! The figures' layout on the study shapes they are drawn for (the thesis GA alone, mixed
//! planners, one run per group, many groups or maps): no text outside the canvas, no tick label
//! repeated along an axis, every group named.

mod study {
    //! The thesis GA's figures on their study shapes (groups of ten runs, one run, many groups).
    use super::super::diversity::{DiversityFigure, DiversityGroup};
    use super::super::pareto::{ParetoFacet, ParetoFigure};
    use super::super::paths::PathsGridFigure;
    use crate::coverage::CoverageGrid;
    use crate::geom::Point;
    use crate::plot::layout::problems;

    fn facet(label: &str, n: usize) -> ParetoFacet {
        let points: Vec<(f64, f64)> = (0..n).map(|k| (0.15 + 0.02 * k as f64, 0.41 - 0.01 * k as f64)).collect();
        ParetoFacet {
            label: label.into(),
            front: (0..n).collect(),
            rows: (0..n).collect(),
            kinds: vec![0; n],
            excluded: vec![(0.3, 0.2)],
            points,
        }
    }

    #[test]
    fn pareto_diversity_and_path_figures_keep_their_texts_on_the_canvas() {
        let mut found = Vec::new();
        for (name, groups) in [
            ("thesis", vec![("selection=elite", 10), ("selection=nsga2", 10)]),
            ("one run", vec![("all", 1)]),
            (
                "many",
                (0..9)
                    .map(|_| ("map.source=experiments/maps/generated/house-1-noisy.yaml, selection=tournament", 5))
                    .collect(),
            ),
        ] {
            let facets = groups.iter().map(|(l, n)| facet(l, *n)).collect();
            let figure = ParetoFigure { facets, shape: None, kinds: Vec::new() };
            for p in
                problems(&figure, &["t_final: 003's time efficiency", "cov_final: share of all free cells"]).unwrap()
            {
                found.push(format!("pareto {name}: {p}"));
            }
            let diversity = DiversityFigure {
                groups: groups
                    .iter()
                    .map(|(l, n)| DiversityGroup {
                        label: l.to_string(),
                        runs: *n,
                        curve: (0..50).map(|i| (i * 10, 40.0, 30.0, 55.0)).collect(),
                        colour: *n,
                    })
                    .collect(),
            };
            for p in problems(&diversity, &[]).unwrap() {
                found.push(format!("diversity {name}: {p}"));
            }
            let texts = crate::plot::layout::drawn_texts(&diversity).unwrap();
            if groups.iter().any(|(_, n)| *n == 1) && !texts.iter().any(|t| t.text.contains("(1 run)")) {
                found.push(format!("diversity {name}: a one-run group says \"1 runs\""));
            }
        }
        let map = crate::map::presets::preset("thesis-1").unwrap();
        let grid = CoverageGrid::new(&map);
        let path = vec![Point::new(1.0, 1.0), Point::new(8.0, 1.0), Point::new(8.0, 8.0)];
        let panel = |title: &str| crate::plot::path::PathFigure {
            map: &map,
            grid: &grid,
            paths: vec![path.clone()],
            width: 0.6,
            robots: Vec::new(),
            title: title.into(),
        };
        for n in [1, 4, 9] {
            let panels = (0..n)
                .map(|k| panel(&format!("selection=elite, c_len=0.{k}: 1234 s, 90.1 % of the reachable cells")))
                .collect();
            for p in problems(&PathsGridFigure { panels }, &["1234 s"]).unwrap() {
                found.push(format!("paths {n}: {p}"));
            }
        }
        assert!(found.is_empty(), "{}", found.join("\n"));
    }
}

mod comparison {
    //! The box and convergence figures and the planners' paths on four study shapes.
    use super::super::boxes::{BoxFigure, BoxSeries};
    use super::super::convergence::{ConvergenceFigure, Curve};
    use super::super::paths::PlannerPathsFigure;
    use crate::plot::layout::problems;
    use crate::plot::path::PathFigure;

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
        let one_run = vec![(
            "basement".to_string(),
            vec![("nearest".to_string(), vec![0.90]), ("boustrophedon".into(), vec![0.91])],
        )];
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
                        .enumerate()
                        .map(|(k, (label, values))| BoxSeries {
                            label: label.clone(),
                            values: values.clone(),
                            excluded: Vec::new(),
                            colour: k,
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
                            Curve { label: label.clone(), runs: values.len(), points, scored: Some(top), colour: 0 }
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
}

mod curves {
    use super::super::curves::{CurvesFigure, Drawn};

    /// The four study shapes: every text on the canvas, no repeated tick, every series and map
    /// named, "1 run" for one.
    #[test]
    fn the_curves_figure_keeps_its_texts_on_the_canvas() {
        let drawn = |label: &str, runs: usize| Drawn {
            label: label.into(),
            runs,
            curve: (0..=10).map(|k| (k as f64 * 400.0, (k as f64 / 10.0).min(0.95), 0.0, 1.0)).collect(),
            colour: runs,
            bound: (0..=10).map(|k| (k as f64 * 150.0, k as f64 / 10.0)).collect(),
        };
        type Panels = Vec<(String, Vec<Drawn>)>;
        let shapes: [(&str, Panels); 4] = [
            ("thesis", vec![("thesis-1".into(), vec![drawn("selection=elite", 10), drawn("selection=nsga2", 10)])]),
            (
                "mixed",
                vec![(
                    "experiments/maps/generated/office-1.yaml".into(),
                    vec![drawn("boustrophedon", 1), drawn("spiral", 1), drawn("solver=ga", 3), drawn("solver=ils", 3)],
                )],
            ),
            ("one run", vec![("basement".into(), vec![drawn("nearest", 1)])]),
            ("many maps", (0..5).map(|m| (format!("maps/house-{m}.yaml"), vec![drawn("ils", 5)])).collect()),
        ];
        let mut found = Vec::new();
        for (name, panels) in shapes {
            let mut expected: Vec<String> =
                panels.iter().flat_map(|(_, d)| d.iter().map(|d| d.label.clone())).collect();
            // Each panel titled as the section titles it: the map and its robot.
            let robot = "robot 0.60 m wide, 0.30 m/s, 0.52 rad/s";
            let panels: Vec<(String, Vec<Drawn>)> =
                panels.into_iter().map(|(m, d)| (format!("{}: {robot}", crate::plot::panel_label(&m)), d)).collect();
            expected.extend(panels.iter().map(|(t, _)| t.clone()));
            expected.push(super::super::curves::BOUND_ENTRY.into());
            let figure = CurvesFigure { panels };
            let expected: Vec<&str> = expected.iter().map(String::as_str).collect();
            for p in crate::plot::layout::problems(&figure, &expected).unwrap() {
                found.push(format!("{name}: {p}"));
            }
            let texts = crate::plot::layout::drawn_texts(&figure).unwrap();
            if texts.iter().any(|t| t.text.contains("(1 runs)") || t.text.starts_with("map ")) {
                found.push(format!("{name}: \"1 runs\" or a map's path as a title"));
            }
        }
        assert!(found.is_empty(), "{}", found.join("\n"));
    }
}
