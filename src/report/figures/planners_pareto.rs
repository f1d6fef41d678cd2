//! The Pareto view of a study that mixes planners: per map, every run's plan as a point of
//! the common scorer's mission time (`time_s`, seconds) and reachable coverage, each group its
//! own colour and marker, and the plans no other plan on that map dominates (as fast or faster
//! and covering as much or more, better in one) ringed, whichever planner made them. 003's
//! `t_final` and `f` are one GA's own measures and do not compare planners.

use crate::cell_order::controls::COVERAGE_TIE;
use crate::plot::{Figure, err, text};
use plotters::coord::Shift;
use plotters::prelude::*;

/// One run's plan: its group (index into [`PlannersPareto::groups`]), time and coverage.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanPoint {
    /// Its group.
    pub group: usize,
    /// Mission time of its plan, in seconds.
    pub time_s: f64,
    /// Share of the reachable cells its plan covers.
    pub coverage: f64,
    /// Whether a robot can drive it (others are drawn as grey crosses, no part of the front).
    pub executable: bool,
}

/// Mission time against reachable coverage, one panel per map.
pub struct PlannersPareto {
    /// The groups' labels (planner and `--by` values), in legend order.
    pub groups: Vec<String>,
    /// `(map, points)` per panel.
    pub panels: Vec<(String, Vec<PlanPoint>)>,
}

const TITLE: &str = "Each run's plan: mission time against coverage of the reachable cells; ringed: no plan of \
                     any planner on that map is as fast and covers as much, coverage within 0.005 counting as \
                     equal (grey ×: not executable; hollow markers, earlier groups larger, so that plans that \
                     coincide all show)";

/// Indices of the executable points no other executable point dominates (time lower is better,
/// coverage higher is better). Coverage within [`COVERAGE_TIE`] of another plan's counts as
/// equal: a plan that overshoots a coverage goal by a few cells gains nothing from it, and the
/// faster of two plans stopped at one goal dominates the other.
pub fn non_dominated(points: &[PlanPoint]) -> Vec<usize> {
    let dominates = |a: &PlanPoint, b: &PlanPoint| {
        let as_much = a.coverage >= b.coverage - COVERAGE_TIE;
        let more = a.coverage > b.coverage + COVERAGE_TIE;
        a.time_s <= b.time_s && as_much && (a.time_s < b.time_s || more)
    };
    (0..points.len())
        .filter(|&i| points[i].executable)
        .filter(|&i| !points.iter().any(|o| o.executable && dominates(o, &points[i])))
        .collect()
}

/// The half-size in pixels of group `k`'s marker among `n` groups: earlier groups larger (by
/// 2 px a step, at most 6 px larger), so that hollow markers of plans that coincide nest
/// inside each other instead of hiding one another.
fn marker_size(k: usize, n: usize) -> i32 {
    4 + 2 * (n.saturating_sub(1 + k).min(3)) as i32
}

/// The marker of group `k` among `n`, hollow, half-size [`marker_size`]: a circle, triangle,
/// square, diamond or downward triangle, round after round.
fn marker<DB: DrawingBackend>(k: usize, n: usize, at: (i32, i32), area: &DrawingArea<DB, Shift>) -> Result<(), String> {
    let style = crate::plot::series_colour(k).stroke_width(2);
    let ((x, y), r) = (at, marker_size(k, n));
    let outline = |points: Vec<(i32, i32)>| {
        let closed = [points.clone(), vec![points[0]]].concat();
        area.draw(&PathElement::new(closed, style)).map_err(err)
    };
    match k % 5 {
        0 => area.draw(&Circle::new(at, r, style)).map_err(err),
        1 => outline(vec![(x, y - r - 1), (x - r - 1, y + r), (x + r + 1, y + r)]),
        2 => outline(vec![(x - r, y - r), (x + r, y - r), (x + r, y + r), (x - r, y + r)]),
        3 => outline(vec![(x, y - r - 2), (x - r - 1, y), (x, y + r + 2), (x + r + 1, y)]),
        _ => outline(vec![(x, y + r + 1), (x - r - 1, y - r), (x + r + 1, y - r)]),
    }
}

impl PlannersPareto {
    fn legend_height(&self, width: u32) -> u32 {
        super::panels::legend_strip_height(&self.legend_labels(), width)
    }

    /// Each group's label with its runs over every map.
    fn legend_labels(&self) -> Vec<String> {
        (0..self.groups.len())
            .map(|k| {
                let runs = self.panels.iter().flat_map(|(_, p)| p).filter(|p| p.group == k).count();
                format!("{} ({})", self.groups[k], crate::plot::runs_text(runs))
            })
            .collect()
    }

    fn grid(&self) -> (usize, usize) {
        let n = self.panels.len().max(1);
        if n <= 2 { (1, n) } else { (n.div_ceil(2), 2) }
    }
}

impl Figure for PlannersPareto {
    fn size(&self) -> (u32, u32) {
        let (rows, columns) = self.grid();
        let width = 620 * columns as u32;
        (width, crate::plot::title_height(TITLE, width, 16.0) + 440 * rows as u32 + self.legend_height(width))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let root = crate::plot::titled(root, TITLE, 16.0)?;
        let (width, height) = root.dim_in_pixel();
        let (panels, strip) = root.split_vertically(height - self.legend_height(width));
        let labels = self.legend_labels();
        let n = self.groups.len();
        super::panels::draw_legend_strip(&strip, &labels, |k, (x, y)| marker(k, n, (x + 11, y), &strip))?;
        for (area, (map, points)) in panels.split_evenly(self.grid()).iter().zip(&self.panels) {
            draw_panel(area, map, points, n)?;
        }
        Ok(())
    }
}

/// The value range of `values` with a margin of a tenth of its span (a twentieth of the value
/// for a single one).
fn padded(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) =
        values.filter(|v| v.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = ((hi - lo) * 0.1).max(hi.abs() * 0.02).max(1e-3);
    (lo - pad, hi + pad)
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    map: &str,
    points: &[PlanPoint],
    groups: usize,
) -> Result<(), String> {
    const TICKS: usize = 8;
    let (x0, x1) = padded(points.iter().map(|p| p.time_s));
    let (y0, y1) = padded(points.iter().map(|p| p.coverage));
    let (y0, y1) = (y0.max(0.0), y1.min(1.0));
    let (xd, yd) = (crate::plot::step_decimals(x1 - x0, TICKS), crate::plot::step_decimals(y1 - y0, TICKS));
    let mut chart = ChartBuilder::on(area)
        .caption(crate::plot::panel_label(map), text(15.0))
        .margin(10)
        .margin_right(24)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_labels(TICKS)
        .y_labels(TICKS)
        .x_label_formatter(&|v| format!("{v:.xd$}"))
        .y_label_formatter(&|v| format!("{v:.yd$}"))
        .light_line_style(RGBColor(235, 235, 235))
        .x_desc("mission time [s]")
        .y_desc("coverage of the reachable cells")
        .label_style(text(14.0))
        .axis_desc_style(text(14.0))
        .draw()
        .map_err(err)?;
    let grey = RGBColor(120, 120, 120);
    let excluded =
        points.iter().filter(|p| !p.executable).map(|p| Cross::new((p.time_s, p.coverage), 4, grey.stroke_width(1)));
    chart.draw_series(excluded).map_err(err)?;
    let (ax, ay) = area.get_base_pixel();
    // The larger markers first, each group's over the earlier ones'.
    let mut drawn: Vec<&PlanPoint> = points.iter().filter(|p| p.executable).collect();
    drawn.sort_by_key(|p| p.group);
    for p in drawn {
        let (x, y) = chart.backend_coord(&(p.time_s, p.coverage));
        marker(p.group, groups, (x - ax, y - ay), area)?;
    }
    let ring = marker_size(0, groups) + 5;
    for i in non_dominated(points) {
        let p = &points[i];
        chart.draw_series([Circle::new((p.time_s, p.coverage), ring, BLACK.stroke_width(1))]).map_err(err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(group: usize, time_s: f64, coverage: f64) -> PlanPoint {
        PlanPoint { group, time_s, coverage, executable: true }
    }

    #[test]
    fn the_front_spans_planners_and_leaves_out_what_cannot_be_driven() {
        let mut points = vec![point(0, 100.0, 0.9), point(1, 90.0, 0.9), point(2, 120.0, 0.95), point(0, 130.0, 0.94)];
        assert_eq!(non_dominated(&points), vec![1, 2]);
        points.push(PlanPoint { executable: false, ..point(3, 10.0, 1.0) });
        assert_eq!(non_dominated(&points), vec![1, 2], "a plan a robot cannot drive dominates nothing");
        let overshoot = vec![point(0, 3502.4, 0.9006), point(1, 3507.7, 0.9007), point(2, 12654.0, 0.943)];
        assert_eq!(non_dominated(&overshoot), vec![0, 2], "a goal overshot by a few cells gains nothing");
    }

    /// The four study shapes: texts on the canvas, distinct ticks, every group in the legend,
    /// every map named.
    #[test]
    fn the_pareto_view_keeps_its_texts_on_the_canvas() {
        type Panels<'a> = Vec<(&'a str, Vec<PlanPoint>)>;
        let shapes: [(&str, Vec<&str>, Panels); 4] = [
            (
                "thesis",
                vec!["elite", "nsga2"],
                vec![(
                    "thesis-1",
                    (0..20).map(|k| point(k % 2, 900.0 + 13.0 * k as f64, 0.6 + 0.01 * k as f64)).collect(),
                )],
            ),
            (
                "mixed",
                vec!["boustrophedon", "spiral", "solver=ga", "solver=ils"],
                vec![(
                    "experiments/maps/generated/office-1.yaml",
                    vec![
                        point(0, 12612.0, 0.943),
                        point(1, 11180.0, 0.966),
                        point(2, 3456.1, 0.9013),
                        point(3, 3455.8, 0.9012),
                    ],
                )],
            ),
            ("one run", vec!["nearest"], vec![("basement", vec![point(0, 6164.0, 0.901)])]),
            (
                "many maps",
                vec!["ils"],
                (0..5)
                    .map(|m| {
                        (["a.yaml", "b.yaml", "c.yaml", "d.yaml", "e.yaml"][m], vec![point(0, 3000.0 + m as f64, 0.9)])
                    })
                    .collect(),
            ),
        ];
        let mut found = Vec::new();
        for (name, groups, panels) in shapes {
            let figure = PlannersPareto {
                groups: groups.iter().map(|g| g.to_string()).collect(),
                panels: panels.iter().map(|(m, p)| (m.to_string(), p.clone())).collect(),
            };
            let mut expected: Vec<String> = groups.iter().map(|g| g.to_string()).collect();
            expected.extend(panels.iter().map(|(m, _)| crate::plot::panel_label(m)));
            expected.push("mission time [s]".into());
            let expected: Vec<&str> = expected.iter().map(String::as_str).collect();
            for p in crate::plot::layout::problems(&figure, &expected).unwrap() {
                found.push(format!("{name}: {p}"));
            }
        }
        assert!(found.is_empty(), "{}", found.join("\n"));
    }
}
