#!/usr/bin/env python3
"""Lays out the cell-order study: generates its 20 floor plans with `covga maps generate` into
experiments/maps/generated/ (10 layouts, each clean and with SLAM-like noise) and writes
grids/cell-order.toml (edit this script, not the grid). Computes nothing about results.

    python3 scripts/cell-order-grid.py target/release/covga

The generated maps are committed; tests/it/generated_maps.rs checks that the command re-makes
them byte for byte.
"""

import re
import subprocess
import sys
from pathlib import Path

# (kind, seed) of the generated layouts; each is made clean and noisy.
LAYOUTS = [("office", s) for s in (1, 2, 3, 4)] + [("house", s) for s in (1, 2, 3)] + [("warehouse", s) for s in (1, 2, 3)]
GENERATED = Path("experiments/maps/generated")
# The real and synthetic maps of the earlier study, with their start stations.
FIXED = [
    ("thesis-2", (1.3, 1.3)),
    ("office", (2.0, 2.0)),
    ("office-ring", (8.75, 8.75)),
    ("experiments/maps/basement.yaml", (0.0, 0.0)),
]
SOLVERS = ["ga", "ils", "nearest", "boustrophedon"]


def generate(covga):
    """Makes every generated map; returns [(source, start)]."""
    GENERATED.mkdir(parents=True, exist_ok=True)
    out = []
    for kind, seed in LAYOUTS:
        for noisy in (False, True):
            cmd = [covga, "maps", "generate", "--kind", kind, "--seed", str(seed), "--out", str(GENERATED)]
            if noisy:
                cmd.append("--noisy")
            text = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
            path = re.search(r"wrote (\S+)", text).group(1)
            x, y = re.search(r"start = \[([-0-9.e]+), ([-0-9.e]+)\]", text).groups()
            out.append((path, (float(x), float(y))))
    return out


def toml_list(xs):
    return "[" + ", ".join(f'"{x}"' for x in xs) + "]"


def main():
    covga = sys.argv[1] if len(sys.argv) > 1 else "target/release/covga"
    maps = FIXED + generate(covga)
    lines = [
        "# The cell-order study (issues: a GA that earns its keep; where the time goes). Laid out by",
        "# scripts/cell-order-grid.py, which also generates the 20 floor plans of",
        "# experiments/maps/generated/ (10 layouts of offices, houses and warehouses, each clean and",
        "# with SLAM-like noise); edit that script, not this file.",
        "#",
        "# On every map, for two robots 0.6 m wide driving at 0.3 m/s (one turning for free, one",
        "# turning at 0.52 rad/s, the ipa benchmark's robot), the cell-order planner's searches (the",
        "# memetic GA alone; the GA and the iterated local search seeded with the no-search control's",
        "# tours and with the classical control's plans among their finalists) against its two",
        "# controls with no search (nearest: the nearest-neighbour cell order at one lane direction;",
        "# boustrophedon: one whole-map boustrophedon; each at the best of its directions). Every",
        "# cell-order plan has every improvement that needs no search: lanes joined across small",
        "# obstacles (merge_gap_m = 2.4), offered beside their split lanes per cell",
        "# (offer_split_lanes), the two dominant wall orientations among the lane directions, the",
        "# searched quota completion (quota_search); all end at the same coverage goal (0.90 of the",
        "# reachable cells), so that time_s compares plans at equal coverage. The classical",
        "# patterns with their own greedy completion run beside them (full coverage, no goal).",
        "# 10 seeds; the controls and the patterns read no seed and run once.",
        "#   covga grid grids/cell-order.toml --jobs 2 --out out/cell-order",
        "#   covga report out/cell-order --name controls --where planner=cell_order \\",
        "#     --compare 'cell_order.solver=nearest|boustrophedon' \\",
        "#     --compare cell_order.solver=nearest --compare cell_order.solver=boustrophedon \\",
        "#     --compare cell_order.solver=ils",
        "seed = 2026",
        "seeds = 10",
        "",
        "[base]",
        'planner = "cell_order"',
        "[base.robot]",
        "width = 0.6",
        "speed = 0.3",
        "[base.cell_order]",
        "coverage_goal = 0.9",
        'completion = "quota_search"',
        "merge_gap_m = 2.4",
        "offer_split_lanes = true",
        "wall_directions = 2",
        "[base.budget]",
        "iterations = 1000000   # the evaluation budget stops the searches",
        "evaluations = 50000",
        "",
        "[axes]",
        '"map.source" = ' + toml_list(m for m, _ in maps),
        '"robot.rot_speed" = [0.0, 0.52]',
        '"planner" = ["cell_order", "boustrophedon", "spiral"]',
        "",
        "[[conditional]]",
        'when = { "planner" = "cell_order" }',
        f'axes = {{ "cell_order.solver" = {toml_list(SOLVERS)} }}',
        "",
        "[[conditional]]",
        'when = { "planner" = "boustrophedon" }',
        'axes = { "pattern.angle_deg" = [0.0, 45.0, 90.0, 135.0] }',
    ]
    for source, (x, y) in maps:
        lines += [
            "",
            "[[conditional]]",
            f'when = {{ "map.source" = "{source}" }}',
            f'axes = {{ "stations.start" = [[{x}, {y}]] }}',
        ]
    lines += [
        "",
        "# After the solver axis they depend on: the GA alone, and both searches seeded with the",
        "# no-search control's tours (kept among their finalists) and with the classical control's",
        "# plans among their finalists.",
        "[[conditional]]",
        'when = { "planner" = "cell_order", "cell_order.solver" = "ga" }',
        'axes = { "cell_order.seed_directions" = [false, true] }',
        "",
        "[[conditional]]",
        'when = { "planner" = "cell_order", "cell_order.solver" = "ga", "cell_order.seed_directions" = true }',
        'axes = { "cell_order.classical_finalists" = [true] }',
        "",
        "[[conditional]]",
        'when = { "planner" = "cell_order", "cell_order.solver" = "ils" }',
        'axes = { "cell_order.seed_directions" = [true], "cell_order.classical_finalists" = [true] }',
    ]
    Path("grids/cell-order.toml").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
