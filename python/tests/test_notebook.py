"""What a notebook draws and digs into: the cells a score counts, a genome's path, the final
population's genomes, a study's curves and fronts."""

import matplotlib
import numpy as np
import pytest
from conftest import SHORT_THESIS

import covga

matplotlib.use("Agg")


def _labels(ax):
    return [t.get_text() for t in ax.get_legend().get_texts()]


def test_a_score_holds_the_cells_it_counts_and_draws_them():
    m = covga.load_map("thesis-2")
    plan = covga.pattern(m, "boustrophedon", start=(1.3, 1.3))
    plain = covga.score(m, plan)
    s = covga.score(m, plan, raster=True)
    assert isinstance(s, dict) and "visits" not in plain
    assert {k: v for k, v in s.items() if k not in ("visits", "reachable")} == dict(plain)
    visits, reachable = s["visits"], s["reachable"]
    assert visits.shape == m.shape == reachable.shape
    assert visits.dtype == np.uint32 and reachable.dtype == np.bool_
    assert int((visits > 0).sum()) == s["unique_cells"]
    assert int(visits.sum()) == s["cells_swept"]
    assert int(((visits > 0) & reachable).sum()) == s["unique_reach_cells"]
    assert int(reachable.sum()) == s["reachable_cells"]
    assert not visits[m.states != 0].any(), "obstacle cells are never counted as covered"
    # Row 0 is the bottom row: the plan starts at (1.3, 1.3), so that cell is swept.
    assert visits[int(1.3 / m.resolution), int(1.3 / m.resolution)] > 0
    ax = s.plot()
    labels = _labels(ax)
    assert labels[:3] == ["path", "path start", "path end"]
    assert {"covered once", "covered 2+ times", "free, not covered", "occupied"} <= set(labels)
    assert ax.get_aspect() == 1.0 and ax.get_title().startswith("coverage ")
    assert _labels(plain.plot())[:3] == ["path", "path start", "path end"]
    with pytest.raises(covga.ConfigError, match="raster"):
        covga.score(m, plan, raster="yes")
    with pytest.raises(covga.ConfigError, match="visits of shape"):
        covga.plot.plot_coverage(m, visits[1:], plan)


@pytest.mark.parametrize("moves", ["straight", "routed"])
def test_genomes_decode_to_the_runs_path_and_the_population_rescores_to_its_table(tmp_path, moves):
    text = SHORT_THESIS.replace("thesis-1", "thesis-2").replace("[thesis]\n", f'[thesis]\nmoves = "{moves}"\n')
    r = covga.run(text + "[output]\npopulation_genomes = true\n", out=tmp_path / "run", figures=False)
    m, start = r.map, (1.3, 1.3)
    best = covga.thesis.decode(m, covga.thesis.read_genome(r.dir), start=start, moves=moves)
    assert np.array_equal(best, r.path), "the decoded best genome is the run's best_path.csv"
    assert r.genomes is not None and len(r.genomes) == len(r.population)
    assert [len(g) + 2 for g in r.genomes] == list(np.asarray(r.population["genome_len"]))
    scores = covga.thesis.evaluate(m, r.genomes, start=start, moves=moves)
    assert np.array_equal(scores[:, 0], np.asarray(r.population["cov_final"]))
    assert np.array_equal(scores[:, 1], np.asarray(r.population["t_final"]))
    assert np.array_equal(scores[:, 3], np.asarray(r.population["obstacle_cells"]))
    assert covga.run(SHORT_THESIS).genomes is None, "written only when asked"
    with pytest.raises(covga.ConfigError, match="genome"):
        covga.thesis.decode(m, np.zeros((0, 2)))


GRID = """\
seed = 3
seeds = 3
[base]
planner = "thesis"
[base.map]
source = "thesis-1"
[base.thesis]
pop_min = 20
init_actions = 20
[base.budget]
iterations = 30
[axes]
"thesis.selection" = ["elite", "nsga2"]
"""


def test_a_studys_curves_and_fronts_as_figures(tmp_path):
    grid_file = tmp_path / "tiny.toml"
    grid_file.write_text(GRID)
    runs = covga.grid(grid_file, jobs=2, out=tmp_path / "study")
    ax = covga.plot.plot_curves(tmp_path / "study", by="thesis.selection")
    labels = _labels(ax)
    assert labels == [
        "thesis.selection = elite (median of 3)",
        "thesis.selection = elite, quartiles",
        "thesis.selection = nsga2 (median of 3)",
        "thesis.selection = nsga2, quartiles",
    ]
    assert ax.get_xlabel() == "evaluations" and ax.get_ylabel() == "best_coverage_reach"
    assert len(ax.get_lines()[0].get_ydata()) == 31, "iterations 0 to 30"
    fitness = covga.plot.plot_curves(tmp_path / "study", by="thesis.selection", column="best_fitness")
    median = fitness.get_lines()[0].get_ydata()
    assert np.all(np.diff(median) >= 0) and median[-1] > median[0], "Elite's best fitness never gets worse"
    ax = covga.plot.plot_fronts(tmp_path / "study", by="thesis.selection")
    labels = _labels(ax)
    assert labels == [
        "thesis.selection = elite: final fronts",
        "thesis.selection = elite: returned plans",
        "thesis.selection = nsga2: final fronts",
        "thesis.selection = nsga2: returned plans",
    ]
    markers = [line for line in ax.get_lines() if line.get_marker() == "o"]
    assert sum(len(line.get_xdata()) for line in markers) == len(runs)
    with pytest.raises(covga.ConfigError, match="not a column"):
        covga.plot.plot_curves(tmp_path / "study", by="thesis.nothing")
