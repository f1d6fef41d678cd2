"""covga.stats against scipy (and statsmodels for Holm), live: the statistics every covga report
prints, checked against an established package on seeded samples."""

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
