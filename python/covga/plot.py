"""Pictures of maps, plans and studies with matplotlib (``pip install covga[examples]``): the
map in map_server's greys (free light, occupied black, unknown grey), north up, equal scale,
axes in metres; each agent's path as a line from its start (circle) to its end (open square);
swept cells in the colours of ``covga run``'s path figures; a study's convergence curves and
final fronts per group; every mark and colour in the legend. Each function draws into ``ax`` (a
new figure's when ``None``) and returns it."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Optional, Union

import numpy as np
import numpy.typing as npt

from ._covga import ConfigError, Map
from ._tables import read_study, read_table

# The colours of covga's own path figures (src/plot/path.rs), as RGB in [0, 1].
_CELL_COLOURS: dict[str, tuple[int, int, int]] = {
    "occupied": (70, 70, 70),
    "unknown": (160, 160, 160),
    "free, not covered": (255, 255, 255),
    "covered once": (150, 215, 150),
    "covered 2+ times": (240, 170, 80),
}


def _axes(ax: Any) -> Any:
    if ax is not None:
        return ax
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:  # pragma: no cover - the test extra installs matplotlib
        raise ImportError("covga's pictures need matplotlib: pip install 'covga[examples]'") from e
    _, new = plt.subplots(figsize=(7, 6))
    return new


def _draw_map(map: Map, ax: Any) -> tuple[Any, list[Any]]:
    """Draws the map; returns the axes and the legend patches of the greys it shows."""
    from matplotlib.patches import Patch

    ax = _axes(ax)
    image = map.to_image()
    ax.imshow(image, cmap="gray", vmin=0, vmax=255, extent=map.extent, interpolation="nearest")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(map.name)
    greys = ((254, "free"), (0, "occupied"), (205, "unknown"))
    patches = [Patch(facecolor=str(g / 255), edgecolor="black", label=s) for g, s in greys if np.any(image == g)]
    return ax, patches


def _legend(ax: Any, handles: list[Any], below: bool = False) -> None:
    """The legend outside the axes: at their right (maps), or below them (a study's panels,
    whose labels are long), so that it covers no data."""
    if below:
        ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.13), fontsize="small", ncol=2)
    else:
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small")


def plot_map(map: Map, ax: Any = None) -> Any:
    """Draws ``map`` in metres at equal scale."""
    ax, patches = _draw_map(map, ax)
    _legend(ax, patches)
    return ax


def _agent_paths(plan: Any) -> list[npt.NDArray[np.float64]]:
    if isinstance(plan, (list, tuple)) and len(plan) > 0 and np.ndim(plan[0]) == 2:
        return [np.asarray(p, dtype=np.float64) for p in plan]
    return [np.asarray(plan, dtype=np.float64)]


def plot_plan(map: Map, plan: Any, ax: Any = None, title: Optional[str] = None) -> Any:
    """Draws ``map`` and ``plan`` (an ``(N, 2)`` array of metres, or one per agent) over it."""
    ax, patches = _draw_map(map, ax)
    return _draw_paths(ax, _agent_paths(plan), patches, title)


def _draw_paths(
    ax: Any, paths: list[npt.NDArray[np.float64]], patches: list[Any], title: Optional[str], lw: float = 1.2
) -> Any:
    handles: list[Any] = []
    for k, p in enumerate(paths):
        if len(p) == 0:
            continue
        name = "path" if len(paths) == 1 else f"robot {k}"
        (line,) = ax.plot(p[:, 0], p[:, 1], lw=lw, label=name)
        (start,) = ax.plot(p[0, 0], p[0, 1], "o", color=line.get_color(), label=f"{name} start")
        (end,) = ax.plot(p[-1, 0], p[-1, 1], "s", mfc="none", color=line.get_color(), label=f"{name} end")
        handles += [line, start, end]
    if title is not None:
        ax.set_title(title)
    _legend(ax, handles + patches)
    return ax


def plot_coverage(
    map: Map, visits: Any, plan: Any = None, ax: Any = None, title: Optional[str] = None
) -> Any:
    """Draws the cells a plan swept, as ``covga run``'s path figures colour them (free cells
    never, once and 2+ times covered; occupied and unknown cells), with the ``plan`` over them
    when given. ``visits`` is ``score(..., raster=True)["visits"]``: a ``(rows, cols)`` array
    of sweeps per cell, row 0 at the bottom."""
    from matplotlib.patches import Patch

    counts = np.asarray(visits)
    if counts.shape != map.shape:
        raise ConfigError(f"visits of shape {counts.shape}: expected the map's {map.shape} (rows, cols)")
    states = map.states
    classes = {
        "occupied": states == 1,
        "unknown": states == 2,
        "free, not covered": (states == 0) & (counts == 0),
        "covered once": (states == 0) & (counts == 1),
        "covered 2+ times": (states == 0) & (counts >= 2),
    }
    image = np.zeros(counts.shape + (3,), dtype=np.uint8)
    for name, cells in classes.items():
        image[cells] = _CELL_COLOURS[name]
    ax = _axes(ax)
    ax.imshow(image[::-1], extent=map.extent, interpolation="nearest")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(map.name if title is None else title)
    patches = [
        Patch(facecolor=_rgb(_CELL_COLOURS[name]), edgecolor="black", label=name)
        for name, cells in classes.items()
        if cells.any()
    ]
    if plan is None:
        _legend(ax, patches)
        return ax
    return _draw_paths(ax, _agent_paths(plan), patches, title, lw=0.6)


def _rgb(colour: tuple[int, int, int]) -> tuple[float, float, float]:
    r, g, b = colour
    return (r / 255, g / 255, b / 255)


def _groups(runs: Any, by: Optional[str]) -> list[tuple[str, list[str]]]:
    """``(label, run ids)`` per value of column ``by`` of a study's runs (one group: all)."""
    ids = [str(i) for i in np.asarray(runs["run_id"])]
    if by is None:
        return [("all runs", ids)]
    if by not in runs:
        raise ConfigError(f"by = {by!r} is not a column of the study's runs.csv")
    values = [str(v) for v in np.asarray(runs[by])]
    return [(f"{by} = {v}", [i for i, w in zip(ids, values) if w == v]) for v in sorted(set(values))]


def plot_curves(
    study: Union[str, "os.PathLike[str]"],
    by: Optional[str] = None,
    column: str = "best_coverage_reach",
    x: str = "evaluations",
    ax: Any = None,
) -> Any:
    """A study's convergence: for each value of ``by`` (a column of ``runs.csv``), the median
    over its runs of ``column`` of their ``history.csv`` against ``x`` (the first run's values;
    every run of a group shares them when the budget does), with the band between the quartiles.
    Runs without a history (patterns) are left out."""
    folder = Path(study)
    runs = read_study(folder)
    ax = _axes(ax)
    for label, ids in _groups(runs, by):
        histories = [folder / "runs" / i / "history.csv" for i in ids]
        tables = [read_table(h) for h in histories if h.is_file()]
        if not tables:
            continue
        if column not in tables[0] or x not in tables[0]:
            raise ConfigError(f"{histories[0]}: no column {column!r} or {x!r}")
        n = min(len(np.asarray(t[column])) for t in tables)
        ys = np.array([np.asarray(t[column], dtype=np.float64)[:n] for t in tables])
        xs = np.asarray(tables[0][x], dtype=np.float64)[:n]
        q1, median, q3 = np.percentile(ys, [25, 50, 75], axis=0)
        (line,) = ax.plot(xs, median, label=f"{label} (median of {len(tables)})")
        ax.fill_between(xs, q1, q3, color=line.get_color(), alpha=0.2, label=f"{label}, quartiles")
    ax.set_xlabel(x)
    ax.set_ylabel(column)
    _legend(ax, ax.get_legend_handles_labels()[0], below=True)
    return ax


def _front(points: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """The non-dominated points (both coordinates maximised), by the first coordinate."""
    order = np.lexsort((-points[:, 1], -points[:, 0]))
    kept, best_y = [], -np.inf
    for i in order:
        if points[i, 1] > best_y:
            kept.append(i)
            best_y = points[i, 1]
    return points[kept][::-1]


def plot_fronts(study: Union[str, "os.PathLike[str]"], by: Optional[str] = None, ax: Any = None) -> Any:
    """A thesis study's final fronts in 003's objectives (``cov_final``, ``t_final``, both
    maximised): for each run, the non-dominated members of its final population that sweep no
    obstacle cell (``population.csv``) as a step line, coloured by the value of ``by``; each
    run's returned plan (``runs.csv``) as a marker."""
    folder = Path(study)
    runs = read_study(folder)
    ax = _axes(ax)
    cov, t = np.asarray(runs["cov_final_free"], dtype=np.float64), np.asarray(runs["t_final"], dtype=np.float64)
    ids = [str(i) for i in np.asarray(runs["run_id"])]
    for k, (label, group) in enumerate(_groups(runs, by)):
        colour = f"C{k % 10}"
        drawn = False
        for i in group:
            path = folder / "runs" / i / "population.csv"
            if not path.is_file():
                continue
            pop = read_table(path)
            clear = np.asarray(pop["obstacle_cells"]) == 0
            points = np.column_stack([np.asarray(pop["cov_final"])[clear], np.asarray(pop["t_final"])[clear]])
            if len(points):
                front = _front(points.astype(np.float64))
                ax.step(front[:, 0], front[:, 1], where="post", color=colour, lw=0.8, alpha=0.6,
                        label=None if drawn else f"{label}: final fronts")
                drawn = True
        rows = [ids.index(i) for i in group]
        ax.plot(cov[rows], t[rows], "o", color=colour, mfc="none", label=f"{label}: returned plans")
    ax.set_xlabel("cov_final (003 eq. 3.6)")
    ax.set_ylabel("t_final (003 eq. 3.10)")
    _legend(ax, ax.get_legend_handles_labels()[0], below=True)
    return ax
