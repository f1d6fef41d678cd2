//! A report file made but not yet written: its name and texts. The comparisons, the measures
//! and the plans are each made before the report folder is touched, so that one that cannot be
//! made leaves nothing half-written; [`Rendered::save`] writes it once everything is made.

use super::ReportError;
use std::path::{Path, PathBuf};

/// A report file made, not yet written: its files' names and texts.
#[derive(Clone, Debug)]
pub struct Rendered {
    /// `compare-KEY` (the key's characters other than letters, digits, `.` and `-` as `_`).
    pub stem: String,
    /// The markdown report.
    pub markdown: String,
    /// One row per stratum, value and metric.
    pub csv: String,
    /// For a comparison, what its design can show (`power`), written by `--design`.
    pub design: Option<String>,
    /// For a time comparison pooled over units, its forest plot, written beside as
    /// `STEM-forest.png` (and `.svg`).
    pub forest: Option<crate::report::figures::forest::ForestFigure>,
}

impl Rendered {
    /// Writes `STEM.md` and `STEM.csv` into `out`, and the forest plot where there is one;
    /// returns the markdown's path.
    pub fn save(&self, out: &Path) -> Result<PathBuf, ReportError> {
        let md = out.join(format!("{}.md", self.stem));
        let csv = out.join(format!("{}.csv", self.stem));
        for (path, text) in [(&md, &self.markdown), (&csv, &self.csv)] {
            crate::io::write_atomic(path, text.as_bytes())
                .map_err(|e| ReportError::Io(format!("{}: {e}", path.display())))?;
        }
        if let Some(forest) = &self.forest {
            // The stem holds the key's dots: the extension is given, for the figure's writer to
            // replace, not the key's last part.
            crate::plot::save(forest, &out.join(format!("{}-forest.png", self.stem)))?;
        }
        Ok(md)
    }

    /// Writes the design file of a comparison, `design-KEY.md` beside `compare-KEY.md`, into
    /// `out`; returns its path (none for files that are not a comparison).
    pub fn save_design(&self, out: &Path) -> Result<Option<PathBuf>, ReportError> {
        let Some(design) = &self.design else { return Ok(None) };
        let path = out.join(format!("design-{}.md", self.stem.trim_start_matches("compare-")));
        crate::io::write_atomic(&path, design.as_bytes())
            .map_err(|e| ReportError::Io(format!("{}: {e}", path.display())))?;
        Ok(Some(path))
    }
}
