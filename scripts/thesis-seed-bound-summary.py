#!/usr/bin/env python3
"""Summary of the seed bound study (grids/thesis-seed-bound.toml): the seeded settings of
grids/thesis-real-maps.toml run again with thesis.seed_bound = "dominate", set beside that
study's unbounded seeded runs and the seed plans. Every number in the summary is computed here.

    python3 scripts/thesis-seed-bound-summary.py OUT REAL_MAPS RESULTS

reads OUT/runs.csv and each run's OUT/runs/<run_id>/{summary.json,population.csv}, and
REAL_MAPS/{runs,seeds,finals}.csv (results/thesis-real-maps: the unbounded runs and the
seed plans); writes RESULTS/runs.csv, RESULTS/finals.csv (per run: the hypervolume and size of
the final population's executable non-dominated set, the reported plan's cov_final and t_final
and the seed genomes' ones from summary.json) and RESULTS/summary.md. With OUT = - it rewrites
summary.md from the CSV files alone.

Coverage is the common scorer's cov_final_reach, time its time_s; the bound itself is on the
GA's objectives, cov_final and t_final of all free cells (003 eqs. 3.10, 3.13). Bounded and
unbounded runs are paired by replicate (the two studies share replicates 0-4 of each setting);
the tests (exact Wilcoxon signed-rank, Holm per measure) are covga's own statistics module,
from its Python package (`pip install ./python`): this script lays numbers out, it does not test.
"""

import csv
import importlib.util
import json
import os
import shutil
import statistics
import sys

from covga import stats
from study_stats import map_name, median_iqr, read_csv

HERE = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location("real_maps", os.path.join(HERE, "thesis-real-maps-summary.py"))
real_maps = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(real_maps)

MAP_ORDER = real_maps.MAP_ORDER
# Differences below this (coverage, and time relative to the seed plan's) count as equal: a run
# that returns the seed genome unchanged drives the seed plan's length up to rounding (1e-11).
EQUAL = 1e-9
SETTINGS = [(moves, sel) for moves in ("straight", "routed") for sel in ("elite", "nsga2")]


def collect(out, results):
    os.makedirs(results, exist_ok=True)
    shutil.copyfile(os.path.join(out, "runs.csv"), os.path.join(results, "runs.csv"))
    with open(os.path.join(results, "finals.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["run_id", "hypervolume", "front_size", "population", "cov_final", "t_final",
                    "seed_cov_final", "seed_t_final"])
        for r in read_csv(os.path.join(out, "runs.csv")):
            folder = os.path.join(out, "runs", r["run_id"])
            pop = read_csv(os.path.join(folder, "population.csv"))
            ok = [(float(p["cov_final"]), float(p["t_final"])) for p in pop if int(p["obstacle_cells"]) == 0]
            hv, size = real_maps.hypervolume(ok)
            with open(os.path.join(folder, "summary.json")) as s:
                summary = json.load(s)
            (seed_cov, seed_t), = summary["seed_bound"]  # one seed plan: the boustrophedon
            w.writerow([r["run_id"], repr(hv), size, len(pop), repr(summary["cov_final"]),
                        repr(summary["t_final"]), repr(seed_cov), repr(seed_t)])


def seeds_of(rows):
    return len({r["replicate"] for r in rows})


def key_of(r):
    return (map_name(r["map.source"]), r["thesis.moves"], r["thesis.selection"])


def groups_of(rows):
    groups = {}
    for r in rows:
        groups.setdefault(key_of(r), []).append(r)
    return groups


def num(rows, key):
    return [float(r[key]) for r in rows]


def span(xs, fmt):
    return real_maps.span(xs, fmt)


def summarise(results, real):
    bounded = read_csv(os.path.join(results, "runs.csv"))
    finals = {f["run_id"]: f for f in read_csv(os.path.join(results, "finals.csv"))}
    real_finals = {f["run_id"]: f for f in read_csv(os.path.join(real, "finals.csv"))}
    seeds = {map_name(s["map.source"]): s for s in read_csv(os.path.join(real, "seeds.csv"))}
    unbounded = [r for r in read_csv(os.path.join(real, "runs.csv"))
                 if real_maps.seeding(r["thesis.seed_population"]) == "boustrophedon"]
    b_groups, u_groups = groups_of(bounded), groups_of(unbounded)
    present = {k[0] for k in b_groups}
    maps = [m for m in MAP_ORDER if m in present] + sorted(present - set(MAP_ORDER))
    hv = lambda rs, fin: [float(fin[r["run_id"]]["hypervolume"]) for r in rs]

    def within(r):
        f = finals[r["run_id"]]
        return float(f["cov_final"]) >= float(f["seed_cov_final"]) and float(f["t_final"]) >= float(f["seed_t_final"])

    rows, tests = [], []
    for m in maps:
        seed = seeds[m]
        sc, st = float(seed["cov_final_reach"]), float(seed["time_s"])
        for moves, sel in SETTINGS:
            b, u = b_groups.get((m, moves, sel)), u_groups.get((m, moves, sel))
            if not b:
                continue
            dc = [float(r["cov_final_reach"]) - sc for r in b]
            dt = [float(r["time_s"]) / st - 1 for r in b]
            rows.append({
                "map": m, "moves": moves, "sel": sel, "runs": b, "unbounded": u or [],
                "executable": sum(r["executable"] == "true" for r in b),
                "within": sum(within(r) for r in b),
                "both": sum(c >= -EQUAL and t <= EQUAL for c, t in zip(dc, dt)),
                "dc": dc, "dt": dt,
                "unbounded_both": sum(float(r["cov_final_reach"]) >= sc - EQUAL and float(r["time_s"]) / st - 1 <= EQUAL
                                      for r in u or []),
            })
            if u:
                # Pairs by replicate: the unbounded run of the same setting and seed.
                by_rep = {r["replicate"]: r for r in u}
                pairs = [(rb, by_rep[rb["replicate"]]) for rb in b if rb["replicate"] in by_rep]
                for measure in ("cov_final_reach", "time_s", "HV"):
                    if measure == "HV":
                        xb = [float(finals[x["run_id"]]["hypervolume"]) for x, _ in pairs]
                        xu = [float(real_finals[y["run_id"]]["hypervolume"]) for _, y in pairs]
                    else:
                        xb, xu = [float(x[measure]) for x, _ in pairs], [float(y[measure]) for _, y in pairs]
                    w = stats.wilcoxon(xb, xu) if measure != "HV" else None
                    tests.append({
                        "map": m, "moves": moves, "sel": sel, "measure": measure, "pairs": len(pairs),
                        "higher": sum(x > y for x, y in zip(xb, xu)), "lower": sum(x < y for x, y in zip(xb, xu)),
                        "b": statistics.median(xb), "u": statistics.median(xu),
                        "p": w["p_value"] if w else None,
                    })
    for measure in ("cov_final_reach", "time_s"):
        family = [t for t in tests if t["measure"] == measure and t["p"] is not None]
        for t, adjusted in zip(family, stats.holm([t["p"] for t in family])):
            t["holm"] = float(adjusted)

    out = ["# The seed bound: seeded thesis GA runs that must end at least as good as their seed", ""]
    out += [
        "Written by `scripts/thesis-seed-bound-summary.py` from `runs.csv` and `finals.csv` of this folder and",
        "`runs.csv`, `seeds.csv` and `finals.csv` of `results/thesis-real-maps` (the same seeded settings without",
        "the bound, and the seed plans); the commands and wall time are in README.md. Coverage is",
        "`cov_final_reach`, time `time_s` (length at 0.2 m/s; the robot turns for free), HV the hypervolume",
        "of the final population's executable non-dominated set in (cov_final, t_final) above (0, 0);",
        f"medians [quartiles] over the seeds ({seeds_of(bounded)} bounded, {seeds_of(unbounded)} unbounded). \"Within the bound\": the reported plan's cov_final and t_final",
        "(all free cells, the GA's objectives) are both at least the seed genome's. \"≥ seed plan on both\":",
        "coverage at least and time_s at most the boustrophedon plan's, as the common scorer reads them (differences",
        "below 1e-9, in coverage or in time relative to the plan's, count as equal).",
        "",
    ]
    out += findings(rows, tests)
    out += ["## Every seeded setting, bounded and unbounded", ""]
    out.append("| map | moves | selection | seed_bound | executable | within the bound | ≥ seed plan on both | coverage | time_s | time change against the seed plan (median, range) | HV |")
    out.append("|---|---|---|---|---|---|---|---|---|---|---|")
    for row in rows:
        m, seed = row["map"], seeds[row["map"]]
        n = len(row["runs"])
        out.append(
            f"| {m} | {row['moves']} | {row['sel']} | dominate | {row['executable']}/{n} | {row['within']}/{n} | "
            f"{row['both']}/{n} | {median_iqr(num(row['runs'], 'cov_final_reach'), 4)} | "
            f"{median_iqr(num(row['runs'], 'time_s'), 0)} | {statistics.median(row['dt']):+.1%} "
            f"({min(row['dt']):+.1%} to {max(row['dt']):+.1%}) | {median_iqr(hv(row['runs'], finals), 4)} |"
        )
        u = row["unbounded"]
        if u:
            st = float(seed["time_s"])
            udt = [float(r["time_s"]) / st - 1 for r in u]
            ub = row["unbounded_both"]
            ue = sum(r["executable"] == "true" for r in u)
            out.append(
                f"| {m} | {row['moves']} | {row['sel']} | none | {ue}/{len(u)} | – | {ub}/{len(u)} | "
                f"{median_iqr(num(u, 'cov_final_reach'), 4)} | {median_iqr(num(u, 'time_s'), 0)} | "
                f"{statistics.median(udt):+.1%} ({min(udt):+.1%} to {max(udt):+.1%}) | {median_iqr(hv(u, real_finals), 4)} |"
            )
        if row is rows[-1] or rows[rows.index(row) + 1]["map"] != m:
            out.append(
                f"| {m} | boustrophedon plan (the seed) | – | – | {'1/1' if seed['executable'] == 'true' else '0/1'} | – | – | "
                f"{float(seed['cov_final_reach']):.4f} | {float(seed['time_s']):.0f} | – | – |"
            )
    out += ["", "## The seed genome against the seed plan", ""]
    out.append("The bound compares with the seed genome, the boustrophedon plan written as actions; its cov_final and")
    out.append("t_final (all free cells, from each run's `summary.json`) against the plan's, as the common scorer")
    out.append("reads it (`seeds.csv`).")
    out.append("")
    out.append("| map | moves | genome cov_final | plan cov_final | genome t_final | plan t_final |")
    out.append("|---|---|---|---|---|---|")
    for m in maps:
        seed = seeds[m]
        for moves in ("straight", "routed"):
            fs = {(float(finals[r["run_id"]]["seed_cov_final"]), float(finals[r["run_id"]]["seed_t_final"]))
                  for row in rows if row["map"] == m and row["moves"] == moves for r in row["runs"]}
            for c, t in sorted(fs):
                out.append(f"| {m} | {moves} | {c:.5f} | {float(seed['cov_final_free']):.5f} | {t:.5f} | "
                           f"{float(seed['t_final']):.5f} |")
    out += ["", "## Bounded against unbounded, paired by seed", ""]
    out.append("Per map and setting, each bounded run against the unbounded run of the same replicate")
    out.append("(`results/thesis-real-maps`): pairs where the bounded run is higher and lower, the medians, and the")
    out.append("two-sided exact Wilcoxon signed-rank p, Holm-adjusted within each measure's family of")
    f_cov = sum(1 for t in tests if t["measure"] == "cov_final_reach" and t["p"] is not None)
    out.append(f"{f_cov} settings. With 5 pairs the smallest possible p is 0.0625: no single setting can")
    out.append("show a difference at 0.05, so read the counts of pairs. HV is not tested: the bound keeps every")
    out.append("counted plan inside the region that dominates the seed, so a smaller hypervolume is what it does by")
    out.append("construction, not a finding.")
    out.append("")
    out.append("| map | moves | selection | measure | pairs | bounded higher | bounded lower | bounded | unbounded | p | Holm p |")
    out.append("|---|---|---|---|---|---|---|---|---|---|---|")
    for t in tests:
        digits = 0 if t["measure"] == "time_s" else 4
        p = "–" if t["p"] is None else f"{t['p']:.3g}"
        holm = f"{t['holm']:.3g}" if "holm" in t else "–"
        out.append(
            f"| {t['map']} | {t['moves']} | {t['sel']} | {t['measure']} | {t['pairs']} | {t['higher']} | {t['lower']} | "
            f"{t['b']:.{digits}f} | {t['u']:.{digits}f} | {p} | {holm} |"
        )
    out.append("")
    with open(os.path.join(results, "summary.md"), "w") as f:
        f.write("\n".join(out))


def where(runs):
    """The settings of (row, value) pairs, named once each."""
    return ", ".join(sorted({f"{r['map']} {r['moves']}/{r['sel']}" for r, _ in runs}))


def findings(rows, tests):
    """The findings in words, each sentence built from the tables below it."""
    total = sum(len(r["runs"]) for r in rows)
    out = ["## Findings", ""]
    n = 1
    out.append(
        f"{n}. **The bound holds**: {sum(r['within'] for r in rows)} of {total} bounded runs report a plan within it "
        f"(cov_final and t_final both at least the seed genome's); {sum(r['executable'] for r in rows)} of {total} "
        f"plans are executable."
    )
    n += 1
    both = sum(r["both"] for r in rows)
    unbounded_both = sum(r["unbounded_both"] for r in rows)
    unbounded_total = sum(len(r["unbounded"]) for r in rows)
    dts = [t for r in rows for t in r["dt"]]
    dcs = [c for r in rows for c in r["dc"]]
    out.append(
        f"{n}. **Against the seed plan** as the common scorer reads it: {both} of {total} bounded runs cover at least "
        f"as much of the reachable space in at most its time. Over all {total}, time_s changes by "
        f"{span(dts, '{:+.1%}')} and coverage by {span(dcs, '{:+.4f}')}. Without the bound, {unbounded_both} of "
        f"{unbounded_total} seeded runs are (results/thesis-real-maps)."
    )
    n += 1
    for moves in ("straight", "routed"):
        rs = [r for r in rows if r["moves"] == moves]
        if rs:
            med_t = [statistics.median(r["dt"]) for r in rs]
            med_c = [statistics.median(r["dc"]) for r in rs]
            out.append(
                f"{n}. **Bounded, {moves} moves**: the median time change against the seed plan per map and selection "
                f"is {span(med_t, '{:+.1%}')}, the median coverage change {span(med_c, '{:+.4f}')}."
            )
            n += 1
    short = [(r, c) for r in rows for c in r["dc"] if c < -EQUAL]
    longer = [(r, t) for r in rows for t in r["dt"] if t > EQUAL]
    if short or longer:
        words = f"{n}. **Where a bounded run is not ≥ the seed plan on both**: "
        if short:
            words += (
                f"{len(short)} {'run covers' if len(short) == 1 else 'runs cover'} less than the seed plan ({where(short)}), by at most "
                f"{-min(c for _, c in short):.4f}; the seed genome itself covers less than the plan it encodes on "
                f"those maps (the table of the seed genome: the viewpoint lattice of the genome moves a lane edge by a few cells), "
                f"and the bound is against the genome. "
            )
        if longer:
            words += (
                f"{len(longer)} {'run takes' if len(longer) == 1 else 'runs take'} longer than the seed plan "
                f"({where(longer)}), by at most {max(t for _, t in longer):+.3%}: t_final is swept-area efficiency, not time, so a plan can be more "
                f"efficient and still longer."
            )
        else:
            words += "None takes longer than the seed plan."
        out.append(words)
        n += 1
    for measure, words in (("cov_final_reach", "coverage"), ("time_s", "time_s")):
        ts = [t for t in tests if t["measure"] == measure]
        if not ts:
            continue
        pairs = sum(t["pairs"] for t in ts)
        higher, lower = sum(t["higher"] for t in ts), sum(t["lower"] for t in ts)
        all_up = sum(t["higher"] == t["pairs"] for t in ts)
        all_down = sum(t["lower"] == t["pairs"] for t in ts)
        least = min((t["holm"] for t in ts if "holm" in t), default=None)
        out.append(
            f"{n}. **Bounded against unbounded, {words}, paired by seed**: the bounded run is higher in {higher} of "
            f"{pairs} pairs and lower in {lower}; in {all_up} of {len(ts)} settings higher in every pair, in "
            f"{all_down} lower in every pair; the medians differ by "
            f"{span([t['b'] - t['u'] for t in ts], '{:+.0f}' if measure == 'time_s' else '{:+.4f}')}. "
            + (f"The smallest Holm-adjusted p is {least:.3g}: " if least is not None else "")
            + "with 5 pairs per setting no setting's difference is significant on its own"
            + ("; every pair of every setting points the same way." if higher == pairs or lower == pairs else ".")
            + f" Across settings (each setting's median difference one sign), the exact sign test gives p = "
            f"{stats.sign_test([t['b'] - t['u'] for t in ts]):.2g}."
        )
        n += 1
    out.append("")
    return out


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    out, real, results = sys.argv[1:]
    if out != "-":
        collect(out, results)
    summarise(results, real)


if __name__ == "__main__":
    main()
