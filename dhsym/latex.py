r"""LaTeX safety and compilation: escaping user text, running pdflatex, reading the log.

Three jobs, one concern (getting a ``.tex`` file safely to a PDF):

* :func:`escape_latex` turns *any* user string (robot name, title, author,
  course, a table's source) into LaTeX that prints that string literally:
  ``\input{/etc/passwd}``, ``\write18{…}``, ``}\end{document}``, ``%``,
  ``$x$`` and the ten special characters ``# $ % & _ { } ~ ^ \`` all come out
  as text. Output is pure ASCII and works with the default OT1 font encoding
  (no ``lmodern``/``cm-super`` needed): accented Latin letters become accent
  commands, Greek letters ``\ensuremath{\alpha}``, and any other character a
  visible ``[U+XXXX]``.
* :func:`compile_pdf` runs ``latexmk`` (or ``pdflatex``) with
  ``-no-shell-escape -halt-on-error -interaction=nonstopmode``, rc files
  ignored, ``openin_any=p``/``openout_any=p``, stdin closed and a timeout.
* :func:`check_log` lists errors, missing characters and ``Overfull \hbox``
  warnings wider than a tolerance (5pt by default).

:class:`TeX` marks a string as trusted LaTeX (printer output); the Jinja2
environments of :mod:`dhsym.rendering` print it verbatim and escape every
other string.

Examples
--------
>>> print(escape_latex(r"\input{/etc/passwd} 100% of $x$"))
\textbackslash{}input\{/etc/passwd\} 100\% of \$x\$
>>> print(escape_latex("Übung: α_1"))
\"{U}bung: \ensuremath{\alpha}{\ttfamily\char95}1
>>> [i.kind for i in check_log("Overfull \\hbox (7.5pt too wide) in paragraph at lines 3--4")]
['overfull']
"""

from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import time
import unicodedata
from dataclasses import dataclass
from pathlib import Path

from .errors import DHError

__all__ = [
    "TEX_PACKAGES",
    "LogIssue",
    "TeX",
    "check_log",
    "compile_pdf",
    "escape_latex",
    "math_width",
    "tex_available",
]

#: Debian packages that provide everything the handouts need.
TEX_PACKAGES = "texlive-latex-base texlive-latex-recommended texlive-latex-extra latexmk"


class TeX(str):
    """A string of trusted LaTeX (from sympy's printers or dhsym), printed verbatim.

    >>> TeX("C_{12}") == "C_{12}", isinstance(TeX("x"), str)
    (True, True)
    """

    __slots__ = ()


# --- escaping -------------------------------------------------------------------------

# ASCII characters with a special meaning in LaTeX. The ones that OT1 text fonts lack
# (or draw as a rule, so that they vanish from copied text) come from the typewriter
# font, which has every ASCII glyph.
_ASCII = {
    "\\": r"\textbackslash{}",
    "{": r"\{",
    "}": r"\}",
    "#": r"\#",
    "$": r"\$",
    "%": r"\%",
    "&": r"\&",
    "_": r"{\ttfamily\char95}",
    "~": r"{\ttfamily\char126}",
    "^": r"{\ttfamily\char94}",
    "<": r"{\ttfamily\char60}",
    ">": r"{\ttfamily\char62}",
    "|": r"{\ttfamily\char124}",
    '"': r"{\ttfamily\char34}",
    "-": "-{}",  # no -- / --- ligatures: a literal "--" stays two dashes
    "!": "!{}",  # no !` ligature
    "?": "?{}",  # no ?` ligature
    "\t": " ",
    "\n": " ",
    "\r": " ",
}

_SPECIAL = {
    "ß": r"\ss{}",
    "æ": r"\ae{}",
    "Æ": r"\AE{}",
    "œ": r"\oe{}",
    "Œ": r"\OE{}",
    "ø": r"\o{}",
    "Ø": r"\O{}",
    "ł": r"\l{}",
    "Ł": r"\L{}",
    "ı": r"\i{}",
    "å": r"\aa{}",
    "Å": r"\AA{}",
    "–": "--",
    "—": "---",
    "‘": "`",
    "’": "'",
    "“": "``",
    "”": "''",
    "„": ",,",
    "…": r"\ldots{}",
    "°": r"\ensuremath{^\circ}",
    "×": r"\ensuremath{\times}",
    "·": r"\ensuremath{\cdot}",
    "±": r"\ensuremath{\pm}",
    "−": r"\ensuremath{-}",
    "≤": r"\ensuremath{\leq}",
    "≥": r"\ensuremath{\geq}",
    "→": r"\ensuremath{\rightarrow}",
    "∞": r"\ensuremath{\infty}",
    "§": r"\S{}",
    "¶": r"\P{}",
    "©": r"\copyright{}",
    "£": r"\pounds{}",
    "¿": "?`",
    "¡": "!`",
    "\u00a0": "~",
}

# combining marks -> OT1 accent commands
_ACCENTS = {
    0x300: "`",
    0x301: "'",
    0x302: "^",
    0x303: "~",
    0x304: "=",
    0x306: "u",
    0x307: ".",
    0x308: '"',
    0x30A: "r",
    0x30B: "H",
    0x30C: "v",
    0x323: "d",
    0x327: "c",
}

_GREEK_CAPITALS = {
    "GAMMA",
    "DELTA",
    "THETA",
    "LAMBDA",
    "XI",
    "PI",
    "SIGMA",
    "UPSILON",
    "PHI",
    "PSI",
    "OMEGA",
}
_GREEK_AS_LATIN = {
    "ALPHA": "A",
    "BETA": "B",
    "EPSILON": "E",
    "ZETA": "Z",
    "ETA": "H",
    "IOTA": "I",
    "KAPPA": "K",
    "MU": "M",
    "NU": "N",
    "OMICRON": "O",
    "RHO": "P",
    "TAU": "T",
    "CHI": "X",
}


def _greek(ch: str) -> str | None:
    name = unicodedata.name(ch, "")
    m = re.fullmatch(r"GREEK (SMALL|CAPITAL) LETTER (FINAL )?([A-Z]+)", name)
    if not m:
        return None
    small, final, letter = m.group(1) == "SMALL", m.group(2), m.group(3)
    if small:
        word = "varsigma" if final else ("o" if letter == "OMICRON" else letter.lower())
        return rf"\ensuremath{{\{word}}}" if word != "o" else "o"
    if letter in _GREEK_CAPITALS:
        return rf"\ensuremath{{\{letter.capitalize()}}}"
    return _GREEK_AS_LATIN.get(letter)


def _accented(ch: str) -> str | None:
    decomposed = unicodedata.normalize("NFD", ch)
    base, marks = decomposed[0], decomposed[1:]
    if not (base.isascii() and base.isalpha()) or not marks:
        return None
    out = {"i": r"\i{}", "j": r"\j{}"}.get(base, base)
    for mark in marks:
        cmd = _ACCENTS.get(ord(mark))
        if cmd is None:
            return None
        out = rf"\{cmd}{{{out}}}"
    return out


def _char(ch: str) -> str:
    if ch in _ASCII:
        return _ASCII[ch]
    if " " <= ch <= "~":
        return ch
    if ch in _SPECIAL:
        return _SPECIAL[ch]
    if unicodedata.category(ch) in ("Cc", "Cf", "Zl", "Zp"):
        return ""  # control and format characters (bidi overrides, zero-width) are dropped
    if unicodedata.category(ch) == "Zs":
        return " "
    found = _accented(ch) or _greek(ch) or _greek(unicodedata.normalize("NFD", ch)[0])
    return found if found is not None else rf"\texttt{{[U+{ord(ch):04X}]}}"


def escape_latex(text: object) -> TeX:
    r"""LaTeX text-mode source that prints ``text`` literally (ASCII output).

    >>> print(escape_latex(r"}\end{document}"))
    \}\textbackslash{}end\{document\}
    >>> print(escape_latex(r"\write18{rm -rf /} #&~^"))
    \textbackslash{}write18\{rm -{}rf /\} \#\&{\ttfamily\char126}{\ttfamily\char94}
    >>> print(escape_latex("Müller — 90° 中"))
    M\"{u}ller --- 90\ensuremath{^\circ} \texttt{[U+4E2D]}
    """
    return TeX("".join(_char(ch) for ch in unicodedata.normalize("NFC", str(text))))


def math_width(tex: str) -> float:
    r"""A rough printed width of math-mode LaTeX, in units of one italic letter (~7.5pt at 11pt).

    Subscripts count 0.7, ``\cos`` three letters, ``\left``/``\right`` nothing,
    binary operators 2.2 (their spacing). Used to decide where to split a formula.

    >>> math_width("C_{12}"), math_width(r"a_{1} \cos{\left(\theta_{1} \right)}")
    (2.4, 8.0)
    """
    s = re.sub(r"\\(?:left|right)(?![A-Za-z])\.?", "", tex)
    s = re.sub(r"\\(?:cos|sin|tan)(?![A-Za-z])", "ccc", s)
    s = re.sub(r"\\[A-Za-z]+", "x", s)
    width, scale, stack, script = 0.0, 1.0, [], False
    for ch in s:
        if ch in "_^":
            script = True
            continue
        if ch == "{":
            stack.append(scale)
            scale = scale * 0.7 if script else scale
        elif ch == "}":
            scale = stack.pop() if stack else 1.0
        elif not ch.isspace():
            w = 2.2 if ch in "+-=" and scale == 1.0 else (0.8 if ch in "()," else 1.0)
            width += w * (0.7 * scale if script else scale)
        script = False
    return width


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


def _commands(name: str) -> list[list[str]]:
    if shutil.which("latexmk"):
        return [["latexmk", "-pdf", "-norc", "-silent", *_SAFE_FLAGS, name]]
    if shutil.which("pdflatex"):
        return [["pdflatex", *_SAFE_FLAGS, name]] * 3  # at most 3 passes (references)
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


def compile_pdf(tex_path: str | os.PathLike[str], *, timeout: float = 180.0) -> Path:
    """Compile ``tex_path`` to PDF next to it, safely; return the PDF's path.

    Shell escape is always off, rc files are ignored, TeX may only read and
    write files below the source's folder (``openin_any=p``), stdin is closed
    and the whole run is killed after ``timeout`` seconds. Raises
    :class:`~dhsym.errors.DHError` naming the first LaTeX errors (and the
    Debian packages to install when TeX is missing).
    """
    tex = Path(tex_path).resolve()
    if not tex.is_file():
        raise DHError(f"no such file: {tex_path}")
    env = dict(
        os.environ,
        openin_any="p",
        openout_any="p",
        shell_escape="f",
        max_print_line="10000",
        TEXMFOUTPUT=str(tex.parent),
    )
    deadline = time.monotonic() + timeout
    log = tex.with_suffix(".log")
    for cmd in _commands(tex.name):
        _run(cmd, tex.parent, env, max(1.0, deadline - time.monotonic()))
        text = log.read_text(encoding="latin-1") if log.exists() else ""
        if cmd[0] == "latexmk" or not re.search(r"Rerun to get|may have changed", text):
            break
    errors = [i for i in check_log(text) if i.kind == "error"]
    pdf = tex.with_suffix(".pdf")
    if errors or not pdf.exists():
        detail = "; ".join(str(e) for e in errors[:3]) or "no PDF was written"
        raise DHError(f"LaTeX failed: {detail} (see {log})", file=str(tex_path))
    return pdf
