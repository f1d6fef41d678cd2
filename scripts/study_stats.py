"""Statistics shared by the study summary scripts: CSV reading, medians with quartiles, the
Mann-Whitney U test with Vargha and Delaney's A12, and short map names."""

import csv
import math
import os
import statistics


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def median_iqr(xs, digits):
    xs = sorted(xs)
    if not xs:
        return "–"
    q = statistics.quantiles(xs, n=4, method="inclusive") if len(xs) > 1 else [xs[0]] * 3
    f = f"{{:.{digits}f}}"
    return f"{f.format(q[1])} [{f.format(q[0])}, {f.format(q[2])}]"


def mann_whitney(a, b):
    """Two-sided p of the Mann-Whitney U test (normal approximation) and A12 = P(a < b)."""
    n1, n2 = len(a), len(b)
    pooled = sorted([(x, 0) for x in a] + [(x, 1) for x in b])
    ranks = [0.0] * len(pooled)
    ties = 0.0
    i = 0
    while i < len(pooled):
        j = i
        while j + 1 < len(pooled) and pooled[j + 1][0] == pooled[i][0]:
            j += 1
        for k in range(i, j + 1):
            ranks[k] = (i + j) / 2 + 1
        t = j - i + 1
        ties += t ** 3 - t
        i = j + 1
    r1 = sum(r for r, (_, g) in zip(ranks, pooled) if g == 0)
    u1 = r1 - n1 * (n1 + 1) / 2
    mean = n1 * n2 / 2
    n = n1 + n2
    var = n1 * n2 / 12 * ((n + 1) - ties / (n * (n - 1)))
    if var <= 0:
        p = 1.0
    else:
        z = (abs(u1 - mean) - 0.5) / math.sqrt(var)
        p = math.erfc(max(z, 0.0) / math.sqrt(2))
    less = sum(1.0 if x < y else 0.5 if x == y else 0.0 for x in a for y in b)
    return p, less / (n1 * n2)


def map_name(source):
    return os.path.splitext(os.path.basename(source))[0]
