"""The Jacobian and singularity derivations: the core's data, printed in each format."""

from __future__ import annotations

import pytest
import sympy as sp

import dhsym
from dhsym.explain.velocity_kinematics import derive_jacobian, derive_singularities
from dhsym.kinematics.jacobian import geometric_jacobian
from dhsym.kinematics.singularities import singularities

ROBOTS = ["planar2r", "scara", "stanford", "puma560", "puma560_modified", "cylindrical"]


@pytest.mark.parametrize("name", ROBOTS)
def test_columns_are_the_cores_columns_printed_in_lecture_notation(name):
    robot = dhsym.load(name)
    d = derive_jacobian(robot)
    J = geometric_jacobian(robot)
    nota = robot.notation
    assert [c.index for c in d.columns] == list(range(1, len(J.columns) + 1))
    for data, col in zip(d.columns, J.columns, strict=True):
        assert data.revolute == (col.joint.value == "R")
        assert [r[0].text for r in data.axis.rows] == [nota.text(x) for x in col.axis]
        shown = [r[0].text for r in data.column.rows]
        assert shown == [nota.text(x) for x in (*col.linear, *col.angular)]
        if data.revolute:
            assert [r[0].text for r in data.lever.rows] == [nota.text(x) for x in col.lever]
        else:
            assert data.lever is None
    assert [[m.text for m in row] for row in d.result.rows] == [
        [nota.text(J.matrix[i, j]) for j in range(J.matrix.cols)] for i in range(6)
    ]


def test_axis_frames_follow_the_convention():
    standard = derive_jacobian("puma560")
    modified = derive_jacobian("puma560_modified")
    assert [c.axis_label.text for c in standard.columns] == [f"z_{k}" for k in range(6)]
    assert [c.axis_label.text for c in modified.columns] == [f"z_{k}" for k in range(1, 7)]
    assert standard.columns[1].origin_label.latex == "o_{1}"
    assert standard.point.latex == "o_{6}"
    text = modified.to_text()
    assert "J_i = [z_i x (o_6 - o_i); z_i]" in " ".join(text.split())


def test_the_2r_jacobian_in_every_format():
    d = derive_jacobian("planar2r")
    text = d.to_text()
    assert "J1 = [z_0 x (o_2 - o_0); z_0] = [-a1*S1 - a2*S12; a1*C1 + a2*C12; 0; 0; 0; 1]" in text
    assert "o_2 - o_1 = [a2*C12; a2*S12; 0]" in text
    md = d.to_markdown()
    assert r"J_{2} = \begin{bmatrix} z_{1} \times (o_{2} - o_{1}) \\ z_{1} \end{bmatrix}" in md
    assert r"-a_{1} S_{1} - a_{2} S_{12} & -a_{2} S_{12} \\" in md
    tex = d.to_latex()
    assert r"\subsection*{The Jacobian, column by column}" in tex
    assert r"-a_{1} S_{1} - a_{2} S_{12} & -a_{2} S_{12} \\" in tex
    assert tex.isascii()


def test_every_column_of_the_text_layout_reads_as_a_column():
    # a short column on one line is written [a; b; c] (rows separated by ";"), the way
    # the column formulas J_i = [z x (o - o_i); z] are written, never as a row (a, b, c)
    text = derive_jacobian("puma560").to_text()
    assert "   z_0 = [0; 0; 1]\n" in text
    assert "   J4 = [z_3 x (o_6 - o_3); z_3] = [0; 0; 0; -C1*S23; -S1*S23; C23]\n" in text
    assert "o_6 - o_4 = [0; 0; 0]" in text
    for line in text.splitlines():
        head, _, rest = line.partition(" = ")
        if head.strip().startswith(("z_", "o_", "J")) and rest.startswith("("):
            raise AssertionError(f"a column printed as a row: {line!r}")


def test_a_prismatic_column_is_its_axis_over_zero():
    d = derive_jacobian("stanford")
    col = d.columns[2]
    assert not col.revolute and col.variable.text == "d3"
    assert "J3 = [z_2; 0] = [C1*S2; S1*S2; C2; 0; 0; 0]" in d.to_text()


def test_a_wide_jacobian_refers_to_its_columns():
    d = derive_jacobian("puma560")
    assert d.result.wide
    assert "J = [J1 J2 J3 J4 J5 J6]" in d.to_text()
    assert r"J = \begin{bmatrix} J_{1} & J_{2} & J_{3} & J_{4} & J_{5} & J_{6} \end{bmatrix}" in (
        d.to_latex()
    )


def test_jacobian_in_the_tool_frame():
    d = derive_jacobian("planar2r", frame="tool")
    assert d.frame.text == "2"
    assert d.result.label.latex == "{}^{2}J"
    assert [r[0].text for r in d.columns[0].column.rows][:2] == ["a1*S2", "a1*C2 + a2"]


def test_puma_singularities_are_factored_and_named():
    robot = dhsym.load("puma560")
    s = derive_singularities(robot)
    core = singularities(robot)
    assert s.method == "blocks" and s.point == "wrist centre"
    assert s.determinant.text_lines == (robot.notation.text(core.determinant),)
    assert [b.label.text for b in s.blocks] == ["J11", "J22"]
    assert s.blocks[0].matrix is None  # too wide for a line: only its determinant is shown
    kinds = {f.kind: f for f in s.factors}
    assert kinds["wrist"].factor.text == "S5"
    assert [z.text for z in kinds["wrist"].zeros] == ["theta5 = 0", "theta5 = pi"]
    assert kinds["elbow"].factor.text == "a3*S3 + d4*C3"
    assert kinds["shoulder"].factor.text == "a2*C2 + a3*C23 - d4*S23"
    text = s.to_text()
    assert "det J = a2*S5*(a2*C2 + a3*C23 - d4*S23)*(a3*S3 + d4*C3)" in text
    assert "wrist singularity: S5 = 0, at theta5 = 0 or theta5 = pi" in " ".join(text.split())
    tex = s.to_latex()
    assert r"\det J_{22} &= -S_{5}" in tex
    assert r"\item \textbf{wrist singularity}: $S_{5} = 0$" in tex
    assert tex.isascii()


@pytest.mark.parametrize(
    ("name", "method", "measure"),
    [
        ("planar2r", "position", "det J_v"),
        ("scara", "rows", "det J"),
        ("planar4r", "manipulability", "det(J J^T)"),
        ("stanford", "blocks", "det J"),
        ("ur5", "whole", "det J"),
    ],
)
def test_each_method_has_its_words_in_every_format(name, method, measure):
    s = derive_singularities(name)
    assert (s.method, s.measure.text) == (method, measure)
    assert f"{measure} = {s.determinant.text_lines[0]}" in s.to_text()
    for out in (s.to_markdown(), s.to_latex()):
        assert f"{s.measure.latex} &= {s.determinant.latex_lines[0]}" in out
    if method == "manipulability":
        assert "Cauchy" in s.to_text() and s.factors == ()


def test_an_arm_without_a_spherical_wrist_is_written_at_its_wrist_point():
    s = derive_singularities("ur5")
    assert (s.method, s.point) == ("whole", "wrist point")
    text = s.to_text()
    assert "take the whole J at the\n   wrist point" in text and "   In frame 4:" in text
    assert "det J = a2*a3*S3*S5*(a2*C2 + a3*C23 + d5*S234)" in text
    assert "wrist singularity: S5 = 0, at theta5 = 0 or theta5 = pi. The axes of joints 4" in text
    tex = s.to_latex()
    assert "In frame 4," in tex and r"\item \textbf{wrist singularity}: $S_{5} = 0$" in tex
    assert tex.isascii()
    assert "In frame 4:" in s.to_markdown()


def test_zeros_of_a_factor_are_where_it_vanishes():
    robot = dhsym.load("puma560")
    s = singularities(robot)
    for f in s.factors:
        for var, value in f.solutions:
            assert sp.simplify(f.expr.subs(var, value)) == 0


def test_hostile_robot_name_is_escaped_in_the_new_documents():
    table = dhsym.DHTable.from_rows(
        [dhsym.DHRow.revolute("theta1", a="a1"), dhsym.DHRow.revolute("theta2", a="a2")],
        name=r"\input{/etc/passwd} $x$",
    )
    robot = dhsym.Robot(table)
    for d in (derive_jacobian(robot), derive_singularities(robot)):
        assert r"\input{/etc" not in d.to_latex()
        assert r"\$x\$" in d.to_markdown()
