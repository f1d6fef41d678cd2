//! What the report's figures share: the legend strip below the panels (each entry a key in its
//! series' colour and a label, in columns), the series' colours, the value axes' ticks and the
//! grids the panels are laid out in.

use crate::plot::{err, text};
use plotters::coord::Shift;
use plotters::prelude::*;

/// Tick labels on a value axis (plotters steps no finer than the span over this).
pub const Y_TICKS: usize = 10;

/// Rows and columns of a panel grid: two columns from three panels on.
pub fn two_columns(n: usize) -> (usize, usize) {
    if n <= 2 { (1, n.max(1)) } else { (n.div_ceil(2), 2) }
}

/// Rows and columns of a near-square panel grid.
pub fn grid_shape(n: usize) -> (usize, usize) {
    let cols = (n as f64).sqrt().ceil().max(1.0) as usize;
    (n.div_ceil(cols).max(1), cols)
}

/// The colour of series `k`, the same in every figure ([`crate::plot::series_colour`]).
pub fn colour(k: usize) -> RGBColor {
    crate::plot::series_colour(k)
}

/// Height of one line of the legend below a figure's panels, in pixels.
const LEGEND_LINE: u32 = 24;

/// Height of the legend strip of `labels` below panels `width` pixels wide (one line for none).
pub fn legend_strip_height(labels: &[String], width: u32) -> u32 {
    let lines = legend_layout(labels, width).last().map_or(1, |(line, _)| line + 1);
    lines * LEGEND_LINE + 16
}

/// Draws the legend strip below a figure's panels: entry `k`'s key drawn by `key(k, (x, y))`
/// at the start of its place (`y` the middle of its line), its label after it.
pub fn draw_legend_strip<DB: DrawingBackend>(
    strip: &DrawingArea<DB, Shift>,
    labels: &[String],
    key: impl Fn(usize, (i32, i32)) -> Result<(), String>,
) -> Result<(), String> {
    for (k, (label, (line, x))) in labels.iter().zip(legend_layout(labels, strip.dim_in_pixel().0)).enumerate() {
        let y = 20 + (line * LEGEND_LINE) as i32;
        key(k, (x, y))?;
        strip.draw(&Text::new(label.clone(), (x + 28, y - 8), text(14.0))).map_err(err)?;
    }
    Ok(())
}

/// Where legend entries of `labels` go in a strip `width` pixels wide: `(line, x)` per entry,
/// in columns as wide as the widest entry, as many as fit side by side (one at least), filled
/// row by row, so that keys and labels line up down the strip.
pub fn legend_layout(labels: &[String], width: u32) -> Vec<(u32, i32)> {
    let entry = |label: &String| 28 + (label.chars().count() as f64 * 0.6 * 14.0) as i32 + 30;
    let column = labels.iter().map(entry).max().unwrap_or(1).max(1);
    let columns = ((width as i32 - 30) / column).max(1) as usize;
    (0..labels.len()).map(|k| ((k / columns) as u32, 20 + (k % columns) as i32 * column)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Entries run left to right in columns as wide as the widest and wrap before the right
    /// edge; an entry wider than the strip still gets a line of its own.
    #[test]
    fn legend_entries_line_up_in_columns_and_wrap_before_the_edge() {
        let labels = |n: &[usize]| n.iter().map(|&k| "x".repeat(k)).collect::<Vec<_>>();
        // An entry of k characters takes 28 + floor(8.4 k) + 30 pixels.
        for (chars, width, expected) in [
            (vec![10, 10], 1000, vec![(0, 20), (0, 162)]),
            (vec![10, 10, 10], 400, vec![(0, 20), (0, 162), (1, 20)]),
            (vec![200, 5], 300, vec![(0, 20), (1, 20)]),
            // Three columns of the widest entry (310 px): the short ones keep its place.
            (vec![30, 5, 5, 30], 1000, vec![(0, 20), (0, 330), (0, 640), (1, 20)]),
        ] {
            assert_eq!(legend_layout(&labels(&chars), width), expected, "{chars:?} in {width} px");
        }
    }
}
