"""Conversion of the arrays users pass in (paths, genomes) to 2-D float arrays."""

from __future__ import annotations

from typing import Any

import numpy as np

from ._covga import ConfigError


def real_numbers(value: Any, what: str, unit: str) -> None:
    """Refuses (``ConfigError`` naming ``what``) an array of booleans or complex numbers, which a
    conversion to float would turn into 0/1 or strip of their imaginary part without a word."""
    kind = np.asarray(value).dtype.kind if not isinstance(value, np.ndarray) else value.dtype.kind
    if kind in "bc":
        name = "booleans" if kind == "b" else "complex numbers"
        raise ConfigError(f"{what}: an array of {name}, expected real {unit}")


def rows_of_pairs(value: Any, what: str, rows: str, unit: str) -> np.ndarray:
    """``value`` as a float64 ``(rows, 2)`` array, or a ``ConfigError`` naming ``what``."""
    try:
        real_numbers(value, what, unit)
        a = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise ConfigError(f"{what}: not an array of {unit} ({e})") from None
    if a.ndim != 2 or a.shape[1] != 2:
        raise ConfigError(f"{what}: shape {a.shape}, expected ({rows}, 2) {unit}")
    return a
