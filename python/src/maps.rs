//! `covga.Map`: an occupancy grid with its metric frame, as numpy arrays.

use crate::{config_error, guarded};
use covga::geom::Point;
use covga::map::{CellState, GridMap};
use numpy::ndarray::Array2;
use numpy::{PyArray2, PyReadonlyArray2, ToPyArray};
use pyo3::prelude::*;

/// An occupancy grid map with its metric frame. Arrays index `[row, col]` with row 0 at the
/// bottom (smallest y), so `imshow(m.free, origin="lower", extent=m.extent)` draws it in metres.
#[pyclass(name = "Map", module = "covga", frozen)]
pub struct Map {
    pub(crate) inner: GridMap,
}

impl Map {
    fn cells_as<T: Copy>(&self, of: impl Fn(CellState) -> T) -> Array2<T> {
        let m = &self.inner;
        Array2::from_shape_fn((m.rows(), m.cols()), |(r, c)| of(m.state(r, c)))
    }
}

#[pymethods]
impl Map {
    /// `(rows, cols)`.
    #[getter]
    fn shape(&self) -> (usize, usize) {
        (self.inner.rows(), self.inner.cols())
    }
    /// Metres per cell.
    #[getter]
    fn resolution(&self) -> f64 {
        self.inner.resolution()
    }
    /// The lower-left corner `(x, y)` in metres.
    #[getter]
    fn origin(&self) -> (f64, f64) {
        let o = self.inner.origin();
        (o.x, o.y)
    }
    /// The map's name (preset or file name).
    #[getter]
    fn name(&self) -> String {
        self.inner.name().to_string()
    }
    /// `(x_min, x_max, y_min, y_max)` in metres, as matplotlib's `extent` takes it.
    #[getter]
    fn extent(&self) -> (f64, f64, f64, f64) {
        let o = self.inner.origin();
        (o.x, o.x + self.inner.width_m(), o.y, o.y + self.inner.height_m())
    }
    /// Free cells, a bool array `(rows, cols)`, row 0 at the bottom.
    #[getter]
    fn free<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<bool>> {
        self.cells_as(|s| s == CellState::Free).to_pyarray(py)
    }
    /// Cell states, an int8 array `(rows, cols)`, row 0 at the bottom: 0 free, 1 occupied,
    /// 2 unknown.
    #[getter]
    fn states<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i8>> {
        self.cells_as(|s| s as i8).to_pyarray(py)
    }
    /// Number of free cells.
    #[getter]
    fn free_cells(&self) -> usize {
        self.inner.free_count()
    }
    /// The map as a grey image (uint8, row 0 at the top, as image files and `imshow` without
    /// `origin` have it): 254 free, 0 occupied, 205 unknown (map_server's trinary values).
    fn to_image<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<u8>> {
        let m = &self.inner;
        Array2::from_shape_fn((m.rows(), m.cols()), |(r, c)| covga::map::picture::grey(m.state(m.rows() - 1 - r, c)))
            .to_pyarray(py)
    }
    /// The map as a PNG picture (north up, small maps enlarged), which Jupyter shows inline.
    fn _repr_png_<'py>(&self, py: Python<'py>) -> Bound<'py, pyo3::types::PyBytes> {
        pyo3::types::PyBytes::new(py, &covga::map::picture::png(&self.inner))
    }
    /// Two maps are equal when their names, frames and every cell are.
    fn __eq__(&self, other: PyRef<'_, Map>) -> bool {
        self.inner == other.inner
    }
    /// A hash consistent with `==`.
    fn __hash__(&self) -> u64 {
        use std::hash::{Hash, Hasher};
        let m = &self.inner;
        let mut h = std::collections::hash_map::DefaultHasher::new();
        (m.name(), m.rows(), m.cols(), m.resolution().to_bits(), m.origin().x.to_bits(), m.origin().y.to_bits())
            .hash(&mut h);
        m.cells().hash(&mut h);
        h.finish()
    }
    /// A map is immutable: a copy is the map itself.
    fn __copy__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }
    /// A map is immutable: a deep copy is the map itself.
    fn __deepcopy__<'py>(slf: PyRef<'py, Self>, _memo: &Bound<'py, PyAny>) -> PyRef<'py, Self> {
        slf
    }
    /// Pickles as its cell states, resolution, origin and name (`covga.map_from_states`
    /// rebuilds it bit for bit), for multiprocessing, joblib and pymoo's saved histories.
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, pyo3::types::PyTuple>)> {
        let rebuild = py.import("covga")?.getattr("_map_from_pickle")?;
        let m = &self.inner;
        let states = self.cells_as(|s| s as i8).to_pyarray(py);
        let args = (states, m.resolution(), (m.origin().x, m.origin().y), m.name().to_string()).into_pyobject(py)?;
        Ok((rebuild, args))
    }
    fn __repr__(&self) -> String {
        let m = &self.inner;
        format!(
            "Map('{}', shape=({}, {}), resolution={}, origin=({}, {}), free_cells={})",
            m.name(),
            m.rows(),
            m.cols(),
            m.resolution(),
            m.origin().x,
            m.origin().y,
            m.free_count()
        )
    }
}

/// Loads a preset, a ROS map YAML, or a PGM/PNG image (with `resolution`; `free_threshold`
/// splits its grey values into free, at or above it, and occupied, as the CLI's
/// `--free-threshold`).
#[pyfunction]
#[pyo3(signature = (source, resolution=None, free_threshold=None))]
pub fn load_map(source: &str, resolution: Option<f64>, free_threshold: Option<i64>) -> PyResult<Map> {
    guarded(|| {
        if let Some(r) = resolution
            && !(r.is_finite() && r > 0.0)
        {
            return Err(config_error(format!("resolution = {r} is out of range: expected metres per pixel > 0")));
        }
        let free_threshold = match free_threshold {
            None => None,
            Some(t) => Some(u8::try_from(t).ok().filter(|&t| t >= 1).ok_or_else(|| {
                config_error(format!("free_threshold = {t} is out of range: allowed [1, 255] grey values"))
            })?),
        };
        let image = covga::map::ros::BareImage { resolution, free_threshold };
        let inner = covga::map::ros::load_map(source, &image).map_err(config_error)?;
        Ok(Map { inner })
    })
}

/// A map from cell states (int8, `(rows, cols)`, row 0 at the bottom: 0 free, 1 occupied,
/// 2 unknown), metres per cell and the lower-left corner.
#[pyfunction]
#[pyo3(signature = (states, resolution, origin=(0.0, 0.0), name="array".to_string()))]
pub fn map_from_states(
    states: PyReadonlyArray2<'_, i8>,
    resolution: f64,
    origin: (f64, f64),
    name: String,
) -> PyResult<Map> {
    guarded(|| {
        let a = states.as_array();
        let (rows, cols) = a.dim();
        if rows == 0 || cols == 0 {
            return Err(config_error(format!("occupancy array of shape ({rows}, {cols}): expected at least one cell")));
        }
        let max = covga::map::ros::MAX_MAP_CELLS;
        if (rows as u64).saturating_mul(cols as u64) > max {
            return Err(config_error(format!(
                "occupancy array of shape ({rows}, {cols}) has {} cells; a map has at most {max}, as a map image \
                 file: crop or coarsen it first",
                rows as u64 * cols as u64
            )));
        }
        if !(origin.0.is_finite() && origin.1.is_finite()) {
            return Err(config_error(format!("origin = ({}, {}) is not a finite position", origin.0, origin.1)));
        }
        let mut cells = Vec::with_capacity(rows * cols);
        for r in 0..rows {
            for c in 0..cols {
                cells.push(match a[[r, c]] {
                    0 => CellState::Free,
                    1 => CellState::Occupied,
                    2 => CellState::Unknown,
                    v => return Err(config_error(format!("cell state {v} at [{r}, {c}]: expected 0, 1 or 2"))),
                });
            }
        }
        let inner =
            GridMap::new(name, cols, rows, resolution, Point::new(origin.0, origin.1), cells).map_err(config_error)?;
        Ok(Map { inner })
    })
}

/// The map an experiment (TOML text, e.g. a run's `config.toml`) runs on, loaded and checked
/// as `covga run` loads and checks it (relative paths from the working directory).
#[pyfunction]
pub fn experiment_map(py: Python<'_>, text: &str, origin: &str) -> PyResult<Map> {
    crate::released(py, || {
        let file = covga::experiment::file::ExperimentFile::parse(text, origin).map_err(config_error)?;
        let experiment = file.validate(origin, std::path::Path::new("."), "run").map_err(config_error)?;
        Ok(Map { inner: experiment.scenario.map })
    })
}
