"""Tables as students write them: YAML lists of rows, no ``type``, degrees as plain integers."""

from __future__ import annotations

import pytest

from dhsym.checking import Key, check_answer
from dhsym.checking.comparing.verdict import Verdict

PUMA_ROWS = [
    "- {theta: theta1, d: 0, a: 0, alpha: 90}",
    "- {theta: theta2, d: 0, a: a2, alpha: 0}",
    "- {theta: theta3, d: d3, a: a3, alpha: -90}",
    "- {theta: theta4, d: d4, a: 0, alpha: 90}",
    "- {theta: theta5, d: 0, a: 0, alpha: -90}",
    "- {theta: theta6, d: 0, a: 0, alpha: 0}",
]


@pytest.fixture(scope="module")
def puma_table() -> Key:
    return Key.load("puma560", "table")


def test_a_plain_yaml_list_in_degrees_is_right(puma_table):
    r = check_answer(puma_table, "\n".join(PUMA_ROWS) + "\n")
    assert r.verdict is Verdict.CORRECT, r.message
    assert "read as degrees" in r.message


def test_joints_without_type_and_with_degree_marks_is_right(puma_table):
    rows = [row.replace("90", "90°") for row in PUMA_ROWS]
    text = "joints:\n" + "".join(f"  {row}\n" for row in rows)
    r = check_answer(puma_table, text)
    assert r.verdict is Verdict.CORRECT, r.message


def test_the_file_may_say_degrees_and_rows_may_be_block_mappings(puma_table):
    block = "angles: deg\njoints:\n"
    for row in PUMA_ROWS:
        cells = row.strip("- {}").split(", ")
        block += "  - " + "\n    ".join(c.replace(": ", ": ", 1) for c in cells) + "\n"
    r = check_answer(puma_table, block)
    assert r.verdict is Verdict.CORRECT, r.message


def test_a_wrong_yaml_list_is_diagnosed_not_refused(puma_table):
    rows = list(PUMA_ROWS)
    rows[2] = "- {theta: theta3, d: d3, a: a3, alpha: 90}"
    r = check_answer(puma_table, "\n".join(rows))
    assert r.verdict is Verdict.INCORRECT, r.message


def test_radians_stay_radians(puma_table):
    rows = [row.replace("-90", "-pi/2").replace("alpha: 90", "alpha: pi/2") for row in PUMA_ROWS]
    r = check_answer(puma_table, "\n".join(rows))
    assert r.verdict is Verdict.CORRECT, r.message
    assert "degrees" not in r.message


def test_prismatic_type_is_inferred_from_d():
    key = Key.load("stanford", "table")
    rows = [[str(c) for c in (row.theta, row.d, row.a, row.alpha)] for row in key.table.rows]
    text = "\n".join(
        f"- {{theta: '{t}', d: '{d}', a: '{a}', alpha: '{al}'}}" for t, d, a, al in rows
    )
    r = check_answer(key, text)
    assert r.verdict is Verdict.CORRECT, r.message


@pytest.mark.parametrize("text", ["just some words\n", "joints: 3\n", "- 1\n- 2\n"])
def test_an_unreadable_table_says_what_form_is_expected(puma_table, text):
    r = check_answer(puma_table, text)
    assert r.verdict is Verdict.UNREADABLE
    assert "- {theta: theta1, d: d1, a: 0, alpha: 90}" in r.message, r.message


def test_a_table_file_may_leave_out_the_joint_type():
    from dhsym.model.tablefile import read_table_text

    t = read_table_text(
        "joints:\n"
        "  - {theta: theta1, d: 0, a: a1, alpha: 0}\n"
        "  - {theta: 0, d: d2, a: 0, alpha: 0}\n"
    )
    assert [r.joint.value for r in t.rows] == ["R", "P"]


@pytest.mark.parametrize(
    "text",
    [
        "Link\tai\tαi\tdi\tθi\n1\t0\t90\t0\tθ1*\n2\ta2\t0\t0\tθ2*\n3\ta3\t-90\td3\tθ3*\n"
        "4\t0\t90\td4\tθ4*\n5\t0\t-90\t0\tθ5*\n6\t0\t0\t0\tθ6*\n",
        "| i | a | alpha | d | theta |\n|---|---|---|---|---|\n"
        + "".join(
            f"| {i} | {a} | {al} | {d} | $\\theta_{i}^{{*}}$ |\n"
            for i, (a, al, d) in enumerate(
                [(0, 90, 0), ("a2", 0, 0), ("a3", -90, "d3"), (0, 90, "d4"), (0, -90, 0)]
                + [(0, 0, 0)],
                1,
            )
        ),
    ],
)
def test_the_star_on_a_joint_variable_is_a_mark_not_a_value(puma_table, text):
    """Spong's tables mark the joint variable with a star (θ1*, \\theta_1^*)."""
    r = check_answer(puma_table, text)
    assert r.verdict is Verdict.CORRECT, r.message


def test_a_star_that_is_not_at_the_end_is_still_refused(puma_table):
    text = "a,alpha,d,theta\n0,90,0,theta1*2\n" + "a2,0,0,theta2\n" * 5
    assert check_answer(puma_table, text).verdict is not Verdict.CORRECT


PUMA_TABULAR_ROWS = [(0, 90, 0), ("a_2", 0, 0), ("a_3", -90, "d_3"), (0, 90, "d_4")]
PUMA_TABULAR_ROWS += [(0, -90, 0), (0, 0, 0)]


def _tabular(rows, rule=r"\hline", env="tabular", spec="{c|c|c|c|c}"):
    body = "".join(
        f"{i} & ${a}$ & ${al}^\\circ$ & ${d}$ & $\\theta_{i}^*$ \\\\\n"
        for i, (a, al, d) in enumerate(rows, 1)
    )
    head = r"Link & $a_i$ & $\alpha_i$ & $d_i$ & $\theta_i$ \\"
    return f"\\begin{{{env}}}{spec}\n{head} {rule}\n{body}\\end{{{env}}}"


@pytest.mark.parametrize(
    "text",
    [
        _tabular(PUMA_TABULAR_ROWS),
        _tabular(PUMA_TABULAR_ROWS, rule=r"\midrule", spec="{ccccc}"),  # booktabs
        "$$" + _tabular(PUMA_TABULAR_ROWS, env="array") + "$$",
    ],
)
def test_a_latex_tabular_is_read_as_the_table(puma_table, text):
    """A table pasted from a LaTeX write-up: tabular or array, rules, $…$ cells."""
    r = check_answer(puma_table, text)
    assert r.verdict is Verdict.CORRECT, r.message


def test_a_wrong_latex_tabular_is_diagnosed_and_a_bad_cell_named_by_row(puma_table):
    wrong = list(PUMA_TABULAR_ROWS)
    wrong[2] = ("a_3", 90, "d_3")  # the sign of alpha3
    r = check_answer(puma_table, _tabular(wrong))
    assert r.verdict is Verdict.INCORRECT, r.message
    bad = list(PUMA_TABULAR_ROWS)
    bad[3] = (0, 90, "d_4 +")
    r = check_answer(puma_table, _tabular(bad))
    assert r.verdict is Verdict.UNREADABLE
    assert "row 4" in r.message, r.message
