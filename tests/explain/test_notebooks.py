"""The notebooks in notebooks/: each is in sync with its jupytext source, is rebuilt from it
keeping its cell ids, speaks to students in their words, and runs top to bottom with no error
and no warning output."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest

from dhsym.cli import main
from dhsym.explain.notebooks import (
    NotebookError,
    build_notebook,
    cell_sources,
    execute_notebook,
    notebook_from_source,
    out_of_sync,
    problems,
)

ROOT = Path(__file__).resolve().parents[2]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))
SOURCES = sorted((ROOT / "notebooks").glob("*.py"))
INTERNAL = re.compile(r"seeds?\s*0\d", re.IGNORECASE)  # "seed 001", "Seeds 000 and 002"


@pytest.fixture(scope="session")
def nbformat():
    """nbformat, imported by a worker that runs these tests, not by every worker at
    collection (it imports jsonschema, whose import builds rfc3987-syntax's grammars)."""
    import nbformat

    return nbformat


pytestmark = pytest.mark.jupyter


def test_every_notebook_has_one_source():
    assert [p.stem for p in SOURCES] == [p.stem for p in NOTEBOOKS]


@pytest.mark.parametrize("source", SOURCES, ids=[p.name for p in SOURCES])
def test_notebook_in_sync_with_its_source(source):
    assert out_of_sync(source) == [], f"run: dhsym notebooks build notebooks/{source.name}"


@pytest.mark.parametrize("source", SOURCES, ids=[p.name for p in SOURCES])
def test_rebuild_without_changes_keeps_ids_and_outputs(source, nbformat):
    committed = nbformat.read(source.with_suffix(".ipynb"), as_version=4)
    rebuilt = notebook_from_source(source, committed)
    assert [(c.id, c.get("outputs")) for c in rebuilt.cells] == [
        (c.id, c.get("outputs")) for c in committed.cells
    ]
    assert len({c.id for c in committed.cells}) == len(committed.cells)


def test_rebuild_after_an_edit_changes_only_the_edited_cells(tmp_path, nbformat):
    for name in ("03_puma560.py", "03_puma560.ipynb"):
        shutil.copy(ROOT / "notebooks" / name, tmp_path / name)
    source = tmp_path / "03_puma560.py"
    before = nbformat.read(source.with_suffix(".ipynb"), as_version=4)
    text = source.read_text()
    assert "# ## 2. Link by link" in text and "\n# %%\npuma.plot()\n" in text
    text = text.replace("# ## 2. Link by link", "# ## 2. One link at a time")  # edit a cell
    text = text.replace("\n# %%\npuma.plot()\n", "\n")  # delete one
    source.write_text(text + "\n# %% [markdown]\n# A new closing remark.\n")  # add one
    assert out_of_sync(source)
    build_notebook(source, execute=False)
    assert out_of_sync(source) == []
    after = nbformat.read(source.with_suffix(".ipynb"), as_version=4)
    old, new = {c.id: c for c in before.cells}, {c.id: c for c in after.cells}
    assert len(new) == len(after.cells)
    edited = [i for i in new if i in old and new[i].source != old[i].source]
    assert [new[i].source.splitlines()[0] for i in edited] == ["## 2. One link at a time"]
    assert [new[i].source for i in set(new) - set(old)] == ["A new closing remark."]
    assert [old[i].source for i in set(old) - set(new)] == ["puma.plot()"]
    assert all(new[i].get("outputs") == old[i].get("outputs") for i in new if i in old)


def test_a_missing_source_is_a_clear_error(tmp_path):
    with pytest.raises(NotebookError, match="cannot read the notebook source"):
        build_notebook(tmp_path / "09_none.py", execute=False)


@pytest.mark.parametrize("source", SOURCES, ids=[p.name for p in SOURCES])
def test_students_read_lectures_not_internal_names(source, nbformat):
    assert not INTERNAL.search(source.read_text())
    nb = nbformat.read(source.with_suffix(".ipynb"), as_version=4)
    assert not [text for _, text in cell_sources(nb) if INTERNAL.search(text)]


@pytest.fixture(scope="session")
def warm_matplotlib():
    """Build matplotlib's font cache here, not in a notebook (where its notice would be stderr).
    Once per worker (session), not per module: the notebooks, the suite's longest quick tests,
    are shared out one by one among the workers (tests/conftest.py), not run by one."""
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
def test_committed_with_outputs(path, nbformat):
    nb = nbformat.read(path, as_version=4)
    code = [c for c in nb.cells if c.cell_type == "code"]
    hint = f"run: dhsym notebooks build notebooks/{path.stem}.py"
    assert code and all(c.execution_count is not None for c in code), hint
    assert sum(len(c.outputs) for c in code) >= len(code) // 2
    assert problems(nb) == []


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.name for p in NOTEBOOKS])
def test_notebook_runs_clean(path, need_jupyter, warm_matplotlib):
    nb = execute_notebook(path, timeout=120, pythonpath=[ROOT])
    kinds = ("image/png", "image/svg+xml")  # notebook 06 shows the grading chart as SVG
    images = sum(
        any(k in o.get("data", {}) for k in kinds) for c in nb.cells for o in c.get("outputs", [])
    )
    assert images >= 1  # every lecture draws a picture


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


def test_build_command_writes_and_executes(tmp_path, need_jupyter, nbformat):
    source = tmp_path / "01_tiny.py"
    source.write_text("# %% [markdown]\n# Tiny\n\n# %%\nprint(6 * 7)\n")
    assert main(["notebooks", "build", str(source), "--no-execute"]) == 0
    nb = nbformat.read(tmp_path / "01_tiny.ipynb", as_version=4)
    assert [c.id for c in nb.cells] == ["nb01-00", "nb01-01"] and not nb.cells[1].outputs
    assert main(["notebooks", "build", str(source), "--timeout", "60"]) == 0
    nb = nbformat.read(tmp_path / "01_tiny.ipynb", as_version=4)
    assert [c.id for c in nb.cells] == ["nb01-00", "nb01-01"]
    assert nb.cells[1].outputs[0]["text"] == "42\n"
    source.write_text("# %%\n1 / 0\n")
    assert main(["notebooks", "build", str(source), "--timeout", "60"]) == 2
