"""The one view of a DH table, and its LaTeX, Markdown and plain-text prints."""

from __future__ import annotations

import re

from hypothesis import given, settings

from dhsym.model.kinds import Convention
from dhsym.model.library import load_table
from dhsym.model.table import DHRow, DHTable
from dhsym.notation.tables import table_latex, table_markdown, table_view, text_table
from tests.strategies import dh_tables

CRAIG = DHTable.from_rows(
    [
        DHRow.revolute("theta1", alpha=90),
        DHRow.prismatic("d2", a="a1", theta=-90),
        DHRow.fixed(d="d6"),
    ],
    convention="modified",
    angles="deg",
)


def test_standard_view_has_the_lecture_headers_and_marks_the_variables():
    heads, rows = table_view(load_table("puma560"))
    assert [h.text for h in heads] == ["i", "theta_i", "d_i", "a_i", "alpha_i", "joint"]
    assert [str(h.latex) for h in heads][1:5] == [r"\theta_i", "d_i", "a_i", r"\alpha_i"]
    assert len(rows) == 6
    assert [c.math.text for c in rows[2]] == ["3", "theta3", "d3", "a3", "-pi/2", "R"]
    assert [c.variable for c in rows[2]] == [False, True, False, False, False, False]


def test_modified_view_reads_in_craigs_order_with_degrees():
    heads, rows = table_view(CRAIG)
    assert [h.text for h in heads] == ["i", "alpha_{i-1}", "a_{i-1}", "d_i", "theta_i", "joint"]
    assert [[c.math.text for c in r] for r in rows] == [
        ["1", "90°", "0", "0", "theta1", "R"],
        ["2", "0", "a1", "d2", "-90°", "P"],
        ["3", "0", "0", "d6", "0", "F"],
    ]
    # the revolute variable is theta, the prismatic one d, a fixed row has none
    assert [
        [c.variable for c in r].index(True) if any(c.variable for c in r) else None for r in rows
    ] == [
        4,
        3,
        None,
    ]


def test_latex_boxes_the_joint_variables():
    assert table_latex(CRAIG) == (
        "\\begin{array}{cccccc}\n"
        r"i & \alpha_{i-1} & a_{i-1} & d_i & \theta_i & \text{joint} \\ \hline" + "\n"
        r"1 & 90^{\circ} & 0 & 0 & \boxed{\theta_{1}} & R \\" + "\n"
        r"2 & 0 & a_{1} & \boxed{d_{2}} & -90^{\circ} & P \\" + "\n"
        r"3 & 0 & 0 & d_{6} & 0 & F" + "\n"
        r"\end{array}"
    )


def test_markdown_is_a_pipe_table_with_math_cells():
    lines = table_markdown(CRAIG).splitlines()
    assert lines[0] == r"| $i$ | $\alpha_{i-1}$ | $a_{i-1}$ | $d_i$ | $\theta_i$ | joint |"
    assert lines[1] == "|---|---|---|---|---|---|"
    assert lines[3] == r"| 2 | $0$ | $a_{1}$ | $d_{2}$ | $-90^{\circ}$ | P |"
    assert r"\boxed" not in table_markdown(CRAIG)


@settings(max_examples=30, deadline=None)
@given(dh_tables())
def test_every_print_shows_every_row_of_the_one_view(table):
    heads, rows = table_view(table)
    n = len(table.rows)
    assert len(rows) == n and all(len(r) == len(heads) == 6 for r in rows)
    assert [r[0].math.text for r in rows] == [str(k) for k in range(1, n + 1)]
    for row, r in zip(table.rows, rows, strict=True):
        assert sum(c.variable for c in r) == (row.variable is not None)
        assert r[-1].math.text == row.joint.value
    order = (
        ("theta", "d") if Convention(table.convention) is Convention.STANDARD else ("alpha", "a")
    )
    assert [h.text.split("_")[0] for h in heads[1:3]] == list(order)
    md = table_markdown(table).splitlines()
    assert len(md) == n + 2 and all(line.count(" | ") == 5 for line in md[2:])
    latex = table_latex(table)
    assert latex.count(r"\boxed{") == sum(row.variable is not None for row in table.rows)
    assert len(re.findall(r" \\\\", latex)) == n  # the header's and n - 1 rows' line ends


def test_text_table_aligns_columns_and_reads_any_cell():
    assert text_table(["a", "bb"], [["xxx", "é"], [1, None]]) == [
        "a   | bb",
        "----+-----",
        "xxx | é",
        "1   | None",
    ]
    assert text_table(["i", "theta_i"], []) == ["i | theta_i", "--+--------"]


def test_text_table_strips_trailing_blanks():
    lines = text_table(["x", "y"], [["long value", ""]])
    assert lines[2] == "long value |"
    assert all(line == line.rstrip() for line in lines)
