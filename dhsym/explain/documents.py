r"""Documents of robots: a derivation as text/Markdown/LaTeX, and handouts (LaTeX and PDF).

:func:`render_derivation` derives a robot and renders it (``dhsym derive``);
:func:`render_handout` puts one or more derivations into a standalone LaTeX
document (answers or problems mode, optional figures of the arm), and
:func:`write_handout` writes it and compiles it to PDF (``dhsym handout``).

Examples
--------
>>> import dhsym
>>> out = render_derivation(dhsym.load("planar2r"), fmt="latex")
>>> "C_{12} & -S_{12} & 0 & a_{1} C_{1} + a_{2} C_{12}" in out
True
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from pathlib import Path

import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.robot import Robot
from dhsym.notation.escape import TeX
from dhsym.notation.printers import Notation, TrigStyle

from .derivation import Derivation, as_robot, derive, general_link
from .latex import compile_pdf
from .rendering import environment, render, render_template

__all__ = ["render_derivation", "render_handout", "write_handout"]


def render_derivation(
    robot: Robot | str | Path,
    fmt: str = "text",
    frm: int = 0,
    to: int | None = None,
    **options: object,
) -> str:
    """``^{frm}T_{to}`` of ``robot`` derived step by step, as text, Markdown or LaTeX.

    ``options`` go to :func:`dhsym.explain.derivation.derive` (``factors``, ``numeric``,
    ``compact``, ``notation``, ``check``, ``width``) except ``template_dir``.
    """
    template_dir = options.pop("template_dir", None)
    d = derive(robot, frm=frm, to=to, **options)  # type: ignore[arg-type]
    return render(d, fmt, template_dir=template_dir)  # type: ignore[arg-type]


_DERIVE_OPTIONS = ("frm", "to", "factors", "numeric", "compact", "notation", "check", "width")


def _derivations(
    robots: Sequence[Robot | str | Path | Derivation], options: dict[str, object]
) -> list[Derivation]:
    """Derive each robot; ``check=True`` applies to those with numbers for every length."""
    out = []
    for r in robots:
        if isinstance(r, Derivation):
            out.append(r)
            continue
        opts = dict(options)
        robot = as_robot(r)
        if opts.get("check") is True and set(robot.table.constants) - set(robot.table.value_map):
            opts["check"] = None
        out.append(derive(robot, **opts))  # type: ignore[arg-type]
    return out


def _unique_keys(derivations: Sequence[Derivation]) -> list[str]:
    keys: list[str] = []
    for d in derivations:
        key, k = d.key, 2
        while key in keys:
            key, k = f"{d.key}-{k}", k + 1
        keys.append(key)
    return keys


def render_handout(
    robots: Sequence[Robot | str | Path | Derivation],
    *,
    title: str | None = None,
    course: str = "",
    author: str = "",
    date: str = "",
    mode: str = "answers",
    convention_note: bool = False,
    template_dir: str | Path | None = None,
    figures: dict[str, str] | None = None,
    **options: object,
) -> str:
    r"""A standalone LaTeX handout for one or more robots.

    ``mode`` is ``answers`` (full derivations) or ``problems`` (table and
    questions with space for answers). ``figures`` maps a robot's key (its
    name in lower case, ``-`` separated) to a graphics file next to the
    ``.tex``. Other options go to :func:`~dhsym.explain.derivation.derive`;
    ``check=True`` checks the robots whose lengths all have numbers.

    >>> tex = render_handout(["planar2r"], title=r"\input{/etc/passwd}")
    >>> r"\textbackslash{}input\{/etc/passwd\}" in tex, r"\input{/etc" in tex
    (True, False)
    """
    if mode not in ("answers", "problems"):
        raise DHError(f"unknown mode {mode!r}: expected 'answers' or 'problems'")
    unknown = set(options) - set(_DERIVE_OPTIONS)
    if unknown:
        raise DHError(f"unknown handout option(s): {', '.join(sorted(unknown))}")
    ds = _derivations(robots, options)
    own = (r.notation.style for r in robots if isinstance(r, Robot))
    nota = Notation(style=options.get("notation") or next(own, TrigStyle.UPPER))  # type: ignore[arg-type]
    items = [
        {"d": d, "key": k, "figure": _graphic((figures or {}).get(k))}
        for d, k in zip(ds, _unique_keys(ds), strict=True)
    ]
    if title is None:
        title = "Forward kinematics: " + ", ".join(d.name for d in ds)
    env = environment("latex", template_dir)
    return render_template(
        env,
        "handout.tex.j2",
        items=items,
        title=title,
        course=course,
        author=author,
        date=date,
        mode=mode,
        convention_note=convention_note,
        general={c: general_link(c, nota) for c in ("standard", "modified")},
        abbrev=_abbreviations(nota),
    )


def _abbreviations(nota: Notation) -> tuple[TeX, TeX, TeX]:
    """``C_i``, ``S_i``, ``C_{ij}`` as the handout's notation prints them."""
    ti, tj = sp.Symbol("theta_i", real=True), sp.Symbol("theta_j", real=True)
    general = Notation(((ti, "i"), (tj, "j")), style=nota.style)
    c, s, cij = (general.latex(f) for f in (sp.cos(ti), sp.sin(ti), sp.cos(ti + tj)))
    return TeX(c), TeX(s), TeX(cij)


def _graphic(name: str | None) -> TeX | None:
    """A graphics file name that LaTeX reads as it is (no escaping needed or allowed)."""
    if name is None:
        return None
    if not re.fullmatch(r"[A-Za-z0-9][A-Za-z0-9._-]*\.(pdf|png|jpg)", name):
        raise DHError(f"figure file names are letters, digits, '.', '_' and '-'; got {name!r}")
    return TeX(name)


def _figures(robots: Sequence[Robot], keys: Sequence[str], folder: Path, stem: str) -> dict:
    try:
        from dhsym.plot.figures import plot_robot
    except ImportError as err:
        raise DHError(f"--figure needs matplotlib, which is not available ({err})") from None
    out = {}
    for robot, key in zip(robots, keys, strict=True):
        name = f"{stem}-{key}-home.pdf"
        fig = plot_robot(robot, None)
        fig.savefig(folder / name, bbox_inches="tight")  # type: ignore[attr-defined]
        out[key] = name
    return out


def write_handout(
    robots: Sequence[Robot | str | Path],
    output: str | Path,
    *,
    pdf: bool = False,
    figure: bool = False,
    keep_aux: bool = False,
    **options: object,
) -> Path:
    """Write the handout's ``.tex`` (and figures); with ``pdf=True`` compile it.

    ``options`` are those of :func:`render_handout`. Returns the path of the
    PDF when compiled, else of the ``.tex``. LaTeX's auxiliary files stay in a
    temporary folder unless ``keep_aux``.
    """
    out = Path(output)
    if out.suffix != ".tex":
        raise DHError(f"the handout file must end in .tex, got {out.name}")
    out.parent.mkdir(parents=True, exist_ok=True)
    loaded = [as_robot(r) for r in robots]
    derive_opts = {k: options.pop(k) for k in _DERIVE_OPTIONS if k in options}
    ds = _derivations(loaded, derive_opts)
    figures = None
    if figure:
        stem = re.sub(r"[^A-Za-z0-9-]+", "-", out.stem).strip("-") or "handout"
        figures = _figures(loaded, _unique_keys(ds), out.parent, stem)
    style = (derive_opts.get("notation") or loaded[0].notation.style) if loaded else None
    out.write_text(render_handout(ds, figures=figures, notation=style, **options), encoding="utf-8")
    return compile_pdf(out, keep_aux=keep_aux) if pdf else out
