#!/usr/bin/env python3
"""Brings a runs.csv of the thesis maps up to today's columns without re-running it.

The common scorer now reports `executable` (the plan sweeps no obstacle or unknown cell and
stays on the map) beside the planner's own `planner_feasible` (formerly `feasible`). On the
thesis maps (1 m of wall around the field, no unknown cells) a footprint cannot leave the map
without sweeping wall cells, so `executable` is `obstacle_cells == 0` there; every other
column is unchanged. Refuses any other map. tests/committed_results.rs re-runs sampled rows of
each study and compares every column, so a wrong migration fails the suite.

Usage: scripts/add-executable-column.py results/thesis-table-4-3/runs.csv.xz
"""
import csv
import io
import lzma
import sys

THESIS_MAPS = {"thesis-1", "thesis-2"}


def migrate(text):
    rows = list(csv.reader(io.StringIO(text)))
    header = rows[0]
    if "executable" in header:
        sys.exit("already has an `executable` column")
    header[header.index("feasible")] = "planner_feasible"
    at = header.index("agents") + 1
    obstacle, map_col = header.index("obstacle_cells"), header.index("map")
    out = [header[:at] + ["executable"] + header[at:]]
    for r in rows[1:]:
        if r[map_col] not in THESIS_MAPS:
            sys.exit(f"run {r[0]} is on map {r[map_col]}: only the thesis maps can be migrated; re-run the study")
        out.append(r[:at] + [str(r[obstacle] == "0").lower()] + r[at:])
    buf = io.StringIO()
    csv.writer(buf, lineterminator="\n").writerows(out)
    return buf.getvalue()


def main(path):
    packed = path.endswith(".xz")
    raw = lzma.open(path, "rt", encoding="utf-8", newline="").read() if packed else open(path, newline="").read()
    text = migrate(raw)
    if packed:
        with lzma.open(path, "wt", encoding="utf-8", newline="", preset=9) as f:
            f.write(text)
    else:
        with open(path, "w", newline="") as f:
            f.write(text)


if __name__ == "__main__":
    for p in sys.argv[1:]:
        main(p)
