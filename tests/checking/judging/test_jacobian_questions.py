"""Questions J, J[r,c] and det J: right answers in any valid form, each mistake named."""

from __future__ import annotations

import pytest
import sympy as sp

import dhsym
from dhsym.checking.mistakes._jacobian_mistakes import next_axis_jacobian
from dhsym.kinematics.jacobian import geometric_jacobian
from dhsym.kinematics.singularities import singularities

from .._keys import KEYS, check_answer, load_key  # each key prepared once, as a grading worker does


def _matrix(M: sp.MatrixBase, nota) -> str:
    rows = [", ".join(nota.text(x) for x in M.row(i)) for i in range(M.rows)]
    return "[" + ", ".join(f"[{r}]" for r in rows) + "]"


def _full(M: sp.MatrixBase) -> str:
    """Expanded cos/sin, as a student who multiplied everything out writes it."""
    rows = [
        ", ".join(sp.sstr(sp.expand(sp.expand_trig(x))) for x in M.row(i)) for i in range(M.rows)
    ]
    return "[" + ", ".join(f"[{r}]" for r in rows) + "]"


@pytest.mark.parametrize("name", ["planar2r", "stanford", "puma560", "puma560_modified"])
def test_the_key_in_lecture_notation_and_expanded_is_right(name):
    robot = dhsym.load(name)
    J = robot.jacobian().matrix
    key = load_key(name, "J")
    r = check_answer(key, _matrix(J, robot.notation))
    assert r.correct, r.message
    assert r.message == f"All {J.rows * J.cols} entries are right."
    if name in ("planar2r", "stanford"):
        assert check_answer(key, _full(J)).correct


def test_the_2r_jacobian_in_latex_with_identities():
    key = load_key("planar2r", "J")
    answer = (
        r"\begin{bmatrix} -a_1 \sin\theta_1 - a_2 \sin(\theta_1 + \theta_2) & -a_2 S_{12} \\"
        r" a_1 c_1 + a_2 (c_1 c_2 - s_1 s_2) & a_2 C_{12} \\ 0 & 0 \\ 0 & 0 \\ 0 & 0 \\"
        r" 1 & 1 \end{bmatrix}"
    )
    assert check_answer(key, answer).correct


def test_a_planar_arms_j_in_its_plane():
    """The rows zero in every configuration may be left out: the 2R's [v_x; v_y; ω_z]
    (the rows it has) is its J; without ω_z (Craig's 2×2) it is not, and the reader says
    which shapes it takes."""
    key = load_key("planar2r", "J")
    v = "[-a1 S1 - a2 S12, -a2 S12], [a1 C1 + a2 C12, a2 C12]"
    assert check_answer(key, f"[{v}, [1, 1]]").correct
    r = check_answer(key, f"[{v}, [1, 0]]")
    assert not r.correct and "(6,2)" in r.message  # entries named as in the whole J
    r = check_answer(key, f"[{v}]")
    assert r.verdict.value == "unreadable" and "6×2 or 3×2" in r.message
    assert KEYS.get(key).form().rows == (0, 1, 5)
    assert KEYS.get(load_key("puma560", "J")).form().rows == ()  # every row moves


@pytest.mark.parametrize("name", ["planar2r", "stanford", "puma560"])
def test_j_written_as_its_blocks_jv_and_jw(name):
    """Spong writes J = [J_v; J_ω]: the two blocks, labelled, in either order, plain or in
    a LaTeX align, are the whole J; a wrong entry is named as in J."""
    robot = dhsym.load(name)
    J = robot.jacobian().matrix
    key = load_key(name, "J")
    jv, jw = _matrix(J[:3, :], robot.notation), _matrix(J[3:, :], robot.notation)
    for text in (
        f"Jv = {jv}\nJw = {jw}",
        f"J_\\omega = {jw}\nJ_v(q) = {jv}",
        f"Jv = {jv}\nJω = {jw}",
    ):
        r = check_answer(key, text)
        assert r.correct, (text, r.message)
    n = J.cols
    wrong = sp.Matrix(J[3:, :])
    wrong[2, n - 1] = -wrong[2, n - 1] if wrong[2, n - 1] != 0 else 1
    r = check_answer(key, f"Jv = {jv}\nJw = {_matrix(wrong, robot.notation)}")
    assert not r.correct and f"(6,{n})" in r.message, r.message


def test_j_blocks_in_latex_and_blocks_missing_or_twice():
    key = load_key("planar2r", "J")
    latex = (
        "\\begin{align}\nJ_v &= \\begin{bmatrix} -a_1 s_1 - a_2 s_{12} & -a_2 s_{12} \\\\"
        " a_1 c_1 + a_2 c_{12} & a_2 c_{12} \\\\ 0 & 0 \\end{bmatrix} \\\\\n"
        "J_\\omega &= \\begin{bmatrix} 0 & 0 \\\\ 0 & 0 \\\\ 1 & 1 \\end{bmatrix}\n\\end{align}"
    )
    assert check_answer(key, latex).correct
    jv = "[-a1 S1 - a2 S12, -a2 S12; a1 C1 + a2 C12, a2 C12; 0, 0]"
    for text in (f"Jv = {jv}", f"Jv = {jv}\nJv = {jv}"):  # was read as [v_x; v_y; ω_z]
        r = check_answer(key, text)
        assert r.verdict.value == "unreadable" and "J_v = … and J_ω = …" in r.message
    # a Cartesian arm's J is its linear part: J_v alone is all of it
    cart = dhsym.load("cartesian")
    jv = _matrix(cart.jacobian().matrix[:3, :], cart.notation)
    assert check_answer(load_key("cartesian", "J"), f"J_v = {jv}").correct


def test_an_entry_of_j():
    key = load_key("puma560", "J[2,1]")  # row 3, column 2: a2 C2 + a3 C23 - d4 S23
    assert check_answer(key, "a2*C2 + a3*C23 - d4*S23").correct
    assert check_answer(key, "a2 cos(theta2) + a3 cos(theta2 + theta3) - d4 sin(q2 + q3)").correct
    wrong = check_answer(key, "a2*C2 + a3*C23 + d4*S23")
    assert not wrong.correct and "wrong_sign" in wrong.kinds


@pytest.mark.parametrize("name", ["planar2r", "puma560", "stanford"])
def test_the_tool_frame_is_named(name):
    robot = dhsym.load(name)
    r = check_answer(
        load_key(name, "J"), _matrix(geometric_jacobian(robot, frame="tool").matrix, robot.notation)
    )
    assert not r.correct and r.kinds[0] == "tool_frame", r.message
    assert "tool frame" in r.message


@pytest.mark.parametrize("name", ["planar2r", "puma560", "puma560_modified", "stanford"])
def test_the_axis_of_the_other_convention_is_named(name):
    robot = dhsym.load(name)
    r = check_answer(load_key(name, "J"), _matrix(next_axis_jacobian(robot), robot.notation))
    assert not r.correct and r.kinds[0] == "next_axis", r.message
    expected = "z_i and o_i" if robot.convention.value == "standard" else "z_(i-1) and o_(i-1)"
    assert expected in r.message


def test_a_missing_prismatic_column_is_named():
    robot = dhsym.load("stanford")
    J = robot.jacobian().matrix
    short = J[:, [0, 1, 3, 4, 5]]
    r = check_answer(load_key("stanford", "J"), _matrix(short, robot.notation))
    assert not r.correct and r.kinds[0] == "missing_column"
    assert "column 3 belongs to the prismatic joint d3" in r.message
    zero = sp.Matrix(J).as_mutable()
    zero[:, 2] = sp.zeros(6, 1)
    r = check_answer(load_key("stanford", "J"), _matrix(zero, robot.notation))
    assert r.kinds[0] == "prismatic_column"


def test_a_prismatic_column_built_like_a_revolute_one_is_named():
    robot = dhsym.load("scara")
    J = sp.Matrix(robot.jacobian().matrix)
    z = sp.Matrix([0, 0, -1])
    lever = robot.transform(0, 4).matrix[:3, 3] - robot.transform(0, 2).matrix[:3, 3]
    J[:, 2] = sp.Matrix.vstack(z.cross(lever), z)
    r = check_answer(load_key("scara", "J"), _matrix(J, robot.notation))
    assert not r.correct and "prismatic_column" in r.kinds, r.message


@pytest.mark.parametrize("name", ["planar2r", "puma560", "stanford", "scara"])
def test_det_j_right_in_any_sign_and_form(name):
    robot = dhsym.load(name)
    det = singularities(robot).determinant
    key = load_key(name, "det J")
    assert check_answer(key, robot.notation.text(det)).correct
    flipped = check_answer(key, robot.notation.text(-det))
    assert flipped.correct and "up to its sign" in flipped.message
    assert check_answer(key, sp.sstr(sp.expand(sp.expand_trig(det)))).correct


def test_det_j_of_the_puma_with_a_missing_factor_or_one_block():
    robot = dhsym.load("puma560")
    s = singularities(robot)
    key = load_key("puma560", "det J")
    r = check_answer(key, "a2*(a2*C2 + a3*C23 - d4*S23)*(a3*S3 + d4*C3)")  # S5 left out
    assert not r.correct and r.kinds[0] == "block_determinant"  # that is det J11 (up to sign)
    r = check_answer(key, "a2*S5*(a3*S3 + d4*C3)")  # the shoulder factor left out
    assert r.kinds[0] == "missing_factor" and "a2*C2 + a3*C23 - d4*S23" in r.message
    r = check_answer(key, robot.notation.text(s.determinant / sp.Symbol("a2", real=True)))
    assert r.kinds[0] == "missing_factor" and "The factor a2" in r.message


def test_question_labels_and_bad_questions():
    assert load_key("planar2r", "J[1,0]").question.label == "J[1,0]"
    with pytest.raises(dhsym.DHError, match="the rows of J are 0"):
        load_key("planar2r", "J[6,0]")
    with pytest.raises(dhsym.DHError, match="the columns of J are 0 … 1"):  # the key's fault
        load_key("planar2r", "J[0,5]")


def test_a_wrong_shape_is_unreadable():
    r = check_answer(load_key("planar2r", "J"), "[[1, 0], [0, 1]]")
    assert r.verdict.value == "unreadable" and "a 6×2 or 3×2 matrix" in r.message
