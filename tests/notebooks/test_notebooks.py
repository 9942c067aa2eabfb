"""The example notebooks of docs/notebooks/ run from top to bottom (nbclient, a fresh kernel).

Each notebook checks its own claims with ``assert`` cells (a colder pad is stiffer, a
faster run rougher, ...), so a notebook that runs but says something false fails here.
They are stored without outputs; docs/notebooks.md describes them.
"""

from pathlib import Path

import pytest

nbformat = pytest.importorskip("nbformat", reason="the test extra (nbclient) is not installed")
nbclient = pytest.importorskip("nbclient", reason="the test extra (nbclient) is not installed")

NOTEBOOKS = sorted((Path(__file__).resolve().parents[2] / "docs" / "notebooks").glob("*.ipynb"))


def test_there_are_notebooks():
    assert len(NOTEBOOKS) >= 3


@pytest.mark.slow  # a kernel and several runs each: 5-30 s
@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_the_notebook_runs(path, tmp_path, monkeypatch):
    monkeypatch.setenv("MPLBACKEND", "Agg")  # no window from the kernel
    book = nbformat.read(path, as_version=4)
    client = nbclient.NotebookClient(
        book, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}
    )
    client.execute()  # raises CellExecutionError with the cell and its traceback
    errors = [
        out
        for cell in book.cells
        for out in cell.get("outputs", [])
        if out["output_type"] == "error"
    ]
    assert not errors


def test_the_notebooks_are_stored_without_outputs():
    for path in NOTEBOOKS:
        book = nbformat.read(path, as_version=4)
        code = [c for c in book.cells if c.cell_type == "code"]
        assert all(not c.outputs and c.execution_count is None for c in code), path.name
