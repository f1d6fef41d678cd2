#!/usr/bin/env python3
"""Summary of the thesis GA on real floor plans (grids/thesis-real-maps.toml): every number in
the summary is computed here from the study's data.

    python3 scripts/thesis-real-maps-summary.py OUT SEEDS RESULTS

reads OUT/runs.csv and each run's OUT/runs/<run_id>/population.csv, and SEEDS/runs.csv (the
boustrophedon seed plans, grids/thesis-real-maps-seeds.toml); writes RESULTS/runs.csv,
RESULTS/seeds.csv, RESULTS/finals.csv (per run: the hypervolume and size of the final
population's non-dominated set of members sweeping no obstacle cell; for a seeded run, whether that population still
holds a plan at least as good as the seed plan on both objectives, and the best cov_final of
its initial population, read from history.csv) and RESULTS/summary.md. With RESULTS alone
(`python3 scripts/thesis-real-maps-summary.py - - results/thesis-real-maps`) it rewrites
summary.md from the three CSV files.

Coverage is the common scorer's cov_final_reach, time its time_s (length at robot.speed; the
robot turns for free). The hypervolume is the area dominated by the final population's
members that sweep no obstacle cell in (cov_final, t_final), 003's two objectives (both to be maximised), above
the reference point (0, 0). The statistical comparisons of the factors are not made here:
`covga report OUT --compare KEY=BASELINE` writes them (README.md of the results folder).
"""

import csv
import os
import shutil
import statistics
import sys

from study_stats import map_name, median_iqr, read_csv

MAP_ORDER = ["thesis-2", "office", "office-ring", "basement"]


# Relative slack when a plan is compared with its seed plan on both objectives.
SEED_TOLERANCE = 1e-3


def seeding(value):
    return "boustrophedon" if "boustrophedon" in value else "none"


def hypervolume(points):
    """Area dominated by `points` (both coordinates maximised) above (0, 0); the size of the
    non-dominated set."""
    front = []
    for x, y in sorted(points, key=lambda p: (-p[0], -p[1])):
        if not front or y > front[-1][1]:
            front.append((x, y))
    area, prev_y = 0.0, 0.0
    for x, y in front:
        area += x * (y - prev_y)
        prev_y = y
    return area, len(front)


def collect(out, seeds, results):
    os.makedirs(results, exist_ok=True)
    shutil.copyfile(os.path.join(out, "runs.csv"), os.path.join(results, "runs.csv"))
    shutil.copyfile(os.path.join(seeds, "runs.csv"), os.path.join(results, "seeds.csv"))
    plans = {s["map.source"]: s for s in read_csv(os.path.join(seeds, "runs.csv"))}
    with open(os.path.join(results, "finals.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["run_id", "hypervolume", "front_size", "population", "holds_seed", "start_max_cov_final"])
        for r in read_csv(os.path.join(out, "runs.csv")):
            folder = os.path.join(out, "runs", r["run_id"])
            pop = read_csv(os.path.join(folder, "population.csv"))
            ok = [(float(p["cov_final"]), float(p["t_final"])) for p in pop if int(p["obstacle_cells"]) == 0]
            hv, size = hypervolume(ok)
            holds, start = "", ""
            if seeding(r["thesis.seed_population"]) != "none":
                plan = plans[r["map.source"]]
                sc, st = float(plan["cov_final_free"]), float(plan["t_final"])
                # The seed genome scores as its plan up to a few cells (thesis::seeding's tests).
                holds = str(any(c >= sc * (1 - SEED_TOLERANCE) and t >= st * (1 - SEED_TOLERANCE) for c, t in ok)).lower()
                start = read_csv(os.path.join(folder, "history.csv"))[0]["max_cov_final"]
            w.writerow([r["run_id"], repr(hv), size, len(pop), holds, start])


def executable(rows):
    return [r for r in rows if r["executable"] == "true"]


def setting(r):
    return (r["thesis.moves"], seeding(r["thesis.seed_population"]), r["thesis.selection"])


def summarise(results):
    rows = read_csv(os.path.join(results, "runs.csv"))
    finals = {f["run_id"]: f for f in read_csv(os.path.join(results, "finals.csv"))}
    seeds = {map_name(s["map.source"]): s for s in read_csv(os.path.join(results, "seeds.csv"))}
    present = {map_name(r["map.source"]) for r in rows}
    maps = [m for m in MAP_ORDER if m in present] + sorted(present - set(MAP_ORDER))
    groups = {}
    for r in rows:
        groups.setdefault((map_name(r["map.source"]), setting(r)), []).append(r)
    num = lambda rs, key: [float(r[key]) for r in rs]
    hv = lambda rs: [float(finals[r["run_id"]]["hypervolume"]) for r in rs]
    out = ["# The thesis GA on real floor plans: routed moves, seeded populations, NSGA-II", ""]
    out += [
        "Written by `scripts/thesis-real-maps-summary.py` from `runs.csv`, `seeds.csv` and `finals.csv` of this",
        "folder; the commands that made the study and its wall time are in README.md. Coverage is",
        "`cov_final_reach` (the reachable space), time `time_s` of the common scorer (length at 0.2 m/s; the",
        "robot turns for free), HV the hypervolume of the non-dominated set of the final population's members",
        "that sweep no obstacle cell (the population file records no more), in (cov_final, t_final) above",
        "(0, 0); medians [quartiles] over the seeds. Executable: the robot's body keeps clear of every wall",
        "and unknown cell along the whole plan (covga's executability rule); coverage and time_s are over",
        "the executable plans (– where there is none), with the median coverage of all plans beside them.",
        "",
        "## Every setting",
        "",
        "| map | moves | seeding | selection | n | executable | coverage | time_s | coverage (all plans) | HV |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for m in maps:
        for key in sorted(k for k in groups if k[0] == m):
            rs = groups[key]
            ok = executable(rs)
            moves, seed, sel = key[1]
            out.append(
                f"| {m} | {moves} | {seed} | {sel} | {len(rs)} | {len(ok)}/{len(rs)} | {median_iqr(num(ok, 'cov_final_reach'), 4)} | "
                f"{median_iqr(num(ok, 'time_s'), 0)} | {statistics.median(num(rs, 'cov_final_reach')):.4f} | {median_iqr(hv(rs), 4)} |"
            )
        seed = seeds.get(m)
        if seed:
            out.append(
                f"| {m} | boustrophedon plan (the seed) | – | – | 1 | {'1/1' if seed['executable'] == 'true' else '0/1'} | "
                f"{float(seed['cov_final_reach']):.4f} | {float(seed['time_s']):.0f} | {float(seed['cov_final_reach']):.4f} | – |"
            )
    out += ["", "## Targets", ""]
    out.append("Routed and unseeded on office and basement: median coverage at least 0.80 with every plan")
    out.append("executable, within the ablation's 100 000 evaluations.")
    out.append("")
    out.append("| map | selection | median coverage, straight | median coverage, routed | executable, routed | meets target |")
    out.append("|---|---|---|---|---|---|")
    met = []
    for m in maps:
        if m not in ("office", "basement"):
            continue
        for sel in ("elite", "nsga2"):
            st, ro = groups.get((m, ("straight", "none", sel))), groups.get((m, ("routed", "none", sel)))
            if not st or not ro:
                continue
            cs, cr = statistics.median(num(st, "cov_final_reach")), statistics.median(num(ro, "cov_final_reach"))
            ex = len(executable(ro))
            ok = cr >= 0.80 and ex == len(ro)
            met.append(ok)
            out.append(f"| {m} | {sel} | {cs:.4f} | {cr:.4f} | {ex}/{len(ro)} | {'yes' if ok else 'no'} |")
    out.append("")
    out.append(f"Met in {sum(met)} of {len(met)} map–selection pairs.")
    seeded = []
    out += ["", "## Seeded runs against their seed plan", ""]
    out.append("Each seeded run's plan against the boustrophedon plan it was seeded with: the change in")
    out.append("coverage and in time_s (the median of run time_s / seed time_s − 1, and its range), how many runs")
    out.append("end at least as good on both (coverage ≥ the seed's and time_s ≤ the seed's), and how many end")
    out.append("with f2 = cov_final × t_final of all free cells (`f_free`, 003 eq. 3.15, what the GA maximises)")
    out.append("at least the seed's.")
    out.append("")
    out.append("The last two columns: how many runs' final populations still hold an executable plan at least as")
    out.append(f"good as the seed plan on both cov_final and t_final (within {SEED_TOLERANCE:.0e} relative), and the best")
    out.append("cov_final (all free cells) of the initial population, where the seed genome is the best member, against")
    out.append("the seed plan's own; the two may differ by the few cells across which the genome's viewpoint")
    out.append("lattice moves a lane's edge (thesis::seeding's tests), under straight and routed moves alike.")
    out.append("")
    out.append("| map | moves | selection | coverage − seed's (median) | time change (median, range) | plans ≥ seed on both | plans with f2 ≥ seed's | final population holds a plan ≥ seed on both | seed genome's cov_final (plan's) |")
    out.append("|---|---|---|---|---|---|---|---|---|")
    for m in maps:
        seed = seeds.get(m)
        if not seed:
            continue
        sc, st = float(seed["cov_final_reach"]), float(seed["time_s"])
        for moves in ("straight", "routed"):
            for sel in ("elite", "nsga2"):
                rs = groups.get((m, (moves, "boustrophedon", sel)))
                if not rs:
                    continue
                dc = [float(r["cov_final_reach"]) - sc for r in rs]
                dt = [float(r["time_s"]) / st - 1 for r in rs]
                both = sum(c >= -1e-12 and t <= 1e-12 for c, t in zip(dc, dt))
                fitter = sum(float(r["f_free"]) >= float(seed["f_free"]) - 1e-12 for r in rs)
                held = sum(finals[r["run_id"]]["holds_seed"] == "true" for r in rs)
                start = statistics.median(float(finals[r["run_id"]]["start_max_cov_final"]) for r in rs)
                seeded.append((m, moves, sel, dc, dt, both, fitter, len(rs), held))
                out.append(
                    f"| {m} | {moves} | {sel} | {statistics.median(dc):+.4f} | {statistics.median(dt):+.1%} "
                    f"({min(dt):+.1%} to {max(dt):+.1%}) | {both}/{len(rs)} | {fitter}/{len(rs)} | {held}/{len(rs)} | "
                    f"{start:.4f} ({float(seed['cov_final_free']):.4f}) |"
                )
    out.append("")
    at = out.index("## Every setting")
    text = out[:at] + findings(seeded, met, groups, maps, num) + out[at:]
    with open(os.path.join(results, "summary.md"), "w") as f:
        f.write("\n".join(text))


def span(xs, fmt):
    lo, hi = min(xs), max(xs)
    return fmt.format(lo) if fmt.format(lo) == fmt.format(hi) else f"{fmt.format(lo)} to {fmt.format(hi)}"


def findings(seeded, met, groups, maps, num):
    """The findings in words, each sentence built from the tables below it."""
    out = ["## Findings", ""]
    out.append("What each factor does, seed by seed, is in `report/compare-thesis.moves.md`,")
    out.append("`report/compare-thesis.seed_population.md` and `report/compare-thesis.selection.md`, written by")
    out.append("`covga report --compare` (runs paired by seed within each map and setting of the other factors,")
    out.append("executable plans only, Wilcoxon signed-rank and exact McNemar tests Holm-corrected per family,")
    out.append("bootstrap intervals). The findings below count the rows of the tables that follow.")
    out.append("")
    n = 1
    if seeded:
        total = sum(s[7] for s in seeded)
        both = sum(s[5] for s in seeded)
        fitter = sum(s[6] for s in seeded)
        dts = [t for s in seeded for t in s[4]]
        dcs = [c for s in seeded for c in s[3]]
        out.append(
            f"{n}. **Seeded runs against their seed plan**: {fitter} of {total} end with f2 at least the seed's "
            f"(the GA's own objective); {both} of {total} are at least as good on both coverage and time_s. "
            f"Against the plan they were seeded with, time_s changes by {span(dts, '{:+.1%}')} and coverage by "
            f"{span(dcs, '{:+.4f}')}"
            + (": the GA trades coverage for time rather than improving both." if both == 0 else ".")
        )
        n += 1
        for sel in ("elite", "nsga2"):
            rs = [s for s in seeded if s[2] == sel]
            if rs:
                out.append(
                    f"{n}. **Seeded, {sel}: the final population** still holds a plan at least as good as the seed on "
                    f"both objectives in {sum(s[8] for s in rs)} of {sum(s[7] for s in rs)} runs (by map and moves: "
                    + ", ".join(f"{s[0]} {s[1]} {s[8]}/{s[7]}" for s in rs) + ")."
                )
                n += 1
        for moves in ("straight", "routed"):
            rs = [s for s in seeded if s[1] == moves]
            if rs:
                med_t = [statistics.median(s[4]) for s in rs]
                med_c = [statistics.median(s[3]) for s in rs]
                out.append(
                    f"{n}. **Seeded, {moves} moves**: the median time change per map and selection is "
                    f"{span(med_t, '{:+.1%}')}, the median coverage change {span(med_c, '{:+.4f}')}."
                )
                n += 1
    if met:
        out.append(
            f"{n}. **Target** (routed, unseeded, office and basement, median coverage ≥ 0.80, every plan "
            f"executable): met in {sum(met)} of {len(met)} map–selection pairs."
        )
        n += 1
    best = []
    for m in maps:
        unseeded = [(statistics.median(num(executable(rs), "cov_final_reach")), k[1]) for k, rs in groups.items()
                    if k[0] == m and k[1][1] == "none" and executable(rs)]
        if unseeded:
            c, (moves, _, sel) = max(unseeded)
            best.append(f"{m} {moves}/{sel} {c:.4f}")
    if best:
        out.append(f"{n}. **Best unseeded setting by median coverage (executable plans)**: " + "; ".join(best) + ".")
    out.append("")
    return out


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    out, seeds, results = sys.argv[1:]
    if out != "-":
        collect(out, seeds, results)
    summarise(results)


if __name__ == "__main__":
    main()
