"""Writes tests/fixtures/stats-reference.json: reference values of covga's statistics
(`covga::stats`) computed by scipy, for the Rust test `tests/it/stats_reference.rs`, which has no
Python at hand. Run from the repository root when a case is added:

    target/python-venv/bin/python python/tests/make_stats_fixtures.py

The cases are seeded, so the file is the same on every run with the same scipy; it records
scipy's version. `python/tests/test_stats.py` checks the same functions against scipy live.
"""

import json

import numpy as np
import scipy
from scipy import stats


def rank_sum(x, y):
    pooled = stats.rankdata(np.concatenate([x, y]))
    return pooled[: len(x)].sum()


def w_plus(x, y):
    d = np.asarray(x) - np.asarray(y)
    d = d[d != 0]
    r = stats.rankdata(np.abs(d))
    return r[d > 0].sum()


def cases():
    rng = np.random.default_rng(2026)
    out = {"scipy": scipy.__version__, "mann_whitney": [], "wilcoxon": [], "kruskal": [], "sign": []}
    for n1, n2, ties in [(3, 4, False), (5, 10, False), (8, 8, False), (10, 10, False), (4, 6, True),
                         (7, 5, True), (20, 25, False), (30, 30, False), (30, 30, True)]:
        x = rng.integers(0, 6, n1).astype(float) if ties else rng.normal(0.0, 1.0, n1).round(6)
        y = rng.integers(1, 7, n2).astype(float) if ties else rng.normal(0.8, 1.0, n2).round(6)
        if n1 + n2 > 50:
            p = stats.mannwhitneyu(x, y, method="asymptotic", use_continuity=True).pvalue
        elif not ties:
            p = stats.mannwhitneyu(x, y, method="exact").pvalue
        else:
            p = stats.permutation_test((x, y), rank_sum, permutation_type="independent",
                                       n_resamples=np.inf, alternative="two-sided").pvalue
        u = stats.mannwhitneyu(x, y, method="asymptotic").statistic
        out["mann_whitney"].append({"a": x.tolist(), "b": y.tolist(), "u": float(u), "p": float(p)})
    for n, ties in [(6, False), (10, False), (15, False), (8, True), (12, True), (60, False), (80, True)]:
        x = rng.integers(0, 5, n).astype(float) if ties else rng.normal(0.3, 1.0, n).round(6)
        y = rng.integers(0, 5, n).astype(float) if ties else rng.normal(0.0, 1.0, n).round(6)
        nonzero = int(np.sum(x != y))
        if nonzero > 50:
            p = stats.wilcoxon(x, y, method="approx", correction=False).pvalue
        elif not ties:
            p = stats.wilcoxon(x, y, method="exact").pvalue
        else:
            p = stats.permutation_test((x, y), w_plus, permutation_type="samples",
                                       n_resamples=np.inf, alternative="two-sided").pvalue
        out["wilcoxon"].append({"a": x.tolist(), "b": y.tolist(), "w_plus": float(w_plus(x, y)),
                                "pairs": nonzero, "p": float(p)})
    for sizes in [(5, 5, 5), (3, 8, 6, 4), (10, 12)]:
        groups = [rng.integers(0, 9, k).astype(float).tolist() for k in sizes]
        h, p = stats.kruskal(*groups)
        out["kruskal"].append({"groups": groups, "h": float(h), "p": float(p)})
    for k, n in [(0, 5), (2, 10), (5, 10), (9, 20)]:
        out["sign"].append({"above": k, "below": n - k, "p": float(stats.binomtest(k, n, 0.5).pvalue)})
    return out


if __name__ == "__main__":
    with open("tests/fixtures/stats-reference.json", "w") as f:
        json.dump(cases(), f, indent=1)
        f.write("\n")
