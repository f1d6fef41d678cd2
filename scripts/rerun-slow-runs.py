#!/usr/bin/env python3
"""Re-measure the wall times of runs that were slowed by other work on the machine.

A study's results do not depend on the machine's load, but `wall_s` (003 Table 4.4) does:
a run that shared its core with a compiler can take ten times its usual time. This script
finds such runs and takes them out of runs.csv, so that resuming the study runs them again;
after the resume it checks that every re-run row equals its first run in every column but
`wall_s`.

  scripts/rerun-slow-runs.py remove STUDY_DIR   # slow rows -> STUDY_DIR/slow-runs.csv
  covga grid GRID --jobs 2 --out STUDY_DIR      # on a quiet machine: runs them again
  scripts/rerun-slow-runs.py check STUDY_DIR    # identical but for wall_s? old and new times

A run is slow when its wall_s exceeds both FACTOR x the median of its group (same selection
scheme, map and rotation cost: the factors that set a run's length) and FLOOR seconds.
"""
import argparse
import csv
import os
import statistics
import sys

GROUP = ("thesis.selection", "map.source", "robot.rot_speed")


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def key(header, row):
    return row[header.index("run_id")], row[header.index("replicate")]


def remove(study, factor, floor):
    runs = os.path.join(study, "runs.csv")
    slow_path = os.path.join(study, "slow-runs.csv")
    if os.path.exists(slow_path):
        sys.exit(f"{slow_path} exists: run `check` first (or remove it by hand)")
    header, rows = read(runs)
    wall = header.index("wall_s")
    cols = [header.index(c) for c in GROUP]
    groups = {}
    for r in rows:
        groups.setdefault(tuple(r[c] for c in cols), []).append(float(r[wall]))
    medians = {g: statistics.median(v) for g, v in groups.items()}
    slow = [r for r in rows if float(r[wall]) > max(factor * medians[tuple(r[c] for c in cols)], floor)]
    if len(slow) > len(rows) // 20:
        sys.exit(f"{len(slow)} slow runs: more than load spikes; re-run the study on a quiet machine")
    slow_keys = {key(header, r) for r in slow}
    keep = [r for r in rows if key(header, r) not in slow_keys]
    with open(slow_path, "w", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows([header] + slow)
    tmp = runs + ".tmp"
    with open(tmp, "w", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows([header] + keep)
    os.replace(tmp, runs)
    print(f"{len(slow)} of {len(rows)} runs slower than max({factor} x group median, {floor} s): "
          f"moved to {slow_path}; resume the study to run them again")


def check(study):
    header, rows = read(os.path.join(study, "runs.csv"))
    old_header, old_rows = read(os.path.join(study, "slow-runs.csv"))
    if old_header != header:
        sys.exit("slow-runs.csv and runs.csv have different columns")
    wall = header.index("wall_s")
    now = {key(header, r): r for r in rows}
    missing, differ = 0, 0
    for old in old_rows:
        new = now.get(key(header, old))
        if new is None:
            missing += 1
            continue
        same = all(a == b for i, (a, b) in enumerate(zip(old, new)) if i != wall)
        differ += not same
        print(f"{old[0]} replicate {old[2]}: {old[wall]} s -> {new[wall]} s{'' if same else '  RESULT DIFFERS'}")
    print(f"{len(old_rows)} re-run rows: {missing} not run yet, {differ} with a different result")
    sys.exit(1 if missing or differ else 0)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("mode", choices=["remove", "check"])
    p.add_argument("study")
    p.add_argument("--factor", type=float, default=5.0)
    p.add_argument("--floor", type=float, default=15.0)
    a = p.parse_args()
    if a.mode == "remove":
        remove(a.study, a.factor, a.floor)
    else:
        check(a.study)


if __name__ == "__main__":
    main()
