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
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from pymoo.algorithms.moo.nsga2 import NSGA2  # noqa: E402
from pymoo.core.problem import Problem  # noqa: E402
from pymoo.optimize import minimize  # noqa: E402

import covga  # noqa: E402

START = (1.3, 1.3)
WIDTH, SPEED = 0.6, 0.2
DIST_MAX = 3.0  # metres, the thesis GA's init_dist_max


class ActionGenomes(Problem):
    """2·L variables (heading, distance) per genome; minimises −cov_final and −t_final subject
    to no swept obstacle cell."""

    def __init__(self, world: covga.Map, actions: int):
        lower = np.tile([0.0, 0.0], actions)
        upper = np.tile([360.0, DIST_MAX], actions)
        super().__init__(n_var=2 * actions, n_obj=2, n_ieq_constr=1, xl=lower, xu=upper)
        self.world, self.actions, self.evaluations = world, actions, 0

    def _evaluate(self, x, out, *args, **kwargs):
        genomes = x.reshape(len(x), self.actions, 2)
        scores = covga.thesis.evaluate(self.world, genomes, width=WIDTH, speed=SPEED, start=START)
        self.evaluations += len(x)
        out["F"] = -scores[:, :2]
        out["G"] = scores[:, 3:4]


def thesis_ga(evaluations: int, seed: int, selection: str = "elite") -> covga.Result:
    """The thesis GA of 003 Table A.1 (e) with an evaluation budget (and another selection)."""
    return covga.run(
        {
            "seed": seed,
            "planner": "thesis",
            "map": {"source": "thesis-1"},
            "robot": {"width": WIDTH, "speed": SPEED},
            "stations": {"start": list(START)},
            "thesis": {"projection": "f2", "selection": selection, "init_actions": 50, "init_dist_max": DIST_MAX},
            "budget": {"evaluations": evaluations, "iterations": 1_000_000},
        }
    )


def non_dominated(points: np.ndarray) -> np.ndarray:
    """The rows no other row beats in both columns (both maximised)."""
    keep = [not np.any(np.all(points >= p, axis=1) & np.any(points > p, axis=1)) for p in points]
    return points[np.array(keep, dtype=bool)]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--actions", type=int, default=50, help="actions per genome (L)")
    parser.add_argument("--pop", type=int, default=100, help="NSGA-II population size")
    parser.add_argument("--generations", type=int, default=200)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--out", type=Path, default=Path("out/pymoo_nsga2.png"))
    a = parser.parse_args()

    world = covga.load_map("thesis-1")
    problem = ActionGenomes(world, a.actions)
    began = time.perf_counter()
    found = minimize(problem, NSGA2(pop_size=a.pop), ("n_gen", a.generations), seed=a.seed, verbose=False)
    nsga_s = time.perf_counter() - began
    feasible = found.pop[found.pop.get("feasible")[:, 0]]
    front = non_dominated(-feasible.get("F")) if len(feasible) else np.empty((0, 2))

    began = time.perf_counter()
    ga = thesis_ga(problem.evaluations, a.seed)
    ga_s = time.perf_counter() - began
    pareto = thesis_ga(problem.evaluations, a.seed, "nsga2")
    covga_front = np.array([row[:2] for row in pareto.summary["front"]])
    population = ga.population
    ga_points = np.column_stack([np.asarray(population["cov_final"]), np.asarray(population["t_final"])])

    print(
        f"pymoo NSGA-II: {problem.evaluations} evaluations in {nsga_s:.1f} s, {len(front)} feasible non-dominated plans"
    )
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
    ax.scatter(*covga_front.T, s=22, c="tab:green", marker="s", label="thesis GA, NSGA-II selection: front")
    ax.scatter([o["cov_final"]], [o["t_final"]], s=90, c="none", edgecolors="black", label=f"{elite} best (f2)")
    ax.set_xlabel("cov_final (share of free cells covered)")
    ax.set_ylabel("t_final (time objective, higher is faster)")
    ax.set_title(f"thesis-1, {problem.evaluations} evaluations each, seed {a.seed}")
    ax.legend(loc="lower left")
    ax.grid(alpha=0.3)
    a.out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(a.out, dpi=120)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
