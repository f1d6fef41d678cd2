"""The installed package: typed (a notebook's code that misuses covga's API fails `mypy
--strict`, correct code passes, with the types the package ships: `py.typed`, `_covga.pyi`) and
stripped of the release profile's debug info."""

import subprocess
import sys
from pathlib import Path

import covga

GOOD = '''
import numpy as np
import covga

m: covga.Map = covga.load_map("thesis-1")
path = covga.pattern(m, "boustrophedon", start=(1.3, 1.3), width=0.6, angle=90.0)
s = covga.score(m, path, width=0.6, speed=0.2)
coverage: float = s["cov_final_reach"]
rows, cols = m.shape
free: np.ndarray = m.free
p = covga.stats.holm([0.01, 0.04])
test = covga.stats.mann_whitney([1.0, 2.0], [3.0, 4.0])
'''

BAD = '''
import covga

m = covga.load_map("thesis-1")
name: int = m.name
covga.pattern(m, "spiral", width="wide")
'''


def _mypy(tmp_path: Path, text: str) -> subprocess.CompletedProcess:
    file = tmp_path / "snippet.py"
    file.write_text(text)
    return subprocess.run(
        [sys.executable, "-m", "mypy", "--strict", "--no-incremental", str(file)],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=300,
    )


def test_the_installed_package_ships_its_types():
    folder = Path(covga.__file__).parent
    assert (folder / "py.typed").is_file()
    assert (folder / "_covga.pyi").is_file()


def test_the_compiled_module_is_stripped():
    # With debug info the module is about 87 MB; stripped, about 10 MB.
    folder = Path(covga.__file__).parent
    (module,) = [p for p in folder.iterdir() if p.name.startswith("_covga") and p.suffix in (".so", ".pyd")]
    assert module.stat().st_size < 30_000_000, module.stat().st_size


def test_mypy_strict_checks_code_that_uses_covga(tmp_path):
    good = _mypy(tmp_path, GOOD)
    assert good.returncode == 0, good.stdout + good.stderr
    bad = _mypy(tmp_path, BAD)
    assert bad.returncode == 1, bad.stdout
    assert 'Incompatible types in assignment (expression has type "str", variable has type "int")' in bad.stdout
    assert 'Argument "width" to "pattern" has incompatible type "str"' in bad.stdout


def test_the_books_python_session_runs_as_written(tmp_path, monkeypatch):
    """The book's "A short session" block (docs/src/guide/python.md), run as a user runs it from
    the repository root (here a folder with the repository's experiments and grids, so that out/
    lands in tmp)."""
    import re

    from conftest import REPO

    text = (REPO / "docs" / "src" / "guide" / "python.md").read_text()
    block = re.search(r"A short session:\n\n```python\n(.*?)```", text, re.S)
    assert block, "the book's Python session"
    for name in ("experiments", "grids"):
        (tmp_path / name).symlink_to(REPO / name)
    monkeypatch.chdir(tmp_path)
    scope: dict = {}
    exec(compile(block.group(1), "docs/src/guide/python.md", "exec"), scope)
    assert scope["scores"].shape == (1000, 4)
    assert len(scope["runs"]) == 36 and (tmp_path / "out" / "smoke" / "report" / "summary.md").is_file()


def test_the_readmes_python_lines_run_as_written(tmp_path, monkeypatch, capsys):
    """The README's ```python block runs from the repository root and prints the scorer's
    measures."""
    import re

    from conftest import REPO

    text = (REPO / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) == 1, "the README has one Python block"
    monkeypatch.chdir(REPO)
    exec(compile(blocks[0], "README.md", "exec"), {})
    printed = capsys.readouterr().out
    assert "cov_final_reach" in printed and "time_s" in printed, printed
