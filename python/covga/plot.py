"""Pictures of maps and plans with matplotlib (``pip install covga[examples]``): the map in
map_server's greys (free light, occupied black, unknown grey), north up, equal scale, axes in
metres; each agent's path as a line from its start (circle) to its end (open square), every
mark and grey in the legend. Each function draws into ``ax`` (a new figure's when ``None``) and
returns it."""

from __future__ import annotations

from typing import Any, Optional

import numpy as np
import numpy.typing as npt

from ._covga import Map


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


def _legend(ax: Any, handles: list[Any]) -> None:
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small")


def plot_map(map: Map, ax: Any = None) -> Any:
    """Draws ``map`` in metres at equal scale."""
    ax, patches = _draw_map(map, ax)
    _legend(ax, patches)
    return ax


def plot_plan(map: Map, plan: Any, ax: Any = None, title: Optional[str] = None) -> Any:
    """Draws ``map`` and ``plan`` (an ``(N, 2)`` array of metres, or one per agent) over it."""
    ax, patches = _draw_map(map, ax)
    paths: list[npt.NDArray[np.float64]]
    if isinstance(plan, (list, tuple)) and len(plan) > 0 and np.ndim(plan[0]) == 2:
        paths = [np.asarray(p, dtype=np.float64) for p in plan]
    else:
        paths = [np.asarray(plan, dtype=np.float64)]
    handles: list[Any] = []
    for k, p in enumerate(paths):
        if len(p) == 0:
            continue
        name = "path" if len(paths) == 1 else f"robot {k}"
        (line,) = ax.plot(p[:, 0], p[:, 1], lw=1.2, label=name)
        (start,) = ax.plot(p[0, 0], p[0, 1], "o", color=line.get_color(), label=f"{name} start")
        (end,) = ax.plot(p[-1, 0], p[-1, 1], "s", mfc="none", color=line.get_color(), label=f"{name} end")
        handles += [line, start, end]
    if title is not None:
        ax.set_title(title)
    _legend(ax, handles + patches)
    return ax
