"""covga.stats against scipy (and statsmodels for Holm), live: the statistics every covga report
prints, checked against an established package on seeded samples."""

import math

import numpy as np
import pytest
from scipy import stats as sp

import covga
from covga import stats

statsmodels = pytest.importorskip("statsmodels.stats.multitest")


def rank_sum(x, y):
    return sp.rankdata(np.concatenate([x, y]))[: len(x)].sum()


def w_plus(x, y):
    d = np.asarray(x) - np.asarray(y)
    d = d[d != 0]
    r = sp.rankdata(np.abs(d))
    return r[d > 0].sum()


@pytest.mark.parametrize("n1,n2", [(2, 3), (4, 4), (5, 10), (9, 7), (12, 13)])
def test_mann_whitney_is_scipys_exact_test_without_ties(n1, n2):
    rng = np.random.default_rng(n1 * 100 + n2)
    x, y = rng.normal(0, 1, n1), rng.normal(0.7, 1, n2)
    got = stats.mann_whitney(x, y)
    want = sp.mannwhitneyu(x, y, method="exact")
    assert got["method"] == "exact"
    assert got["u"] == pytest.approx(want.statistic, rel=1e-12)
    assert got["p_value"] == pytest.approx(want.pvalue, rel=1e-9)
    assert stats.a12(x, y) == pytest.approx(want.statistic / (n1 * n2), rel=1e-12)


@pytest.mark.parametrize("n1,n2", [(3, 4), (6, 6), (8, 5)])
def test_mann_whitney_with_ties_is_the_exact_permutation_test(n1, n2):
    rng = np.random.default_rng(n1 + 7 * n2)
    x, y = rng.integers(0, 4, n1).astype(float), rng.integers(1, 5, n2).astype(float)
    want = sp.permutation_test((x, y), rank_sum, permutation_type="independent", n_resamples=np.inf)
    got = stats.mann_whitney(x, y)
    assert got["method"] == "exact"
    assert got["p_value"] == pytest.approx(want.pvalue, rel=1e-9)


def test_mann_whitney_beyond_fifty_values_is_the_normal_approximation():
    rng = np.random.default_rng(3)
    x, y = rng.integers(0, 20, 30).astype(float), rng.integers(3, 23, 31).astype(float)
    got = stats.mann_whitney(x, y)
    want = sp.mannwhitneyu(x, y, method="asymptotic", use_continuity=True)
    assert got["method"] == "normal"
    assert got["p_value"] == pytest.approx(want.pvalue, rel=1e-9)


@pytest.mark.parametrize("n", [5, 10, 20])
def test_wilcoxon_is_scipys_exact_test_without_ties(n):
    rng = np.random.default_rng(n)
    x, y = rng.normal(0.4, 1, n), rng.normal(0, 1, n)
    got = stats.wilcoxon(x, y)
    want = sp.wilcoxon(x, y, method="exact")
    assert got["method"] == "exact" and got["pairs"] == n
    assert min(got["w_plus"], n * (n + 1) / 2 - got["w_plus"]) == pytest.approx(want.statistic)
    assert got["p_value"] == pytest.approx(want.pvalue, rel=1e-9)


def test_wilcoxon_with_ties_and_zeros_is_the_exact_permutation_test():
    rng = np.random.default_rng(11)
    x, y = rng.integers(0, 4, 12).astype(float), rng.integers(0, 4, 12).astype(float)
    assert np.any(x == y)
    want = sp.permutation_test((x, y), w_plus, permutation_type="samples", n_resamples=np.inf)
    got = stats.wilcoxon(x, y)
    assert got["pairs"] == int(np.sum(x != y))
    assert got["p_value"] == pytest.approx(want.pvalue, rel=1e-9)


def test_wilcoxon_beyond_fifty_pairs_is_the_normal_approximation():
    rng = np.random.default_rng(5)
    x, y = rng.integers(0, 9, 70).astype(float), rng.integers(0, 8, 70).astype(float)
    got = stats.wilcoxon(x, y)
    want = sp.wilcoxon(x, y, method="approx", correction=False)
    assert got["method"] == "normal"
    assert got["p_value"] == pytest.approx(want.pvalue, rel=1e-9)


def test_sign_test_kruskal_wallis_and_holm_agree_with_the_reference_packages():
    a = np.array([3.0, 5, 2, 8, 9, 4, 7, 7, 6, 10])
    b = np.array([1.0, 5, 3, 2, 4, 1, 2, 3, 5, 6])
    d = a - b
    k, n = int(np.sum(d > 0)), int(np.sum(d != 0))
    assert stats.sign_test(a, b) == pytest.approx(sp.binomtest(k, n, 0.5).pvalue, rel=1e-12)
    above = int(np.sum(a > 5.5))
    assert stats.sign_test(a, against=5.5) == pytest.approx(sp.binomtest(above, 10, 0.5).pvalue, rel=1e-12)
    groups = ([1.0, 3, 3, 5, 7], [2.0, 4, 6, 6], [5.0, 8, 9, 9, 9, 10])
    got = stats.kruskal_wallis(*groups)
    want = sp.kruskal(*groups)
    assert got["h"] == pytest.approx(want.statistic, rel=1e-12)
    assert got["p_value"] == pytest.approx(want.pvalue, rel=1e-9)
    p = [0.01, 0.04, 0.03, 0.2, 0.005]
    np.testing.assert_allclose(stats.holm(p), statsmodels.multipletests(p, method="holm")[1], rtol=1e-12)


@pytest.mark.parametrize("contrast", ["median_difference", "median_ratio"])
def test_bootstrap_intervals_match_scipys_percentile_bootstrap(contrast):
    rng = np.random.default_rng(8)
    a, b = rng.gamma(4, 2, 25) + 1, rng.gamma(3, 2, 30) + 1
    def stat(x, y, axis=-1):
        mx, my = np.median(x, axis=axis), np.median(y, axis=axis)
        return mx - my if contrast == "median_difference" else mx / my

    want = sp.bootstrap((a, b), stat, method="percentile", n_resamples=20000, rng=1).confidence_interval
    got = stats.bootstrap_ci(a, b, contrast, resamples=20000, seed=1)
    width = want.high - want.low
    assert got["estimate"] == pytest.approx(stat(a, b))
    # Two generators, one distribution: the ends agree to a few percent of the width.
    assert abs(got["low"] - want.low) < 0.08 * width and abs(got["high"] - want.high) < 0.08 * width
    assert stats.bootstrap_ci(a, b, contrast, resamples=20000, seed=1) == got


def test_paired_bootstrap_keeps_pairs_together():
    a = np.arange(20.0)
    got = stats.bootstrap_ci(a, a + 1.0, paired=True, resamples=500, seed=3)
    assert (got["estimate"], got["low"], got["high"]) == (-1.0, -1.0, -1.0)


@pytest.mark.parametrize(
    "call,message",
    [
        (lambda: stats.mann_whitney([1, float("nan")], [2, 3]), "a: holds NaN"),
        (lambda: stats.mann_whitney([[1, 2]], [2, 3]), "a: shape (1, 2)"),
        (lambda: stats.mann_whitney([], [2, 3]), "each sample needs"),
        (lambda: stats.wilcoxon([1, 2], [1, 2, 3]), "b: 3 values for the 2 of a"),
        (lambda: stats.a12([True, False], [1.0]), "a: an array of booleans"),
        (lambda: stats.holm([0.5, 1.5]), "p_values: every p-value lies in [0, 1]"),
        (lambda: stats.bootstrap_ci([1, 2], [1, 2], "mean"), "contrast = 'mean'"),
        (lambda: stats.bootstrap_ci([1, 2], [1, 2], level=1.0), "level = 1.0"),
        (lambda: stats.bootstrap_ci([1, 2], [1, 2], resamples=0), "resamples = 0"),
        (lambda: stats.bootstrap_ci([1, 2], [1, 2], seed=-1), "seed = -1"),
        (lambda: stats.kruskal_wallis([1, 2], ["x"]), "groups[1]: not an array of numbers"),
    ],
)
def test_bad_samples_are_refused_with_the_argument_named(call, message):
    with pytest.raises(covga.ConfigError) as e:
        call()
    assert message in str(e.value)


def test_constant_samples_are_not_tested():
    assert stats.mann_whitney([2, 2, 2], [2, 2]) is None
    assert stats.wilcoxon([1, 2, 3], [1, 2, 3]) is None
    assert stats.sign_test([4, 4], against=4) is None


def test_smallest_p_is_scipys_exact_extreme_times_the_family():
    for n in (4, 8, 10, 16):
        extreme = sp.wilcoxon(np.arange(1, n + 1) + 0.5, method="exact").pvalue
        for tests in (1, 3, 126):
            assert stats.smallest_p(n, tests) == pytest.approx(min(1.0, extreme * tests), rel=1e-12)


@pytest.mark.parametrize("d,tests", [(0.5, 1), (0.8, 3), (0.2, 10), (3.0, 126)])
def test_units_for_an_effect_follow_the_normal_approximation(d, tests):
    z = sp.norm.ppf(1 - 0.05 / tests / 2) + sp.norm.ppf(0.8)
    normal = math.ceil((z / d) ** 2 / (3 / math.pi))
    reach = next(n for n in range(1, 65) if min(1.0, tests * 2 * 0.5**n) <= 0.05)
    assert stats.units_for_effect(d, tests=tests) == max(normal, reach)
    assert stats.units_for_effect(-d, tests=tests) is None


def test_cluster_bootstrap_resamples_whole_clusters_as_numpy_does():
    rng = np.random.default_rng(11)
    clusters = [rng.normal(k, 0.3, size=int(rng.integers(3, 8))) for k in range(12)]
    got = stats.cluster_bootstrap_ci([list(c) for c in clusters], resamples=20000, seed=2)
    draws = np.random.default_rng(5).integers(0, len(clusters), size=(20000, len(clusters)))
    medians = [np.median(np.concatenate([clusters[i] for i in row])) for row in draws]
    low, high = np.percentile(medians, [2.5, 97.5])
    assert got["estimate"] == pytest.approx(np.median(np.concatenate(clusters)), rel=1e-12)
    # Two generators, one distribution: the ends agree to a few percent of the width.
    assert abs(got["low"] - low) < 0.08 * (high - low) and abs(got["high"] - high) < 0.08 * (high - low)
    with pytest.raises(covga.ConfigError, match="clusters"):
        stats.cluster_bootstrap_ci([])


def _runs(study):
    import csv
    import lzma

    from conftest import REPO

    folder = REPO / "results" / study
    plain = folder / "runs.csv"
    text = plain.read_text() if plain.exists() else lzma.open(folder / "runs.csv.xz", "rt").read()
    return list(csv.DictReader(text.splitlines())), folder


def _pooled_p(folder, report, stem, value, metric="time_s"):
    import csv

    rows = csv.DictReader((folder / report / f"{stem}.csv").read_text().splitlines())
    row = next(r for r in rows if r["stratum"] == "pooled" and r["value"] == value and r["metric"] == metric)
    return float(row["p"]), int(row["units"])


def test_committed_pooled_tests_are_scipys_over_the_units():
    """The committed comparisons' pooled p, recomputed with scipy from runs.csv: the unit effects
    (median log-ratio of time per unit) and the exact signed-rank test over them."""
    # The seed bound: both sides seeded; pooled over floor plans, the floor plan is the unit
    # (the strata of moves and selection on it together), its effect the median of its pairs.
    runs, folder = _runs("thesis-seed-bound")
    by = {}
    for r in runs:
        key = (r["map.source"], r["thesis.moves"], r["thesis.selection"], r["seed"])
        by.setdefault(key, {})[r["thesis.seed_bound"]] = r
    effects = {}
    for (m, mv, sel, _), sides in by.items():
        b, v = sides.get("none"), sides.get("dominate")
        if b and v and b["executable"] == "true" and v["executable"] == "true":
            plan = m.replace("-noisy.yaml", ".yaml")
            effects.setdefault(plan, []).append(math.log(float(v["time_s"]) / float(b["time_s"])))
    units = [np.median(e) for e in effects.values()]
    want = sp.wilcoxon(units, method="exact").pvalue
    p, n = _pooled_p(folder, "report", "compare-thesis.seed_bound", "dominate")
    assert (p, n) == (pytest.approx(want, rel=1e-12), len(units))
    # The cell-order search against a control that runs once per map and robot: the floor plan
    # (robots and a generated plan's clean and noisy twins together) is the unit.
    runs, folder = _runs("cell-order")
    runs = [r for r in runs if r["planner"] == "cell_order" and r["executable"] == "true"]
    control = {(r["map.source"], r["robot.rot_speed"]): float(r["time_s"]) for r in runs
               if r["cell_order.solver"] == "nearest"}
    effects = {}
    for r in runs:
        if r["cell_order.solver"] == "ils":
            plan = r["map.source"].replace("-noisy.yaml", ".yaml")
            base = control[(r["map.source"], r["robot.rot_speed"])]
            effects.setdefault(plan, []).append(math.log(float(r["time_s"]) / base))
    units = [np.median(e) for e in effects.values()]
    want = sp.wilcoxon(units, method="exact").pvalue
    p, n = _pooled_p(folder, "report-controls", "compare-cell_order.solver-nearest",
                     "ils (cell_order.seed_directions=true) (cell_order.classical_finalists=true)")
    assert (p, n) == (pytest.approx(want, rel=1e-12), len(units))
