"""The pymoo example runs as the README states it and draws its figure."""

import re
import subprocess
import sys
from pathlib import Path

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "pymoo_nsga2.py"


def test_pymoo_nsga2_example_runs(tmp_path):
    figure = tmp_path / "front.png"
    done = subprocess.run(
        [sys.executable, str(EXAMPLE), "--out", str(figure)], capture_output=True, text=True, timeout=300
    )
    assert done.returncode == 0, done.stderr
    assert "pymoo NSGA-II: 20000 evaluations" in done.stdout
    assert "thesis GA (Elite, f2):" in done.stdout
    assert "thesis GA with covga's NSGA-II selection:" in done.stdout
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def _without_times(out):
    """The example's report without its timings and the history line."""
    return [re.sub(r" in [0-9.]+ s", "", s) for s in out.splitlines() if "history:" not in s and "wrote" not in s]


def test_the_example_runs_on_a_process_pool_and_keeps_its_history(tmp_path):
    runs = {}
    for name, extra in [("in-process", []), ("pool", ["--processes", "2", "--save-history"])]:
        done = subprocess.run(
            [sys.executable, str(EXAMPLE), "--generations", "5", "--pop", "20", "--out", str(tmp_path / f"{name}.png")]
            + extra,
            capture_output=True,
            text=True,
            timeout=300,
        )
        assert done.returncode == 0, done.stderr
        runs[name] = done.stdout
    # The map is pickled to each process and deep-copied into each generation's copy.
    assert "history: 5 generations kept" in runs["pool"]
    assert "pymoo NSGA-II: 100 evaluations" in runs["pool"]
    assert _without_times(runs["pool"]) == _without_times(runs["in-process"]), "the same results either way"
