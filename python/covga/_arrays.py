"""Conversion of the arrays users pass in (paths, genomes) to 2-D float arrays."""

from __future__ import annotations

from typing import Any

import numpy as np

from ._covga import ConfigError


def rows_of_pairs(value: Any, what: str, rows: str, unit: str) -> np.ndarray:
    """``value`` as a float64 ``(rows, 2)`` array, or a ``ConfigError`` naming ``what``."""
    try:
        a = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise ConfigError(f"{what}: not an array of {unit} ({e})") from None
    if a.ndim != 2 or a.shape[1] != 2:
        raise ConfigError(f"{what}: shape {a.shape}, expected ({rows}, 2) {unit}")
    return a
