"""Build the course notebooks from their sources, run them headless, export them.

Each notebook has a readable source, a jupytext percent-format ``.py`` beside it
(``notebooks/03_puma560.py`` for ``notebooks/03_puma560.ipynb``); the ``.ipynb`` is
committed with its outputs. :func:`build_notebook` writes the ``.ipynb`` from its
source, keeping the id (and, until it runs, the outputs) of every cell that is
still there, and executes it; :func:`out_of_sync` says where a notebook's cells
differ from its source. :func:`execute_notebook` runs a notebook top to bottom
with nbclient (kernel ``python3``) and fails on any error output and on any
output written to stderr (which is where warnings go). :func:`export_notebook`
converts with nbconvert; the HTML loads MathJax from Debian's ``libjs-mathjax``
when it is installed, so its math renders offline.

Command line (the same functions)::

    dhsym notebooks build notebooks/03_puma560.py [--no-execute]
    dhsym notebooks run notebooks/*.ipynb [--timeout 120] [--write]
    dhsym notebooks export notebooks/01_planar_2R.ipynb -o build/notebooks

Examples
--------
>>> import nbformat
>>> nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(
...     "1 / 0", outputs=[nbformat.v4.new_output("error", ename="ZeroDivisionError",
...                                               evalue="division by zero", traceback=[])])])
>>> problems(nb)
['cell 1: error ZeroDivisionError: division by zero']
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from dhsym.errors import DHError

__all__ = [
    "LOCAL_MATHJAX",
    "NotebookError",
    "build_notebook",
    "cell_sources",
    "execute_notebook",
    "export_notebook",
    "local_mathjax_url",
    "notebook_from_source",
    "out_of_sync",
    "problems",
]

LOCAL_MATHJAX = Path("/usr/share/javascript/mathjax")
_MATHJAX_CONFIG = "TeX-AMS_CHTML-full"


class NotebookError(DHError):
    """A notebook failed: a cell raised, or wrote an error or a warning."""


def local_mathjax_url(root: Path = LOCAL_MATHJAX) -> str | None:
    """``file://`` URL of a local MathJax 2 (Debian ``libjs-mathjax``), or None.

    >>> local_mathjax_url(Path("/nonexistent")) is None
    True
    """
    if (
        not (root / "MathJax.js").is_file()
        or not (root / "config" / f"{_MATHJAX_CONFIG}.js").is_file()
    ):
        return None
    return f"{(root / 'MathJax.js').resolve().as_uri()}?config={_MATHJAX_CONFIG},Safe"


def problems(nb: Any) -> list[str]:
    """Error outputs and stderr output (warnings) of an executed notebook, one line each."""
    found = []
    for k, cell in enumerate(nb.cells, start=1):
        for out in cell.get("outputs", []):
            if out.get("output_type") == "error":
                found.append(f"cell {k}: error {out.get('ename')}: {out.get('evalue')}")
            elif out.get("output_type") == "stream" and out.get("name") == "stderr":
                text = "".join(out.get("text", "")).strip().splitlines()
                found.append(f"cell {k}: stderr: {text[0] if text else ''}")
    return found


def execute_notebook(
    path: str | Path,
    timeout: int = 120,
    *,
    kernel_name: str = "python3",
    write: bool = False,
    pythonpath: Sequence[str | Path] = (),
) -> Any:
    """Run a notebook top to bottom in its own folder; return the executed notebook.

    Parameters
    ----------
    path
        The ``.ipynb`` file.
    timeout
        Seconds allowed per cell.
    write
        Save the outputs back into ``path`` (how the committed outputs are made).
    pythonpath
        Folders put in front of ``PYTHONPATH`` for the kernel (a source tree).

    Raises
    ------
    NotebookError
        When a cell raises, or any output is an error or goes to stderr.
    """
    import nbformat
    from nbclient import NotebookClient
    from nbclient.exceptions import CellExecutionError

    path = Path(path)
    nb = nbformat.read(path, as_version=4)
    env = {k: v for k, v in os.environ.items() if k != "MPLBACKEND"}  # keep the inline backend
    if pythonpath:
        env["PYTHONPATH"] = os.pathsep.join(
            [str(Path(p).resolve()) for p in pythonpath] + [env.get("PYTHONPATH", "")]
        ).rstrip(os.pathsep)
    client = NotebookClient(
        nb,
        timeout=timeout,
        kernel_name=kernel_name,
        record_timing=False,
        # a widget's state is the page's to rebuild when it runs: stored, the 3D view would
        # carry its whole bundled JavaScript into the notebook file
        store_widget_state=False,
        resources={"metadata": {"path": str(path.parent.resolve())}},
    )
    try:
        client.execute(env=env)
    except CellExecutionError as err:
        lines = str(err).strip().splitlines()
        raise NotebookError(
            f"a cell failed: {lines[-1] if lines else err}", file=str(path)
        ) from None
    found = problems(nb)
    if found:
        raise NotebookError("; ".join(found), file=str(path))
    if write:
        nbformat.write(nb, path)
    return nb


def cell_sources(nb: Any) -> list[tuple[str, str]]:
    """The cells of a notebook as ``(cell type, source)`` pairs: what a source file holds.

    >>> import nbformat
    >>> cell_sources(nbformat.v4.new_notebook(cells=[nbformat.v4.new_markdown_cell("# Hi")]))
    [('markdown', '# Hi')]
    """
    return [(cell.cell_type, cell.source) for cell in nb.cells]


def notebook_from_source(source: str | Path, previous: Any = None) -> Any:
    """The notebook written in a jupytext ``source``, with ids taken from ``previous``.

    A cell of ``previous`` (the notebook built last time) whose text is still in the
    source, or that was edited in place, gives its id, outputs and metadata to the new
    cell (jupytext matches them); any other cell gets the id ``nbNN-KK`` from the file
    name's number ``NN`` and its position ``KK``. So a rebuild changes only what changed.

    >>> import tempfile
    >>> folder = Path(tempfile.mkdtemp())
    >>> _ = (folder / "03_demo.py").write_text("# %% [markdown]\\n# Hello\\n\\n# %%\\n1 + 1\\n")
    >>> nb = notebook_from_source(folder / "03_demo.py")
    >>> [(cell.id, cell.cell_type, cell.source) for cell in nb.cells]
    [('nb03-00', 'markdown', 'Hello'), ('nb03-01', 'code', '1 + 1')]
    >>> text = "# %%\\nx = 2\\n\\n# %% [markdown]\\n# Hello!\\n\\n# %%\\n1 + 1\\n"
    >>> _ = (folder / "03_demo.py").write_text(text)   # a new first cell, an edited one
    >>> [cell.id for cell in notebook_from_source(folder / "03_demo.py", nb).cells]
    ['nb03-00-1', 'nb03-00', 'nb03-01']
    """
    import jupytext
    import nbformat
    from jupytext.combine import combine_inputs_with_outputs

    source = Path(source)
    try:
        text = jupytext.read(source)
    except OSError as err:
        raise NotebookError(f"cannot read the notebook source: {err}", file=str(source)) from None
    for cell in text.cells:
        cell["id"] = ""  # jupytext's random ids: replaced below unless a cell matches
    nb = combine_inputs_with_outputs(
        text, previous if previous is not None else nbformat.v4.new_notebook()
    )
    nb.metadata.get("jupytext", {}).pop("text_representation", None)
    prefix = "nb" + source.stem.split("_")[0]
    used = {cell["id"] for cell in nb.cells}
    for k, cell in enumerate(nb.cells):
        if cell["id"]:
            continue
        candidates = (f"{prefix}-{k:02d}" + (f"-{j}" if j else "") for j in range(len(used) + 1))
        cell["id"] = next(c for c in candidates if c not in used)
        used.add(cell["id"])
    return nb


def build_notebook(
    source: str | Path,
    notebook: str | Path | None = None,
    *,
    execute: bool = True,
    timeout: int = 120,
) -> Path:
    """Write the ``.ipynb`` of a jupytext ``source`` and execute it in place; return its path.

    ``notebook`` defaults to the source with the suffix ``.ipynb``; its cell ids are
    kept (:func:`notebook_from_source`). Without ``execute`` only the cells are
    updated: unchanged cells keep their outputs, new or edited ones have none.

    Raises
    ------
    NotebookError
        When the source cannot be read, or the notebook fails (:func:`execute_notebook`).
    """
    import nbformat

    source = Path(source)
    path = Path(notebook) if notebook is not None else source.with_suffix(".ipynb")
    previous = nbformat.read(path, as_version=4) if path.exists() else None
    nbformat.write(notebook_from_source(source, previous), path)
    if execute:
        execute_notebook(path, timeout, write=True)
    return path


def out_of_sync(source: str | Path, notebook: str | Path | None = None) -> list[str]:
    """Where the cells of ``notebook`` differ from its jupytext ``source``; empty when in sync.

    Only cell types and sources count, not outputs, ids or metadata. ``notebook``
    defaults to the source with the suffix ``.ipynb``.

    >>> import tempfile
    >>> folder = Path(tempfile.mkdtemp())
    >>> _ = (folder / "01_demo.py").write_text("# %%\\n1 + 1\\n")
    >>> path = build_notebook(folder / "01_demo.py", execute=False)
    >>> out_of_sync(folder / "01_demo.py")
    []
    >>> _ = (folder / "01_demo.py").write_text("# %%\\n1 + 2\\n\\n# %% [markdown]\\n# New\\n")
    >>> out_of_sync(folder / "01_demo.py")
    ['cell 1 (code) differs from the source', 'the source has 2 cells, the notebook 1']
    """
    import jupytext
    import nbformat

    source = Path(source)
    path = Path(notebook) if notebook is not None else source.with_suffix(".ipynb")
    want = cell_sources(jupytext.read(source))
    have = cell_sources(nbformat.read(path, as_version=4))
    found = [
        f"cell {k} ({w[0]}) differs from the source"
        for k, (w, h) in enumerate(zip(want, have), start=1)
        if w != h
    ]
    if len(want) != len(have):
        found.append(f"the source has {len(want)} cells, the notebook {len(have)}")
    return found


def export_notebook(
    path: str | Path,
    out_dir: str | Path,
    formats: Sequence[str] = ("html", "markdown"),
    mathjax_url: str | None = None,
) -> list[Path]:
    """Export a notebook (with its outputs) to HTML and/or Markdown in ``out_dir``.

    The HTML embeds its pictures; Markdown gets a ``NAME_files/`` folder of
    images. ``mathjax_url`` defaults to the local MathJax when installed
    (:func:`local_mathjax_url`), else nbconvert's CDN address.
    Returns the files written.
    """
    import nbformat
    from nbconvert import HTMLExporter, MarkdownExporter
    from nbconvert.writers import FilesWriter

    path, out = Path(path), Path(out_dir)
    unknown = set(formats) - {"html", "markdown"}
    if unknown:
        raise DHError(f"unknown export format {sorted(unknown)}: expected html or markdown")
    nb = nbformat.read(path, as_version=4)
    out.mkdir(parents=True, exist_ok=True)
    writer = FilesWriter(build_directory=str(out))
    written = []
    for fmt in formats:
        if fmt == "html":
            url = mathjax_url or local_mathjax_url()
            exporter: Any = HTMLExporter(**({"mathjax_url": url} if url else {}))
        else:
            exporter = MarkdownExporter()
        resources = {
            "metadata": {"name": path.stem, "path": str(path.parent)},
            "output_files_dir": f"{path.stem}_files",
        }
        body, resources = exporter.from_notebook_node(nb, resources=resources)
        written.append(Path(writer.write(body, resources, notebook_name=path.stem)))
    return written
