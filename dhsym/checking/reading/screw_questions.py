r"""What is asked of a robot as a product of exponentials (Lynch and Park, *Modern Robotics*):
the space screw axes ``S`` (6×n, rows ``[ω; v]``) or one of them ``S3``, the body axes ``B``
(``B3``), the home configuration ``Mhome``, the space and body Jacobians ``Js``, ``Jb``, and
the forward kinematics ``T(theta)`` in PoE form; each with ``[row,col]`` for one entry
(0-based).

The home configuration is ``Mhome`` (also ``M_home``, ``M0``, ``M_0``), never ``M``: in an
assignment ``M`` is already the inertia matrix of the dynamics questions.

Examples
--------
>>> parse_screw("S_{3}", 6), parse_screw("Jb[0,1]", 2), parse_screw("M0", 2)
(('S', None, 3), ('Jb', (0, 1), None), ('Mhome', None, None))
>>> parse_screw("T0_2", 2) is None, parse_screw("M", 2) is None
(True, True)
>>> [screw_label(*parse_screw(s, 6)) for s in ("S", "B_2", "J_s", "T(θ)", "poe[0,3]")]
['S', 'B2', 'Js', 'T(theta)', 'T(theta)[0,3]']
>>> screw_latex("S", None, 3), screw_latex("Mhome", None, None), screw_latex("Jb", (0, 1), None)
('\\mathcal{S}_{3}', 'M', 'J_b[1,2]')
"""

from __future__ import annotations

import re

from dhsym.errors import DHError

__all__ = ["SCREW_PARTS", "parse_screw", "screw_label", "screw_latex"]

#: the parts a PoE question asks for, by their canonical names
SCREW_PARTS = ("S", "B", "Mhome", "Js", "Jb", "T")

_SCREW = re.compile(
    r"^(?:(?P<axes>[SB])(?:_?\{?(?P<col>\d{1,2})\}?)?"
    r"|(?P<home>M_?(?:home|\{home\}|0|\{0\})|home)"
    r"|J_?\{?(?P<jac>[sSbB])\}?"
    r"|(?P<fk>T\((?:theta|θ|q)\)|T_?\{?poe\}?|poe|fk_?poe))"
    r"(?:\[(?P<r>\d{1,2}),(?P<c>\d{1,2})\])?$"
)
_SHAPES = {"S": 6, "B": 6, "Js": 6, "Jb": 6, "Mhome": 4, "T": 4}
_LATEX = {
    "S": r"\mathcal{S}",
    "B": r"\mathcal{B}",
    "Mhome": "M",
    "Js": "J_s",
    "Jb": "J_b",
    "T": r"T(\theta)",
}


def parse_screw(compact: str, n: int) -> tuple[str, tuple[int, int] | None, int | None] | None:
    """``(part, entry, column)`` of a PoE question written without spaces, or None when
    ``compact`` asks something else; ``column`` is 1-based (``S3``), ``entry`` 0-based.

    A question that is a PoE question but out of range raises :class:`~dhsym.errors.DHError`.

    >>> parse_screw("S9", 2)
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: question 'S9': the screw axes are S1 … S2
    """
    m = _SCREW.match(compact)
    if m is None:
        return None
    column = None
    if m["axes"] is not None:
        part = m["axes"]
        if m["col"] is not None:
            column = int(m["col"])
            if not 1 <= column <= n:
                raise DHError(f"question {compact!r}: the screw axes are {part}1 … {part}{n}")
    elif m["home"] is not None:
        part = "Mhome"
    elif m["jac"] is not None:
        part = "J" + m["jac"].lower()
    else:
        part = "T"
    entry = None
    if m["r"] is not None:
        entry = (int(m["r"]), int(m["c"]))
        cols = 1 if column is not None else (4 if _SHAPES[part] == 4 else n)
        if not (entry[0] < _SHAPES[part] and entry[1] < cols):
            raise DHError(
                f"question {compact!r}: rows and columns are 0-based, "
                f"at most [{_SHAPES[part] - 1},{cols - 1}]"
            )
    return part, entry, column


def screw_label(part: str, entry: tuple[int, int] | None, column: int | None) -> str:
    """The canonical text of a PoE question: ``S``, ``S3``, ``Mhome``, ``Js[0,1]``,
    ``T(theta)``."""
    base = ("T(theta)" if part == "T" else part) + (str(column) if column else "")
    return f"{base}[{entry[0]},{entry[1]}]" if entry else base


def screw_latex(part: str, entry: tuple[int, int] | None, column: int | None) -> str:
    r"""A heading in LaTeX: ``\mathcal{S}_{3}``, ``J_b[1,2]`` (1-based, as a heading)."""
    base = _LATEX[part] + (f"_{{{column}}}" if column else "")
    return f"{base}[{entry[0] + 1},{entry[1] + 1}]" if entry else base
