"""Run the course notebooks headless and export them to HTML and Markdown.

:func:`execute_notebook` runs a notebook top to bottom with nbclient (kernel
``python3``) and fails on any error output and on any output written to
stderr (which is where warnings go). :func:`export_notebook` converts with
nbconvert; the HTML loads MathJax from Debian's ``libjs-mathjax`` when it is
installed, so its math renders offline.

Command line (the same functions)::

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
    "execute_notebook",
    "export_notebook",
    "local_mathjax_url",
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
