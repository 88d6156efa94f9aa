"""What is asked: a DH table, a transform ``^iT_j``, a link matrix ``A_k`` or one entry.

Examples
--------
>>> Question.parse("T0_6[0,3]", n=6)
Question(spec='T0_6[0,3]', kind='entry', frm=0, to=6, entry=(0, 3))
>>> Question.parse("A3", n=6).label, Question.parse("arm", n=6).label, Question.parse("px", 6).label
('T2_3', 'T0_6', 'T0_6[0,3]')
>>> Question.parse("^0T_2", n=6).label_latex
'{}^{0}T_{2}'
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from dhsym.errors import DHError

__all__ = ["Question"]

_TRANSFORM = re.compile(  # frame numbers have at most 4 digits (no 5000-digit int() ever)
    r"^(?:\^\{?(?P<a>\d{1,4})\}?T_\{?(?P<b>\d{1,4})\}?"
    r"|[TH]_?\{?(?P<i>\d{1,4})\}?[_,]\{?(?P<j>\d{1,4})\}?"
    r"|[TH](?P<ij>\d\d)|[AH]_?\{?(?P<k>\d{1,4})\}?|(?P<arm>arm|T0_n|T_?0_?n)|p_?(?P<p>[xyz]))"
    r"(?:\s*\[\s*(?P<r>\d{1,4})\s*,\s*(?P<c>\d{1,4})\s*\])?$"
)


@dataclass(frozen=True)
class Question:
    """One question: ``kind`` is ``table``, ``matrix`` (``^frm T_to``) or ``entry`` (0-based)."""

    spec: str
    kind: str
    frm: int = 0
    to: int = 0
    entry: tuple[int, int] | None = None

    @classmethod
    def parse(cls, spec: str, n: int) -> Question:
        """Read ``table``, ``T0_2``, ``T02``, ``^0T_2``, ``A3``, ``arm``, ``px`` and ``…[r,c]``."""
        text = str(spec).strip()
        if len(text) > 200:
            raise DHError(f"unknown question {text[:40]!r}…: a question is at most 200 characters")
        if text.lower() in ("table", "dh", "dh table", "dh_table"):
            return cls(text, "table")
        m = _TRANSFORM.match(text.replace(" ", ""))
        if m is None:
            raise DHError(
                f"unknown question {text!r}: expected table, T<i>_<j>, A<k>, arm, px/py/pz, "
                "optionally with [row,col] (0-based), e.g. T0_6[0,3]"
            )
        if m["k"] is not None:
            frm, to = int(m["k"]) - 1, int(m["k"])
        elif m["arm"] is not None or m["p"] is not None:
            frm, to = 0, n
        elif m["ij"] is not None:
            frm, to = int(m["ij"][0]), int(m["ij"][1])
        else:
            frm, to = int(m["a"] or m["i"]), int(m["b"] or m["j"])
        if not (0 <= frm <= n and 0 <= to <= n) or frm == to:
            raise DHError(f"question {text!r}: frames are 0 … {n} and must differ")
        entry = None
        if m["p"] is not None:
            entry = ("xyz".index(m["p"]), 3)
        if m["r"] is not None:
            entry = (int(m["r"]), int(m["c"]))
            if not (0 <= entry[0] < 4 and 0 <= entry[1] < 4):
                raise DHError(f"question {text!r}: row and column are 0 … 3")
        return cls(text, "entry" if entry else "matrix", frm, to, entry)

    @property
    def label(self) -> str:
        """Canonical text: ``table``, ``T0_2`` or ``T0_6[0,3]``."""
        if self.kind == "table":
            return "table"
        base = f"T{self.frm}_{self.to}"
        return f"{base}[{self.entry[0]},{self.entry[1]}]" if self.entry else base

    @property
    def label_latex(self) -> str:
        """``{}^{0}T_{2}`` (or ``\\text{DH table}``), for headings."""
        if self.kind == "table":
            return r"\text{DH table}"
        base = f"{{}}^{{{self.frm}}}T_{{{self.to}}}"
        if self.entry:
            return f"{base}[{self.entry[0] + 1},{self.entry[1] + 1}]"
        return base
