"""The statistics of ``covga report``, for notebooks: the same Rust code (``covga::stats``), so a
number computed here is the number a committed summary prints.

Every test is two-sided. Rank tests use mid-ranks for ties and are exact for small samples
(at most 50 values in all for :func:`mann_whitney`, 50 non-tied pairs for :func:`wilcoxon`),
conditionally on the ties; larger samples use the normal approximation. Each result says
which (``method``). :func:`a12` counts in one direction, written in its name: the probability
that a value of ``a`` exceeds one of ``b``.

>>> from covga import stats
>>> stats.mann_whitney([1, 2, 3], [4, 5, 6])["p_value"]
0.1
"""

from __future__ import annotations

import math
from typing import Any, Optional, Sequence

import numpy as np
import numpy.typing as npt

from . import _covga
from ._arrays import real_numbers
from ._covga import ConfigError

__all__ = [
    "a12",
    "bootstrap_ci",
    "cluster_bootstrap_ci",
    "holm",
    "kruskal_wallis",
    "mann_whitney",
    "sign_test",
    "smallest_p",
    "units_for_effect",
    "wilcoxon",
]


def _sample(value: Any, what: str) -> list[float]:
    """``value`` as a list of finite floats, or a ``ConfigError`` naming ``what``."""
    try:
        real_numbers(value, what, "numbers")
        a = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise ConfigError(f"{what}: not an array of numbers ({e})") from None
    if a.ndim != 1:
        raise ConfigError(f"{what}: shape {a.shape}, expected a one-dimensional sample")
    if not np.all(np.isfinite(a)):
        raise ConfigError(f"{what}: holds NaN or infinite values; drop or impute them first")
    values: list[float] = a.tolist()
    return values


def _paired(a: Any, b: Any) -> tuple[list[float], list[float]]:
    x, y = _sample(a, "a"), _sample(b, "b")
    if len(x) != len(y):
        raise ConfigError(f"b: {len(y)} values for the {len(x)} of a; paired samples have one each")
    return x, y


def mann_whitney(a: Sequence[float], b: Sequence[float]) -> Optional[dict[str, Any]]:
    """Two-sided Mann–Whitney U test of independent samples: ``{"u", "p_value", "method"}``
    (``u`` counts the pairs with ``a > b``, ties half), or ``None`` when every value is tied."""
    a, b = _sample(a, "a"), _sample(b, "b")
    if not a or not b:
        raise ConfigError("a and b: each sample needs at least one value")
    out = _covga.stats_mann_whitney(a, b)
    return None if out is None else dict(zip(("u", "p_value", "method"), out))


def wilcoxon(a: Sequence[float], b: Sequence[float]) -> Optional[dict[str, Any]]:
    """Two-sided Wilcoxon signed-rank test of pairs ``(a[i], b[i])`` (for example the same seed
    under two settings): ``{"w_plus", "pairs", "p_value", "method"}``; tied pairs are dropped
    (``pairs`` counts the rest). ``None`` when every pair ties."""
    a, b = _paired(a, b)
    out = _covga.stats_wilcoxon(a, b)
    return None if out is None else dict(zip(("w_plus", "pairs", "p_value", "method"), out))


def sign_test(a: Sequence[float], b: Optional[Sequence[float]] = None, *, against: float = 0.0) -> Optional[float]:
    """Two-sided exact sign test: of the pairs ``a[i] − b[i]`` against 0 when ``b`` is given,
    else of ``a`` against the constant ``against``. Ties are dropped; ``None`` when all tie."""
    if b is None:
        if isinstance(against, bool) or not isinstance(against, (int, float, np.integer, np.floating)):
            raise ConfigError(f"against = {against!r}: expected a number")
        return _covga.stats_sign_test(_sample(a, "a"), float(against))
    a, b = _paired(a, b)
    return _covga.stats_sign_test([x - y for x, y in zip(a, b)], 0.0)


def a12(a: Sequence[float], b: Sequence[float]) -> float:
    """Vargha–Delaney A₁₂: P(a > b) + ½ P(a = b) over all pairs (0.5: no effect)."""
    a, b = _sample(a, "a"), _sample(b, "b")
    if not a or not b:
        raise ConfigError("a and b: each sample needs at least one value")
    return _covga.stats_a12(a, b)


def holm(p_values: Sequence[float]) -> npt.NDArray[np.float64]:
    """Holm–Bonferroni adjusted p-values of one family of tests, in the input order."""
    p = _sample(p_values, "p_values")
    if any(x < 0.0 or x > 1.0 for x in p):
        raise ConfigError("p_values: every p-value lies in [0, 1]")
    return np.asarray(_covga.stats_holm(p))


def kruskal_wallis(*groups: Sequence[float]) -> Optional[dict[str, Any]]:
    """Kruskal–Wallis test of k independent groups: ``{"h", "df", "p_value", "epsilon_squared"}``,
    or ``None`` with fewer than two non-empty groups or every value tied."""
    samples = [_sample(g, f"groups[{i}]") for i, g in enumerate(groups)]
    out = _covga.stats_kruskal_wallis(samples)
    return None if out is None else dict(zip(("h", "df", "p_value", "epsilon_squared"), out))


def bootstrap_ci(
    a: Sequence[float],
    b: Sequence[float],
    contrast: str = "median_difference",
    *,
    paired: bool = False,
    level: float = 0.95,
    resamples: int = 10_000,
    seed: int = 0,
) -> Optional[dict[str, Any]]:
    """Percentile bootstrap interval of ``median(a) − median(b)`` (``contrast =
    "median_difference"``) or ``median(a) / median(b)`` (``"median_ratio"``): ``{"estimate",
    "low", "high"}``. With ``paired`` a resample keeps each pair together. Seeded: the same
    inputs and seed give the same interval. ``None`` for a ratio whose ``b`` is not positive."""
    if contrast not in ("median_difference", "median_ratio"):
        raise ConfigError(f'contrast = {contrast!r}: expected "median_difference" or "median_ratio"')
    if not isinstance(paired, (bool, np.bool_)):
        raise ConfigError(f"paired = {paired!r}: expected True or False")
    a, b = _paired(a, b) if paired else (_sample(a, "a"), _sample(b, "b"))
    if not a or not b:
        raise ConfigError("a and b: each sample needs at least one value")
    if isinstance(level, bool) or not isinstance(level, (int, float)) or not (0.0 < level < 1.0) or math.isnan(level):
        raise ConfigError(f"level = {level!r}: expected a number in (0, 1)")
    for name, value, low, high in (("resamples", resamples, 1, 10**8), ("seed", seed, 0, 2**64 - 1)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not (low <= value <= high):
            raise ConfigError(f"{name} = {value!r}: expected a whole number in [{low}, {high}]")
    out = _covga.stats_bootstrap_ci(a, b, contrast, bool(paired), float(level), int(resamples), int(seed))
    return None if out is None else dict(zip(("estimate", "low", "high"), out))


def _count(value: Any, name: str, low: int, high: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not (low <= value <= high):
        raise ConfigError(f"{name} = {value!r}: expected a whole number in [{low}, {high}]")
    return int(value)


def _probability(value: Any, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or math.isnan(value) or not (0.0 < value < 1.0):
        raise ConfigError(f"{name} = {value!r}: expected a number in (0, 1)")
    return float(value)


def cluster_bootstrap_ci(
    clusters: Sequence[Sequence[float]], *, level: float = 0.95, resamples: int = 10_000, seed: int = 0
) -> Optional[dict[str, Any]]:
    """Percentile bootstrap interval of the median of clustered values, each resample drawing
    whole clusters with replacement (``covga report --compare`` resamples its units so: the pairs
    of one stratum or floor plan never count as independent): ``{"estimate", "low", "high"}``.
    Seeded. ``None`` for an empty cluster."""
    if isinstance(clusters, (str, bytes)) or len(clusters) == 0:
        raise ConfigError("clusters: expected a non-empty list of lists of numbers")
    values = [_sample(c, f"clusters[{i}]") for i, c in enumerate(clusters)]
    level = _probability(level, "level")
    resamples = _count(resamples, "resamples", 1, 10**8)
    seed = _count(seed, "seed", 0, 2**64 - 1)
    out = _covga.stats_cluster_bootstrap_ci(values, level, resamples, seed)
    return None if out is None else dict(zip(("estimate", "low", "high"), out))


def smallest_p(units: int, tests: int = 1) -> float:
    """The smallest p a family of ``tests`` paired comparisons of ``units`` units each can reach
    after Holm's correction: every unit pointing one way gives the exact signed-rank p
    ``2 · 2⁻ⁿ``, and Holm multiplies the smallest by the family's size. Above 0.05, the design
    cannot show anything at that level."""
    return _covga.stats_smallest_p(_count(units, "units", 0, 10**9), _count(tests, "tests", 1, 10**9))


def units_for_effect(d: float, *, alpha: float = 0.05, power: float = 0.8, tests: int = 1) -> Optional[int]:
    """Units a paired comparison needs to show a standardised effect ``d`` (mean over standard
    deviation of the unit effects) with probability ``power``, in a family of ``tests`` tests
    corrected by Holm (planned for Bonferroni's worst case): the normal approximation divided
    by the signed-rank test's efficiency 3/π, and never fewer than the design needs to reach
    ``alpha`` at all. ``None`` for ``d`` ≤ 0."""
    if isinstance(d, bool) or not isinstance(d, (int, float)) or math.isnan(d):
        raise ConfigError(f"d = {d!r}: expected a number")
    return _covga.stats_units_for_effect(
        float(d), _probability(alpha, "alpha"), _probability(power, "power"), _count(tests, "tests", 1, 10**9)
    )
