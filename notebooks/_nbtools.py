"""Writing a course notebook from a cell list and executing it in place.

Shared by the build scripts ``notebooks/_build*.py``. A cell list is a list of
``("md" | "code", source)`` pairs; cell ids are fixed (``nb01-00``, ``nb01-01``,
… from the file name's number), so a rebuild changes only what really changed.
Execution goes through :func:`dhsym.explain.notebooks.execute_notebook` with this source
tree on the kernel's path; it fails on any error or warning output.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from pathlib import Path

import nbformat

ROOT = Path(__file__).resolve().parents[1]
HERE = ROOT / "notebooks"
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from dhsym.explain.notebooks import execute_notebook

__all__ = ["HERE", "ROOT", "build_notebook", "write_notebook"]


def write_notebook(name: str, cells: Sequence[tuple[str, str]]) -> Path:
    """Write ``notebooks/<name>`` from its cell list (no outputs yet)."""
    stem = name.split("_")[0]
    nb = nbformat.v4.new_notebook()
    nb.metadata["kernelspec"] = {
        "name": "python3",
        "display_name": "Python 3",
        "language": "python",
    }
    nb.metadata["language_info"] = {"name": "python"}
    for k, (kind, source) in enumerate(cells):
        make = nbformat.v4.new_markdown_cell if kind == "md" else nbformat.v4.new_code_cell
        cell = make(source)
        cell["id"] = f"nb{stem}-{k:02d}"
        nb.cells.append(cell)
    path = HERE / name
    nbformat.write(nb, path)
    return path


def build_notebook(name: str, cells: Sequence[tuple[str, str]], timeout: int = 120) -> Path:
    """Write ``notebooks/<name>``, execute it in place (``timeout`` seconds per cell), report."""
    path = write_notebook(name, cells)
    execute_notebook(path, timeout=timeout, write=True, pythonpath=[ROOT])
    print(f"built {path.relative_to(ROOT)}")
    return path
