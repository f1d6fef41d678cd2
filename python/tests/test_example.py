"""The pymoo example runs as the README states it and draws its figure."""

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
