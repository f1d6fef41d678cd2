"""`covga.thesis.evaluate`: the thesis GA's own fitness for genomes made in Python."""

import numpy as np
import pytest

import covga
from covga import thesis


@pytest.mark.parametrize(
    "setting",
    [
        {},
        {"robot": {"width": 0.6, "speed": 0.2, "rot_speed": 0.5}, "scorer": {"projection": "f1"}},
        {"map": {"source": "thesis-2"}, "stations": {"start": [1.3, 1.3], "end": [9.7, 1.3]}},
        {"map": {"source": "thesis-2"}, "thesis": {"moves": "routed"}},
    ],
)
def test_batch_evaluation_equals_the_gas_fitness_of_its_best_genome(tmp_path, setting):
    experiment = {"seed": 4, "planner": "thesis", "budget": {"iterations": 40}, **setting}
    experiment.setdefault("thesis", {}).update(pop_min=30, init_actions=30)
    result = covga.run(experiment, out=tmp_path / "run", figures=False)
    genome = thesis.read_genome(tmp_path / "run")
    robot = setting.get("robot", {})
    stations = setting.get("stations", {})
    scores = thesis.evaluate(
        covga.load_map(setting.get("map", {}).get("source", "thesis-1")),
        [genome],
        width=0.6,
        speed=0.2,
        rot_speed=robot.get("rot_speed", 0.0),
        start=stations.get("start", (1.3, 1.3)),
        end=stations.get("end"),
        projection=setting.get("scorer", {}).get("projection", "f2"),
        moves=setting.get("thesis", {}).get("moves", "straight"),
    )
    assert scores.shape == (1, 4) and thesis.COLUMNS == ("cov_final", "t_final", "f", "obstacle_cells")
    objectives = result.summary["objectives"]
    assert scores[0, 0] == objectives["cov_final"]
    assert scores[0, 1] == objectives["t_final"]
    assert scores[0, 2] == objectives["fitness"]
    assert (scores[0, 3] == 0) == result.summary["planner_feasible"]


def test_arrays_and_lists_agree_and_each_genome_stands_alone():
    rng = np.random.default_rng(1)
    batch = np.stack([rng.uniform(0, 360, 25), rng.uniform(0, 3, 25)], axis=-1)[None].repeat(6, axis=0)
    batch[:, :, 0] += np.arange(6)[:, None] * 10.0
    m = covga.load_map("thesis-1")
    as_array = thesis.evaluate(m, batch)
    as_list = thesis.evaluate(m, [g for g in batch])
    one_by_one = np.vstack([thesis.evaluate(m, [g]) for g in batch])
    assert np.array_equal(as_array, as_list) and np.array_equal(as_array, one_by_one)
    ragged = thesis.evaluate(m, [batch[0][:5], batch[1], [[90.0, 1.0]]])
    assert ragged.shape == (3, 4)
    assert np.array_equal(ragged[1], as_array[1])
    assert ((as_array[:, 0] > 0) & (as_array[:, 0] <= 1)).all()


def test_a_move_into_the_wall_is_penalised():
    m = covga.load_map("thesis-1")
    scores = thesis.evaluate(m, [[[0.0, 2.0]], [[180.0, 5.0]]])
    assert scores[0, 3] == 0 and scores[1, 3] > 0
    assert scores[1, 2] < scores[0, 2]
    # Routed, the move into the wall ends where the robot can stand and sweeps no wall.
    routed = thesis.evaluate(m, [[[0.0, 2.0]], [[180.0, 5.0]]], moves="routed")
    assert np.array_equal(routed[0], scores[0]) and routed[1, 3] == 0


@pytest.mark.parametrize(
    "genomes,kwargs,message",
    [
        (np.zeros((3, 2)), {}, "expected (n, L, 2)"),
        (np.zeros((2, 3, 3)), {}, "genomes: shape (2, 3, 3), expected (n, L, 2)"),
        (np.zeros((2, 0, 2)), {}, "genome 0, action 0: has 0 actions"),
        ([np.zeros((3, 3))], {}, "genome 0: shape (3, 3), expected (L, 2)"),
        ([np.zeros((0, 2))], {}, "genome 0, action 0: has 0 actions"),
        ([[[0.0, 1.0]], [[np.nan, 1.0]]], {}, "genome 1, action 0: angle = NaN"),
        ([[[0.0, 1.0], [0.0, -2.0]]], {}, "genome 0, action 1: distance = -2"),
        ([[["a", 1.0]]], {}, "genome 0: not an array of numbers"),
        ([[[0.0, 1.0]]], {"start": (-5.0, 1.0)}, "start (-5, 1) m is outside map"),
        ([[[0.0, 1.0]]], {"projection": "f9"}, "projection = 'f9'"),
        ([[[0.0, 1.0]]], {"moves": "curved"}, "moves = 'curved': expected 'straight'"),
        ([[[0.0, 1.0]]], {"width": -0.6}, "width = -0.6 is out of range"),
    ],
)
def test_bad_genomes_raise_config_error(genomes, kwargs, message):
    with pytest.raises(covga.ConfigError) as e:
        thesis.evaluate(covga.load_map("thesis-1"), genomes, **kwargs)
    assert message in str(e.value)


def test_read_genome_needs_a_thesis_run(tmp_path):
    with pytest.raises(covga.ConfigError, match="no best_genome.csv"):
        thesis.read_genome(tmp_path)


def test_a_panic_inside_covga_is_a_runtime_error():
    with pytest.raises(RuntimeError, match="internal error in covga"):
        covga._covga.raise_panic()
    assert covga.load_map("thesis-1").shape == (55, 55)


def test_a_batch_too_large_for_memory_is_refused_before_it_is_built():
    one = np.tile([[0.5, 1.0]], (100_000, 1))
    with pytest.raises(covga.ConfigError, match="genomes: 200000 genomes of 20000000000 actions in all would need"):
        covga.thesis.evaluate("thesis-1", [one] * 200_000)


def test_ctrl_c_stops_a_batch_within_a_second():
    import time

    from conftest import interrupt_after

    rng = np.random.default_rng(5)
    batch = np.stack([np.column_stack([rng.uniform(-180, 180, 150), rng.uniform(0, 6, 150)]) for _ in range(12000)])
    started = time.monotonic()
    timer = interrupt_after(0.3)
    with pytest.raises(KeyboardInterrupt):
        covga.thesis.evaluate("office", batch, start=(2.0, 2.0), moves="routed")
    timer.join()
    assert time.monotonic() - started < 1.5
    # The library goes on as before.
    assert covga.thesis.evaluate("thesis-1", batch[:2]).shape == (2, 4)


def test_the_thread_count_changes_nothing_but_the_threads(tmp_path, short_thesis):
    genomes = np.random.default_rng(3).uniform([0, 0], [360, 3], size=(64, 40, 2))
    one = thesis.evaluate("thesis-1", genomes, threads=1)
    assert np.array_equal(one, thesis.evaluate("thesis-1", genomes, threads=np.int64(2)))
    assert np.array_equal(one, thesis.evaluate("thesis-1", genomes))
    runs = [covga.run(short_thesis, seed=2, threads=n, out=tmp_path / f"t{n}", figures=False) for n in (1, 2)]
    assert np.array_equal(runs[0].path, runs[1].path)
    assert runs[0].summary["score"] == runs[1].summary["score"]
    for bad, message in [(0, r"threads = 0 is out of range: allowed \[1, 1024\]"), (1.5, "expected a whole number"),
                         ("2", "expected a whole number"), (-1, "out of range")]:
        with pytest.raises(covga.ConfigError, match=message):
            thesis.evaluate("thesis-1", genomes, threads=bad)
        with pytest.raises(covga.ConfigError, match=message):
            covga.run(short_thesis, threads=bad)
