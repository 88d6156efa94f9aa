r"""Documents of robots: a derivation as text/Markdown/LaTeX, and handouts (LaTeX and PDF).

:func:`document` derives one of the derivations of a robot (:data:`WHAT`: forward
kinematics, the Jacobian, its singularities, the inverse kinematics, the equations of
motion);
:func:`render_derivation` renders it (``dhsym derive --what``); :func:`render_handout`
puts the asked sections of one or more robots into a standalone LaTeX document (answers
or problems mode, optional figures of the arm), and :func:`write_handout` writes it and
compiles it to PDF (``dhsym handout --sections``).

Examples
--------
>>> import dhsym
>>> out = render_derivation(dhsym.load("planar2r"), fmt="latex")
>>> "C_{12} & -S_{12} & 0 & a_{1} C_{1} + a_{2} C_{12}" in out
True
>>> print(render_derivation("planar2r", what="singularities").splitlines()[0])
Planar 2R: singular configurations (standard DH convention)
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Any

import sympy as sp

from dhsym.errors import DHError
from dhsym.model.table import DHTable
from dhsym.notation.escape import TeX
from dhsym.notation.printers import Notation, TrigStyle
from dhsym.robot import Robot

from .data import Document
from .derivation import Derivation, as_robot, derive, general_link
from .equations_of_motion import derive_dynamics
from .inverse_kinematics import derive_inverse
from .latex import compile_pdf
from .rendering import environment, render, render_template
from .trajectories import derive_control, derive_trajectory
from .velocity_kinematics import derive_jacobian, derive_singularities

__all__ = [
    "SECTION_TITLES",
    "WHAT",
    "HandoutSheet",
    "document",
    "render_derivation",
    "render_handout",
    "render_sheets",
    "write_handout",
]

#: What can be derived: forward kinematics, the Jacobian, its singularities, the inverse,
#: the equations of motion.
WHAT = ("fk", "jacobian", "singularities", "screws", "ik", "dynamics", "trajectory", "control")

#: Headings of the handout sections.
SECTION_TITLES = MappingProxyType(
    {
        "fk": "Forward kinematics",
        "jacobian": "The Jacobian",
        "singularities": "Singular configurations",
        "screws": "Screw axes and the product of exponentials",
        "ik": "Inverse kinematics",
        "dynamics": "Equations of motion",
        "trajectory": "Trajectories",
        "control": "Control",
    }
)

_DERIVE_OPTIONS = ("frm", "to", "factors", "numeric", "compact", "notation", "check", "width")
#: the options each derivation takes (the forward kinematics takes all of _DERIVE_OPTIONS)
_OPTIONS = MappingProxyType(
    {
        "jacobian": ("frame", "point", "compact", "notation", "width", "numeric"),
        "singularities": ("compact", "notation", "width", "numeric"),
        "screws": ("compact", "notation", "width", "numeric"),
        "ik": ("compact", "notation", "width", "check", "numeric"),
        "dynamics": ("compact", "notation", "width", "numeric", "progress"),
        "trajectory": (),
        "control": (),
    }
)


def _what(what: str) -> str:
    key = str(what).strip().lower()
    if key not in WHAT:
        raise DHError(f"unknown derivation {what!r}: expected one of {', '.join(WHAT)}")
    return key


def document(
    robot: Robot | str | Path | DHTable,
    what: str = "fk",
    **options: Any,  # the derivation's keywords, checked by name below
) -> Document:
    """One derivation of ``robot``: ``what`` is ``fk``, ``jacobian``, ``singularities``, ``ik``
    or ``dynamics``.

    ``options`` are those of :func:`~dhsym.explain.derivation.derive` (``fk``),
    :func:`~dhsym.explain.velocity_kinematics.derive_jacobian` (``frame``, ``point``),
    :func:`~dhsym.explain.velocity_kinematics.derive_singularities` or
    :func:`~dhsym.explain.inverse_kinematics.derive_inverse` (``check``); ``numeric``
    substitutes the table's numbers for its lengths. Options a derivation does not take are
    refused.

    >>> document("planar2r", "ik").count
    2
    """
    what = _what(what)
    if what == "fk":
        return derive(robot, **options)
    unknown = set(options) - set(_OPTIONS[what])
    if unknown:
        raise DHError(f"option(s) {', '.join(sorted(unknown))} do not apply to --what {what}")
    opts = dict(options)
    r = as_robot(robot)
    if opts.pop("numeric", False):
        r = Robot(r.table.substituted(), compact=r.notation.compact, style=r.notation.style)
    if what == "jacobian":
        return derive_jacobian(r, **opts)
    if what == "singularities":
        return derive_singularities(r, **opts)
    if what == "dynamics":
        return derive_dynamics(r, **opts)
    if what == "screws":
        from .screw_axes import derive_screws

        return derive_screws(r, **opts)
    if what == "trajectory":
        return derive_trajectory(r)
    if what == "control":
        return derive_control(r)
    return derive_inverse(r, **opts)


def render_derivation(
    robot: Robot | str | Path,
    fmt: str = "text",
    frm: int = 0,
    to: int | None = None,
    *,
    what: str = "fk",
    **options: Any,  # document's keywords and template_dir
) -> str:
    """A derivation of ``robot`` step by step, as text, Markdown or LaTeX.

    ``what`` is ``fk`` (``^{frm}T_{to}``, the default), ``jacobian``, ``singularities`` or
    ``ik``; ``options`` go to :func:`document` except ``template_dir``.
    """
    template_dir = options.pop("template_dir", None)
    if _what(what) == "fk":
        options.update(frm=frm, to=to)
    d = document(robot, what, **options)
    return render(d, fmt, template_dir=template_dir)


def _sections(sections: Sequence[str] | str) -> tuple[str, ...]:
    """The asked sections, each once, in the order of :data:`WHAT`."""
    asked = [sections] if isinstance(sections, str) else list(sections)
    keys = {_what(k) for part in asked for k in str(part).split(",") if k.strip()}
    if not keys:
        raise DHError(f"no handout sections given: choose from {', '.join(WHAT)}")
    return tuple(k for k in WHAT if k in keys)


def _options_for(what: str, robot: Robot, options: dict[str, Any]) -> dict[str, Any]:
    """The handout's options that ``what`` takes; ``check=True`` only with numbers for all
    lengths; the inverse kinematics is checked at a configuration away from singularities."""
    allowed = _DERIVE_OPTIONS if what == "fk" else _OPTIONS[what]
    opts = {k: v for k, v in options.items() if k in allowed}
    if opts.get("check") is True and set(robot.table.constants) - set(robot.table.value_map):
        opts["check"] = None
    return opts


def _item_documents(
    r: Robot | str | Path | Derivation, sections: Sequence[str], options: dict[str, Any]
) -> tuple[Derivation, list[tuple[str, Document]]]:
    """The forward kinematics (always: it holds the table) and the asked sections."""
    if isinstance(r, Derivation):
        if set(sections) != {"fk"}:
            raise DHError("sections other than fk need robots, not derivations")
        return r, [("fk", r)]
    robot = as_robot(r)
    fk = derive(robot, **_options_for("fk", robot, options))
    docs: list[tuple[str, Document]] = []
    for what in sections:
        doc = fk if what == "fk" else document(robot, what, **_options_for(what, robot, options))
        docs.append((what, doc))
    return fk, docs


def _unique_keys(names: Sequence[str]) -> list[str]:
    """One key per robot (its name in lower case, ``-`` separated), numbered when repeated."""
    keys: list[str] = []
    for name in names:
        base = re.sub(r"[^a-z0-9]+", "-", name.lower()).strip("-") or "robot"
        key, k = base, 2
        while key in keys:
            key, k = f"{base}-{k}", k + 1
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
    sections: Sequence[str] | str = ("fk",),
    convention_note: bool = False,
    template_dir: str | Path | None = None,
    figures: dict[str, str] | None = None,
    **options: Any,  # the derivations' keywords, checked by name below
) -> str:
    r"""A standalone LaTeX handout for one or more robots.

    ``mode`` is ``answers`` (full derivations) or ``problems`` (table and
    questions with space for answers). ``sections`` are any of :data:`WHAT`
    (``fk,jacobian,singularities,ik``; default ``fk``), each a part of every robot's
    section. ``figures`` maps a robot's key (its name in lower case, ``-`` separated)
    to a graphics file next to the ``.tex``. Other options go to the derivations
    (:func:`document`); ``check=True`` checks the robots whose lengths all have numbers.

    >>> tex = render_handout(["planar2r"], title=r"\input{/etc/passwd}")
    >>> r"\textbackslash{}input\{/etc/passwd\}" in tex, r"\input{/etc" in tex
    (True, False)
    >>> tex = render_handout(["planar2r"], sections="fk,ik")
    >>> r"\subsection{Inverse kinematics}" in tex, r"\subsubsection{Position: joints 1, 2}" in tex
    (True, True)
    """
    if mode not in ("answers", "problems"):
        raise DHError(f"unknown mode {mode!r}: expected 'answers' or 'problems'")
    unknown = set(options) - set(_DERIVE_OPTIONS) - {"frame", "point"}
    if unknown:
        raise DHError(f"unknown handout option(s): {', '.join(sorted(unknown))}")
    wanted = _sections(sections)
    items, title = _sheet_items(robots, wanted, title, figures, options)
    own = (r.notation.style for r in robots if isinstance(r, Robot))
    nota = Notation(style=options.get("notation") or next(own, TrigStyle.UPPER))
    sheet = {"items": items, "title": title, "author": author}
    common = dict(course=course, date=date, mode=mode, convention_note=convention_note)
    return _render_handout(template_dir, nota, wanted, sheet, None, **common)


def _sheet_items(
    robots: Sequence[Robot | str | Path | Derivation],
    wanted: Sequence[str],
    title: str | None,
    figures: dict[str, str] | None,
    options: dict[str, Any],
) -> tuple[list[dict[str, Any]], str]:
    """The handout's items (a robot each: its derivations, key and figure) and its title
    (the sections and robots' names when not given)."""
    built = [_item_documents(r, wanted, options) for r in robots]
    keys = _unique_keys([fk.name for fk, _ in built])
    items = [
        {
            "d": fk,
            "key": k,
            "figure": _graphic((figures or {}).get(k)),
            "sections": [
                {"kind": what, "title": SECTION_TITLES[what], "doc": doc} for what, doc in docs
            ],
        }
        for (fk, docs), k in zip(built, keys, strict=True)
    ]
    if title is None:
        heads = [SECTION_TITLES[w] for w in wanted]
        heads = heads[:1] + [h[:1].lower() + h[1:] for h in heads[1:]]
        title = ", ".join(heads) + ": " + ", ".join(fk.name for fk, _ in built)
    return items, title


@dataclass(frozen=True)
class HandoutSheet:
    """One sheet of a merged handout (:func:`render_sheets`): its robots, title, author,
    and the derivations' options that are its own (``check``: the joint values of its
    numeric check and of its IK pose)."""

    robots: tuple[Robot | str | Path, ...]
    title: str | None = None
    author: str = ""
    check: Sequence[object] | bool | None = None


def render_sheets(
    sheets: Sequence[HandoutSheet],
    *,
    course: str = "",
    date: str = "",
    mode: str = "problems",
    sections: Sequence[str] | str = ("fk",),
    convention_note: bool = False,
    template_dir: str | Path | None = None,
    **options: Any,  # the derivations' keywords, as render_handout's
) -> str:
    r"""Several handouts as one LaTeX document, from the one handout template: each sheet
    starts on a new page, its pages and sections numbered from 1 (a class's problem
    sheets, one per student, to print at once).

    >>> tex = render_sheets([HandoutSheet(("planar2r",), "HW", "Ada"),
    ...                      HandoutSheet(("planar2r",), "HW", "Bo")])
    >>> tex.count(r"\documentclass"), tex.count(r"\setcounter{page}{1}"), tex.count("Bo")
    (1, 2, 1)
    """
    if not sheets:
        raise DHError("a merged handout needs at least one sheet")
    if mode not in ("answers", "problems"):
        raise DHError(f"unknown mode {mode!r}: expected 'answers' or 'problems'")
    unknown = set(options) - set(_DERIVE_OPTIONS) - {"frame", "point"}
    if unknown:
        raise DHError(f"unknown handout option(s): {', '.join(sorted(unknown))}")
    if "check" in options:
        raise DHError("check is each sheet's own: HandoutSheet(..., check=...)")
    wanted = _sections(sections)
    parts = []
    for sheet in sheets:
        own = {**options, **({"check": sheet.check} if sheet.check is not None else {})}
        items, title = _sheet_items(sheet.robots, wanted, sheet.title, None, own)
        parts.append({"items": items, "title": title, "author": sheet.author})
    first = [as_robot(r) for r in sheets[0].robots]
    style = options.get("notation") or (first[0].notation.style if first else TrigStyle.UPPER)
    common = dict(course=course, date=date, mode=mode, convention_note=convention_note)
    return _render_handout(template_dir, Notation(style=style), wanted, parts[0], parts, **common)


def _render_handout(
    template_dir: str | Path | None,
    nota: Notation,
    wanted: Sequence[str],
    sheet: dict[str, Any],
    sheets: list[dict[str, Any]] | None,
    **common: Any,  # course, date, mode, convention_note
) -> str:
    """The handout template rendered: one sheet (``items``, ``title``, ``author``), or
    ``sheets`` merged (the first is also the context's)."""
    env = environment("latex", template_dir)
    merged = {"sheets": sheets} if sheets is not None else {}
    return render_template(
        env,
        "handout.tex.j2",
        **merged,
        **sheet,
        sections=wanted,
        **common,
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


def _figures(
    robots: Sequence[Robot], keys: Sequence[str], folder: Path, stem: str
) -> dict[str, str]:
    try:
        from dhsym.plot.figures import plot_robot
    except ImportError as err:
        raise DHError(f"--figure needs matplotlib, which is not available ({err})") from None
    out = {}
    for robot, key in zip(robots, keys, strict=True):
        name = f"{stem}-{key}-home.pdf"
        fig = plot_robot(robot, None)
        fig.savefig(folder / name, bbox_inches="tight")
        out[key] = name
    return out


def write_handout(
    robots: Sequence[Robot | str | Path],
    output: str | Path,
    *,
    pdf: bool = False,
    figure: bool = False,
    keep_aux: bool = False,
    **options: Any,  # render_handout's keywords, passed on
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
    figures = None
    if figure:
        stem = re.sub(r"[^A-Za-z0-9-]+", "-", out.stem).strip("-") or "handout"
        keys = _unique_keys([r.name or "robot" for r in loaded])
        figures = _figures(loaded, keys, out.parent, stem)
    style = options.pop("notation", None) or (loaded[0].notation.style if loaded else None)
    tex = render_handout(loaded, figures=figures, notation=style, **options)
    out.write_text(tex, encoding="utf-8")
    return compile_pdf(out, keep_aux=keep_aux) if pdf else out
