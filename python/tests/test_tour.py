"""The shipped notebook `python/examples/tour.ipynb` runs from a fresh kernel (as nbclient runs
it, from its own folder), raises nothing, and shows and saves what it says it does."""

import nbformat
from conftest import REPO
from nbclient import NotebookClient

EXAMPLES = REPO / "python" / "examples"


def _text(cell):
    return "".join(o.get("text", "") for o in cell.outputs if o.output_type == "stream")


def test_the_tour_notebook_runs_and_draws_its_figures(tmp_path, monkeypatch):
    monkeypatch.setenv("COVGA_TOUR_FIGURES", str(tmp_path))
    nb = nbformat.read(EXAMPLES / "tour.ipynb", as_version=4)
    NotebookClient(nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(EXAMPLES)}}).execute()
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert not [o for c in code for o in c.outputs if o.output_type == "error"]
    # The map shows itself as a picture; each figure cell draws one.
    assert "image/png" in code[1].outputs[-1].get("data", {}), "the Map's own picture"
    assert _text(code[1]).startswith("basement (")
    assert "executable: True" in _text(code[2])
    assert _text(code[3]).startswith("Result(thesis on thesis-2, seed 11")
    assert "nsga2" in _text(code[4]) and "elite" in _text(code[4])
    for cell in code[2:]:
        assert any("image/png" in o.get("data", {}) for o in cell.outputs), cell.source[:40]
    for name in ("basement-boustrophedon.png", "thesis-run.png", "study.png"):
        assert (tmp_path / name).stat().st_size > 10_000, name
