//! The forest plot of a `--compare` time comparison pooled over floor plans: per compared
//! value a panel, one row per unit (floor plan) with its ratio (value ÷ baseline: the
//! exponential of the median log-ratio of its pairs) and the range of its pairs' ratios, the
//! pooled median with its bootstrap interval over the units, the units' mean, the margin
//! (0.95: at least 5 % faster) and 1 (no difference).

use super::panels::{draw_legend_strip, legend_strip_height};
use crate::plot::{Figure, err, text};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// One unit's row: its name, ratio and the lowest and highest of its pairs' ratios.
#[derive(Clone, Debug, PartialEq)]
pub struct ForestRow {
    /// The unit's name (a floor plan).
    pub name: String,
    /// Its ratio, value ÷ baseline.
    pub ratio: f64,
    /// The lowest of its pairs' ratios.
    pub low: f64,
    /// The highest of its pairs' ratios.
    pub high: f64,
}

/// One compared value's panel.
#[derive(Clone, Debug, PartialEq)]
pub struct ForestPanel {
    /// What the panel compares (`key=value` against `key=baseline`, the time measure).
    pub title: String,
    /// The units' rows, in the comparison's order.
    pub rows: Vec<ForestRow>,
    /// Mean of the units' ratios.
    pub mean: f64,
    /// Median of the units' ratios with its bootstrap interval over the units.
    pub median: crate::stats::Interval,
    /// The margin tested (0.95: at least 5 % faster).
    pub margin: f64,
}

/// The forest plot: one panel per compared value, one legend below.
#[derive(Clone, Debug, PartialEq)]
pub struct ForestFigure {
    /// The panels.
    pub panels: Vec<ForestPanel>,
    /// What a unit is ("floor plan").
    pub unit: String,
}

const ROW_PX: u32 = 24;
const NAME_PX: u32 = 230;

impl ForestFigure {
    fn title(&self) -> String {
        format!("Ratio value ÷ baseline per {}, pooled median with its bootstrap interval", self.unit)
    }

    fn legend(&self) -> Vec<String> {
        vec![
            "one unit: its ratio (exponential of the median log-ratio of its pairs), bar = range of its pairs".into(),
            "pooled median of the units' ratios, bar = its 95 % bootstrap interval over the units".into(),
            "mean of the units' ratios".into(),
            format!("margin {:.2}: at least 5 % faster left of it", self.panels.first().map_or(0.95, |p| p.margin)),
            "1: no difference".into(),
        ]
    }

    fn panel_height(p: &ForestPanel) -> u32 {
        90 + ROW_PX * (p.rows.len() as u32 + 1)
    }
}

impl Figure for ForestFigure {
    fn size(&self) -> (u32, u32) {
        let width = 900;
        let panels: u32 = self.panels.iter().map(Self::panel_height).sum();
        (
            width,
            crate::plot::title_height(&self.title(), width, 16.0) + panels + legend_strip_height(&self.legend(), width),
        )
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let root = crate::plot::titled(root, &self.title(), 16.0)?;
        let (width, height) = root.dim_in_pixel();
        let legend = self.legend();
        let (mut rest, strip) = root.split_vertically(height - legend_strip_height(&legend, width));
        draw_legend_strip(&strip, &legend, |k, (x, y)| legend_key(&strip, k, (x, y)))?;
        for p in &self.panels {
            let (area, below) = rest.split_vertically(Self::panel_height(p));
            draw_panel(&area, p)?;
            rest = below;
        }
        Ok(())
    }
}

/// The legend's key `k` at `(x, y)`.
fn legend_key<DB: DrawingBackend>(strip: &DrawingArea<DB, Shift>, k: usize, (x, y): (i32, i32)) -> Result<(), String> {
    let grey = RGBColor(90, 90, 90);
    match k {
        0 => {
            strip.draw(&PathElement::new(vec![(x, y), (x + 22, y)], grey.stroke_width(2))).map_err(err)?;
            strip.draw(&Circle::new((x + 11, y), 4, BLACK.filled())).map_err(err)
        }
        1 => {
            strip.draw(&PathElement::new(vec![(x, y), (x + 22, y)], BLUE.stroke_width(3))).map_err(err)?;
            strip
                .draw(&Polygon::new(vec![(x + 11, y - 6), (x + 5, y), (x + 11, y + 6), (x + 17, y)], BLUE.filled()))
                .map_err(err)
        }
        _ => {
            let colour = [BLUE, RED, grey][(k - 2).min(2)];
            for a in [0, 9, 18] {
                strip.draw(&PathElement::new(vec![(x + a, y), (x + a + 5, y)], colour.stroke_width(2))).map_err(err)?;
            }
            Ok(())
        }
    }
}

/// One panel: the units top to bottom, the pooled median last, the vertical lines.
fn draw_panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, p: &ForestPanel) -> Result<(), String> {
    let n = p.rows.len() as f64;
    let values =
        p.rows.iter().flat_map(|r| [r.low, r.high]).chain([p.median.low, p.median.high, p.margin, 1.0, p.mean]);
    let (lo, hi) =
        values.filter(|v| v.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
    let pad = ((hi - lo) * 0.08).max(0.01);
    let mut chart = ChartBuilder::on(area)
        .caption(&p.title, text(14.0))
        .margin(8)
        .margin_right(24)
        .x_label_area_size(40)
        .y_label_area_size(NAME_PX)
        .build_cartesian_2d((lo - pad)..(hi + pad), -0.7..(n + 0.3))
        .map_err(err)?;
    chart
        .configure_mesh()
        .y_labels(0)
        .disable_y_mesh()
        .x_labels(10)
        .x_label_formatter(&|v| format!("{v:.2}"))
        .x_desc("ratio, value ÷ baseline (below 1: the value is faster)")
        .label_style(text(13.0))
        .axis_desc_style(text(13.0))
        .draw()
        .map_err(err)?;
    let grey = RGBColor(90, 90, 90);
    let vertical =
        |x: f64, colour: RGBColor| DashedLineSeries::new([(x, -0.7), (x, n + 0.3)], 6, 5, colour.stroke_width(2));
    chart.draw_series(vertical(1.0, grey)).map_err(err)?;
    chart.draw_series(vertical(p.margin, RED)).map_err(err)?;
    chart.draw_series(vertical(p.mean, BLUE)).map_err(err)?;
    let name_style = text(13.0).pos(Pos::new(HPos::Right, VPos::Center));
    let (ax, ay) = area.get_base_pixel();
    let left = chart.plotting_area().get_base_pixel().0 - ax - 8;
    for (i, r) in p.rows.iter().enumerate() {
        let y = n - i as f64;
        chart.draw_series([PathElement::new(vec![(r.low, y), (r.high, y)], grey.stroke_width(2))]).map_err(err)?;
        chart.draw_series([Circle::new((r.ratio, y), 4, BLACK.filled())]).map_err(err)?;
        let (_, py) = chart.backend_coord(&(r.ratio, y));
        area.draw(&Text::new(r.name.clone(), (left, py - ay), name_style.clone())).map_err(err)?;
    }
    let m = &p.median;
    chart.draw_series([PathElement::new(vec![(m.low, 0.0), (m.high, 0.0)], BLUE.stroke_width(3))]).map_err(err)?;
    let (px, py) = chart.backend_coord(&(m.estimate, 0.0));
    let (px, py) = (px - ax, py - ay);
    area.draw(&Polygon::new(vec![(px, py - 7), (px - 7, py), (px, py + 7), (px + 7, py)], BLUE.filled()))
        .map_err(err)?;
    area.draw(&Text::new("pooled median".to_string(), (left, py), name_style)).map_err(err)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Texts on the canvas and apart: every unit named, the pooled row, the legend, the axis.
    #[test]
    fn the_forest_plot_keeps_its_texts_on_the_canvas() {
        let row =
            |name: &str, ratio: f64| ForestRow { name: name.into(), ratio, low: ratio - 0.02, high: ratio + 0.03 };
        let median = crate::stats::Interval { estimate: 0.97, low: 0.93, high: 1.0 };
        let panel = |title: &str| ForestPanel {
            title: title.into(),
            rows: vec![row("basement", 0.9), row("house-1", 1.0), row("warehouse-3, rot_speed=0.52", 0.97)],
            mean: 0.96,
            median,
            margin: 0.95,
        };
        let figure = ForestFigure {
            panels: vec![panel("solver=ga against ils: time_to_90_s"), panel("solver=nearest against ils")],
            unit: "floor plan".into(),
        };
        let expected = ["basement", "house-1", "warehouse-3, rot_speed=0.52", "pooled median", "1: no difference"];
        let problems = crate::plot::layout::problems(&figure, &expected).unwrap();
        assert!(problems.is_empty(), "{}", problems.join("\n"));
    }
}
