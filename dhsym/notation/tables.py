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

from dhsym.model.kinds import AngleUnit, Convention

from .printers import Notation, format_angle

__all__ = ["table_latex", "table_markdown", "text_table"]


def _table_rows(table: object, latex: bool, box: bool = True) -> tuple[list[str], list[list[str]]]:
    t = table  # a DHTable
    deg = t.angles is AngleUnit.DEG  # type: ignore[attr-defined]
    mod = t.convention is Convention.MODIFIED  # type: ignore[attr-defined]
    if latex:
        heads = (
            ["i", r"\alpha_{i-1}", "a_{i-1}", "d_i", r"\theta_i", r"\text{joint}"]
            if mod
            else ["i", r"\theta_i", "d_i", "a_i", r"\alpha_i", r"\text{joint}"]
        )
    else:
        heads = (
            ["i", "alpha_{i-1}", "a_{i-1}", "d_i", "theta_i", "joint"]
            if mod
            else ["i", "theta_i", "d_i", "a_i", "alpha_i", "joint"]
        )
    order = ["alpha", "a", "d", "theta"] if mod else ["theta", "d", "a", "alpha"]
    rows = []
    for i, row in enumerate(t.rows, start=1):  # type: ignore[attr-defined]
        cells = [str(i)]
        for name in order:
            value = getattr(row, name)
            if name in ("theta", "alpha"):
                cell = format_angle(value, deg, latex)
            else:
                cell = Notation().latex(value) if latex else Notation().text(value)
            if row.variable_field == name and latex and box:
                cell = rf"\boxed{{{cell}}}"
            cells.append(cell)
        cells.append(row.joint.value)
        rows.append(cells)
    return heads, rows


def table_latex(table: object) -> str:
    r"""The table as a LaTeX ``array``; the joint variable's cell is boxed.

    >>> from dhsym.model.table import DHTable, DHRow
    >>> print(table_latex(DHTable.from_rows([DHRow.revolute("theta1", a="a1")])))
    \begin{array}{cccccc}
    i & \theta_i & d_i & a_i & \alpha_i & \text{joint} \\ \hline
    1 & \boxed{\theta_{1}} & 0 & a_{1} & 0 & R
    \end{array}
    """
    heads, rows = _table_rows(table, latex=True)
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


def table_markdown(table: object) -> str:
    """The table as a Markdown pipe table with ``$…$`` math cells.

    >>> from dhsym.model.table import DHTable, DHRow
    >>> print(table_markdown(DHTable.from_rows([DHRow.revolute("theta1", a="a1")])))
    | $i$ | $\\theta_i$ | $d_i$ | $a_i$ | $\\alpha_i$ | joint |
    |---|---|---|---|---|---|
    | 1 | $\\theta_{1}$ | $0$ | $a_{1}$ | $0$ | R |
    """
    heads, rows = _table_rows(table, latex=True, box=False)
    head = "| " + " | ".join(f"${h}$" if h != r"\text{joint}" else "joint" for h in heads) + " |"
    sep = "|" + "---|" * len(heads)
    lines = [head, sep]
    for r in rows:
        cells = [r[0]] + [f"${c}$" for c in r[1:-1]] + [r[-1]]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def text_table(heads: Sequence[object], rows: Sequence[Sequence[object]]) -> list[str]:
    """A plain-text table with ``|`` separators, one string per line.

    >>> print("\\n".join(text_table(["i", "theta_i"], [["1", "theta1 - 90°"]])))
    i | theta_i
    --+-------------
    1 | theta1 - 90°
    """
    heads = [str(h) for h in heads]
    cells = [[str(c) for c in r] for r in rows]
    widths = [max([len(h), *(len(r[k]) for r in cells)]) for k, h in enumerate(heads)]

    def line(row: Sequence[str]) -> str:
        return " | ".join(c.ljust(w) for c, w in zip(row, widths, strict=True)).rstrip()

    return [line(heads), "-+-".join("-" * w for w in widths), *map(line, cells)]
