//! The common scorer, the patterns and the thesis GA's fitness, over numpy arrays.

use crate::maps::Map;
use crate::{config_error, guarded, released};
use covga::coverage::Footprint;
use covga::coverage::fitness::Projection;
use covga::coverage::score::Scorer;
use covga::geom::Point;
use covga::patterns::{self, Pattern};
use covga::planner::sections::CameraSection;
use covga::thesis::batch::{COLUMNS, evaluate_genomes_until, genome_of};
use covga::thesis::scenario::{Moves, ThesisScenario};
use numpy::ndarray::{Array2, ArrayView2};
use numpy::{PyArray2, PyReadonlyArray2, PyReadonlyArray3, ToPyArray};
use pyo3::prelude::*;

/// The robot of `width`, `speed` and `rot_speed`, checked as `covga eval` checks them.
fn robot(map: &Map, width: f64, speed: f64, rot_speed: f64) -> PyResult<Footprint> {
    let footprint = Footprint { width, speed, rot_speed };
    if let Some((name, v, allowed)) = footprint.out_of_range() {
        return Err(config_error(format!("{name} = {v} is out of range: allowed {allowed}")));
    }
    footprint.check_fits(&map.inner).map_err(|m| config_error(format!("width {m}")))?;
    Ok(footprint)
}

fn projection(name: &str) -> PyResult<Projection> {
    match name {
        "f1" => Ok(Projection::F1),
        "f2" => Ok(Projection::F2),
        other => Err(config_error(format!("projection = '{other}': expected 'f1' or 'f2' (003 eqs. 3.14-3.15)"))),
    }
}

fn moves(name: &str) -> PyResult<Moves> {
    match name {
        "straight" => Ok(Moves::Straight),
        "routed" => Ok(Moves::Routed),
        other => Err(config_error(format!(
            "moves = '{other}': expected 'straight' (003) or 'routed' (around obstacles, thesis.moves)"
        ))),
    }
}

fn point(what: &str, p: (f64, f64)) -> PyResult<Point> {
    if p.0.is_finite() && p.1.is_finite() {
        Ok(Point::new(p.0, p.1))
    } else {
        Err(config_error(format!("{what} = ({}, {}) is not a finite position in metres", p.0, p.1)))
    }
}

/// The rows of an `(N, 2)` array of metres as points, named `what` in messages.
fn points(what: &str, a: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<Point>> {
    let a = a.as_array();
    if a.ncols() != 2 || a.nrows() == 0 {
        return Err(config_error(format!("{what}: shape {:?}, expected (N, 2) metres with N >= 1", a.dim())));
    }
    a.rows().into_iter().enumerate().map(|(i, r)| point(&format!("{what} point {i}"), (r[0], r[1]))).collect()
}

fn array_of(points: &[Point]) -> Array2<f64> {
    Array2::from_shape_fn((points.len(), 2), |(i, k)| if k == 0 { points[i].x } else { points[i].y })
}

/// The genome of `rows` (heading in degrees, distance in metres per row), genome `i` of a batch.
fn genome_of_rows(i: usize, rows: ArrayView2<'_, f64>) -> PyResult<Vec<covga::thesis::genome::Action>> {
    if rows.ncols() != 2 {
        return Err(config_error(format!(
            "genome {i}: shape {:?}, expected (L, 2): heading in degrees and distance in metres",
            rows.dim()
        )));
    }
    let moves: Vec<(f64, f64)> = rows.rows().into_iter().map(|r| (r[0], r[1])).collect();
    genome_of(i, &moves).map_err(config_error)
}

/// The layers of [`score`] with `raster`: visits per cell (uint32) and the coverable cells
/// of `cov_final_reach` (bool), each `(rows, cols)` with row 0 at the bottom.
type Raster<'py> = (Bound<'py, PyArray2<u32>>, Bound<'py, PyArray2<bool>>);

/// The common scorer's metrics (as JSON text) of `paths`, one per agent of this robot, as
/// `covga eval` reports them under `common`; with `raster`, the layers they count as well.
#[pyfunction]
#[pyo3(signature = (map, paths, width, speed, rot_speed, camera_json, projection_name, raster=false))]
#[allow(clippy::too_many_arguments)]
pub fn score<'py>(
    py: Python<'py>,
    map: &Map,
    paths: Vec<PyReadonlyArray2<'py, f64>>,
    width: f64,
    speed: f64,
    rot_speed: f64,
    camera_json: Option<&str>,
    projection_name: &str,
    raster: bool,
) -> PyResult<(String, Option<Raster<'py>>)> {
    let plan = guarded(|| {
        if paths.is_empty() {
            return Err(config_error("path: no path given (an (N, 2) array, or a list of them for agents)"));
        }
        let plan =
            paths.iter().enumerate().map(|(k, p)| points(&format!("path {k}"), p)).collect::<PyResult<Vec<_>>>()?;
        covga::coverage::score::check_camera_poses(&plan).map_err(|m| config_error(format!("path: {m}")))?;
        Ok(plan)
    })?;
    let m = &map.inner;
    let (text, layers) = released(py, || {
        let robot = robot(map, width, speed, rot_speed)?;
        let projection = projection(projection_name)?;
        for (k, p) in plan.iter().enumerate() {
            m.check_station(p[0], &format!("path {k} start")).map_err(config_error)?;
            m.check_station(*p.last().expect("checked non-empty"), &format!("path {k} end")).map_err(config_error)?;
        }
        let section: CameraSection = match camera_json {
            Some(text) => serde_json::from_str(text).map_err(|e| config_error(format!("camera: {e}")))?,
            None => CameraSection::default(),
        };
        let camera = section.spec("camera", m).map_err(config_error)?;
        let stations: Vec<Point> = plan.iter().map(|p| p[0]).collect();
        let widths = vec![width; plan.len()];
        let scorer = Scorer::for_widths(m, robot, &widths, projection, &camera, &stations);
        let score = scorer.score_agents(&plan, &vec![robot; plan.len()]);
        let text =
            serde_json::to_string(&score).map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
        let layers = raster.then(|| (scorer.visits(&plan, &widths), scorer.reach().coverable().to_vec()));
        Ok((text, layers))
    })?;
    let shape = (m.rows(), m.cols());
    let as_grid = |v: Vec<u32>, c: Vec<bool>| -> PyResult<Raster<'py>> {
        let bad = |e: numpy::ndarray::ShapeError| pyo3::exceptions::PyRuntimeError::new_err(e.to_string());
        Ok((
            Array2::from_shape_vec(shape, v).map_err(bad)?.to_pyarray(py),
            Array2::from_shape_vec(shape, c).map_err(bad)?.to_pyarray(py),
        ))
    };
    Ok((text, layers.map(|(v, c)| as_grid(v, c)).transpose()?))
}

/// A boustrophedon or spiral plan from `start` to `end` (default: back to the start), as
/// `covga eval --pattern` plans it.
#[pyfunction]
#[pyo3(signature = (map, kind, start, width, angle, end, complete))]
#[allow(clippy::too_many_arguments)]
pub fn pattern<'py>(
    py: Python<'py>,
    map: &Map,
    kind: &str,
    start: (f64, f64),
    width: f64,
    angle: f64,
    end: Option<(f64, f64)>,
    complete: bool,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let m = &map.inner;
    let planned = released(py, || {
        let robot = robot(map, width, 1.0, 0.0)?;
        let pattern = match kind {
            "boustrophedon" if angle.is_finite() => Pattern::Boustrophedon { angle_deg: angle },
            "boustrophedon" => return Err(config_error(format!("angle = {angle} is not a finite number of degrees"))),
            "spiral" => Pattern::Spiral,
            other => return Err(config_error(format!("pattern '{other}': expected 'boustrophedon' or 'spiral'"))),
        };
        let start = point("start", start)?;
        let end = match end {
            Some(e) => point("end", e)?,
            None => start,
        };
        patterns::check_plan_inputs(m, robot.width, start, end, ["start", "end", "width"]).map_err(config_error)?;
        patterns::plan(m, pattern, robot.width, start, end, complete).map_err(config_error)
    })?;
    Ok(array_of(&planned.points).to_pyarray(py))
}

/// Bytes one action of a genome takes once built (the genome and its decoded viewpoint).
const BYTES_PER_ACTION: f64 = 32.0;

/// Refuses a batch of `genomes` genomes of `actions` actions in all whose genomes would need
/// more than the memory available (a `ConfigError` naming the size and the bound).
fn check_batch_memory(genomes: usize, actions: usize) -> PyResult<()> {
    let need = BYTES_PER_ACTION * actions as f64 + 256.0 * genomes as f64;
    match covga::experiment::memory::memory_limit(None) {
        Some(limit) if need > limit.bytes as f64 => Err(config_error(format!(
            "genomes: {genomes} genomes of {actions} actions in all would need about {} once built, more than the \
             {} of memory this process may still allocate ({}); evaluate them in smaller batches",
            covga::io::human_bytes(need),
            covga::io::human_bytes(limit.bytes as f64),
            limit.bound
        ))),
        _ => Ok(()),
    }
}

/// The thesis GA's scenario on `map` for the robot `(width, speed, rot_speed)` between the
/// stations, each input checked as `covga run` checks it.
fn thesis_scenario(
    map: &Map,
    (width, speed, rot_speed): (f64, f64, f64),
    start: (f64, f64),
    end: Option<(f64, f64)>,
    projection_name: &str,
    moves_name: &str,
) -> PyResult<ThesisScenario> {
    let m = &map.inner;
    let robot = robot(map, width, speed, rot_speed)?;
    let projection = projection(projection_name)?;
    let moves = moves(moves_name)?;
    let start = point("start", start)?;
    let end = match end {
        Some(e) => point("end", e)?,
        None => start,
    };
    m.check_station(start, "start").map_err(config_error)?;
    m.check_station(end, "end").map_err(config_error)?;
    Ok(ThesisScenario::new(m.clone(), robot, start, end, projection).with_moves(moves))
}

/// The path a genome (an `(L, 2)` array of live moves: heading in degrees, distance in metres)
/// drives, decoded as the thesis GA decodes its own, as an `(N, 2)` array of metres.
#[pyfunction]
#[pyo3(signature = (map, genome, width, start, end, moves_name))]
pub fn thesis_decode<'py>(
    py: Python<'py>,
    map: &Map,
    genome: PyReadonlyArray2<'py, f64>,
    width: f64,
    start: (f64, f64),
    end: Option<(f64, f64)>,
    moves_name: &str,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let genome = genome_of_rows(0, genome.as_array())?;
    let moves: Vec<(f64, f64)> = genome[..genome.len() - 2].iter().map(|a| (a.alpha_deg(), a.dist_m())).collect();
    let path = released(py, || {
        let scenario = thesis_scenario(map, (width, 1.0, 0.0), start, end, "f2", moves_name)?;
        covga::thesis::batch::decode(&scenario, &moves).map_err(config_error)
    })?;
    Ok(array_of(&path).to_pyarray(py))
}

/// The thesis GA's fitness of a batch of genomes (an `(n, L, 2)` array, or a list of `(L, 2)`
/// arrays), each genome its live moves (heading in degrees, distance in metres; S's move first,
/// the connector to E added), as an `(n, 4)` array with the columns of `THESIS_COLUMNS`;
/// evaluated in parallel, with straight or routed moves (`thesis.moves`).
#[pyfunction]
#[pyo3(signature = (map, genomes, width, speed, rot_speed, start, end, projection_name, moves_name, threads=None))]
#[allow(clippy::too_many_arguments)]
pub fn thesis_evaluate<'py>(
    py: Python<'py>,
    map: &Map,
    genomes: Bound<'py, PyAny>,
    width: f64,
    speed: f64,
    rot_speed: f64,
    start: (f64, f64),
    end: Option<(f64, f64)>,
    projection_name: &str,
    moves_name: &str,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let built = guarded(|| {
        // One (n, L, 2) array is read in place; a list is read array by array. The genomes'
        // memory is checked before any is built.
        if let Ok(batch) = genomes.extract::<PyReadonlyArray3<'py, f64>>() {
            let a = batch.as_array();
            if a.dim().2 != 2 {
                return Err(config_error(format!("genomes: shape {:?}, expected (n, L, 2)", a.dim())));
            }
            check_batch_memory(a.dim().0, a.dim().0 * a.dim().1)?;
            return a.outer_iter().enumerate().map(|(i, g)| genome_of_rows(i, g)).collect::<PyResult<Vec<_>>>();
        }
        let list: Vec<PyReadonlyArray2<'py, f64>> = genomes.extract()?;
        check_batch_memory(list.len(), list.iter().map(|g| g.as_array().nrows()).sum())?;
        list.iter().enumerate().map(|(i, g)| genome_of_rows(i, g.as_array())).collect::<PyResult<Vec<_>>>()
    })?;
    let robot = (width, speed, rot_speed);
    let scenario = released(py, || thesis_scenario(map, robot, start, end, projection_name, moves_name))?;
    // Ctrl-C stops the batch within about one evaluation per thread (KeyboardInterrupt).
    let stop = std::sync::atomic::AtomicBool::new(false);
    // A panic in the evaluation reaches Python as a RuntimeError (the thread's join).
    let rows = crate::runs::interruptible(py, &|| stop.store(true, std::sync::atomic::Ordering::SeqCst), || {
        crate::with_threads(threads, || evaluate_genomes_until(&scenario, built, &stop))
    })??
    .unwrap_or_default();
    let out = Array2::from_shape_fn((rows.len(), COLUMNS.len()), |(i, k)| rows[i].row()[k]);
    Ok(out.to_pyarray(py))
}
