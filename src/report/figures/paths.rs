//! Plans drawn on their maps: the best path of each group as a grid of small maps (003 Figs.
//! A.17/A.18), and the best path of every planner (columns) on every map (rows) side by side.

use super::panels::grid_shape;
use crate::plot::path::{PathFigure, draw_map_paths};
use crate::plot::{Figure, err};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

const PATHS_TITLE: &str =
    "Best path per group: blue path; cells green once, orange 2+, red obstacle hit; ▲ start, ✕ end";

/// The best path of each group as small maps.
pub struct PathsGridFigure<'a> {
    /// One panel per group (title = group and scores).
    pub panels: Vec<PathFigure<'a>>,
}

impl Figure for PathsGridFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let (r, c) = grid_shape(self.panels.len());
        (c as u32 * 400, r as u32 * 420 + 40)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let root = root
            .titled(PATHS_TITLE, crate::plot::fitting_text(PATHS_TITLE, root.dim_in_pixel().0, 18.0))
            .map_err(err)?;
        let (r, c) = grid_shape(self.panels.len());
        for (area, panel) in root.split_evenly((r, c)).iter().zip(&self.panels) {
            // A caption too wide for one line goes on two: the group, then the scores.
            let width = area.dim_in_pixel().0;
            match panel.title.split_once(": ") {
                Some((group, scores)) if !crate::plot::fits(&panel.title, width, 13.0) => {
                    let below = area.titled(group, crate::plot::fitting_text(group, width, 14.0)).map_err(err)?;
                    draw_map_paths(&below, &PathFigure { title: scores.to_string(), ..panel.clone() }, (13.0, 11.0))?;
                }
                _ => {
                    draw_map_paths(area, panel, (13.0, 11.0))?;
                }
            }
        }
        Ok(())
    }
}

/// The title of [`PlannerPathsFigure`].
const PLANNER_PATHS_TITLE: &str = "Best executable run of each planner on each map: blue path; cells green once, orange 2+ \
                                   times, red obstacle hit; ▲ start, ✕ end";

/// The best path of each planner (columns) on each map (rows).
pub struct PlannerPathsFigure<'a> {
    /// Rows of panels; a `None` cell is left empty.
    pub rows: Vec<Vec<Option<PathFigure<'a>>>>,
    /// For each empty cell, what it says instead (a planner that ran without an executable
    /// plan); same shape as `rows`.
    pub missing: Vec<Vec<Option<String>>>,
}

impl Figure for PlannerPathsFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let cols = self.rows.iter().map(Vec::len).max().unwrap_or(1).max(1) as u32;
        let title = crate::plot::title_height(PLANNER_PATHS_TITLE, cols * 330, 18.0);
        (cols * 330, self.rows.len().max(1) as u32 * 350 + title)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let root = crate::plot::titled(root, PLANNER_PATHS_TITLE, 18.0)?;
        let cols = self.rows.iter().map(Vec::len).max().unwrap_or(1).max(1);
        let areas = root.split_evenly((self.rows.len().max(1), cols));
        for (r, row) in self.rows.iter().enumerate() {
            for (c, panel) in row.iter().enumerate() {
                let area = &areas[r * cols + c];
                let Some(p) = panel else {
                    if let Some(note) = self.missing.get(r).and_then(|m| m.get(c)).and_then(Option::as_ref) {
                        // The planner on one line, what is missing on the next.
                        let (w, h) = area.dim_in_pixel();
                        let lines: Vec<&str> = note.splitn(2, ": ").collect();
                        for (k, line) in lines.iter().enumerate() {
                            let style =
                                crate::plot::fitting_text(line, w, 14.0).pos(Pos::new(HPos::Center, VPos::Center));
                            let y = h as i32 / 2 + (k as i32 * 2 - lines.len() as i32 + 1) * 10;
                            area.draw_text(line, &style, (w as i32 / 2, y)).map_err(err)?;
                        }
                    }
                    continue;
                };
                // The planner on a line of its own, then the map and scores: a narrow panel
                // keeps both readable.
                match p.title.split_once(", ") {
                    Some((planner, rest)) => {
                        let width = area.dim_in_pixel().0;
                        let below =
                            area.titled(planner, crate::plot::fitting_text(planner, width, 14.0)).map_err(err)?;
                        // The map on a line of its own where map and scores do not fit one.
                        let (below, rest) = match rest.split_once(": ") {
                            Some((map, scores)) if !crate::plot::fits(rest, width, 14.0) => {
                                (below.titled(map, crate::plot::fitting_text(map, width, 13.0)).map_err(err)?, scores)
                            }
                            _ => (below, rest),
                        };
                        draw_map_paths(&below, &PathFigure { title: rest.to_string(), ..p.clone() }, (14.0, 10.0))?;
                    }
                    None => {
                        draw_map_paths(area, p, (14.0, 10.0))?;
                    }
                }
            }
        }
        Ok(())
    }
}
