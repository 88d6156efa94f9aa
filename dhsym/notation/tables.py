"""The view of a DH table: headers in the convention's order, cells in lecture notation.

Examples
--------
>>> from dhsym.model.table import DHTable, DHRow
>>> print(table_markdown(DHTable.from_rows([DHRow.revolute("theta1", a="a1")])))
| $i$ | $\\theta_i$ | $d_i$ | $a_i$ | $\\alpha_i$ | joint |
|---|---|---|---|---|---|
| 1 | $\\theta_{1}$ | $0$ | $a_{1}$ | $0$ | R |
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from dhsym.model.kinds import AngleUnit, Convention

from .escape import TeX
from .layout import Math
from .printers import Notation, format_angle

if TYPE_CHECKING:
    from dhsym.model.table import DHTable

__all__ = ["TableCell", "table_latex", "table_markdown", "table_view", "text_table"]


@dataclass(frozen=True)
class TableCell:
    """A cell of the DH table; ``variable`` marks the joint variable's entry."""

    math: Math
    variable: bool = False


_HEADS = {
    Convention.STANDARD: (("theta", r"\theta_i", "theta_i"), ("d", "d_i", "d_i"))
    + (("a", "a_i", "a_i"), ("alpha", r"\alpha_i", "alpha_i")),
    Convention.MODIFIED: (("alpha", r"\alpha_{i-1}", "alpha_{i-1}"), ("a", "a_{i-1}", "a_{i-1}"))
    + (("d", "d_i", "d_i"), ("theta", r"\theta_i", "theta_i")),
}


def table_view(table: DHTable) -> tuple[tuple[Math, ...], tuple[tuple[TableCell, ...], ...]]:
    """The one view of a DH table: the convention's headers and each row's cells.

    Columns ``i``, the four parameters in the convention's order, ``joint``; angles in
    the table's unit; every cell printed as LaTeX and as text. :func:`table_latex`,
    :func:`table_markdown` and the derivations all print this view.

    >>> from dhsym.model.table import DHTable, DHRow
    >>> heads, rows = table_view(DHTable.from_rows([DHRow.revolute("theta1", a="a1")]))
    >>> [h.text for h in heads], [c.math.text for c in rows[0]], rows[0][1].variable
    (['i', 'theta_i', 'd_i', 'a_i', 'alpha_i', 'joint'], ['1', 'theta1', '0', 'a1', '0', 'R'], True)
    """
    t = table  # a DHTable
    deg = t.angles is AngleUnit.DEG
    columns = _HEADS[Convention(t.convention)]
    heads = (
        Math(TeX("i"), "i"),
        *(Math(TeX(latex), text) for _, latex, text in columns),
        Math(TeX(r"\text{joint}"), "joint"),
    )
    plain = Notation()
    rows = []
    for i, row in enumerate(t.rows, start=1):
        cells = [TableCell(Math(TeX(str(i)), str(i)))]
        for name, _, _ in columns:
            value = getattr(row, name)
            if name in ("theta", "alpha"):
                m = Math(TeX(format_angle(value, deg)), format_angle(value, deg, latex=False))
            else:
                m = Math(TeX(plain.latex(value)), plain.text(value))
            cells.append(TableCell(m, row.variable_field == name))
        cells.append(TableCell(Math(TeX(row.joint.value), row.joint.value)))
        rows.append(tuple(cells))
    return heads, tuple(rows)


def table_latex(table: DHTable) -> str:
    r"""The table as a LaTeX ``array``; the joint variable's cell is boxed.

    >>> from dhsym.model.table import DHTable, DHRow
    >>> print(table_latex(DHTable.from_rows([DHRow.revolute("theta1", a="a1")])))
    \begin{array}{cccccc}
    i & \theta_i & d_i & a_i & \alpha_i & \text{joint} \\ \hline
    1 & \boxed{\theta_{1}} & 0 & a_{1} & 0 & R
    \end{array}
    """
    heads, rows = _latex_cells(table, box=True)
    body = " \\\\\n".join(" & ".join(r) for r in rows)
    return (
        "\\begin{array}{"
        + "c" * len(heads)
        + "}\n"
        + " & ".join(heads)
        + " \\\\ \\hline\n"
        + body
        + "\n\\end{array}"
    )


def table_markdown(table: DHTable) -> str:
    """The table as a Markdown pipe table with ``$…$`` math cells.

    >>> from dhsym.model.table import DHTable, DHRow
    >>> print(table_markdown(DHTable.from_rows([DHRow.revolute("theta1", a="a1")])))
    | $i$ | $\\theta_i$ | $d_i$ | $a_i$ | $\\alpha_i$ | joint |
    |---|---|---|---|---|---|
    | 1 | $\\theta_{1}$ | $0$ | $a_{1}$ | $0$ | R |
    """
    heads, rows = _latex_cells(table, box=False)
    head = "| " + " | ".join(f"${h}$" if h != r"\text{joint}" else "joint" for h in heads) + " |"
    sep = "|" + "---|" * len(heads)
    lines = [head, sep]
    for r in rows:
        cells = [r[0]] + [f"${c}$" for c in r[1:-1]] + [r[-1]]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def _latex_cells(table: DHTable, box: bool) -> tuple[list[str], list[list[str]]]:
    """The view in LaTeX: header strings and cell strings (variables boxed if ``box``)."""
    heads, rows = table_view(table)
    return [str(h.latex) for h in heads], [
        [rf"\boxed{{{c.math.latex}}}" if c.variable and box else str(c.math.latex) for c in row]
        for row in rows
    ]


def text_table(heads: Sequence[object], rows: Sequence[Sequence[object]]) -> list[str]:
    """A plain-text table with ``|`` separators, one string per line.

    >>> print("\\n".join(text_table(["i", "theta_i"], [["1", "theta1 - 90°"]])))
    i | theta_i
    --+-------------
    1 | theta1 - 90°
    """
    names = [str(h) for h in heads]
    cells = [[str(c) for c in r] for r in rows]
    widths = [max([len(h), *(len(r[k]) for r in cells)]) for k, h in enumerate(names)]

    def line(row: Sequence[str]) -> str:
        return " | ".join(c.ljust(w) for c, w in zip(row, widths, strict=True)).rstrip()

    return [line(names), "-+-".join("-" * w for w in widths), *map(line, cells)]
