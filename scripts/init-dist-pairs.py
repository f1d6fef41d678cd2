#!/usr/bin/env python3
"""Paired comparison of the initial-move lengths of grids/init-dist.toml: for every
configuration of the other parameters, the mean over its executable seeds of cov_final, t_final
and f at each length, and how often one length beats another (two-sided sign test on the
differences); then the executable share and the means per selection scheme and length.
f is a different function under each projection (f1, 003 eq. 3.14; f2, eq. 3.15), so its rows
are per projection. A configuration with no executable run at one of the two lengths is left
out of that comparison, and the table says how many were. With --all-runs every run counts,
executable or not (what the GA optimised, whether a robot can drive its plan or not).
Usage: python3 scripts/init-dist-pairs.py out/init-dist/runs.csv [--all-runs]"""
import csv
import math
import sys
from collections import defaultdict

rows = list(csv.reader(open(sys.argv[1])))
head, body = rows[0], rows[1:]
col = {n: i for i, n in enumerate(head)}  # later duplicates win: the metric `planner`
params = [n for n in head[col["seed"] + 1:] if n.startswith(("thesis.", "map.", "robot."))]
other = [p for p in params if p != "thesis.init_dist_max"]
runs = defaultdict(lambda: defaultdict(list))
for r in body:
    runs[tuple(r[col[p]] for p in other)][r[col["thesis.init_dist_max"]]].append(r)
projection_at = other.index("thesis.projection")


ALL_RUNS = "--all-runs" in sys.argv[2:]


def executable(rs):
    return list(rs) if ALL_RUNS else [r for r in rs if r[col["executable"]] == "true"]


def mean_of(metric, rs, digits):
    return f"{sum(float(r[col[metric]]) for r in rs) / len(rs):.{digits}f}" if rs else "–"


def sign_p(wins, losses):
    n = wins + losses
    k = min(wins, losses)
    return min(1.0, 2 * sum(math.comb(n, i) for i in range(k + 1)) / 2 ** n)


print("| metric | A vs B | configurations compared | left out (no executable run) | A better | B better | mean difference A − B | sign-test p |")
print("|---|---|---|---|---|---|---|---|")
metrics = [("cov_final_free", None), ("t_final", None), ("f_free", "f1"), ("f_free", "f2")]
for metric, projection in metrics:
    for a, b in [("3.0", "10.0"), ("3.0", "50.0"), ("10.0", "50.0")]:
        d, left_out = [], 0
        for key, by_len in runs.items():
            if projection and key[projection_at] != projection:
                continue
            ea, eb = executable(by_len[a]), executable(by_len[b])
            if not ea or not eb:
                left_out += 1
                continue
            m = lambda rs: sum(float(r[col[metric]]) for r in rs) / len(rs)
            d.append(m(ea) - m(eb))
        w, l = sum(x > 0 for x in d), sum(x < 0 for x in d)
        name = f"{metric} ({projection})" if projection else metric
        diff = f"{sum(d) / len(d):+.4f}" if d else "–"
        p = f"{sign_p(w, l):.1e}" if d else "–"
        print(f"| {name} | {a} m vs {b} m | {len(d)} | {left_out} | {w} | {l} | {diff} | {p} |")

print()
print(f"Means over the {'' if ALL_RUNS else 'executable '}runs of each selection scheme and length (f per projection).")
print()
print("| selection | init_dist_max [m] | runs | executable | cov_final mean | t_final mean | f1 mean | f2 mean |")
print("|---|---|---|---|---|---|---|---|")
groups = defaultdict(list)
for r in body:
    groups[(r[col["thesis.selection"]], float(r[col["thesis.init_dist_max"]]))].append(r)
for (sel, d), rs in sorted(groups.items()):
    ok = executable(rs)
    f = {p: [r for r in ok if r[col["thesis.projection"]] == p] for p in ("f1", "f2")}
    n_exec = sum(r[col["executable"]] == "true" for r in rs)
    print(
        f"| {sel} | {d:g} | {len(rs)} | {n_exec}/{len(rs)} | {mean_of('cov_final_free', ok, 3)} | "
        f"{mean_of('t_final', ok, 3)} | {mean_of('f_free', f['f1'], 4)} | {mean_of('f_free', f['f2'], 4)} |"
    )
