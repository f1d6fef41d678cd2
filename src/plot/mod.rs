//! Figure primitives, drawn with plotters and written as PNG and SVG: the map with paths
//! ([`path`]), a run's history ([`history`]), and the charts, legends and text sizes every
//! figure shares. Each planner draws its own figures and the reports theirs with these.
//!
//! Text uses DejaVu Sans embedded in the binary (plotters' `ab_glyph` backend), so building
//! needs no system font libraries. Files are written atomically.

pub mod history;
pub mod layout;
pub mod path;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;

/// The embedded font (licence in `assets/fonts/DejaVuSans-LICENSE.txt`).
static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

/// Font family name used by every figure.
pub const FAMILY: &str = "sans-serif";

pub(crate) fn register_font() {
    REGISTER.call_once(|| {
        if plotters::style::register_font(FAMILY, FontStyle::Normal, FONT).is_err() {
            unreachable!("the embedded DejaVu Sans is a valid TrueType font");
        }
    });
}

/// Error while drawing or writing a figure.
#[derive(Debug, thiserror::Error)]
#[error("cannot write figure {path}: {message}")]
pub struct PlotError {
    /// The file.
    pub path: String,
    /// What failed.
    pub message: String,
}

/// Something that draws itself on any plotters backend.
pub trait Figure {
    /// Pixel size of the PNG (the SVG uses the same units).
    fn size(&self) -> (u32, u32);
    /// Draws the figure.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String>;
}

/// Converts a drawing error to a message.
pub fn err<E: std::fmt::Debug>(e: E) -> String {
    format!("{e:?}")
}

/// Renders `figure` to `<stem>.png` and `<stem>.svg`.
pub fn save<F: Figure>(figure: &F, stem: &Path) -> Result<(), PlotError> {
    register_font();
    let (w, h) = figure.size();
    let fail = |ext: &str, message: String| PlotError { path: stem.with_extension(ext).display().to_string(), message };
    let mut rgb = vec![0u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| fail("png", err(e)))?;
        figure.draw(&root).map_err(|m| fail("png", m))?;
        root.present().map_err(|e| fail("png", err(e)))?;
    }
    let png = crate::io::png::encode(&rgb, w, h, crate::io::png::Channels::Rgb).map_err(|e| fail("png", e))?;
    crate::io::write_atomic(&stem.with_extension("png"), &png).map_err(|e| fail("png", e.to_string()))?;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| fail("svg", err(e)))?;
        figure.draw(&root).map_err(|m| fail("svg", m))?;
        root.present().map_err(|e| fail("svg", err(e)))?;
    }
    crate::io::write_atomic(&stem.with_extension("svg"), svg.as_bytes()).map_err(|e| fail("svg", e.to_string()))
}

/// Margins `(top, bottom, left, right)` in pixels that make a chart's plotting area show
/// `extent_m = (width, height)` metres at one scale on both axes, in an area of `area_px`
/// pixels with the given label-area sizes and base margin.
pub fn equal_scale_margins(
    area_px: (u32, u32),
    labels_px: (u32, u32),
    margin: u32,
    extent_m: (f64, f64),
) -> (u32, u32, u32, u32) {
    let (x_label, y_label) = labels_px;
    let pw = area_px.0.saturating_sub(y_label + 2 * margin) as f64;
    let ph = area_px.1.saturating_sub(x_label + 2 * margin) as f64;
    let aspect = extent_m.1 / extent_m.0;
    if pw <= 0.0 || ph <= 0.0 || !aspect.is_finite() {
        return (margin, margin, margin, margin);
    }
    if ph > pw * aspect {
        let extra = (ph - pw * aspect).round() as u32;
        (margin + extra / 2, margin + extra - extra / 2, margin, margin)
    } else {
        let extra = (pw - ph / aspect).round() as u32;
        (margin, margin, margin + extra / 2, margin + extra - extra / 2)
    }
}

/// Builds a chart of `x` × `y` metres in `area` at one scale on both axes: the title is drawn
/// above, and the plotting area is padded to the map's aspect ratio.
pub fn equal_scale_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    title: &str,
    title_font: f64,
    labels_px: (u32, u32),
    margin: u32,
    x: std::ops::Range<f64>,
    y: std::ops::Range<f64>,
) -> Result<ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>, String> {
    // The caption takes its text height plus padding (plotters' `titled`).
    let (_, text_h) = area.estimate_text_size(title, &text(title_font)).map_err(err)?;
    let caption = text_h + 2 * (text_h / 2).min(5);
    let (w, h) = area.dim_in_pixel();
    let (top, bottom, left, right) =
        equal_scale_margins((w, h.saturating_sub(caption)), labels_px, margin, (x.end - x.start, y.end - y.start));
    ChartBuilder::on(area)
        .caption(title, text(title_font))
        .margin_top(top)
        .margin_bottom(bottom)
        .margin_left(left)
        .margin_right(right)
        .x_label_area_size(labels_px.0)
        .y_label_area_size(labels_px.1)
        .build_cartesian_2d(x, y)
        .map_err(err)
}

/// A group label as a panel caption: `map.source=thesis-1, thesis.c_len=0.2` becomes
/// `source=thesis-1, c_len=0.2`. Each key keeps its last name only, so that a panel of a
/// study grouped by several keys still has a caption that fits; the report's tables keep the
/// full names.
pub fn panel_label(label: &str) -> String {
    label
        .split(", ")
        .map(|part| match part.split_once('=') {
            // A map file is named by its stem (`experiments/maps/basement.yaml` → `basement`).
            Some((key, value)) => {
                let value = if value.contains('/') {
                    std::path::Path::new(value).file_stem().map_or(value.into(), |s| s.to_string_lossy())
                } else {
                    value.into()
                };
                format!("{}={value}", key.rsplit('.').next().unwrap_or(key))
            }
            // A bare map file (a panel of one map) is named by its stem too.
            None if part.contains('/') => {
                std::path::Path::new(part).file_stem().map_or(part.to_string(), |s| s.to_string_lossy().into_owned())
            }
            None => part.to_string(),
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// Colours of data series, told apart in print and by readers with colour-vision deficiency
/// (Okabe & Ito's palette without its yellow, which vanishes on white).
pub const SERIES: [RGBColor; 7] = [
    RGBColor(213, 94, 0),
    RGBColor(0, 114, 178),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
];

/// The colour of data series `k` (cycling through [`SERIES`]).
pub fn series_colour(k: usize) -> RGBColor {
    SERIES[k % SERIES.len()]
}

/// Whether line series `k` is drawn dashed: [`SERIES`]'s sky blue is close in hue to its blue,
/// so its lines (and their legend strokes) are dashed as well; past the palette's length the
/// colours come round again with the dashes the other way, so that series `k` and
/// `k + SERIES.len()` differ.
pub fn series_dashed(k: usize) -> bool {
    (k % SERIES.len() == 5) != ((k / SERIES.len()) % 2 == 1)
}

/// Width in pixels of `s` drawn at `size` in the embedded font (its glyph layout).
pub fn text_width(s: &str, size: f64) -> u32 {
    register_font();
    text(size).font.box_size(s).map_or_else(|_| (0.6 * size * s.chars().count() as f64) as u32, |b| b.0)
}

/// `title` broken at spaces into lines that each fit `width_px` at `size` (less 16 px of
/// margin); a word wider than the width gets a line of its own.
pub fn wrap(title: &str, width_px: u32, size: f64) -> Vec<String> {
    let room = width_px.saturating_sub(16);
    let mut lines: Vec<String> = Vec::new();
    for word in title.split(' ') {
        match lines.last_mut() {
            Some(line) if text_width(&format!("{line} {word}"), size) <= room => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// Height in pixels of `title` wrapped to `width_px` at `size`, with the gap below it.
pub fn title_height(title: &str, width_px: u32, size: f64) -> u32 {
    wrap(title, width_px, size).len() as u32 * (clean_size(size) * 1.3) as u32 + 10
}

/// Draws `title` centred at the top of `area`, wrapped to its width, and returns the area below.
pub fn titled<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    size: f64,
) -> Result<DrawingArea<DB, Shift>, String> {
    let width = area.dim_in_pixel().0;
    let line = (clean_size(size) * 1.3) as i32;
    let centred = text(size).pos(plotters::style::text_anchor::Pos::new(
        plotters::style::text_anchor::HPos::Center,
        plotters::style::text_anchor::VPos::Top,
    ));
    for (k, l) in wrap(title, width, size).iter().enumerate() {
        area.draw(&Text::new(l.clone(), (width as i32 / 2, 4 + line * k as i32), centred.clone())).map_err(err)?;
    }
    Ok(area.margin(title_height(title, width, size), 0, 0, 0))
}

/// Whether `title` fits `width_px` at `size` px (the estimate of [`fitting_text`]).
pub fn fits(title: &str, width_px: u32, size: f64) -> bool {
    0.55 * size * title.chars().count() as f64 <= 0.92 * f64::from(width_px)
}

/// A text style for `title` no larger than `size` that fits `width_px` (about 0.55 em per
/// character in DejaVu Sans, with a margin).
pub fn fitting_text(title: &str, width_px: u32, size: f64) -> TextStyle<'static> {
    let fit = 0.92 * f64::from(width_px) / (0.55 * title.chars().count().max(1) as f64);
    let wanted = size.min(fit).max(8.0);
    // The largest clean size that still fits.
    let clean = CLEAN_SIZES.iter().rev().copied().find(|&c| c <= wanted).unwrap_or(CLEAN_SIZES[0]);
    (FAMILY, if wanted > CLEAN_SIZES[CLEAN_SIZES.len() - 1] { clean_size(wanted) } else { clean }).into_font().into()
}

/// Font sizes (px) at which the glyph placement of plotters' text renderer stays on the
/// baseline: it truncates each glyph's vertical offset `size/2 + top` toward zero, so glyphs
/// above and below half the size round in opposite directions, and at some sizes (9, 11, 12,
/// 13, 15, 17 px) a decimal point rises to mid-height and digits drift apart. Checked by eye
/// on "10.0 0.855 a.b x [m]" at each size.
const CLEAN_SIZES: [f64; 4] = [10.0, 14.0, 18.0, 20.0];

/// The clean size nearest to `size`, the larger one on a tie (even sizes above 20 px are
/// clean too).
pub fn clean_size(size: f64) -> f64 {
    if size > 21.0 {
        return (size / 2.0).round() * 2.0;
    }
    CLEAN_SIZES.iter().rev().copied().min_by(|a, b| (a - size).abs().total_cmp(&(b - size).abs())).unwrap_or(14.0)
}

/// A text style of the embedded font, at the clean size nearest to `size`.
pub fn text(size: f64) -> TextStyle<'static> {
    (FAMILY, clean_size(size)).into_font().into()
}

/// Draws a legend as colour swatches with labels in `area`, one entry per line.
pub fn legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(RGBColor, String)],
    y0: i32,
) -> Result<(), String> {
    for (k, (colour, label)) in entries.iter().enumerate() {
        let y = y0 + 26 * k as i32;
        area.draw(&Rectangle::new([(8, y), (26, y + 18)], colour.filled())).map_err(err)?;
        area.draw(&Rectangle::new([(8, y), (26, y + 18)], BLACK.stroke_width(1))).map_err(err)?;
        area.draw(&Text::new(label.clone(), (34, y + 1), text(17.0))).map_err(err)?;
    }
    Ok(())
}

/// The standard series-label box of every chart: white, framed, at `position`.
pub fn series_legend<'a, DB: DrawingBackend + 'a, CT: plotters::coord::CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    position: SeriesLabelPosition,
) -> Result<(), String> {
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(text(13.0))
        .draw()
        .map_err(err)
}

/// Width of the legend column right of a time-series panel, in pixels.
pub const SIDE_LEGEND_W: u32 = 150;

/// Draws a time series as two 1-px lines one pixel apart (`one_px` in data units) instead of
/// one 2-px stroke: the backends join thick polylines with mitres, and a series that turns
/// back on itself (thousands of iterations on a few hundred pixels) grows a spike far outside
/// its data range and its panel.
pub fn draw_series_line<'a, DB: DrawingBackend + 'a, X>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, plotters::coord::types::RangedCoordf64>>,
    points: &[(X::ValueType, f64)],
    colour: RGBColor,
    one_px: f64,
) -> Result<(), String>
where
    X: plotters::coord::ranged1d::Ranged + Clone + 'a,
    X::ValueType: Clone + 'static,
{
    for offset in [0.0, one_px] {
        let shifted = points.iter().filter(|p| p.1.is_finite()).map(|(x, y)| (x.clone(), y + offset));
        chart.draw_series(LineSeries::new(shifted, colour.stroke_width(1))).map_err(err)?;
    }
    Ok(())
}

/// A legend drawn in the right margin of `area` (a chart's own legend is clipped to its
/// plotting area, where it hides data): one coloured stroke and label per entry.
pub fn side_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    entries: &[(&str, RGBColor)],
) -> Result<(), String> {
    let (x0, y0) = (area.dim_in_pixel().0 as i32 - SIDE_LEGEND_W as i32 + 14, 14);
    for (k, (label, colour)) in entries.iter().enumerate() {
        let y = y0 + 20 * k as i32;
        area.draw(&PathElement::new(vec![(x0, y), (x0 + 22, y)], colour.stroke_width(3))).map_err(err)?;
        area.draw(&Text::new(label.to_string(), (x0 + 28, y - 8), text(14.0))).map_err(err)?;
    }
    Ok(())
}

/// "1 run", "3 runs".
pub fn runs_text(n: usize) -> String {
    if n == 1 { "1 run".into() } else { format!("{n} runs") }
}

/// A metre tick label in its shortest form (`5`, `2.5`), never `5.0`.
pub fn metre_tick(v: &f64) -> String {
    format!("{}", (v * 1e6).round() / 1e6 + 0.0)
}

/// Decimals that tell apart the ticks of an axis over `span` with at most `ticks` labels:
/// plotters steps by 1, 2 or 5 times a power of ten, no finer than `span / ticks`.
pub fn step_decimals(span: f64, ticks: usize) -> usize {
    if span.is_nan() || span <= 0.0 || !span.is_finite() {
        return 2;
    }
    let raw = span / ticks.max(1) as f64;
    let power = raw.log10().floor();
    let mantissa = raw / 10f64.powf(power);
    let nice = if mantissa <= 1.0 + 1e-9 {
        1.0
    } else if mantissa <= 2.0 + 1e-9 {
        2.0
    } else if mantissa <= 5.0 + 1e-9 {
        5.0
    } else {
        10.0
    };
    let step = nice * 10f64.powf(power);
    (-(step.log10() + 1e-9).floor()).max(0.0) as usize
}

/// Tick labels with as many decimals as the range `span` needs (counts need none).
pub fn tick_decimals(span: f64) -> usize {
    if span >= 20.0 {
        0
    } else if span >= 2.0 {
        1
    } else {
        2
    }
}

/// Runs of equal classes along each row of a `width × height` raster (row 0 at the bottom):
/// `(row, first column, end column, class)`. Drawing runs instead of cells keeps SVGs small.
pub fn cell_runs<C: PartialEq + Copy>(
    width: usize,
    height: usize,
    class: impl Fn(usize) -> C,
) -> Vec<(usize, usize, usize, C)> {
    let mut out = Vec::new();
    for r in 0..height {
        let mut c = 0;
        while c < width {
            let k = class(r * width + c);
            let start = c;
            while c < width && class(r * width + c) == k {
                c += 1;
            }
            out.push((r, start, c, k));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_decimals_follow_the_step() {
        for (span, ticks, decimals) in
            [(1.0, 10, 1), (0.05, 10, 3), (0.005, 10, 4), (0.012, 8, 3), (10000.0, 10, 0), (1.5, 10, 1)]
        {
            assert_eq!(step_decimals(span, ticks), decimals, "{span} over {ticks}");
        }
    }

    #[test]
    fn a_title_wraps_at_spaces_to_fit() {
        let title = "one two three four five six seven eight nine ten eleven twelve";
        let lines = wrap(title, 200, 14.0);
        assert!(lines.len() > 1 && lines.join(" ") == title, "{lines:?}");
        assert!(lines.iter().all(|l| text_width(l, 14.0) <= 184), "{lines:?}");
        assert_eq!(wrap("short", 400, 14.0), vec!["short".to_string()]);
    }

    /// Metre ticks print without a trailing `.0` and without a negative zero.
    /// Every series of up to two rounds of the palette has its own look (colour, dashes).
    #[test]
    fn series_looks_differ_for_two_rounds_of_the_palette() {
        let looks: Vec<(RGBColor, bool)> =
            (0..2 * SERIES.len()).map(|k| (series_colour(k), series_dashed(k))).collect();
        for a in 0..looks.len() {
            for b in a + 1..looks.len() {
                assert_ne!(looks[a], looks[b], "series {a} and {b}");
            }
        }
        assert!(series_dashed(5) && !series_dashed(12) && series_dashed(7) && !series_dashed(0));
    }

    #[test]
    fn metre_ticks_are_short() {
        for (v, label) in [(5.0, "5"), (2.5, "2.5"), (-0.0, "0"), (-17.4, "-17.4"), (0.1 + 0.2, "0.3")] {
            assert_eq!(metre_tick(&v), label);
        }
    }

    #[test]
    fn text_sizes_snap_to_clean_sizes() {
        for (asked, used) in
            [(9.0, 10.0), (11.0, 10.0), (12.5, 14.0), (13.0, 14.0), (15.0, 14.0), (17.0, 18.0), (23.0, 24.0)]
        {
            assert_eq!(clean_size(asked), used, "{asked}");
        }
        assert_eq!(tick_decimals(100.0), 0);
        assert_eq!(tick_decimals(0.5), 2);
    }

    #[test]
    fn panel_labels_keep_the_last_name_of_each_key() {
        for (label, caption) in [
            ("map.source=thesis-1, thesis.c_len=0.2", "source=thesis-1, c_len=0.2"),
            ("thesis.selection=elite", "selection=elite"),
            ("seeds=3", "seeds=3"),
            ("all runs", "all runs"),
            ("map.source=a.b", "source=a.b"),
        ] {
            assert_eq!(panel_label(label), caption, "{label}");
        }
        assert!(fits(&"x".repeat(66), 400, 10.0) && !fits(&"x".repeat(67), 400, 10.0));
    }
}
