#!/usr/bin/env python3
"""Make a committed study's reports again without re-running all of it.

`covga report` reads runs.csv and, for some runs, their folders: the histories of the runs its
diversity figures and claims read, and the best paths it draws. A committed study keeps only
runs.csv. This script lays out a study folder whose runs.csv holds the committed rows minus the
runs whose folders are needed, so that resuming the study (`covga grid`) runs exactly those;
then it checks that every re-run row equals its committed row in every column but `wall_s`,
and puts the committed rows back (their timings are the study's, Table 4.4's among them).

  scripts/report-histories.py prepare RUNS_CSV STUDY_DIR GRID [--all COL=VAL ...] [--not-executable]
      [--report 'COL=VAL,...;BY,...' ...]
  covga grid GRID --jobs 2 --out STUDY_DIR
  scripts/report-histories.py restore RUNS_CSV STUDY_DIR

Needed: every run matching all `--all` filters (the runs whose diversity the thesis claims
read: map 1 without rotation cost), every run whose plan is not executable with
`--not-executable`, and for each `--report` (its `--where` filters; its `--by` columns) the
runs on each group's drawn front (non-dominated in t_final and cov_final_free among executable
runs, coverage at least 1 %) and the best run by f_free of each group and projection (all runs
tied at the best). RUNS_CSV may be .xz.
"""
import argparse
import csv
import io
import lzma
import os
import shutil
import sys

FRONT_MIN_COVERAGE = 0.01  # src/report/analysis/runs.rs


def read(path):
    text = lzma.open(path, "rt").read() if path.endswith(".xz") else open(path).read()
    rows = list(csv.reader(io.StringIO(text)))
    return rows[0], rows[1:]


def matches(row, h, filters):
    for col, val in filters:
        a = row[h[col]]
        try:
            if float(a) != float(val):
                return False
        except ValueError:
            if a != val:
                return False
    return True


def needed(header, rows, alls, not_executable, reports):
    h = {c: i for i, c in enumerate(header)}
    need = {r[h["run_id"]] for r in rows if alls and matches(r, h, alls)}
    if not_executable:
        need |= {r[h["run_id"]] for r in rows if r[h["executable"]] == "false"}
    for filters, by in reports:
        groups = {}
        for r in rows:
            if matches(r, h, filters):
                groups.setdefault(tuple(r[h[c]] for c in by), []).append(r)
        for g in groups.values():
            ex = [r for r in g if r[h["executable"]] == "true"]
            pts = [(float(r[h["t_final"]]), float(r[h["cov_final_free"]])) for r in ex]
            best_y, last = float("-inf"), None
            for i in sorted(range(len(pts)), key=lambda i: (-pts[i][0], -pts[i][1])):
                if pts[i][1] > best_y or last == pts[i]:
                    if pts[i][1] >= FRONT_MIN_COVERAGE:
                        need.add(ex[i][h["run_id"]])
                    best_y, last = max(best_y, pts[i][1]), pts[i]
            for proj in {r[h["scorer.projection"]] for r in g}:
                scope = [r for r in g if r[h["scorer.projection"]] == proj]
                pool = [r for r in scope if r[h["executable"]] == "true"] or scope
                top = max(float(r[h["f_free"]]) for r in pool)
                need |= {r[h["run_id"]] for r in pool if float(r[h["f_free"]]) == top}
    return need


def pairs(items):
    return [tuple(x.split("=", 1)) for x in items if x]


def prepare(a):
    header, rows = read(a.runs)
    reports = []
    for spec in a.report:
        where, by = spec.split(";")
        reports.append((pairs(where.split(",")), [c for c in by.split(",") if c]))
    need = needed(header, rows, pairs(a.all), a.not_executable, reports)
    os.makedirs(a.study, exist_ok=True)
    if os.path.exists(os.path.join(a.study, "runs.csv")):
        sys.exit(f"{a.study}/runs.csv exists: prepare an empty folder")
    committed = os.path.join(os.path.dirname(a.runs), "study.json")
    shutil.copy(committed, os.path.join(a.study, "study.json"))
    shutil.copy(a.grid, os.path.join(a.study, "grid.toml"))
    i = header.index("run_id")
    with open(os.path.join(a.study, "runs.csv"), "w", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows([header] + [r for r in rows if r[i] not in need])
    print(f"{len(need)} of {len(rows)} runs to re-run: covga grid GRID --jobs 2 --out {a.study}")


def restore(a):
    header, rows = read(a.runs)
    new_header, new_rows = read(os.path.join(a.study, "runs.csv"))
    if new_header != header:
        sys.exit("the study folder's runs.csv has other columns than the committed one")
    i, wall = header.index("run_id"), header.index("wall_s")
    now = {r[i]: r for r in new_rows}
    missing = [r[i] for r in rows if r[i] not in now]
    differ = [r[i] for r in rows if r[i] in now and any(x != y for k, (x, y) in enumerate(zip(r, now[r[i]])) if k != wall)]
    if missing or differ:
        sys.exit(f"{len(missing)} runs not run yet, {len(differ)} differ from the committed rows (e.g. {(missing + differ)[:3]})")
    with open(os.path.join(a.study, "runs.csv"), "w", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows([header] + sorted(rows, key=lambda r: r[i]))
    print(f"all {len(rows)} rows equal the committed ones but wall_s; the committed rows are back in runs.csv")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    q = sub.add_parser("prepare")
    q.add_argument("runs"), q.add_argument("study"), q.add_argument("grid")
    q.add_argument("--all", action="append", default=[])
    q.add_argument("--not-executable", action="store_true")
    q.add_argument("--report", action="append", default=[])
    r = sub.add_parser("restore")
    r.add_argument("runs"), r.add_argument("study")
    a = p.parse_args()
    prepare(a) if a.cmd == "prepare" else restore(a)


if __name__ == "__main__":
    main()
