"""covga from Python: maps, the common scorer, patterns, runs and grid studies.

The Rust library does the work; this package converts. Arrays are numpy arrays in metres;
tables are pandas DataFrames when pandas is installed, else dicts of numpy arrays. Bad input
raises :class:`ConfigError` (a ``ValueError``) with the command line's message; a fault
inside covga raises ``RuntimeError``. Long calls release the GIL, and Ctrl-C stops them.

>>> import covga
>>> m = covga.load_map("thesis-1")
>>> path = covga.pattern(m, "boustrophedon", start=(1.3, 1.3), width=0.6)
>>> covga.score(m, path, width=0.6)["cov_final_reach"]
"""

from __future__ import annotations

import json
import os
import tempfile
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, List, Mapping, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from . import _covga, plot, stats, thesis
from ._arrays import rows_of_pairs
from ._covga import ConfigError, Map
from ._tables import read_study, read_table

__all__ = [
    "ConfigError",
    "Map",
    "Result",
    "Score",
    "grid",
    "load_map",
    "pattern",
    "planners",
    "plot",
    "read_study",
    "report",
    "run",
    "score",
    "stats",
    "thesis",
]
__version__ = _covga.__version__

# map_server's default thresholds on the occupancy percentages of a ROS OccupancyGrid, as the
# Rust map reader defines them.
_OCCUPIED_ABOVE = _covga.OCCUPIED_ABOVE_PERCENT
_FREE_BELOW = _covga.FREE_BELOW_PERCENT


def _cell_states(occupancy: np.ndarray) -> np.ndarray:
    """Cell states (0 free, 1 occupied, 2 unknown) of an occupancy array."""
    if occupancy.dtype == np.bool_:
        # Which of True and False is free depends on who built the array (Map.free is True on
        # free cells, an obstacle mask True on occupied ones): a guess would invert half of them.
        raise ConfigError(
            "occupancy array of dtype bool: True could mean occupied (an obstacle mask) or free (Map.free); "
            "pass occupancy percentages instead: np.where(occupied, 100, 0) for a mask of obstacles, "
            "np.where(free, 0, 100) for a mask of free cells"
        )
    if not np.issubdtype(occupancy.dtype, np.number) or occupancy.dtype.kind == "c":
        raise ConfigError(f"occupancy array of dtype {occupancy.dtype}: expected bool or real numbers")
    values = occupancy.astype(np.float64)
    bad = ~np.isfinite(values) | (values > 100.0)
    if bad.any():
        r, c = np.argwhere(bad)[0]
        raise ConfigError(
            f"occupancy {values[r, c]} at [{r}, {c}] is out of range: expected -1 (unknown) or a percentage in [0, 100]"
        )
    states = np.full(values.shape, 2, dtype=np.int8)
    states[(values >= 0.0) & (values < _FREE_BELOW)] = 0
    states[values > _OCCUPIED_ABOVE] = 1
    return states


def _map_from_pickle(states: npt.NDArray[Any], resolution: float, origin: tuple[float, float], name: str) -> Map:
    """Rebuilds a pickled :class:`Map` (``Map.__reduce__``) bit for bit."""
    x, y = origin
    return _covga.map_from_states(np.ascontiguousarray(states, dtype=np.int8), float(resolution), (float(x), float(y)), str(name))


def _number(value: Any, key: str, integer: bool = False) -> Any:
    """``value`` as a float (or, with ``integer``, an int), or ConfigError naming ``key``: text,
    bools and, for integers, fractions are refused rather than converted."""
    ok = isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_))
    if ok and integer and not float(value).is_integer():
        ok = False
    if not ok:
        kind = "a whole number" if integer else "a number"
        raise ConfigError(f"{key} = {value!r}: expected {kind}")
    return int(value) if integer else float(value)


def _flag(value: Any, key: str) -> bool:
    """``value`` as a bool, or ConfigError naming ``key``: numbers and text are refused rather
    than read by their truth (``"no"`` would be True)."""
    if not isinstance(value, (bool, np.bool_)):
        raise ConfigError(f"{key} = {value!r}: expected True or False")
    return bool(value)


def _threads(value: Any) -> Optional[int]:
    """``threads=`` as a count of worker threads (``None``: one per CPU, or ``RAYON_NUM_THREADS``)."""
    if value is None:
        return None
    n = int(_number(value, "threads", integer=True))
    if not 1 <= n <= _covga.MAX_THREADS:
        raise ConfigError(f"threads = {value!r} is out of range: allowed [1, {_covga.MAX_THREADS}]")
    return n


def _point(value: Any, key: str) -> tuple[float, float]:
    """``value`` as ``(x, y)`` in metres, or ConfigError naming ``key``."""
    try:
        items = list(value)
    except TypeError:
        raise ConfigError(f"{key} = {value!r}: expected a point (x, y) in metres") from None
    if len(items) != 2:
        raise ConfigError(f"{key} = {value!r}: expected a point (x, y) in metres, two numbers")
    return (_number(items[0], key), _number(items[1], key))


def load_map(
    source: Union[str, "os.PathLike[str]", npt.NDArray[Any], Map],
    resolution: Optional[float] = None,
    origin: Sequence[float] = (0.0, 0.0),
    name: str = "array",
    free_threshold: Optional[int] = None,
) -> Map:
    """Loads a map.

    ``source`` is a preset name (``thesis-1``, ``thesis-2``, ``office``, ``office-large``,
    ``office-ring``), a ROS map YAML, a PGM/PNG image (with ``resolution`` in metres per pixel),
    or a 2-D occupancy array indexed ``[row, col]`` with row 0 at the bottom (smallest y), as a
    ROS ``OccupancyGrid`` stores it: occupancy percentages (negative unknown, above 65
    occupied, below 19.6 free, between unknown, as map_server thresholds them), so a ROS grid's
    ``data`` reshaped to ``(height, width)`` loads as it is. An array needs ``resolution``;
    ``origin`` is its lower-left corner in metres. A bool array is refused (``ConfigError``):
    whether ``True`` marks occupied cells (an obstacle mask) or free ones (:meth:`Map.free`) is
    the caller's to say, as ``np.where(occupied, 100, 0)`` or ``np.where(free, 0, 100)``.

    A bare image is read with map_server's default thresholds (grey >= 206 free, <= 89
    occupied, unknown between) unless ``free_threshold`` is given: then grey values at or above
    it are free and darker ones occupied (the ipa room-segmentation benchmark uses 250).
    """
    if isinstance(source, Map):
        return source
    if isinstance(source, (str, os.PathLike)):
        # A file or preset brings its own frame and name.
        if tuple(origin) != (0.0, 0.0) or name != "array":
            raise ConfigError(f"{os.fspath(source)}: origin= and name= apply to occupancy arrays only")
        return _covga.load_map(
            os.fspath(source),
            None if resolution is None else _number(resolution, "resolution"),
            None if free_threshold is None else _number(free_threshold, "free_threshold", integer=True),
        )
    if free_threshold is not None:
        raise ConfigError("free_threshold applies to a bare PGM/PNG image only, not to an occupancy array")
    occupancy = np.asarray(source)
    if occupancy.ndim != 2:
        raise ConfigError(f"occupancy array of shape {occupancy.shape}: expected 2-D (rows, cols)")
    if occupancy.size > _covga.MAX_MAP_CELLS:
        # Refused before its cell states are built (a copy of the whole array).
        raise ConfigError(
            f"occupancy array of shape {occupancy.shape} has {occupancy.size} cells; a map has at most "
            f"{_covga.MAX_MAP_CELLS}, as a map image file: crop or coarsen it first"
        )
    if resolution is None:
        raise ConfigError("resolution: an occupancy array needs its metres per cell (resolution=...)")
    x, y = _point(origin, "origin")
    return _covga.map_from_states(_cell_states(occupancy), _number(resolution, "resolution"), (x, y), str(name))


def _paths(path: Any) -> list[npt.NDArray[np.float64]]:
    """One ``(N, 2)`` float array per agent."""
    if isinstance(path, (list, tuple)) and len(path) > 0 and np.ndim(path[0]) == 2:
        items = list(path)
    else:
        items = [path]
    return [rows_of_pairs(p, f"path {k}", "N", "metres") for k, p in enumerate(items)]


class Score(dict[str, Any]):
    """The common scorer's metrics of a plan (a ``dict``, as ``covga eval`` reports them under
    ``common``), with the map and plan they measure; with ``raster=True`` also ``visits``
    (uint32 ``(rows, cols)``, row 0 at the bottom: how many times the footprint swept each free
    cell) and ``reachable`` (bool, the cells ``cov_final_reach`` counts). ``plot()`` draws them."""

    def __init__(self, metrics: Mapping[str, Any], map: Map, plan: list[npt.NDArray[np.float64]]) -> None:
        super().__init__(metrics)
        self.map = map
        self.plan = plan

    def plot(self, ax: Any = None) -> Any:
        """The plan over the map, its swept cells in the CLI's colours when the score has its
        raster (:func:`covga.plot.plot_coverage`), else the plan alone; returns the axes."""
        title = (
            f"coverage {self['cov_final_reach']:.3f} of the reachable cells, "
            f"{'executable' if self['executable'] else 'not executable'}"
        )
        if "visits" in self:
            return plot.plot_coverage(self.map, self["visits"], self.plan, ax, title)
        return plot.plot_plan(self.map, self.plan, ax, title)


def score(
    map: Map,
    path: Any,
    width: Optional[float] = None,
    speed: Optional[float] = None,
    rot_speed: Optional[float] = None,
    camera: Optional[Mapping[str, Any]] = None,
    projection: str = "f2",
    raster: bool = False,
) -> Score:
    """The common scorer's metrics of a plan, as ``covga eval`` reports them (``common``), as a
    :class:`Score` (a dict with ``plot()``).

    ``path`` is an ``(N, 2)`` array of metres, or a list of them (one per agent, all with this
    robot). The robot is ``width`` (m), ``speed`` (m/s) and ``rot_speed`` (rad/s): give all three
    for your robot; any left out takes the thesis robot's value (0.6 m, 0.2 m/s, 0 rad/s: turning
    free) with a ``UserWarning`` naming it. ``projection`` is ``f2`` by default, as in experiment
    files. ``camera`` holds ``[scorer.camera]`` keys (``scale``, ``d_min``, ``d_max``,
    ``fov_deg``, ``sections``, ``wall_band``); by default an experiment file's default camera. With ``raster``,
    the result also holds the cell layers the coverage counts (``visits``, ``reachable``).
    """
    defaults = {"width": (width, 0.6, "m"), "speed": (speed, 0.2, "m/s"), "rot_speed": (rot_speed, 0.0, "rad/s")}
    unset = [f"{k} = {d} {unit}" for k, (v, d, unit) in defaults.items() if v is None]
    if unset:
        warnings.warn(
            "covga.score: the robot's " + ", ".join(unset) + " (the thesis robot's; rot_speed = 0 makes turning "
            "free): pass width, speed and rot_speed for your robot",
            UserWarning,
            stacklevel=2,
        )
    width = 0.6 if width is None else _number(width, "width")
    speed = 0.2 if speed is None else _number(speed, "speed")
    rot_speed = 0.0 if rot_speed is None else _number(rot_speed, "rot_speed")
    raster = _flag(raster, "raster")
    if not isinstance(projection, str):
        raise ConfigError(f"projection = {projection!r}: expected 'f1' or 'f2'")
    camera_json = None if camera is None else json.dumps(dict(camera))
    the_map, paths = load_map(map), _paths(path)
    text, layers = _covga.score(
        the_map, paths, float(width), float(speed), float(rot_speed), camera_json, projection, bool(raster)
    )
    result = Score(json.loads(text), the_map, paths)
    if layers is not None:
        result["visits"], result["reachable"] = layers
    return result


def pattern(
    map: Map,
    kind: str = "boustrophedon",
    start: Sequence[float] = (1.3, 1.3),
    width: float = 0.6,
    angle: float = 0.0,
    end: Optional[Sequence[float]] = None,
    complete: bool = True,
) -> np.ndarray:
    """A ``boustrophedon`` (lanes at ``angle`` degrees from +x) or ``spiral`` plan from
    ``start`` back to ``end`` (default: the start), as an ``(N, 2)`` array of metres; with
    ``complete``, the strips the pattern leaves are visited afterwards (as ``covga eval``)."""
    s = _point(start, "start")
    e = None if end is None else _point(end, "end")
    if not isinstance(kind, str):
        raise ConfigError(f"kind = {kind!r}: expected 'boustrophedon' or 'spiral'")
    width, angle = _number(width, "width"), _number(angle, "angle")
    return _covga.pattern(load_map(map), kind, s, width, angle, e, _flag(complete, "complete"))


@dataclass
class Result:
    """One run: ``summary`` (``summary.json``), ``history`` (``history.csv``: a DataFrame with
    pandas, else a dict of arrays), ``plan`` (one ``(N, 2)`` array per agent), ``path`` (the
    first agent's), ``population`` (the thesis GA's final population, ``population.csv``;
    ``None`` for other planners), ``dir`` (the results folder, ``None`` when not kept),
    ``warnings``, ``config`` (the run's ``config.toml``) and ``genomes`` (with
    ``output.population_genomes = true``, the final population's genomes in the order of
    ``population``: one ``(L, 2)`` array of live moves each, for :func:`covga.thesis.decode` and
    :func:`covga.thesis.evaluate`; else ``None``); ``map`` and ``plot()`` draw it."""

    summary: dict[str, Any]
    history: Any
    plan: list[npt.NDArray[np.float64]]
    population: Any = None
    dir: Optional[Path] = None
    warnings: list[str] = field(default_factory=list)
    config: str = ""
    genomes: Optional[list[npt.NDArray[np.float64]]] = None

    @property
    def map(self) -> Map:
        """The map the run planned on, loaded from its ``config.toml`` as ``covga run`` loads it."""
        return _covga.experiment_map(self.config, "config.toml")

    def plot(self, ax: Any = None) -> Any:
        """The run's plan over its map (:func:`covga.plot.plot_plan`), titled with its planner,
        seed, reachable coverage and executability; returns the matplotlib axes."""
        s = self.summary.get("score", {})
        title = (
            f"{self.summary.get('planner')}, seed {self.summary.get('seed')}: "
            f"coverage {s.get('cov_final_reach', float('nan')):.3f}, "
            f"{'executable' if s.get('executable') else 'not executable'}"
        )
        return plot.plot_plan(self.map, self.plan, ax, title)

    @property
    def path(self) -> npt.NDArray[np.float64]:
        """The first (for one robot, the only) agent's path."""
        return self.plan[0]

    def __repr__(self) -> str:
        s, nan = self.summary.get("score", {}), float("nan")
        return (
            f"Result({self.summary.get('planner')} on {self.summary.get('map')}, seed {self.summary.get('seed')}: "
            f"cov_final_reach {s.get('cov_final_reach', nan):.4f}, t_final {s.get('t_final', nan):.4f}, "
            f"executable {s.get('executable')})"
        )


def _plain(value: Any, key: str) -> Any:
    """An experiment dict's value as JSON takes it: numpy scalars and arrays as numbers and
    lists, paths as text; a value that is neither (or a NaN or infinity) raises ConfigError
    naming its dotted ``key``."""
    if isinstance(value, Mapping):
        return {str(k): _plain(v, f"{key}.{k}" if key else str(k)) for k, v in value.items()}
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        return [_plain(v, f"{key}[{i}]") for i, v in enumerate(value)]
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        if not np.isfinite(value):
            raise ConfigError(f"experiment dict: `{key}` = {value}: expected a finite number")
        return float(value)
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, str):
        return value
    raise ConfigError(
        f"experiment dict: `{key}` = {value!r} of type {type(value).__name__}: expected a number, text, a list or a table"
    )


def _experiment(experiment: Any) -> tuple[str, str]:
    """``(kind, payload)`` of a TOML path, TOML text or dict."""
    if isinstance(experiment, Mapping):
        return "json", json.dumps(_plain(experiment, ""))
    if isinstance(experiment, os.PathLike):
        return "path", os.fspath(experiment)
    if isinstance(experiment, str):
        if "=" in experiment and not os.path.isfile(experiment):
            return "text", experiment
        return "path", experiment
    raise ConfigError(f"experiment of type {type(experiment).__name__}: expected a TOML path, TOML text or a dict")


def _read_plan(csv_path: Path) -> list[npt.NDArray[np.float64]]:
    table: Any = np.atleast_1d(np.genfromtxt(csv_path, delimiter=",", names=True, dtype=np.float64))
    names = table.dtype.names or ()
    agents = table["agent"].astype(np.int64) if "agent" in names else np.zeros(len(table), np.int64)
    points = np.column_stack([table["x_m"], table["y_m"]])
    return [points[agents == k] for k in range(int(agents.max()) + 1 if len(agents) else 0)]


def _read_result(folder: Path, kept: bool, messages: list[str]) -> Result:
    summary = json.loads((folder / "summary.json").read_text())
    tables = {}
    for name in ("history", "population"):
        csv_file = folder / f"{name}.csv"
        tables[name] = read_table(csv_file) if csv_file.is_file() else None
    plan = _read_plan(folder / "best_path.csv")
    config = (folder / "config.toml").read_text()
    genomes = thesis.read_population_genomes(folder) if (folder / "population_genomes.csv").is_file() else None
    return Result(
        summary, tables["history"], plan, tables["population"], folder if kept else None, messages, config, genomes
    )


def planners() -> list[str]:
    """The planners an experiment may name (``planner = "…"``), from covga's one registry of
    planners, in the order studies list them: covga's own, then those registered from outside
    by the program covga runs in. :func:`run` runs any of them by name."""
    return list(_covga.planners())


def run(
    experiment: Any,
    seed: Optional[int] = None,
    out: Optional[Union[str, "os.PathLike[str]"]] = None,
    figures: Optional[bool] = None,
    threads: Optional[int] = None,
) -> Result:
    """Runs one experiment: a TOML file path, TOML text, or a dict with the experiment file's
    keys (``{"planner": "thesis", "map": {"source": "thesis-1"}, ...}``). ``seed`` overrides the
    file's. With ``out``, the run's folder is written there as ``covga run --out`` writes it
    (figures too unless ``figures=False``), and refused in the same way when it holds another
    run's files; without, it is read back and removed. The GIL is
    released while it runs; Ctrl-C stops it and raises ``KeyboardInterrupt``. ``threads``: worker
    threads of the run (default one per CPU, or ``RAYON_NUM_THREADS``); results do not depend on
    it."""
    kind, payload = _experiment(experiment)
    n_threads = _threads(threads)
    if seed is not None and not (isinstance(seed, (int, np.integer)) and 0 <= int(seed) <= 2**63 - 1):
        raise ConfigError(f"seed = {seed!r} is out of range: expected an integer in [0, {2**63 - 1}]")
    seed = None if seed is None else int(seed)
    if figures is not None:
        figures = _flag(figures, "figures")
    if out is None:
        with tempfile.TemporaryDirectory(prefix="covga-run-") as tmp:
            folder = Path(tmp) / "run"
            messages = _covga.run_experiment(kind, payload, seed, str(folder), bool(figures), n_threads)
            result = _read_result(folder, False, messages)
    else:
        folder = Path(out)
        messages = _covga.run_experiment(
            kind, payload, seed, str(folder), figures is None or bool(figures), n_threads
        )
        result = _read_result(folder, True, messages)
    for m in messages:
        warnings.warn(m, stacklevel=2)
    return result


def grid(
    file: Union[str, "os.PathLike[str]"],
    jobs: Optional[int] = None,
    out: Optional[Union[str, "os.PathLike[str]"]] = None,
    order: str = "longest-first",
) -> Any:
    """Runs (or resumes) a grid study as ``covga grid`` does, ``jobs`` runs at a time (default:
    one per CPU), into ``out`` (default ``out/<grid stem>``); returns :func:`read_study` of it.
    ``order`` is ``covga grid --order``: ``"longest-first"`` (by recorded or budgeted time, so
    that few cores idle at the end) or ``"seeds"`` (seed by seed); results are the same.
    Ctrl-C stops it after the runs in progress, which stay recorded: call again to resume."""
    file = Path(file)
    folder = Path(out) if out is not None else Path("out") / file.stem
    n = (os.cpu_count() or 1) if jobs is None else jobs
    if not isinstance(n, (int, np.integer)) or isinstance(n, bool):
        raise ConfigError(f"jobs = {jobs!r}: expected a whole number of runs at a time, at least 1")
    if n < 1:
        raise ConfigError(f"jobs = {jobs!r} is out of range: at least 1")
    _covga.run_grid(str(file), int(n), str(folder), str(order))
    return read_study(folder)


def report(
    dir: Union[str, "os.PathLike[str]"],
    by: Union[str, Sequence[str]] = (),
    where: Optional[Mapping[str, Any]] = None,
    name: Optional[str] = None,
    compare: Optional[Mapping[str, Any]] = None,
    compare_every_plan: Optional[Mapping[str, Any]] = None,
    anova_condensed: bool = False,
    plans: bool = False,
    reference: Optional[Union[str, "os.PathLike[str]"]] = None,
    seed_to_seed: bool = False,
    measures: Sequence[str] = (),
    design: bool = False,
) -> Path:
    """Writes ``covga report`` of a study folder, grouped ``by`` these columns, keeping the
    runs ``where`` each column equals its value; returns the path of ``summary.md``. ``compare``
    maps swept keys to their baseline values (``{"thesis.moves": "straight"}``): each adds
    ``compare-KEY.md`` and ``.csv`` beside it (``covga report --compare``; the tables read back
    with :func:`read_table`); a list of baselines (``{"cell_order.solver": ["nearest",
    "boustrophedon"]}``) compares with each, into ``compare-KEY-BASELINE.md``.
    ``compare_every_plan`` does the same over every plan, executable or not
    (``--compare-every-plan``, ``compare-KEY-every-plan.md``). ``anova_condensed`` also writes
    ``anova-condensed.md`` (``--anova-condensed``: each analysis of variance's main effects,
    three largest interactions and residual). ``plans`` also writes ``plans.md`` and ``plans.csv``
    (``--plans``: every configuration's plans and final populations, with findings in words);
    ``reference``, a runs.csv of one plan per map, sets every run against its map's plan there
    (``--reference``). ``seed_to_seed`` also writes ``seed-to-seed.md`` (``--seed-to-seed``: how
    far one replicate's ranking of the configurations carries to another). ``measures`` names
    figures the runs record (a runs.csv column, ``history.COLUMN@ITERATION`` or a dotted path
    into ``summary.json``) and writes ``measures.md`` and ``measures.csv`` (``--measure``: each
    group's median [min, max], or the count of runs where a yes/no figure holds). ``design`` also
    writes each comparison's ``design-KEY.md`` (``--design``: what the design can show, each
    family's smallest p after its correction, and the seeds or units needed to show an effect
    of a given size)."""
    by = [by] if isinstance(by, str) else list(by)

    def text(v: Any) -> str:
        return str(v).lower() if isinstance(v, bool) else str(v)

    pairs = [(str(k), text(v)) for k, v in (where or {}).items()]
    def each(m: Optional[Mapping[str, Any]]) -> List[str]:
        out = []
        for k, v in (m or {}).items():
            values = v if isinstance(v, (list, tuple)) else [v]
            out += [f"{k}={text(x)}" for x in values]
        return out

    comparisons = each(compare)
    every = each(compare_every_plan)
    if not isinstance(anova_condensed, (bool, np.bool_)):
        raise ConfigError(f"anova_condensed = {anova_condensed!r}: expected True or False")
    for flag, value in (("plans", plans), ("seed_to_seed", seed_to_seed), ("design", design)):
        if not isinstance(value, (bool, np.bool_)):
            raise ConfigError(f"{flag} = {value!r}: expected True or False")
    if design and not comparisons and not every:
        raise ConfigError("design: tells what a comparison can show; name one with compare")
    ref = None if reference is None else os.fspath(reference)
    if isinstance(measures, str) or not all(isinstance(m, str) for m in measures):
        raise ConfigError(f"measures = {measures!r}: expected a list of keys, e.g. ['objectives.wall_coverage']")
    return Path(
        _covga.write_report(os.fspath(dir), by, pairs, name, comparisons, every, bool(anova_condensed), bool(plans), ref,
        bool(seed_to_seed), list(measures), bool(design))
    )
