r"""A derivation as plain data, in the order the lectures teach it (IRob2305
Lecture 5; Mohan, Lecture 9).

:func:`derive` builds a :class:`Derivation` from a robot: the DH table with
the convention's own headers, the general link matrix as the product of its
four elementary transforms, each link matrix, the successive products
``^0T_1 … ^0T_n`` with the sum-angle identities named where joints combine
(``C_1 C_2 - S_1 S_2 = C_{12}``), the arm matrix in ``[n s a p; 0 0 0 1]`` form,
the legend of abbreviations and an optional numeric check. Every formula is
printed twice, LaTeX and plain text, by the project's
:class:`~dhsym.notation.Notation`; the templates of :mod:`dhsym.explain.rendering` only
arrange these strings. Entries too wide for a line are split at their ``+``/``-``
signs (outermost first) into aligned lines.

Examples
--------
>>> d = derive("planar2r")
>>> d.result.rows[0][3].latex
'a_{1} C_{1} + a_{2} C_{12}'
>>> [(t.sign, t.math.text) for t in d.products[0].identities[0].terms]
[('+', 'C1*C2'), ('-', 'S1*S2')]
>>> d.legend[4].abbrev.text, d.legend[4].meaning.text
('C12', 'cos(theta1 + theta2)')
>>> [x.text for x in derive("puma560", check=True).check.rows[1]]
['0', '1', '0', '-0.15']
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from pathlib import Path
from types import MappingProxyType
from typing import TypedDict

import sympy as sp

from dhsym.errors import DHError
from dhsym.kinematics.chain import KinematicChain
from dhsym.kinematics.pose import Pose
from dhsym.kinematics.transforms import chain_word, elementary_matrix
from dhsym.model.table import AngleUnit, Convention, DHTable, Elementary
from dhsym.notation.escape import TeX
from dhsym.notation.layout import (
    LATEX_WIDTH,
    Equation,
    LegendLine,
    Math,
    MatrixBlock,
    Term,
    as_decimal,
    as_math,
    legend_lines,
    math_width,
    matrix_block,
    word_math,
)
from dhsym.notation.printers import Notation, TrigStyle
from dhsym.notation.tables import table_view
from dhsym.robot import Robot

from .data import (
    Derivation,
    Factor,
    GeneralLink,
    Identity,
    NumericCheck,
    Step,
    TableCell,
    TableData,
)

__all__ = [
    "MAX_LINKS",
    "Derivation",
    "Equation",
    "Factor",
    "GeneralLink",
    "Identity",
    "LegendLine",
    "Math",
    "MatrixBlock",
    "NumericCheck",
    "Step",
    "TableCell",
    "TableData",
    "Heading",
    "Term",
    "as_robot",
    "derive",
    "general_link",
    "heading",
    "label_key",
]

#: Links one derivation shows step by step (a 60-row planar chain takes seconds).
MAX_LINKS = 60

# --- the general link matrix ------------------------------------------------------------


class _General(sp.Symbol):
    """θ_i, α_{i-1}, …: a parameter with a symbolic index (prints as in the lectures)."""

    def _latex(self, printer: object) -> str:
        return _GENERAL_TEX[self.name]


_GENERAL_TEX = MappingProxyType(
    {
        "theta_i": r"\theta_{i}",
        "d_i": "d_{i}",
        "a_i": "a_{i}",
        "alpha_i": r"\alpha_{i}",
        "a_{i-1}": "a_{i-1}",
        "alpha_{i-1}": r"\alpha_{i-1}",
    }
)


def _general_row(modified: bool) -> tuple[_General, ...]:
    names = ("alpha_{i-1}", "a_{i-1}") if modified else ("alpha_i", "a_i")
    return tuple(_General(n, real=True) for n in ("theta_i", "d_i", names[1], names[0]))


# --- sections ---------------------------------------------------------------------------------


def _table(table: DHTable) -> TableData:
    heads, rows = table_view(table)
    plain = Notation()
    values = tuple((as_math(s, plain), as_decimal(v, plain)) for s, v in table.values)
    return TableData(
        heads,
        rows,
        table.angles is AngleUnit.DEG,
        values,
        tuple(as_math(v, plain) for v in table.variables),
    )


def label_math(pose: Pose) -> Math:
    """The pose's label, ``^iT_j``."""
    return Math(TeX(pose.label_latex), pose.label_text)


def product_math(left: Pose, right: Pose) -> Math:
    """``^iT_{k-1} ^{k-1}T_k`` as written in a derivation step."""
    return Math(
        TeX(rf"{left.label_latex}\,{right.label_latex}"), f"{left.label_text}*{right.label_text}"
    )


def inverse_math(pose: Pose) -> Math:
    """``(^jT_i)^{-1}``, where the inverse result comes from."""
    return Math(TeX(rf"\left({pose.label_latex}\right)^{{-1}}"), f"({pose.label_text})^-1")


def _frame_notes(table: DHTable, frm: int, to: int, n: int, nota: Notation) -> tuple[str, ...]:
    """Say where the table's base and tool transforms are (``convert`` moves lengths there):
    ^0T_n below stops at the last DH frame."""

    def word(steps: tuple[Elementary, ...]) -> str:
        return "·".join(f"{e.kind}{e.axis}({nota.text(e.value)})" for e in steps)

    out = []
    if table.tool and n in (frm, to):
        out.append(
            f"The table has a tool transform {word(table.tool)} after frame {n}: the matrices "
            f"below stop at frame {n}; the tool pose is T0_{n}·{word(table.tool)} "
            f"(derive --to {n + 1})."
        )
    if table.base and 0 in (frm, to):
        out.append(
            f"The table has a base transform {word(table.base)} before frame 0: the world "
            "pose of frame 0 is that transform (derive --from -1)."
        )
    return tuple(out)


def general_link(convention: Convention | str, nota: Notation | None = None) -> GeneralLink:
    """The general link matrix of a convention, from its four elementary factors.

    >>> general_link("standard").result.rows[0][1].text
    '-Si*c_alpha_i'
    """
    convention = Convention.parse(convention)
    nota = nota or Notation()
    from dhsym.kinematics.transforms import link_word, plain_product
    from dhsym.model.table import DHRow

    modified = convention is Convention.MODIFIED
    theta, d, a, alpha = _general_row(modified)
    gnota = Notation(((theta, "i"),), compact=nota.compact, style=nota.style)
    row = DHRow.fixed(theta, d, a, alpha)
    word = link_word(row, convention)
    factors = tuple(
        Factor(
            e.kind,
            e.axis,
            as_math(e.value, gnota),
            matrix_block(word_math([e], gnota), elementary_matrix(e), gnota),
        )
        for e in word
    )
    matrix = plain_product(word)
    params = (alpha, a, d, theta) if modified else (theta, d, a, alpha)
    return GeneralLink(
        tuple(as_math(p, gnota) for p in params),
        word_math(word, gnota),
        factors,
        matrix_block(Math(TeX("{}^{i-1}T_{i}"), "T(i-1)_i"), matrix, gnota),
        legend_lines(list(matrix), gnota),
    )


def _check(robot: Robot, frm: int, to: int, q: Sequence[float]) -> NumericCheck:
    missing = [str(s) for s in robot.table.constants if s not in robot.table.value_map]
    if missing:
        raise DHError(
            f"the numeric check needs values for {', '.join(missing)} "
            f"(add them under 'values:' in the table)"
        )
    if len(q) != len(robot.variables):
        raise DHError(f"the numeric check needs {len(robot.variables)} joint values, got {len(q)}")
    T = robot.fk_function(frm, to)([float(x) for x in q])
    plain = Notation()

    def num(x: float) -> Math:
        s = f"{x:.4f}".rstrip("0").rstrip(".")
        s = "0" if s in ("-0", "") else s
        return Math(TeX(s), s)

    return NumericCheck(
        tuple((as_math(v, plain), num(float(x))) for v, x in zip(robot.variables, q, strict=True)),
        tuple(tuple(num(float(T[r, c])) for c in range(4)) for r in range(4)),
    )


def as_robot(name_or_robot: object) -> Robot:
    """A Robot from a built-in name, a table file, a DHTable or a Robot (returned as is)."""
    if isinstance(name_or_robot, Robot):
        return name_or_robot
    if isinstance(name_or_robot, DHTable):
        return Robot(name_or_robot)
    if isinstance(name_or_robot, (str, Path)):
        from dhsym.robot import load

        return load(name_or_robot)
    raise DHError(
        f"expected a robot name, table file, DHTable or Robot; got {type(name_or_robot).__name__}"
    )


def label_key(name: str) -> str:
    """A robot's name as a LaTeX label and file key: lower case, words joined by ``-``.

    >>> label_key("PUMA 560 (modified)"), label_key("")
    ('puma-560-modified', 'robot')
    """
    return re.sub(r"[^a-z0-9]+", "-", name.lower()).strip("-") or "robot"


class Heading(TypedDict):
    """What every document of a robot starts with (its keyword arguments ``**heading``)."""

    name: str
    key: str
    convention: str
    n: int


def heading(robot: KinematicChain, n: int) -> Heading:
    """The robot's name (``robot`` when it has none), the :func:`label_key` of that name,
    its convention and the ``n`` the document counts (joints, columns, screw axes).

    >>> import dhsym
    >>> h = heading(dhsym.load("puma560_modified"), 6)
    >>> h["key"], h["convention"], h["n"]
    ('puma-560-modified-dh-craig', 'modified', 6)
    """
    name = robot.name or "robot"
    return Heading(name=name, key=label_key(name), convention=robot.convention.value, n=n)


def _steps(robot: Robot, lo: int, hi: int, final: bool, width: float) -> list[Step]:
    """``^{lo}T_k = ^{lo}T_{k-1} ^{k-1}T_k`` for k = lo + 2 … hi, with their identities."""
    steps = []
    for k in range(lo + 2, hi + 1):
        left, right, res = (
            robot.transform(lo, k - 1),
            robot.transform(k - 1, k),
            robot.transform(lo, k),
        )
        block = matrix_block(
            label_math(res), res.matrix, robot.notation, [product_math(left, right)], width
        )
        ids = identities(left.matrix, right.matrix, res.matrix, robot.notation, width)
        steps.append(Step(block, ids, final and k == hi))
    return steps


def derive(
    name_or_robot: str | Path | DHTable | Robot,
    *,
    frm: int = 0,
    to: int | None = None,
    factors: bool = True,
    numeric: bool = False,
    compact: bool | None = None,
    notation: TrigStyle | str | None = None,
    check: bool | Sequence[float] | None = None,
    width: float = LATEX_WIDTH,
) -> Derivation:
    r"""Derive ``^{frm}T_{to}`` of a robot step by step, as the lectures do.

    Parameters
    ----------
    name_or_robot
        A built-in name (``"puma560"``), a table file, a DHTable or a Robot.
    frm, to
        The frames of ``^iT_j`` (default ``0`` and ``n``: the arm matrix);
        ``-1`` is the world and ``n + 1`` the tool frame; ``to < frm`` gives
        the inverse.
    factors
        Include the general link matrix built from its four elementary factors.
    numeric
        Substitute the table's numeric values for the symbolic lengths.
    compact
        ``C_{12}`` notation (default: the robot's own setting) or full cos/sin.
    notation
        The case of the abbreviations (:class:`~dhsym.notation.printers.TrigStyle`):
        ``C1`` (``C_{12}``, the lectures), ``c1`` (``c_{12}``, Craig, Spong) or
        ``c_theta`` (``c_{\theta_{12}}``); default: the robot's own.
    check
        Evaluate the result numerically at these joint values (``True``: at zero).
    width
        Line width of the LaTeX output in :func:`~dhsym.notation.layout.math_width` units: the
        default fits the handout's 17 cm text; about 40 fits the 12 cm of a default
        ``article`` when a fragment is included in your own document.

    >>> d = derive("puma560_modified", factors=True)
    >>> print(d.general.result.rows[1][3].latex)
    -d_{i} s_{\alpha_{i-1}}
    >>> [e.name.text + " = " + e.text_lines[0] for e in d.result.entries][9]
    'p_x = C1*(a2*C2 + a3*C23 - d4*S23) - d3*S1'
    """
    robot = as_robot(name_or_robot)
    table = robot.table.substituted() if numeric else robot.table
    compact = robot.notation.compact if compact is None else compact
    style = robot.notation.style if notation is None else TrigStyle.parse(notation)
    robot = Robot(table, compact=compact, style=style)
    nota, n = robot.notation, robot.n
    to = n if to is None else to
    for k in (frm, to):
        if not -1 <= k <= n + 1:
            raise DHError(
                f"frames of {robot.name or 'this robot'} are -1 (world), 0 … {n}, "
                f"{n + 1} (tool); got {k}"
            )
    if frm == to:
        raise DHError(f"^{frm}T_{to} is the identity: choose two different frames")
    lo, hi = min(frm, to), max(frm, to)
    if hi - lo > MAX_LINKS:
        raise DHError(
            f"^{frm}T_{to} spans {hi - lo} links; a derivation shows at most {MAX_LINKS}: "
            f"derive parts of the chain with --from/--to (frm=/to= in Python), e.g. "
            f"^{lo}T_{lo + MAX_LINKS} and ^{lo + MAX_LINKS}T_{hi}"
        )
    robot.check_transform_size(frm, to)
    links = []
    for k in range(lo + 1, hi + 1):
        pose, word = robot.transform(k - 1, k), chain_word(table, k - 1, k)
        links.append(
            matrix_block(label_math(pose), pose.matrix, nota, [word_math(word, nota)], width)
        )
    pose = robot.transform(frm, to)
    prefix = [inverse_math(robot.transform(to, frm))] if frm > to else []
    shown = list(pose.matrix)
    for k in range(lo + 1, hi + 1):
        shown += list(robot.transform(k - 1, k).matrix) + list(robot.transform(lo, k).matrix)
    q = None if check is None or check is False else check
    if q is True:
        q = [0.0] * len(robot.variables)
    return Derivation(
        **heading(robot, n),
        source=table.source,
        notes=table.notes,
        warnings=(*table.warnings, *_frame_notes(table, frm, to, n, nota)),
        compact=compact,
        numeric=numeric,
        table=_table(table),
        general=general_link(robot.convention, nota) if factors else None,
        links=tuple(links),
        products=tuple(_steps(robot, lo, hi, frm < to, width)),
        result=matrix_block(label_math(pose), pose.matrix, nota, prefix, width),
        inverse=frm > to,
        legend=legend_lines(shown, nota),
        check=_check(robot, frm, to, list(q)) if q is not None else None,
        width=width,
    )


def _angles(matrix: sp.MatrixBase) -> set[sp.Expr]:
    return {f.args[0] for f in matrix.atoms(sp.sin, sp.cos)}


def _identity(
    result: sp.Expr,
    terms: Sequence[tuple[str, tuple[sp.Expr, sp.Expr]]],
    nota: Notation,
    width: float,
) -> Identity:
    """``±f(A)g(B) ± … = result``, each product printed factor by factor in textbook order."""
    ts = tuple(
        Term(sign, Math(TeX(" ".join(nota.latex(f) for f in fs)), "*".join(map(nota.text, fs))))
        for sign, fs in terms
    )
    rhs = as_math(result, nota)
    size = sum(math_width(t.math.latex) + 2.2 for t in ts) + math_width(rhs.latex)
    return Identity(ts, rhs, size > width / 2, size > width)


def identities(
    left: sp.MatrixBase,
    right: sp.MatrixBase,
    result: sp.MatrixBase,
    nota: Notation,
    width: float = LATEX_WIDTH,
) -> tuple[Identity, ...]:
    """The sum-angle identities that turn ``left · right`` into ``result``.

    An angle of ``result`` found in neither factor is ``A ± B`` with ``A`` an angle of
    ``left`` and ``B`` one of ``right`` (``θ_2 + θ_3``; ``θ_{12} - θ_4`` after a flip).
    """
    la, ra = _angles(left), _angles(right)
    trig = result.atoms(sp.sin, sp.cos)
    found = []
    for x in sorted(_angles(result) - la - ra, key=sp.default_sort_key):
        for A in sorted(la, key=sp.default_sort_key):
            B = sp.expand(x - A)
            sign = 1 if B in ra else (-1 if -B in ra else 0)
            if sign:
                break
        else:
            continue
        B = B * sign
        cA, sA, cB, sB = sp.cos(A), sp.sin(A), sp.cos(B), sp.sin(B)
        minus, plus = ("-", "+") if sign > 0 else ("+", "-")
        if sp.cos(x) in trig:
            found.append(_identity(sp.cos(x), [("+", (cA, cB)), (minus, (sA, sB))], nota, width))
        if sp.sin(x) in trig:
            found.append(_identity(sp.sin(x), [("+", (sA, cB)), (plus, (cA, sB))], nota, width))
    return tuple(found)
