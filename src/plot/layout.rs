//! A check of a figure's layout, for tests and for anyone adding a figure: the figure is drawn
//! on a backend that records where each text lands (its box, from the embedded font's glyph
//! layout and the text's anchor and rotation), and [`problems`] lists text drawn outside the
//! canvas, a tick label repeated along one axis (ticks closer than their decimals can tell
//! apart), and expected labels (series, groups) missing.

use super::Figure;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};
use plotters_backend::{BackendColor, BackendCoord, BackendTextStyle, DrawingErrorKind};

/// A text as drawn: its string and box in pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct DrawnText {
    /// The string.
    pub text: String,
    /// Left, top, right and bottom edge of its box.
    pub bounds: (i32, i32, i32, i32),
}

/// A backend that draws nothing and records every text.
struct Recorder {
    size: (u32, u32),
    texts: std::rc::Rc<std::cell::RefCell<Vec<DrawnText>>>,
}

impl DrawingBackend for Recorder {
    type ErrorType = std::fmt::Error;

    fn get_size(&self) -> (u32, u32) {
        self.size
    }

    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        Ok(())
    }

    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        Ok(())
    }

    fn draw_pixel(&mut self, _: BackendCoord, _: BackendColor) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        Ok(())
    }

    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        if text.trim().is_empty() {
            return Ok(());
        }
        let ((min_x, min_y), (max_x, max_y)) =
            style.layout_box(text).map_err(|e| DrawingErrorKind::FontError(Box::new(e)))?;
        let (width, height) = (max_x - min_x, max_y - min_y);
        // Where the default text drawing puts the box, as plotters-backend does.
        let dx = match style.anchor().h_pos {
            HPos::Left => 0,
            HPos::Right => -width,
            HPos::Center => -width / 2,
        };
        let dy = match style.anchor().v_pos {
            VPos::Top => 0,
            VPos::Center => -height / 2,
            VPos::Bottom => -height,
        };
        let t = style.transform();
        let (a, b) = (t.transform(dx, dy), t.transform(dx + width, dy + height));
        let bounds = (pos.0 + a.0.min(b.0), pos.1 + a.1.min(b.1), pos.0 + a.0.max(b.0), pos.1 + a.1.max(b.1));
        self.texts.borrow_mut().push(DrawnText { text: text.to_string(), bounds });
        Ok(())
    }
}

/// Every text `figure` draws, with its box.
pub fn drawn_texts<F: Figure>(figure: &F) -> Result<Vec<DrawnText>, String> {
    super::register_font();
    let texts = std::rc::Rc::default();
    let root = Recorder { size: figure.size(), texts: std::rc::Rc::clone(&texts) }.into_drawing_area();
    figure.draw(&root)?;
    drop(root);
    Ok(texts.take())
}

/// What is wrong with `figure`'s layout: texts outside its canvas, a numeric label repeated by
/// its neighbour along one axis, and each of `expected` that no text contains.
pub fn problems<F: Figure>(figure: &F, expected: &[&str]) -> Result<Vec<String>, String> {
    let (w, h) = figure.size();
    let texts = drawn_texts(figure)?;
    let mut out = Vec::new();
    for t in &texts {
        let (l, top, r, b) = t.bounds;
        if l < 0 || top < 0 || r > w as i32 || b > h as i32 {
            out.push(format!("{:?} is drawn at {:?}, outside the {w} × {h} canvas", t.text, t.bounds));
        }
    }
    let numeric: Vec<&DrawnText> = texts.iter().filter(|t| t.text.trim().parse::<f64>().is_ok()).collect();
    for (i, a) in numeric.iter().enumerate() {
        for b in &numeric[i + 1..] {
            let same_column = (a.bounds.2 - b.bounds.2).abs() <= 1 && (a.bounds.1 - b.bounds.1).abs() <= 80;
            let same_row = (a.bounds.1 - b.bounds.1).abs() <= 1 && (a.bounds.0 - b.bounds.0).abs() <= 120;
            if a.text == b.text && a.bounds != b.bounds && (same_column || same_row) {
                out.push(format!("tick label {:?} repeated at {:?} and {:?}", a.text, a.bounds, b.bounds));
            }
        }
    }
    for e in expected {
        if !texts.iter().any(|t| t.text.contains(e)) {
            out.push(format!("no text says {e:?}"));
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use plotters::coord::Shift;

    /// A figure that draws what it is given: a title at `title_x`, and y ticks.
    struct Probe {
        title_x: i32,
        ticks: Vec<&'static str>,
    }

    impl Figure for Probe {
        fn size(&self) -> (u32, u32) {
            (300, 200)
        }

        fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
            root.draw(&Text::new("A long title of the figure", (self.title_x, 5), super::super::text(14.0)))
                .map_err(super::super::err)?;
            let right = super::super::text(14.0).pos(plotters::style::text_anchor::Pos::new(HPos::Right, VPos::Center));
            for (k, t) in self.ticks.iter().enumerate() {
                root.draw(&Text::new(t.to_string(), (60, 40 + 30 * k as i32), right.clone()))
                    .map_err(super::super::err)?;
            }
            Ok(())
        }
    }

    #[test]
    fn texts_off_the_canvas_repeated_ticks_and_missing_labels_are_found() {
        let fine = Probe { title_x: 10, ticks: vec!["0.97", "0.98", "0.99"] };
        assert_eq!(problems(&fine, &["long title"]).unwrap(), Vec::<String>::new());
        let clipped = Probe { title_x: 200, ticks: fine.ticks.clone() };
        let found = problems(&clipped, &[]).unwrap();
        assert!(found.len() == 1 && found[0].contains("outside the 300 × 200 canvas"), "{found:?}");
        let repeated = Probe { title_x: 10, ticks: vec!["0.98", "0.98", "0.97", "0.97"] };
        let found = problems(&repeated, &["legend entry"]).unwrap();
        assert_eq!(found.iter().filter(|p| p.starts_with("tick label")).count(), 2, "{found:?}");
        assert!(found.iter().any(|p| p == "no text says \"legend entry\""), "{found:?}");
        // The box of a right-anchored text ends at its anchor.
        let texts = drawn_texts(&fine).unwrap();
        assert!(texts[1..].iter().all(|t| (t.bounds.2 - 60).abs() <= 1), "{texts:?}");
    }
}
