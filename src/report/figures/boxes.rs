//! Box plots of a metric per planner and map: one panel per map, one box per planner.

use super::panels::{Y_TICKS, colour, two_columns};
use crate::plot::{Figure, err, text};
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// One box: a planner's values on one map.
pub struct BoxSeries {
    /// Planner label.
    pub label: String,
    /// The values of its executable plans (one per run): the box.
    pub values: Vec<f64>,
    /// The values of its plans that are not executable: drawn as crosses beside the box.
    pub excluded: Vec<f64>,
    /// Its colour's number ([`crate::plot::series_colour`]), the same in every figure of the
    /// report.
    pub colour: usize,
}

/// Box plots of one metric: one panel per map, one box per planner.
pub struct BoxFigure {
    /// Metric name with unit, for the y axis.
    pub metric: String,
    /// `(map, boxes)` per panel.
    pub panels: Vec<(String, Vec<BoxSeries>)>,
}

impl BoxFigure {
    /// Each box's axis label: the planner, with its executable share where some plans are not,
    /// and "(1 run)" for a group of one run (drawn as a point: a box needs several).
    fn labels(boxes: &[BoxSeries]) -> Vec<String> {
        boxes
            .iter()
            .map(|b| {
                let runs = b.values.len() + b.excluded.len();
                match (b.excluded.is_empty(), runs) {
                    (true, 1) => format!("{} (1 run)", b.label),
                    (true, _) => b.label.clone(),
                    (false, _) => format!("{} ({}/{runs})", b.label, b.values.len()),
                }
            })
            .collect()
    }

    fn title(&self) -> String {
        format!(
            "{} per planner (box = IQR, line = median, whiskers = min..max of executable plans; a group of one \
             run is a point; grey × = not executable; (k/n) = executable share)",
            self.metric
        )
    }

    /// Height of the band under each panel that holds its labels, written upwards.
    fn label_band(&self) -> u32 {
        let longest = self.panels.iter().flat_map(|(_, b)| Self::labels(b)).map(|l| l.chars().count()).max();
        (longest.unwrap_or(4) as f64 * 0.52 * 12.0) as u32 + 24
    }
}

impl Figure for BoxFigure {
    fn size(&self) -> (u32, u32) {
        let (r, c) = two_columns(self.panels.len());
        // Labels written upwards under the boxes: a box needs its width, not its label's.
        let boxes = self.panels.iter().map(|(_, b)| b.len()).max().unwrap_or(1) as u32;
        let width = c as u32 * (70 * boxes + 90).max(520);
        (width, r as u32 * (300 + self.label_band()) + crate::plot::title_height(&self.title(), width, 16.0))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let root = crate::plot::titled(root, &self.title(), 16.0)?;
        // One y range for every panel, so that the maps compare at a glance.
        let all: Vec<f64> = self
            .panels
            .iter()
            .flat_map(|(_, boxes)| boxes.iter().flat_map(|b| b.values.iter().chain(&b.excluded).copied()))
            .filter(|v| v.is_finite())
            .collect();
        let (lo, hi) = all.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| (l.min(v), h.max(v)));
        let (lo, hi) = if lo.is_finite() { (lo, hi) } else { (0.0, 1.0) };
        let pad = ((hi - lo) * 0.08).max(1e-3);
        for (area, (map, boxes)) in root.split_evenly(two_columns(self.panels.len())).iter().zip(&self.panels) {
            let n = boxes.len().max(1);
            let mut chart = ChartBuilder::on(area)
                .caption(map, text(15.0))
                .margin(8)
                .x_label_area_size(self.label_band())
                .y_label_area_size(60)
                .build_cartesian_2d(0.0..n as f64, (lo - pad)..(hi + pad))
                .map_err(err)?;
            let labels = Self::labels(boxes);
            let decimals = crate::plot::step_decimals(hi - lo + 2.0 * pad, Y_TICKS);
            chart
                .configure_mesh()
                .disable_x_mesh()
                .light_line_style(RGBColor(235, 235, 235))
                .x_labels(0)
                .y_labels(Y_TICKS)
                .y_label_formatter(&|v| format!("{v:.decimals$}"))
                .y_desc(&self.metric)
                .label_style(text(12.0))
                .axis_desc_style(text(13.0))
                .draw()
                .map_err(err)?;
            // Labels written upwards under their boxes, ending just below the axis.
            let upwards = text(12.0).transform(FontTransform::Rotate270).pos(Pos::new(HPos::Right, VPos::Center));
            let (below, (ax, ay)) = (lo - pad, area.get_base_pixel());
            for (k, label) in labels.iter().enumerate() {
                let (x, y) = chart.backend_coord(&(k as f64 + 0.5, below));
                area.draw(&Text::new(label.clone(), (x - ax, y - ay + 8), upwards.clone())).map_err(err)?;
            }
            for (k, b) in boxes.iter().enumerate() {
                draw_box(&mut chart, k, b)?;
            }
        }
        Ok(())
    }
}

/// Draws box `b` in slot `k` of `chart`: its plans that are not executable as grey crosses
/// beside it, a group of one run as a point, else whiskers, box and median.
fn draw_box<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    k: usize,
    b: &BoxSeries,
) -> Result<(), String> {
    let grey = RGBColor(120, 120, 120);
    chart
        .draw_series(b.excluded.iter().map(|&v| Cross::new((k as f64 + 0.85, v), 4, grey.stroke_width(1))))
        .map_err(err)?;
    if b.values.is_empty() {
        return Ok(());
    }
    if b.values.len() == 1 {
        let point = Circle::new((k as f64 + 0.5, b.values[0]), 5, colour(b.colour).filled());
        chart.draw_series([point]).map_err(err)?;
        chart.draw_series([Circle::new((k as f64 + 0.5, b.values[0]), 5, BLACK.stroke_width(1))]).map_err(err)?;
        return Ok(());
    }
    let (q1, med, q3) = crate::stats::quartiles(&b.values);
    let min = b.values.iter().copied().fold(f64::INFINITY, f64::min);
    let max = b.values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let (x0, x1, xc) = (k as f64 + 0.2, k as f64 + 0.8, k as f64 + 0.5);
    let c = colour(b.colour);
    let series: Vec<PathElement<(f64, f64)>> = vec![
        PathElement::new(vec![(xc, min), (xc, q1)], BLACK.stroke_width(1)),
        PathElement::new(vec![(xc, q3), (xc, max)], BLACK.stroke_width(1)),
        PathElement::new(vec![(x0 + 0.15, min), (x1 - 0.15, min)], BLACK.stroke_width(1)),
        PathElement::new(vec![(x0 + 0.15, max), (x1 - 0.15, max)], BLACK.stroke_width(1)),
    ];
    chart.draw_series(series).map_err(err)?;
    chart.draw_series([Rectangle::new([(x0, q1), (x1, q3)], c.mix(0.45).filled())]).map_err(err)?;
    chart.draw_series([Rectangle::new([(x0, q1), (x1, q3)], BLACK.stroke_width(1))]).map_err(err)?;
    // The median in the group's colour with a black core: a box of equal values (no
    // height) still shows its colour.
    chart.draw_series([PathElement::new(vec![(x0, med), (x1, med)], c.stroke_width(7))]).map_err(err)?;
    chart.draw_series([PathElement::new(vec![(x0, med), (x1, med)], BLACK.stroke_width(2))]).map_err(err)?;
    Ok(())
}
