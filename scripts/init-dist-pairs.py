#!/usr/bin/env python3
"""Paired comparison of the initial-move lengths of grids/init-dist.toml: for every
configuration of the other parameters, the mean over its seeds of cov_final, t_final and f at
each length, and how often one length beats another (two-sided sign test on the differences).
Usage: python3 scripts/init-dist-pairs.py out/init-dist/runs.csv"""
import csv, math, sys
from collections import defaultdict

rows = list(csv.reader(open(sys.argv[1])))
head, body = rows[0], rows[1:]
col = {n: i for i, n in enumerate(head)}  # later duplicates win: the metric `planner`
params = [n for n in head[col["seed"] + 1: len(head) - 0] if n.startswith(("thesis.", "map.", "robot."))]
other = [p for p in params if p != "thesis.init_dist_max"]
means = defaultdict(lambda: defaultdict(list))
for r in body:
    key = tuple(r[col[p]] for p in other)
    means[key][r[col["thesis.init_dist_max"]]].append(r)


def sign_p(wins, losses):
    n = wins + losses
    k = min(wins, losses)
    return min(1.0, 2 * sum(math.comb(n, i) for i in range(k + 1)) / 2 ** n)


print("| metric | A vs B | configurations | A better | B better | mean difference A − B | sign-test p |")
print("|---|---|---|---|---|---|---|")
for metric in ["cov_final_free", "t_final", "f_free"]:
    for a, b in [("3.0", "10.0"), ("3.0", "50.0"), ("10.0", "50.0")]:
        d = []
        for by_len in means.values():
            m = lambda L: sum(float(r[col[metric]]) for r in by_len[L]) / len(by_len[L])
            d.append(m(a) - m(b))
        w, l = sum(x > 0 for x in d), sum(x < 0 for x in d)
        print(f"| {metric} | {a} m vs {b} m | {len(d)} | {w} | {l} | {sum(d) / len(d):+.4f} | {sign_p(w, l):.1e} |")

print()
print("| selection | init_dist_max [m] | runs | cov_final mean | t_final mean | f mean | feasible |")
print("|---|---|---|---|---|---|---|")
groups = defaultdict(list)
for r in body:
    groups[(r[col["thesis.selection"]], float(r[col["thesis.init_dist_max"]]))].append(r)
for (sel, d), rs in sorted(groups.items()):
    mean = lambda m: sum(float(r[col[m]]) for r in rs) / len(rs)
    feas = sum(r[col["feasible"]] == "true" for r in rs)
    print(f"| {sel} | {d:g} | {len(rs)} | {mean('cov_final_free'):.3f} | {mean('t_final'):.3f} | {mean('f_free'):.4f} | {feas}/{len(rs)} |")
