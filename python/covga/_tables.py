"""CSV tables of covga (``history.csv``, a study's ``runs.csv``) with typed columns."""

from __future__ import annotations

import csv
import os
from pathlib import Path
from typing import Any, Union

import numpy as np
import numpy.typing as npt

from ._covga import ConfigError

try:  # pandas is optional: without it, tables are dicts of numpy arrays.
    import pandas as _pd  # type: ignore[import-untyped,unused-ignore]
except ImportError:  # pragma: no cover - exercised only where pandas is missing
    _pd = None  # type: ignore[assignment,unused-ignore]

# Identifiers that look like numbers now and then (hex ids made only of digits) stay text.
_TEXT_COLUMNS = ("run_id", "config_id")


def _typed(values: list[str]) -> npt.NDArray[Any]:
    """One column as int64, float64 (empty cells NaN), bool, or text, whichever fits all."""
    present = [v for v in values if v != ""]
    if present and all(v in ("true", "false") for v in present) and len(present) == len(values):
        return np.array([v == "true" for v in values], dtype=bool)
    try:
        if len(present) == len(values):
            return np.array([int(v) for v in values], dtype=np.int64)
    except (ValueError, OverflowError):
        pass
    try:
        return np.array([float(v) if v != "" else np.nan for v in values], dtype=np.float64)
    except ValueError:
        return np.array(values, dtype=object)


def _columns(path: Path) -> dict[str, npt.NDArray[Any]]:
    """Column name to typed array; a column repeated with the same values is kept once, one
    repeated with other values gets a ``.1`` suffix (as pandas names it)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        raise ConfigError(f"{path}: empty table (no header)")
    header, body = rows[0], rows[1:]
    columns: dict[str, npt.NDArray[Any]] = {}
    for i, name in enumerate(header):
        raw = [r[i] if i < len(r) else "" for r in body]
        values = np.array(raw, dtype=object) if name in _TEXT_COLUMNS else _typed(raw)
        if name in columns:
            if np.array_equal(columns[name], values):
                continue
            name = f"{name}.1"
        columns[name] = values
    return columns


def read_table(path: Union[str, "os.PathLike[str]"]) -> Any:
    """A covga CSV table: a pandas DataFrame when pandas is installed, else a dict of arrays."""
    columns = _columns(Path(path))
    if _pd is None:
        return columns
    return _pd.DataFrame(columns)


def read_study(dir: Union[str, "os.PathLike[str]"]) -> Any:
    """The ``runs.csv`` of a study folder, one row per run, with typed columns (ids as text,
    counts as integers, metrics as floats with NaN where a planner has none, flags as bool)."""
    path = Path(dir) / "runs.csv"
    if not path.is_file():
        raise ConfigError(f"{dir}: not a study folder with runs (no runs.csv); run covga.grid into it first")
    return read_table(path)
