r"""LaTeX to PDF, safely: running latexmk/pdflatex and reading the log.

* :func:`compile_pdf` runs ``latexmk`` (or ``pdflatex``) with
  ``-no-shell-escape -halt-on-error -interaction=nonstopmode``, rc files
  ignored, ``openin_any=p``/``openout_any=p``, stdin closed and a timeout. The
  auxiliary files (``.aux``, ``.log``, ``.fls``, ``.fdb_latexmk``) go to a temporary
  folder, so only the PDF appears beside the ``.tex`` (``keep_aux=True`` keeps them
  there instead); :func:`run_latex` also returns the log and its issues.
* :func:`check_log` lists errors, missing characters and ``Overfull \hbox``
  warnings wider than a tolerance (5pt by default).

What goes into the ``.tex`` file is escaped before (:mod:`dhsym.notation.escape`).

Examples
--------
>>> [i.kind for i in check_log("Overfull \\hbox (7.5pt too wide) in paragraph at lines 3--4")]
['overfull']
"""

from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import tempfile
import time
from contextlib import nullcontext
from dataclasses import dataclass
from pathlib import Path

from dhsym.errors import DHError

__all__ = [
    "TEX_PACKAGES",
    "LatexRun",
    "LogIssue",
    "check_log",
    "compile_pdf",
    "run_latex",
    "tex_available",
]

#: Debian packages that provide everything the handouts need.
TEX_PACKAGES = "texlive-latex-base texlive-latex-recommended texlive-latex-extra latexmk"


# --- escaping -------------------------------------------------------------------------


# --- the log --------------------------------------------------------------------------


@dataclass(frozen=True)
class LogIssue:
    """One problem found in a LaTeX log: ``kind`` is ``error``, ``overfull`` or ``missing``."""

    kind: str
    message: str
    line: int | None = None
    width_pt: float = 0.0

    def __str__(self) -> str:
        where = f"line {self.line}: " if self.line is not None else ""
        return f"{self.kind}: {where}{self.message}"


_ERROR = re.compile(
    r"^(?:!\s*(?P<bang>.+)|(?P<file>[^\s:][^:]*\.tex):(?P<line>\d+):\s*(?P<msg>.+))$"
)
_OVERFULL = re.compile(r"^Overfull \\hbox \((?P<pt>[\d.]+)pt too wide\)(?P<rest>.*)$")
_AT_LINE = re.compile(r"lines? (\d+)")
_L_LINE = re.compile(r"^l\.(\d+)")
_MISSING = re.compile(r"^Missing character: (?P<msg>.+)$")


def check_log(log: str | os.PathLike[str], *, max_overfull_pt: float = 5.0) -> list[LogIssue]:
    r"""Errors, missing characters and ``Overfull \hbox`` wider than ``max_overfull_pt``.

    ``log`` is the text of a ``.log`` file, or its path as a :class:`~pathlib.Path`.

    >>> text = "\n".join(["Overfull \\hbox (3.0pt too wide) in paragraph at lines 7--7",
    ...                   "Overfull \\hbox (12.5pt too wide) detected at line 40",
    ...                   "! Undefined control sequence.", "l.41 \\foo"])
    >>> for issue in check_log(text):
    ...     print(issue)
    overfull: line 40: 12.5pt too wide detected at line 40
    error: line 41: Undefined control sequence.
    """
    text = Path(log).read_text(encoding="latin-1") if isinstance(log, os.PathLike) else log
    lines = text.splitlines()
    issues: list[LogIssue] = []
    for k, raw in enumerate(lines):
        line = raw.strip()
        m = _OVERFULL.match(line)
        if m:
            pt = float(m.group("pt"))
            if pt > max_overfull_pt:
                at = _AT_LINE.search(m.group("rest"))
                issues.append(
                    LogIssue(
                        "overfull",
                        f"{pt}pt too wide{m.group('rest')}",
                        int(at.group(1)) if at else None,
                        pt,
                    )
                )
            continue
        m = _MISSING.match(line)
        if m:
            issues.append(LogIssue("missing", m.group("msg")))
            continue
        m = _ERROR.match(line)
        if m and not line.startswith("!  ==>"):
            if m.group("bang") is not None:
                number = next(
                    (int(x.group(1)) for x in map(_L_LINE.match, lines[k + 1 : k + 12]) if x), None
                )
                issues.append(LogIssue("error", m.group("bang").strip(), number))
            else:
                issues.append(LogIssue("error", m.group("msg").strip(), int(m.group("line"))))
    return _dedupe(issues)


def _dedupe(issues: list[LogIssue]) -> list[LogIssue]:
    """With ``-file-line-error`` TeX may print an error twice; keep one of each."""
    seen: set[tuple[str, str, int | None]] = set()
    out = []
    for issue in issues:
        key = (issue.kind, issue.message, issue.line)
        if key not in seen:
            seen.add(key)
            out.append(issue)
    return out


# --- compiling ------------------------------------------------------------------------


def tex_available() -> bool:
    """True when ``latexmk`` or ``pdflatex`` is on the PATH."""
    return bool(shutil.which("latexmk") or shutil.which("pdflatex"))


_SAFE_FLAGS = ("-no-shell-escape", "-halt-on-error", "-interaction=nonstopmode", "-file-line-error")


def _commands(name: str, outdir: Path | None) -> list[list[str]]:
    if shutil.which("latexmk"):
        out = [f"-outdir={outdir}"] if outdir else []
        return [["latexmk", "-pdf", "-norc", "-silent", *_SAFE_FLAGS, *out, name]]
    if shutil.which("pdflatex"):
        out = [f"-output-directory={outdir}"] if outdir else []
        return [["pdflatex", *_SAFE_FLAGS, *out, name]] * 3  # at most 3 passes (references)
    raise DHError(
        "cannot compile the handout: neither latexmk nor pdflatex is installed. "
        f"On Debian/Ubuntu: apt-get install --no-install-recommends {TEX_PACKAGES}"
    )


def _run(cmd: list[str], cwd: Path, env: dict[str, str], timeout: float) -> None:
    proc = subprocess.Popen(
        cmd,
        cwd=cwd,
        env=env,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    try:
        proc.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)  # latexmk and the pdflatex it started
        proc.wait()
        raise DHError(f"LaTeX did not finish within {timeout:.0f} s on {cmd[-1]}") from None


@dataclass(frozen=True)
class LatexRun:
    """A compiled document: the PDF, the text of the log, and the issues found in it."""

    pdf: Path
    log: str
    issues: tuple[LogIssue, ...]


def run_latex(
    tex_path: str | os.PathLike[str], *, timeout: float = 180.0, keep_aux: bool = False
) -> LatexRun:
    """Compile ``tex_path`` to PDF next to it, safely; the PDF, its log and the log's issues.

    Shell escape is always off, rc files are ignored, TeX may only read files below
    the source's folder and write to its output folder (``openin_any=p``), stdin is
    closed and the whole run is killed after ``timeout`` seconds. The auxiliary files
    are written to a temporary folder that is removed afterwards, unless ``keep_aux``
    (then they stay beside the ``.tex``). Raises :class:`~dhsym.errors.DHError`
    naming the first LaTeX errors (the log is then copied beside the ``.tex``), and
    the Debian packages to install when TeX is missing.
    """
    tex = Path(tex_path).resolve()
    if not tex.is_file():
        raise DHError(f"no such file: {tex_path}")
    folder = nullcontext(None) if keep_aux else tempfile.TemporaryDirectory(prefix="dhsym-tex-")
    with folder as tmp:
        aux = Path(tmp) if tmp else tex.parent
        env = dict(
            os.environ,
            openin_any="p",
            openout_any="p",
            shell_escape="f",
            max_print_line="10000",
            TEXMFOUTPUT=str(aux),
        )
        deadline = time.monotonic() + timeout
        log = aux / f"{tex.stem}.log"
        text = ""
        for cmd in _commands(tex.name, Path(tmp) if tmp else None):
            _run(cmd, tex.parent, env, max(1.0, deadline - time.monotonic()))
            text = log.read_text(encoding="latin-1") if log.exists() else ""
            if cmd[0] == "latexmk" or not re.search(r"Rerun to get|may have changed", text):
                break
        issues = tuple(check_log(text))
        errors = [i for i in issues if i.kind == "error"]
        built = aux / f"{tex.stem}.pdf"
        pdf = tex.with_suffix(".pdf")
        if errors or not built.exists():
            if tmp and log.exists():
                shutil.copyfile(log, tex.with_suffix(".log"))
            detail = "; ".join(str(e) for e in errors[:3]) or "no PDF was written"
            where = os.path.join(os.path.dirname(os.fspath(tex_path)), log.name)
            raise DHError(f"LaTeX failed: {detail} (see {where})", file=str(tex_path))
        if built != pdf:
            shutil.move(built, pdf)
    return LatexRun(pdf, text, issues)


def compile_pdf(
    tex_path: str | os.PathLike[str], *, timeout: float = 180.0, keep_aux: bool = False
) -> Path:
    """Compile ``tex_path`` to PDF next to it, safely (see :func:`run_latex`); the PDF's path."""
    return run_latex(tex_path, timeout=timeout, keep_aux=keep_aux).pdf
