"""The thesis GA's fitness (003 eqs. 3.1-3.16) for genomes made outside covga.

A genome is its live actions: an ``(L, 2)`` array of (heading in degrees from +x, distance in
metres), S's move first. Each is decoded as the GA decodes its own (moves that leave the map
are clamped, 003 eqs. 3.7-3.8), joined to the end station by the connector, and scored with
the GA's fitness, so a pymoo or DEAP population is compared with covga's GA on equal terms.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Optional, Sequence, Union

import numpy as np

from . import _covga
from ._arrays import real_numbers, rows_of_pairs
from ._covga import ConfigError

#: The columns of :func:`evaluate`'s result.
COLUMNS = tuple(_covga.THESIS_COLUMNS)


def _genomes(genomes: Any) -> Any:
    """An ``(n, L, 2)`` float array as it is, else a list of ``(L, 2)`` float arrays."""
    if isinstance(genomes, np.ndarray) and genomes.ndim == 3:
        real_numbers(genomes, "genomes", "numbers (heading in degrees, distance in metres)")
        return np.asarray(genomes, dtype=np.float64)
    if isinstance(genomes, np.ndarray) and genomes.ndim == 2:
        raise ConfigError(
            f"genomes of shape {genomes.shape}: expected (n, L, 2), or a list of (L, 2) arrays; "
            "for one genome, pass [genome]"
        )
    unit = "numbers (heading in degrees, distance in metres)"
    return [rows_of_pairs(g, f"genome {i}", "L", unit) for i, g in enumerate(genomes)]


def evaluate(
    map: Any,
    genomes: Any,
    width: float = 0.6,
    speed: float = 0.2,
    rot_speed: float = 0.0,
    start: Sequence[float] = (1.3, 1.3),
    end: Optional[Sequence[float]] = None,
    projection: str = "f2",
    moves: str = "straight",
    threads: Optional[int] = None,
) -> np.ndarray:
    """Scores a batch of genomes with the thesis GA's fitness, in parallel in Rust.

    ``genomes``: an ``(n, L, 2)`` array or a list of ``(L_i, 2)`` arrays. Returns an ``(n, 4)``
    array with the columns :data:`COLUMNS`: ``cov_final``, ``t_final``, ``f`` (``f_obstacle``
    with ``projection``, maximised) and ``obstacle_cells`` (0 for a plan that stays in free
    space). ``end`` defaults to ``start``. ``moves``: ``"straight"`` (003) or ``"routed"`` (a move
    that would sweep an obstacle drives around it, as ``thesis.moves = "routed"``). ``threads``:
    worker threads (default one per CPU, or ``RAYON_NUM_THREADS``); the scores do not depend on it.
    """
    from . import _number, _point, _threads, load_map

    s = _point(start, "start")
    e = None if end is None else _point(end, "end")
    return _covga.thesis_evaluate(
        load_map(map),
        _genomes(genomes),
        _number(width, "width"),
        _number(speed, "speed"),
        _number(rot_speed, "rot_speed"),
        s,
        e,
        projection,
        moves,
        _threads(threads),
    )


def decode(
    map: Any,
    genome: Any,
    width: float = 0.6,
    start: Sequence[float] = (1.3, 1.3),
    end: Optional[Sequence[float]] = None,
    moves: str = "straight",
) -> np.ndarray:
    """The path a genome drives, as an ``(N, 2)`` array of metres: ``genome`` (an ``(L, 2)``
    array of live moves, as :func:`evaluate` takes them) decoded as the GA decodes its own
    (moves leaving the map clamped, 003 eqs. 3.7-3.8, the connector aimed at ``end``), joined
    by straight or routed ``moves``; for a run's best genome, its ``best_path.csv``."""
    from . import _number, _point, load_map

    s = _point(start, "start")
    e = None if end is None else _point(end, "end")
    g = rows_of_pairs(genome, "genome", "L", "numbers (heading in degrees, distance in metres)")
    return _covga.thesis_decode(load_map(map), g, _number(width, "width"), s, e, moves)


def read_population_genomes(run_dir: Union[str, "os.PathLike[str]"]) -> list[np.ndarray]:
    """The genomes of a thesis run's final population (``population_genomes.csv``, written with
    ``output.population_genomes = true``), one ``(L, 2)`` array of live moves per member in the
    order of ``population.csv``."""
    path = Path(run_dir) / "population_genomes.csv"
    if not path.is_file():
        raise ConfigError(f"{run_dir}: no population_genomes.csv (a thesis run with output.population_genomes = true writes one)")
    table = np.atleast_2d(np.loadtxt(path, delimiter=",", skiprows=1, dtype=np.float64))
    if table.size == 0:
        return []
    member = table[:, 0].astype(np.int64)
    cuts = np.flatnonzero(np.diff(member)) + 1
    return [np.ascontiguousarray(rows[:, 2:4]) for rows in np.split(table, cuts)]


def read_genome(run_dir: Union[str, "os.PathLike[str]"]) -> np.ndarray:
    """The live actions of a thesis run's best genome (``best_genome.csv``: the start's move
    and every action, without the connector and the end) as an ``(L, 2)`` array."""
    path = Path(run_dir) / "best_genome.csv"
    if not path.is_file():
        raise ConfigError(f"{run_dir}: no best_genome.csv (only thesis runs write one)")
    table = np.atleast_1d(np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding="utf-8"))
    live = np.isin(table["role"], ["start", "action"])
    return np.column_stack([table["alpha_deg"][live], table["dist_m"][live]]).astype(np.float64)
