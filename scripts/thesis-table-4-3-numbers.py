#!/usr/bin/env python3
"""Three tables for results/thesis-table-4-3/summary.md that `covga report` does not make
because they are about the thesis rather than the study:

1. How far one seed's conclusions carry to another (003 §5.3 worried that its single seed
   might not generalise): the Spearman correlation of the configurations' f between
   replicates, and where each replicate's best configurations rank in the other replicates.
2. 003 Tables A.1/A.2 (the best individual of each map x R_rot x fitness function x selection
   cell of the thesis's single-seed grid) beside the same cells of this study: our best run,
   the median run, and how many runs reach or dominate the thesis's point.
3. Where the infeasible runs (best path sweeping obstacle cells: 003's penalty,
   `obstacle_sweeps` > 0) lie: per replicate, map and C_child, and how many of them share their
   first viewpoint (the end of S's move) with other runs of the same replicate; beside them, the
   runs whose plan is not executable (the robot's body touches a wall somewhere). Every configuration of a replicate runs with the same seed, so
   configurations with the same initial-population settings start from the same individuals.

Usage: python3 scripts/thesis-table-4-3-numbers.py out/thesis-table-4-3/runs.csv
"""
import csv
import sys
from collections import defaultdict

# 003 Tables A.1 (thesis-1) and A.2 (thesis-2): (R_rot, projection, selection) -> (cov_final,
# t_final) of the best individual. Several of their rows use C_len 0.1 or 0.3, which are not
# Table 4.3 values, so the configurations cannot be matched one to one; the cells can.
THESIS = {
    "thesis-1": {
        ("0.0", "f1", "elite"): (0.810864, 0.889973),
        ("0.0", "f1", "tournament"): (0.743704, 0.963532),
        ("0.0", "f1", "prws"): (0.827654, 0.794313),
        ("0.0", "f1", "rrws"): (0.768395, 0.825027),
        ("0.0", "f2", "elite"): (0.858765, 0.805839),
        ("0.0", "f2", "tournament"): (0.784198, 0.852389),
        ("0.0", "f2", "prws"): (0.814815, 0.818859),
        ("0.0", "f2", "rrws"): (0.777778, 0.795455),
        ("6.28", "f1", "elite"): (0.874074, 0.776625),
        ("6.28", "f1", "tournament"): (0.822222, 0.926432),
        ("6.28", "f1", "prws"): (0.692346, 0.897165),
        ("6.28", "f1", "rrws"): (0.824691, 0.799912),
        ("6.28", "f2", "elite"): (0.84642, 0.799684),
        ("6.28", "f2", "tournament"): (0.813333, 0.782359),
        ("6.28", "f2", "prws"): (0.809383, 0.810188),
        ("6.28", "f2", "rrws"): (0.781235, 0.791927),
    },
    "thesis-2": {
        ("0.0", "f1", "elite"): (0.866279, 0.817783),
        ("0.0", "f1", "tournament"): (0.819186, 0.876244),
        ("0.0", "f1", "prws"): (0.86686, 0.846678),
        ("0.0", "f1", "rrws"): (0.836628, 0.78249),
        ("0.0", "f2", "elite"): (0.861628, 0.830717),
        ("0.0", "f2", "tournament"): (0.796512, 0.875399),
        ("0.0", "f2", "prws"): (0.843605, 0.783901),
        ("0.0", "f2", "rrws"): (0.830233, 0.787211),
        ("6.28", "f1", "elite"): (0.819767, 0.864434),
        ("6.28", "f1", "tournament"): (0.845349, 0.830881),
        ("6.28", "f1", "prws"): (0.794186, 0.853525),
        ("6.28", "f1", "rrws"): (0.773256, 0.866285),
        ("6.28", "f2", "elite"): (0.853488, 0.868523),
        ("6.28", "f2", "tournament"): (0.859884, 0.837755),
        ("6.28", "f2", "prws"): (0.85814, 0.817946),
        ("6.28", "f2", "rrws"): (0.82093, 0.779031),
    },
}


def ranks(values):
    """Average ranks (1-based) with ties sharing their mean rank."""
    order = sorted(range(len(values)), key=lambda i: values[i])
    r = [0.0] * len(values)
    i = 0
    while i < len(order):
        j = i
        while j + 1 < len(order) and values[order[j + 1]] == values[order[i]]:
            j += 1
        for k in range(i, j + 1):
            r[order[k]] = (i + j) / 2 + 1
        i = j + 1
    return r


def spearman(a, b):
    ra, rb = ranks(a), ranks(b)
    n = len(a)
    ma, mb = sum(ra) / n, sum(rb) / n
    cov = sum((x - ma) * (y - mb) for x, y in zip(ra, rb))
    va = sum((x - ma) ** 2 for x in ra)
    vb = sum((y - mb) ** 2 for y in rb)
    return cov / (va * vb) ** 0.5


def median(v):
    s = sorted(v)
    n = len(s)
    return s[n // 2] if n % 2 else (s[n // 2 - 1] + s[n // 2]) / 2


def main(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    by_config = defaultdict(dict)
    for r in rows:
        by_config[r["config_id"]][int(r["replicate"])] = r
    reps = sorted({int(r["replicate"]) for r in rows})
    complete = {c: v for c, v in by_config.items() if all(k in v for k in reps)}
    print(f"## Seed to seed ({len(complete)} configurations with all {len(reps)} replicates)\n")
    print("| replicates | Spearman ρ of f | of cov_final | of t_final |")
    print("|---|---|---|---|")
    ids = sorted(complete)
    col = {m: {k: [float(complete[c][k][m]) for c in ids] for k in reps} for m in ["f_free", "cov_final_free", "t_final"]}
    for i, a in enumerate(reps):
        for b in reps[i + 1:]:
            rho = [spearman(col[m][a], col[m][b]) for m in ["f_free", "cov_final_free", "t_final"]]
            print(f"| {a} vs {b} | {rho[0]:.3f} | {rho[1]:.3f} | {rho[2]:.3f} |")
    n = len(ids)
    print("\n| replicate | its best configuration: rank in the other replicates (of %d) | its top 1 %% still in the other replicates' top 10 %% |" % n)
    print("|---|---|---|")
    order = {k: sorted(range(n), key=lambda i: -col["f_free"][k][i]) for k in reps}
    rank_of = {k: {i: pos + 1 for pos, i in enumerate(order[k])} for k in reps}
    top1 = max(1, n // 100)
    top10 = max(1, n // 10)
    for k in reps:
        best = order[k][0]
        others = [b for b in reps if b != k]
        where = ", ".join(f"{rank_of[b][best]}" for b in others)
        kept = [sum(1 for i in order[k][:top1] if rank_of[b][i] <= top10) / top1 for b in others]
        print(f"| {k} | {where} | " + ", ".join(f"{x:.0%}" for x in kept) + " |")

    print("\n## 003 Tables A.1/A.2 beside this study\n")
    print("Per cell: the thesis's best individual (one seed, its own C_len set), our best run by f over all")
    print("configurations and seeds of the cell, our median run, and the share of our runs whose")
    print("(cov_final, t_final) reaches or dominates the thesis's point.\n")
    print("| map | R_rot | fitness | selection | thesis cov / t | our best run cov / t | our median cov / t | runs | reach the thesis point |")
    print("|---|---|---|---|---|---|---|---|---|")
    cells = defaultdict(list)
    for r in rows:
        cells[(r["map.source"], r["robot.rot_speed"], r["scorer.projection"], r["thesis.selection"])].append(r)
    for m in ["thesis-1", "thesis-2"]:
        for rot in ["0.0", "6.28"]:
            for proj in ["f1", "f2"]:
                for sel in ["elite", "tournament", "prws", "rrws"]:
                    runs = cells.get((m, rot, proj, sel), [])
                    if not runs:
                        continue
                    tc, tt = THESIS[m][(rot, proj, sel)]
                    best = max(runs, key=lambda r: float(r["f_free"]))
                    covs = [float(r["cov_final_free"]) for r in runs]
                    ts = [float(r["t_final"]) for r in runs]
                    reach = sum(1 for c, t in zip(covs, ts) if c >= tc and t >= tt)
                    print(
                        f"| {m} | {rot} | {proj} | {sel} | {tc:.3f} / {tt:.3f} | "
                        f"{float(best['cov_final_free']):.3f} / {float(best['t_final']):.3f} | "
                        f"{median(covs):.3f} / {median(ts):.3f} | {len(runs)} | {reach} ({reach / len(runs):.1%}) |"
                    )

    print("\n## Infeasible runs\n")
    print("Infeasible: the best path's footprint rectangles sweep obstacle cells (003's penalty,")
    print("`obstacle_sweeps` > 0). Not executable: the robot's body touches a non-free cell anywhere")
    print("on the path, vertices and turns included (`executable` false).\n")
    print("| replicate | map | C_child | infeasible runs | not executable | of |")
    print("|---|---|---|---|---|---|")
    groups = defaultdict(lambda: [0, 0, 0])
    for r in rows:
        g = groups[(r["replicate"], r["map.source"], r["thesis.c_child"])]
        g[0] += int(r["obstacle_sweeps"]) > 0
        g[1] += r["executable"] == "false"
        g[2] += 1
    for key in sorted(groups):
        bad, body, n = groups[key]
        print(f"| {key[0]} | {key[1]} | {key[2]} | {bad} ({bad / n:.1%}) | {body} ({body / n:.1%}) | {n} |")
    runs_dir = path.rsplit("/", 1)[0] + "/runs" if "/" in path else "runs"
    first = defaultdict(lambda: defaultdict(int))
    for r in rows:
        if int(r["obstacle_sweeps"]) == 0:
            continue
        try:
            with open(f"{runs_dir}/{r['run_id']}/best_path.csv") as f:
                next(f), next(f)
                x, y = next(f).strip().split(",")[2:4]
        except (OSError, StopIteration, ValueError):
            continue
        first[r["replicate"]][(round(float(x), 6), round(float(y), 6))] += 1
    for rep in sorted(first):
        counts = sorted(first[rep].values(), reverse=True)
        shared = sum(c for c in counts if c > 1)
        print(
            f"\nReplicate {rep}: {sum(counts)} infeasible runs with a path file; {shared} share their first "
            f"viewpoint with another run of the replicate; the most common one is shared by {counts[0]}."
        )


if __name__ == "__main__":
    main(sys.argv[1])
