"""An established solver's answer to covga's tour problem: the GTSPLIB instance `covga gtsp`
writes, turned into an asymmetric TSP by the Noon–Bean transform (Noon & Bean 1993) and solved
by LKH (Helsgaun; through the `elkai` package), then read back as a tour of the cells.

Run as a script it measures the check on experiment files:

    python python/tests/gtsp_reference.py EXPERIMENT.toml...

prints, per file, the weight of the search's tour (`covga run`'s `tour_cost_s`), LKH's, and
their ratio. LKH's native code is for non-commercial use (its licence ships with `elkai`): covga
uses it only here, as a test's reference, never in the library.
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

# Seconds per unit of weight in covga's GTSPLIB files.
WEIGHT_S = 1e-3
# LKH reads integers and scales them by its precision (100) internally: the transformed matrix
# is handed to it in units of this many weights (10 ms) so that the big-M arcs stay in range.
LKH_UNIT = 10


@dataclass
class Gtsp:
    """A GTSPLIB instance: the full weight matrix (node 0 the stations) and the sets."""

    weights: np.ndarray
    sets: list[list[int]]

    def set_of(self) -> np.ndarray:
        out = np.empty(len(self.weights), dtype=np.int64)
        for s, members in enumerate(self.sets):
            out[members] = s
        return out

    def tour_weight(self, nodes: list[int]) -> int:
        """The weight of the closed tour through `nodes` (0-based, the stations first)."""
        return int(sum(self.weights[a, b] for a, b in zip(nodes, nodes[1:] + nodes[:1])))


def read_gtsplib(path: Path) -> Gtsp:
    """Reads a `TYPE : AGTSP` full-matrix file as `covga gtsp` writes it."""
    lines = Path(path).read_text().split("\n")
    head: dict[str, str] = {}
    i = 0
    while lines[i] != "EDGE_WEIGHT_SECTION":
        key, _, value = lines[i].partition(" : ")
        head[key] = value
        i += 1
    n = int(head["DIMENSION"])
    weights = np.array([[int(w) for w in lines[i + 1 + r].split()] for r in range(n)], dtype=np.int64)
    j = i + 1 + n
    assert lines[j] == "GTSP_SET_SECTION", lines[j]
    sets = []
    for line in lines[j + 1 :]:
        if line == "EOF":
            break
        fields = [int(f) for f in line.split()]
        assert fields[-1] == -1 and fields[0] == len(sets) + 1, line
        sets.append([node - 1 for node in fields[1:-1]])
    assert len(sets) == int(head["GTSP_SETS"])
    return Gtsp(weights, sets)


def greedy_weight(weights: np.ndarray, g: Gtsp) -> int:
    """The weight of the nearest-neighbour tour over the sets (the cheapest arc into a set not
    yet entered, from the stations and back to them)."""
    set_of = g.set_of()
    open_sets = np.ones(len(g.sets), dtype=bool)
    open_sets[set_of[0]] = False
    here, total = 0, 0
    while open_sets.any():
        row = np.where(open_sets[set_of], weights[here], np.iinfo(np.int64).max)
        here = int(np.argmin(row))
        total += int(row[here])
        open_sets[set_of[here]] = False
    return total + int(weights[here, 0])


def noon_bean(g: Gtsp, unit: int = LKH_UNIT) -> np.ndarray:
    """The asymmetric TSP, in units of `unit` weights, whose optimal tours are the GTSP's: each
    set's members on a cycle of zero arcs, and every arc leaving a set moved to the member
    before the one it left from, plus a constant M, so that a tour enters each set once."""
    n = len(g.weights)
    set_of = g.set_of()
    succ = np.empty(n, dtype=np.int64)
    for members in g.sets:
        succ[members] = np.roll(members, -1)
    c = np.rint(g.weights / unit).astype(np.int64)
    # Above the weight of one proper tour, so above the optimum's: a tour that enters a set
    # twice pays M once more than any tour that enters each once, and loses to the optimum.
    big = greedy_weight(c, g) + 1
    out = c[succ, :] + big
    out[set_of[:, None] == set_of[None, :]] = 3 * big
    out[np.arange(n), succ] = 0
    np.fill_diagonal(out, 0)
    return out


def solve(g: Gtsp, runs: int = 1, unit: int = LKH_UNIT) -> list[int]:
    """LKH's tour of `g` (its weights handed over in units of `unit`): one node per set, the
    stations first."""
    import elkai

    order = elkai.DistanceMatrix(noon_bean(g, unit).tolist()).solve_tsp(runs=runs)[:-1]
    start = order.index(0)
    order = order[start:] + order[:start]
    set_of = g.set_of()
    tour, seen = [], set()
    for node in order:
        s = int(set_of[node])
        if not tour or set_of[tour[-1]] != s:
            if s in seen:
                raise AssertionError(f"LKH's tour enters set {s + 1} twice: M is too small")
            seen.add(s)
            tour.append(node)
    assert len(tour) == len(g.sets)
    return tour


def search_tour(g: Gtsp, nodes_csv: Path, summary: dict) -> list[int]:
    """The nodes of the tour a cell-order run's `summary.json` reports, the stations first."""
    import csv

    node = {}
    with open(nodes_csv) as f:
        for row in csv.DictReader(f):
            if row["cell"]:
                node[(int(row["cell"]), float(row["direction_deg"]), int(row["entry"]))] = int(row["node"]) - 1
    return [0] + [node[(s["cell"], float(s["direction_deg"]), s["entry"])] for s in summary["tour"]]


def measure(covga_bin: Path, experiment: Path, work: Path, runs: int = 1) -> dict:
    """`covga run` and `covga gtsp` on `experiment`, LKH on the instance: the search's tour
    weight, LKH's, in seconds, and LKH's wall time."""
    problem, nodes = work / "problem.gtsp", work / "nodes.csv"
    subprocess.run([str(covga_bin), "gtsp", str(experiment), "--out", str(problem), "--nodes", str(nodes)], check=True)
    subprocess.run([str(covga_bin), "run", str(experiment), "--out", str(work / "run"), "--quiet"], check=True)
    summary = json.loads((work / "run" / "summary.json").read_text())
    g = read_gtsplib(problem)
    started = time.monotonic()
    lkh = solve(g, runs)
    wall = time.monotonic() - started
    searched = search_tour(g, nodes, summary)
    return {
        "cells": len(g.sets) - 1,
        "nodes": len(g.weights),
        "search_s": summary["tour_cost_s"],
        "search_weight_s": g.tour_weight(searched) * WEIGHT_S,
        "lkh_s": g.tour_weight(lkh) * WEIGHT_S,
        "lkh_wall_s": wall,
    }


if __name__ == "__main__":
    binary = Path(__file__).resolve().parents[2] / "target" / "release" / "covga"
    print("file,cells,nodes,search_s,lkh_s,search_over_lkh,lkh_wall_s")
    for arg in sys.argv[1:]:
        with tempfile.TemporaryDirectory() as tmp:
            m = measure(binary, Path(arg), Path(tmp))
        ratio = m["search_s"] / m["lkh_s"]
        print(f"{arg},{m['cells']},{m['nodes']},{m['search_s']:.1f},{m['lkh_s']:.1f},{ratio:.4f},{m['lkh_wall_s']:.1f}")
