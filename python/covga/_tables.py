"""CSV tables of covga (``history.csv``, a study's ``runs.csv``) with typed columns."""

from __future__ import annotations

import csv
import os
from pathlib import Path
from typing import Any, Union

import numpy as np
import numpy.typing as npt

from ._covga import RUNS_COLUMN_KINDS, ConfigError

try:  # pandas is optional: without it, tables are dicts of numpy arrays.
    import pandas as _pd  # type: ignore[import-untyped,unused-ignore]
except ImportError:  # pragma: no cover - exercised only where pandas is missing
    _pd = None  # type: ignore[assignment,unused-ignore]

# What each id and metric column of runs.csv holds, declared by the Rust side: a study reads
# with the same dtypes whatever values it happens to have (a float column whose values are all
# whole stays float, an empty fleet column stays its kind).
_RUNS_KINDS: dict[str, str] = dict(RUNS_COLUMN_KINDS)


def _kind_of(values: list[str]) -> str:
    """The kind a column of another table (a history, a swept key) holds, from its values: flags
    if every present value is true/false, integers if whole, floats if numbers, else text."""
    present = [v for v in values if v != ""]
    if not present:
        return "float"
    if all(v in ("true", "false") for v in present):
        return "flag"
    try:
        for v in present:
            int(v)
        return "integer"
    except ValueError:
        pass
    try:
        for v in present:
            float(v)
        return "float"
    except ValueError:
        return "text"


def _as_array(values: list[str], kind: str) -> npt.NDArray[Any]:
    """One column as numpy: integers as int64 (uint64 for unsigned; float64 with NaN where a
    cell is empty), floats as float64, flags as bool (object with None where a cell is empty),
    text as object."""
    missing = any(v == "" for v in values)
    if kind in ("integer", "unsigned"):
        if missing:
            return np.array([float(v) if v != "" else np.nan for v in values], dtype=np.float64)
        return np.array([int(v) for v in values], dtype=np.uint64 if kind == "unsigned" else np.int64)
    if kind == "float":
        return np.array([float(v) if v != "" else np.nan for v in values], dtype=np.float64)
    if kind == "flag":
        if missing:
            return np.array([None if v == "" else v == "true" for v in values], dtype=object)
        return np.array([v == "true" for v in values], dtype=bool)
    return np.array(values, dtype=object)


def _as_series(values: list[str], kind: str) -> Any:
    """One column as pandas, one dtype per kind whatever the values: nullable ``Int64``
    (``UInt64`` for unsigned), ``float64``, nullable ``boolean``, ``string``."""
    if kind in ("integer", "unsigned"):
        dtype = "UInt64" if kind == "unsigned" else "Int64"
        return _pd.array([int(v) if v != "" else None for v in values], dtype=dtype)
    if kind == "float":
        return np.array([float(v) if v != "" else np.nan for v in values], dtype=np.float64)
    if kind == "flag":
        return _pd.array([None if v == "" else v == "true" for v in values], dtype="boolean")
    return _pd.array(values, dtype="string")


def _columns(path: Path, kinds: dict[str, str]) -> dict[str, tuple[list[str], str]]:
    """Column name to its raw values and kind (`kinds` first, else read off the values); a
    column repeated with the same values is kept once, one repeated with other values gets a
    ``.1`` suffix (as pandas names it)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        raise ConfigError(f"{path}: empty table (no header)")
    header, body = rows[0], rows[1:]
    columns: dict[str, tuple[list[str], str]] = {}
    for i, name in enumerate(header):
        raw = [r[i] if i < len(r) else "" for r in body]
        if name in columns:
            if columns[name][0] == raw:
                continue
            name = f"{name}.1"
        columns[name] = (raw, kinds.get(name) or _kind_of(raw))
    return columns


def _table(path: Path, kinds: dict[str, str]) -> Any:
    columns = _columns(path, kinds)
    if _pd is None:
        return {name: _as_array(raw, kind) for name, (raw, kind) in columns.items()}
    return _pd.DataFrame({name: _as_series(raw, kind) for name, (raw, kind) in columns.items()})


def read_table(path: Union[str, "os.PathLike[str]"]) -> Any:
    """A covga CSV table: a pandas DataFrame when pandas is installed, else a dict of arrays;
    each column typed by what its values hold (see :func:`read_study` for a study's runs)."""
    return _table(Path(path), _ID_KINDS)


# Identifiers that look like numbers now and then (hex ids made only of digits) stay text.
_ID_KINDS = {"run_id": "text", "config_id": "text"}


def read_study(dir: Union[str, "os.PathLike[str]"]) -> Any:
    """The ``runs.csv`` of a study folder, one row per run. Every id and metric column has the
    dtype of what it holds, whatever the study's values: ids and names ``string``, counts
    ``Int64`` (seeds ``UInt64``), metrics ``float64`` (NaN where a planner has none), flags
    ``boolean``, empty cells missing; a swept key's column is typed by its values."""
    path = Path(dir) / "runs.csv"
    if not path.is_file():
        raise ConfigError(f"{dir}: not a study folder with runs (no runs.csv); run covga.grid into it first")
    return _table(path, _RUNS_KINDS)
