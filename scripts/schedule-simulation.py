#!/usr/bin/env python3
"""How long a recorded study would take on more cores, by the order its runs are started in:
a list-scheduling simulation from the `wall_s` each run took.

    python3 scripts/schedule-simulation.py STUDY_RUNS... [--cores 16,64]

STUDY_RUNS: runs.csv or runs.csv.xz files of studies (results/*/runs.csv*). Each core takes the
next run in the order as soon as it is free, which is what `covga grid --jobs N` does. Orders:

- `seed by seed`: the order `covga grid` uses, replicate by replicate and in run-id order within
  each (a study stopped part-way holds whole seeds);
- `longest first, budget`: what `covga grid --order longest-first` does when nothing is recorded:
  by decreasing fitness evaluations (`budget.evaluations`, else `budget.iterations` where the
  grid sweeps them; the same for all runs where it does not) times the map's free cells, the
  patterns by free cells alone, ties seed by seed;
- `longest first, estimated`: what `covga grid --order longest-first` does with times recorded
  in the study folder (an earlier sitting, other shards, a calibration): all runs by decreasing
  estimated time, the estimate of a run being the mean `wall_s` of the other replicates of its
  configuration (`config_id`); a configuration run once (a pattern, a deterministic fleet
  method) gets its budget figure at the study's seconds per unit of budget (covga would first
  use its branch's mean, which runs.csv does not record);
- `longest first, exact`: by decreasing recorded `wall_s` (the list-scheduling optimum's usual
  stand-in; it knows what no scheduler can).

The makespan is divided by the lower bound max(total / cores, longest run): 1.000 is as good as
any order can be. The recorded times come from the machine the study ran on (with whatever else
ran there), so the figures speak of the order, not of a particular machine.
"""

import csv
import heapq
import io
import lzma
import os
import statistics
import sys


def read_runs(path):
    if path.endswith(".xz"):
        with lzma.open(path, "rt", newline="") as f:
            return list(csv.DictReader(io.StringIO(f.read())))
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def makespan(times, cores):
    """List scheduling: each run starts on the core that frees first."""
    free = [0.0] * cores
    for t in times:
        heapq.heappush(free, heapq.heappop(free) + t)
    return max(free)


def orders(rows):
    wall = lambda r: float(r["wall_s"])
    by_config = {}
    for r in rows:
        by_config.setdefault(r["config_id"], []).append(r)

    def estimate(r):
        others = [wall(o) for o in by_config[r["config_id"]] if o is not r]
        return statistics.fmean(others) if others else budget(r) * rate

    def budget(r):
        free = float(r.get("free_cells") or 1)
        if r.get("planner") in ("boustrophedon", "spiral"):
            return free
        for key in ("budget.evaluations", "budget.iterations"):
            if float(r.get(key) or 0) > 0:
                return float(r[key]) * free
        return free

    rate = sum(wall(r) for r in rows) / sum(budget(r) for r in rows)
    seed_key = lambda r: (int(r["replicate"]), r["run_id"])
    seeds = sorted(rows, key=seed_key)
    by_budget = sorted(rows, key=lambda r: (-budget(r), seed_key(r)))
    estimated = sorted(rows, key=lambda r: (-estimate(r), seed_key(r)))
    exact = sorted(rows, key=lambda r: (-wall(r), seed_key(r)))
    return [("seed by seed", seeds), ("longest first, budget", by_budget),
            ("longest first, estimated", estimated), ("longest first, exact", exact)]


def main():
    args = sys.argv[1:]
    cores = [16, 64]
    if "--cores" in args:
        at = args.index("--cores")
        cores = [int(c) for c in args[at + 1].split(",")]
        del args[at:at + 2]
    if not args:
        sys.exit(__doc__)
    print("| study | runs | run time [h] | longest run [s] | cores | lower bound [s] | "
          + " | ".join(name for name, _ in orders([{"wall_s": "1", "config_id": "a", "replicate": "0", "run_id": "a"}]))
          + " |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for path in args:
        rows = read_runs(path)
        name = os.path.basename(os.path.dirname(os.path.abspath(path)))
        times = [float(r["wall_s"]) for r in rows]
        total, longest = sum(times), max(times)
        for c in cores:
            bound = max(total / c, longest)
            ratios = [makespan([float(r["wall_s"]) for r in order], c) / bound for _, order in orders(rows)]
            print(f"| {name} | {len(rows)} | {total / 3600:.2f} | {longest:.1f} | {c} | {bound:.0f} | "
                  + " | ".join(f"{x:.3f}" for x in ratios) + " |")


if __name__ == "__main__":
    main()
