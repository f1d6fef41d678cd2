//! Occupancy grid maps in metres: the grid itself, ROS map_server files and bare images
//! ([`ros`]), and the built-in presets ([`presets`]).
//!
//! Cell `(row, col)` covers `[ox + col·res, ox + (col+1)·res) × [oy + row·res, oy + (row+1)·res)`
//! (thesis-ga §0), so row 0 is the bottom row; image row 0 is the top row and is flipped
//! on load and save. Unknown cells are not free.

pub mod body;
pub mod clearance;
pub mod coverable;
pub mod generate;
pub mod orientation;
pub mod passages;
pub mod picture;
pub mod presets;
pub mod reach;
pub mod refine;
pub mod ros;
pub mod wall_rows;

use crate::geom::Point;
use std::path::PathBuf;

/// Errors while building or loading a map. Each names the file (or preset) and what is allowed.
#[derive(Debug, thiserror::Error)]
pub enum MapError {
    /// The file could not be read.
    #[error("{path}: cannot read map file: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The YAML is malformed or has a bad or missing field.
    #[error("{path}: {message}")]
    Yaml {
        /// The YAML file.
        path: PathBuf,
        /// What is wrong (with line and column when known).
        message: String,
    },
    /// The image could not be decoded.
    #[error("{path}: cannot decode map image (expected a PGM or PNG file): {message}")]
    Image {
        /// The image file.
        path: PathBuf,
        /// The decoder's message.
        message: String,
    },
    /// A field has a value outside its allowed range.
    #[error("{source_name}: `{field}` = {value} is out of range: {allowed}")]
    OutOfRange {
        /// File or preset name.
        source_name: String,
        /// The field.
        field: &'static str,
        /// The value as given.
        value: String,
        /// The allowed range.
        allowed: &'static str,
    },
    /// A bare image was given without its metres per pixel.
    #[error(
        "the resolution is missing: the bare image `{source_name}` needs its metres per pixel, e.g. --resolution 0.05 \
         (`resolution = 0.05` under [map] in an experiment file), or give a ROS map YAML"
    )]
    MissingResolution {
        /// The image as given.
        source_name: String,
    },
    /// The map has no free cell to cover.
    #[error("{source_name}: the map has no free cell")]
    NoFreeCell {
        /// File or preset name.
        source_name: String,
    },
    /// A name is neither a preset nor a map file.
    #[error(
        "unknown map `{name}`: expected a preset ({presets}), a ROS map file (.yaml/.yml) or an image (.pgm/.png) with --resolution"
    )]
    UnknownMap {
        /// The name as given.
        name: String,
        /// The preset names.
        presets: String,
    },
}

/// State of one grid cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum CellState {
    /// Traversable, to be covered.
    Free = 0,
    /// Wall or obstacle.
    Occupied = 1,
    /// Not known; treated as not traversable.
    Unknown = 2,
}

/// An occupancy grid with its metric frame.
#[derive(Clone, Debug, PartialEq)]
pub struct GridMap {
    name: String,
    cols: usize,
    rows: usize,
    resolution: f64,
    origin: Point,
    cells: Vec<CellState>,
    free_count: usize,
    /// The cell size of the raster a plan made on this map is scored on: the resolution, or for
    /// a planning raster split from a coarser map ([`refine::refined`]), that map's.
    scored_resolution: f64,
}

impl GridMap {
    /// Builds a map from row-major cells (row 0 at the bottom). Fails when no cell is free or the
    /// resolution is not positive and finite.
    pub fn new(
        name: impl Into<String>,
        cols: usize,
        rows: usize,
        resolution: f64,
        origin: Point,
        cells: Vec<CellState>,
    ) -> Result<Self, MapError> {
        let name = name.into();
        assert_eq!(cells.len(), cols * rows, "cell vector does not match the grid size");
        if !(resolution.is_finite() && resolution > 0.0) {
            return Err(MapError::OutOfRange {
                source_name: name,
                field: "resolution",
                value: resolution.to_string(),
                allowed: "a finite number of metres per cell > 0",
            });
        }
        let free_count = cells.iter().filter(|&&c| c == CellState::Free).count();
        if free_count == 0 {
            return Err(MapError::NoFreeCell { source_name: name });
        }
        Ok(Self { name, cols, rows, resolution, origin, cells, free_count, scored_resolution: resolution })
    }

    /// This map, scored on cells of `resolution` metres sharing its origin (a planning raster
    /// split from a map of that resolution).
    pub fn scored_on(mut self, resolution: f64) -> Self {
        self.scored_resolution = resolution;
        self
    }

    /// The cell size of the raster plans on this map are scored on (the map's own, unless it
    /// was split from a coarser map for planning).
    pub fn scored_resolution(&self) -> f64 {
        self.scored_resolution
    }

    /// A short name (preset name or file name) used in outputs.
    pub fn name(&self) -> &str {
        &self.name
    }
    /// Number of columns (x direction).
    pub fn cols(&self) -> usize {
        self.cols
    }
    /// Number of rows (y direction).
    pub fn rows(&self) -> usize {
        self.rows
    }
    /// Edge length of a cell in metres (`M_res`).
    pub fn resolution(&self) -> f64 {
        self.resolution
    }
    /// World position of the lower-left corner of cell (0, 0).
    pub fn origin(&self) -> Point {
        self.origin
    }
    /// Width of the map in metres (`M_width`).
    pub fn width_m(&self) -> f64 {
        self.extent_m(self.cols)
    }
    /// Height of the map in metres (`M_height`).
    pub fn height_m(&self) -> f64 {
        self.extent_m(self.rows)
    }

    /// The length of `n` cells: `n · resolution`, or on a planning raster split `k × k` from a
    /// coarser map, `(n / k) · that map's resolution`, so that the split map's edges are its
    /// map's to the bit (`n·(res/k)` and `(n/k)·res` differ in the last bit for about one split
    /// in five, and a plan at the clearance limit off one edge would leave the other).
    fn extent_m(&self, n: usize) -> f64 {
        if self.scored_resolution == self.resolution {
            return n as f64 * self.resolution;
        }
        let k = (self.scored_resolution / self.resolution).round() as usize;
        if k > 1 && n.is_multiple_of(k) { (n / k) as f64 * self.scored_resolution } else { n as f64 * self.resolution }
    }
    /// Number of free cells (`A_pix` of 003 §3.1 when obstacles are excluded, R29).
    pub fn free_count(&self) -> usize {
        self.free_count
    }
    /// Row-major index of a cell.
    #[inline]
    pub fn index(&self, row: usize, col: usize) -> usize {
        row * self.cols + col
    }
    /// `cell(row, col)` for every cell, row-major, the rows shared out among the worker
    /// threads (for per-cell values that depend on the map alone: the same for any number of
    /// threads).
    pub fn par_cells<T: Send + Default + Clone>(&self, cell: impl Fn(usize, usize) -> T + Sync) -> Vec<T> {
        use rayon::prelude::*;
        let mut out = vec![T::default(); self.rows * self.cols];
        if self.cols > 0 {
            out.par_chunks_mut(self.cols).enumerate().for_each(|(row, line)| {
                for (col, value) in line.iter_mut().enumerate() {
                    *value = cell(row, col);
                }
            });
        }
        out
    }
    /// State of the cell at a row-major index.
    #[inline]
    pub fn state_at(&self, index: usize) -> CellState {
        self.cells[index]
    }
    /// State of a cell.
    #[inline]
    pub fn state(&self, row: usize, col: usize) -> CellState {
        self.cells[self.index(row, col)]
    }
    /// Whether a cell is free.
    #[inline]
    pub fn is_free(&self, row: usize, col: usize) -> bool {
        self.state(row, col) == CellState::Free
    }
    /// All cells, row-major from the bottom row.
    pub fn cells(&self) -> &[CellState] {
        &self.cells
    }
    /// A copy with the cells whose centres lie in the half-open metre rectangle
    /// `[x0, x1) × [y0, y1)` made obstacles, and how many of them were free before (the
    /// "obstacle placed under the path" of 003 §3.2.2). Fails when no free cell would remain.
    pub fn with_obstacle(&self, [x0, y0, x1, y1]: [f64; 4]) -> Result<(GridMap, usize), MapError> {
        let mut cells = self.cells.clone();
        let mut placed = 0;
        for r in 0..self.rows {
            for c in 0..self.cols {
                let p = self.cell_centre(r, c);
                let i = self.index(r, c);
                if p.x >= x0 && p.x < x1 && p.y >= y0 && p.y < y1 && cells[i] != CellState::Occupied {
                    placed += usize::from(cells[i] == CellState::Free);
                    cells[i] = CellState::Occupied;
                }
            }
        }
        Ok((GridMap::new(self.name.clone(), self.cols, self.rows, self.resolution, self.origin, cells)?, placed))
    }
    /// Centre of a cell in world coordinates.
    pub fn cell_centre(&self, row: usize, col: usize) -> Point {
        Point::new(
            self.origin.x + (col as f64 + 0.5) * self.resolution,
            self.origin.y + (row as f64 + 0.5) * self.resolution,
        )
    }
    /// The cell containing a world point, if it lies on the map.
    pub fn cell_at(&self, p: Point) -> Option<(usize, usize)> {
        let cx = ((p.x - self.origin.x) / self.resolution).floor();
        let cy = ((p.y - self.origin.y) / self.resolution).floor();
        if cx < 0.0 || cy < 0.0 || cx >= self.cols as f64 || cy >= self.rows as f64 {
            return None;
        }
        Some((cy as usize, cx as usize))
    }
    /// Whether a point lies inside the map's rectangle (edges included).
    pub fn contains(&self, p: Point) -> bool {
        p.x >= self.origin.x
            && p.y >= self.origin.y
            && p.x <= self.origin.x + self.width_m()
            && p.y <= self.origin.y + self.height_m()
    }
    /// The nearest point of the map's rectangle (the clamp of 003 §3.3.4, R8).
    pub fn clamp(&self, p: Point) -> Point {
        Point::new(
            p.x.clamp(self.origin.x, self.origin.x + self.width_m()),
            p.y.clamp(self.origin.y, self.origin.y + self.height_m()),
        )
    }
    /// Whether the point lies on a free cell.
    pub fn is_free_point(&self, p: Point) -> bool {
        self.cell_at(p).is_some_and(|(r, c)| self.is_free(r, c))
    }

    /// Checks that a station (start or end) lies on a free cell; `what` names it in the message.
    pub fn check_station(&self, p: Point, what: &str) -> Result<(), String> {
        if !p.x.is_finite() || !p.y.is_finite() {
            return Err(format!("{what} ({}, {}) is not a finite position", p.x, p.y));
        }
        match self.cell_at(p) {
            None => Err(format!(
                "{what} ({}, {}) m is outside map `{}`, which spans x in [{}, {}) m, y in [{}, {}) m",
                p.x,
                p.y,
                self.name,
                self.origin.x,
                self.origin.x + self.width_m(),
                self.origin.y,
                self.origin.y + self.height_m()
            )),
            Some((r, c)) if !self.is_free(r, c) => Err(format!(
                "{what} ({}, {}) m lies inside an obstacle of map `{}` (cell row {r}, column {c} is {:?})",
                p.x,
                p.y,
                self.name,
                self.state(r, c)
            )),
            Some(_) => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tiny() -> GridMap {
        let mut cells = vec![CellState::Free; 6];
        cells[5] = CellState::Occupied;
        GridMap::new("tiny", 3, 2, 0.5, Point::new(-1.0, 2.0), cells).unwrap()
    }

    #[test]
    fn frame_and_cells() {
        let m = tiny();
        assert_eq!(m.free_count(), 5);
        assert_eq!(m.cell_at(Point::new(-1.0, 2.0)), Some((0, 0)));
        assert_eq!(m.cell_at(Point::new(0.49, 2.99)), Some((1, 2)));
        assert_eq!(m.cell_at(Point::new(0.5, 2.0)), None);
        assert_eq!(m.cell_centre(1, 2), Point::new(0.25, 2.75));
        assert!(!m.is_free_point(Point::new(0.25, 2.75)));
        assert!(m.check_station(Point::new(0.25, 2.75), "start").unwrap_err().contains("obstacle"));
        assert!(m.check_station(Point::new(5.0, 2.0), "end").unwrap_err().contains("outside"));
        assert_eq!(m.clamp(Point::new(9.0, -9.0)), Point::new(0.5, 2.0));
    }

    #[test]
    fn map_without_free_cell_is_rejected() {
        let err = GridMap::new("walls", 2, 1, 1.0, Point::origin(), vec![CellState::Occupied; 2]).unwrap_err();
        assert!(err.to_string().contains("no free cell"));
    }

    #[test]
    fn an_obstacle_takes_the_cells_whose_centres_it_holds() {
        // Centres of tiny(): x ∈ {-0.75, -0.25, 0.25}, y ∈ {2.25, 2.75}; cell (1, 2) is a wall.
        let (m, placed) = tiny().with_obstacle([-0.25, 2.25, 0.5, 3.0]).unwrap();
        assert_eq!(placed, 3, "(0, 1), (0, 2), (1, 1) were free; (1, 2) already a wall");
        assert_eq!(m.free_count(), 2);
        assert!(m.is_free(0, 0) && m.is_free(1, 0) && !m.is_free(0, 1) && !m.is_free(1, 1));
        // Half-open: x1 = -0.25 ends on the centre of (0, 1) and leaves it free; only (0, 0) is in.
        let (_, placed) = tiny().with_obstacle([-1.0, 2.0, -0.25, 2.5]).unwrap();
        assert_eq!(placed, 1);
        assert!(tiny().with_obstacle([-1.0, 2.0, 0.5, 3.0]).is_err(), "no free cell left");
    }
}
