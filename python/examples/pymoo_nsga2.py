"""NSGA-II from pymoo on covga's exact coverage fitness, beside the thesis GA.

pymoo evolves fixed-length action genomes (L actions of heading in degrees and distance in
metres) on thesis map 1, scored by ``covga.thesis.evaluate``: both objectives of 003,
``cov_final`` and ``t_final``, maximised, and the swept obstacle cells as a constraint (a
plan must stay in free space). The thesis GA (003 Table A.1 (e), Elite, f2) runs with the same
number of evaluations, once with its own selection and once with covga's NSGA-II selection.
The figure shows pymoo's final non-dominated set beside the thesis GA's final population and
front; the script prints the best plans.

    pip install ./python pymoo matplotlib
    python python/examples/pymoo_nsga2.py --out out/pymoo_nsga2.png

``--processes 4`` evaluates one genome per task on a pool of 4 processes (pymoo's
``StarmapParallelization``; the problem, map included, is pickled to each), with the same result;
``--save-history`` keeps a copy of the algorithm per generation (``save_history=True``, which
deep-copies the problem and its map).
"""

from __future__ import annotations

import argparse
import multiprocessing
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from typing import Any  # noqa: E402

# pymoo ships no type information: its names are Any to mypy.
from pymoo.algorithms.moo.nsga2 import NSGA2  # type: ignore[import-untyped]  # noqa: E402
from pymoo.core.problem import ElementwiseProblem, Problem  # type: ignore[import-untyped]  # noqa: E402
from pymoo.optimize import minimize  # type: ignore[import-untyped]  # noqa: E402
from pymoo.parallelization import StarmapParallelization  # type: ignore[import-untyped]  # noqa: E402

import covga  # noqa: E402

START = (1.3, 1.3)
WIDTH, SPEED = 0.6, 0.2
DIST_MAX = 3.0  # metres, the thesis GA's init_dist_max


class ActionGenomes(Problem):  # type: ignore[misc]
    """2·L variables (heading, distance) per genome; minimises −cov_final and −t_final subject
    to no swept obstacle cell."""

    def __init__(self, world: covga.Map, actions: int) -> None:
        lower = np.tile([0.0, 0.0], actions)
        upper = np.tile([360.0, DIST_MAX], actions)
        super().__init__(n_var=2 * actions, n_obj=2, n_ieq_constr=1, xl=lower, xu=upper)
        self.world, self.actions = world, actions

    def _evaluate(self, x: np.ndarray, out: dict[str, Any], *args: Any, **kwargs: Any) -> None:
        genomes = x.reshape(len(x), self.actions, 2)
        scores = covga.thesis.evaluate(self.world, genomes, width=WIDTH, speed=SPEED, start=START)
        out["F"] = -scores[:, :2]
        out["G"] = scores[:, 3:4]


class OneGenome(ElementwiseProblem):  # type: ignore[misc]
    """The same problem one genome at a time, for a runner that hands genomes to processes."""

    def __init__(self, world: covga.Map, actions: int, **kwargs: Any) -> None:
        lower = np.tile([0.0, 0.0], actions)
        upper = np.tile([360.0, DIST_MAX], actions)
        super().__init__(n_var=2 * actions, n_obj=2, n_ieq_constr=1, xl=lower, xu=upper, **kwargs)
        self.world, self.actions = world, actions

    def _evaluate(self, x: np.ndarray, out: dict[str, Any], *args: Any, **kwargs: Any) -> None:
        scores = covga.thesis.evaluate(
            self.world, x.reshape(1, self.actions, 2), width=WIDTH, speed=SPEED, start=START, threads=1
        )
        out["F"] = -scores[0, :2]
        out["G"] = scores[0, 3:4]


def thesis_ga(evaluations: int, seed: int, selection: str = "elite") -> covga.Result:
    """The thesis GA of 003 Table A.1 (e) with an evaluation budget (and another selection)."""
    return covga.run(
        {
            "seed": seed,
            "planner": "thesis",
            "map": {"source": "thesis-1"},
            "robot": {"width": WIDTH, "speed": SPEED},
            "stations": {"start": list(START)},
            "scorer": {"projection": "f2"},
            "thesis": {"selection": selection, "init_actions": 50, "init_dist_max": DIST_MAX},
            "budget": {"evaluations": evaluations, "iterations": 1_000_000},
        }
    )


def non_dominated(points: np.ndarray) -> np.ndarray:
    """The rows no other row beats in both columns (both maximised)."""
    keep = [not np.any(np.all(points >= p, axis=1) & np.any(points > p, axis=1)) for p in points]
    kept: np.ndarray = points[np.array(keep, dtype=bool)]
    return kept


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--actions", type=int, default=50, help="actions per genome (L)")
    parser.add_argument("--pop", type=int, default=100, help="NSGA-II population size")
    parser.add_argument("--generations", type=int, default=200)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--out", type=Path, default=Path("out/pymoo_nsga2.png"))
    parser.add_argument("--processes", type=int, default=0, help="a pool of this many processes (0: in-process)")
    parser.add_argument("--save-history", action="store_true", help="pymoo's save_history=True")
    a = parser.parse_args()

    world = covga.load_map("thesis-1")
    began = time.perf_counter()
    options = dict(seed=a.seed, verbose=False, save_history=a.save_history)
    if a.processes > 0:
        with multiprocessing.Pool(a.processes) as pool:
            problem = OneGenome(world, a.actions, elementwise_runner=StarmapParallelization(pool.starmap))
            found = minimize(problem, NSGA2(pop_size=a.pop), ("n_gen", a.generations), **options)
    else:
        problem = ActionGenomes(world, a.actions)
        found = minimize(problem, NSGA2(pop_size=a.pop), ("n_gen", a.generations), **options)
    nsga_s = time.perf_counter() - began
    evaluations = found.algorithm.evaluator.n_eval
    feasible = found.pop[found.pop.get("feasible")[:, 0]]
    front = non_dominated(-feasible.get("F")) if len(feasible) else np.empty((0, 2))

    began = time.perf_counter()
    ga = thesis_ga(evaluations, a.seed)
    ga_s = time.perf_counter() - began
    pareto = thesis_ga(evaluations, a.seed, "nsga2")
    covga_front = np.array([row[:2] for row in pareto.summary["front"]])
    population = ga.population
    ga_points = np.column_stack([np.asarray(population["cov_final"]), np.asarray(population["t_final"])])

    print(
        f"pymoo NSGA-II: {evaluations} evaluations in {nsga_s:.1f} s, {len(front)} feasible non-dominated plans"
    )
    if a.save_history:
        print(f"  history: {len(found.history)} generations kept")
    if len(front):
        best = front[np.argmax(front[:, 0] * front[:, 1])]
        print(f"  best f2 plan: cov_final {best[0]:.3f}, t_final {best[1]:.3f}, f2 {best[0] * best[1]:.3f}")
    o = ga.summary["objectives"]
    print(f"thesis GA (Elite, f2): {ga.summary['evaluations']} evaluations in {ga_s:.1f} s")
    f2 = o["cov_final"] * o["t_final"]
    print(f"  best plan: cov_final {o['cov_final']:.3f}, t_final {o['t_final']:.3f}, f2 {f2:.3f}")
    k = pareto.summary["objectives"]
    print(f"thesis GA with covga's NSGA-II selection: {len(covga_front)} plans on its final front")
    print(f"  knee plan: cov_final {k['cov_final']:.3f}, t_final {k['t_final']:.3f}")

    fig, ax = plt.subplots(figsize=(6.4, 4.8), constrained_layout=True)
    elite = "thesis GA (Elite)"
    ax.scatter(ga_points[:, 0], ga_points[:, 1], s=14, c="tab:blue", alpha=0.5, label=f"{elite} final population")
    ax.scatter(front[:, 0], front[:, 1], s=22, c="tab:orange", marker="D", label="pymoo NSGA-II front (feasible)")
    ax.scatter(covga_front[:, 0], covga_front[:, 1], s=22, c="tab:green", marker="s", label="thesis GA, NSGA-II selection: front")
    ax.scatter([o["cov_final"]], [o["t_final"]], s=90, c="none", edgecolors="black", label=f"{elite} best (f2)")
    ax.set_xlabel("cov_final (share of free cells covered)")
    ax.set_ylabel("t_final (time objective, higher is faster)")
    ax.set_title(f"thesis-1, {evaluations} evaluations each, seed {a.seed}")
    ax.legend(loc="lower left")
    ax.grid(alpha=0.3)
    a.out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(a.out, dpi=120)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
