#!/usr/bin/env python3
"""The cell-order study's figures against fixed targets, from two of its runs.csv files.

Reads an earlier and a later `runs.csv` (or `.csv.xz`) of `results/cell-order` and prints, for
each robot (free turning, 0.52 rad/s):

- over the 20 generated floor plans, the median of (the later study's fastest executable
  cell-order plan ÷ the earlier study's), with its extremes;
- basement's fastest executable cell-order plan in each study;
- per search, on basement and the 20 generated maps, how many maps have the search's median
  time at or below 0.90×, and at or below 0.97×, the strongest no-search control's time (the
  faster of `nearest` and `boustrophedon`, which read no seed and run once).

Times are `time_s`, the common scorer's mission time of the plan that stops at the coverage
goal and drives back to its station. The study's statistics live in `covga report`; this
script only measures distances to targets set before the study was run. For example:

    git show 6281771:results/cell-order/runs.csv.xz > /tmp/before.csv.xz
    python3 scripts/cell-order-targets.py /tmp/before.csv.xz results/cell-order/runs.csv.xz
"""
import csv
import lzma
import statistics
import sys

ROBOTS = ("0.0", "0.52")
SEARCHES = ("ils, seeded", "ga, seeded", "ga")


def load(path):
    """Executable cell-order runs' times, by (map, robot) and solver."""
    opener = lzma.open if path.endswith(".xz") else open
    times = {}
    with opener(path, "rt", newline="") as f:
        for row in csv.DictReader(f):
            if row["planner"] != "cell_order" or row["executable"] != "true":
                continue
            solver = row["cell_order.solver"]
            if row.get("cell_order.seed_directions") == "true":
                solver += ", seeded"
            key = (row["map.source"], row["robot.rot_speed"])
            times.setdefault(key, {}).setdefault(solver, []).append(float(row["time_s"]))
    return times


def fastest(by_solver):
    return min(min(values) for values in by_solver.values())


def strongest_control(by_solver):
    return min(by_solver["nearest"][0], by_solver["boustrophedon"][0])


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: cell-order-targets.py EARLIER_RUNS_CSV LATER_RUNS_CSV")
    before, after = load(sys.argv[1]), load(sys.argv[2])
    generated = sorted(key for key in after if "/generated/" in key[0])
    for robot in ROBOTS:
        ratios = [fastest(after[k]) / fastest(before[k]) for k in generated if k[1] == robot and k in before]
        if ratios:
            print(
                f"rot_speed {robot}: {len(ratios)} generated maps, fastest plan later/earlier: "
                f"median {statistics.median(ratios):.3f}, from {min(ratios):.3f} to {max(ratios):.3f}"
            )
        for key in sorted(k for k in after if k[1] == robot and k[0].endswith("basement.yaml")):
            earlier = f"{fastest(before[key]):.0f} s" if key in before else "not run"
            print(f"rot_speed {robot}: basement fastest plan {fastest(after[key]):.0f} s (earlier {earlier})")
        maps = [k for k in after if k[1] == robot and ("/generated/" in k[0] or k[0].endswith("basement.yaml"))]
        for search in SEARCHES:
            ratios = [statistics.median(after[k][search]) / strongest_control(after[k]) for k in maps if search in after[k]]
            if not ratios:
                continue
            print(
                f"rot_speed {robot}: {search}: median over seeds / strongest control on {len(ratios)} maps: "
                f"<= 0.90 on {sum(r <= 0.90 for r in ratios)}, <= 0.97 on {sum(r <= 0.97 for r in ratios)}; "
                f"best {min(ratios):.3f}, median {statistics.median(ratios):.3f}"
            )


if __name__ == "__main__":
    main()
