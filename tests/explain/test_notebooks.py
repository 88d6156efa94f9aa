"""Every notebook in notebooks/ runs top to bottom with no error and no warning output."""

from __future__ import annotations

from pathlib import Path

import pytest

from dhsym.cli import main
from dhsym.explain.notebooks import NotebookError, execute_notebook, problems

ROOT = Path(__file__).resolve().parents[2]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))

pytestmark = pytest.mark.jupyter


@pytest.fixture(scope="module")
def warm_matplotlib():
    """Build matplotlib's font cache here, not in a notebook (where its notice would be stderr)."""
    pytest.importorskip("matplotlib")
    import matplotlib.font_manager  # noqa: F401


def test_there_are_notebooks():
    names = [p.name for p in NOTEBOOKS]
    for expected in (
        "01_planar_2R.ipynb",
        "02_planar_4R.ipynb",
        "03_puma560.ipynb",
        "04_prismatic.ipynb",
        "05_standard_vs_modified.ipynb",
    ):
        assert expected in names


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.name for p in NOTEBOOKS])
def test_committed_with_outputs(path):
    import nbformat

    nb = nbformat.read(path, as_version=4)
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert code and all(c.execution_count is not None for c in code), "run notebooks/_build.py"
    assert sum(len(c.outputs) for c in code) >= len(code) // 2
    assert problems(nb) == []


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.name for p in NOTEBOOKS])
def test_notebook_runs_clean(path, need_jupyter, warm_matplotlib):
    nb = execute_notebook(path, timeout=120, pythonpath=[ROOT])
    images = sum("image/png" in o.get("data", {}) for c in nb.cells for o in c.get("outputs", []))
    assert images >= 1  # every lecture draws its robot


def _notebook(tmp_path: Path, source: str) -> Path:
    import nbformat

    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(source)])
    nb.metadata["kernelspec"] = {
        "name": "python3",
        "display_name": "Python 3",
        "language": "python",
    }
    path = tmp_path / "t.ipynb"
    nbformat.write(nb, path)
    return path


def test_warning_and_error_cells_fail(tmp_path, need_jupyter):
    path = _notebook(tmp_path, "import warnings\nwarnings.warn('careful')\n1 / 0")
    with pytest.raises(NotebookError, match="ZeroDivisionError"):
        execute_notebook(path, timeout=60)
    path = _notebook(tmp_path, "import warnings\nwarnings.warn('careful')\nprint('done')")
    with pytest.raises(NotebookError, match="stderr: .*careful"):
        execute_notebook(path, timeout=60)
    assert main(["notebooks", "run", str(path), "--timeout", "60"]) == 2
