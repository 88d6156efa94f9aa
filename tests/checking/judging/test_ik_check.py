"""Question ik: any valid branch is right (named), in any form; each classic mistake is named."""

from __future__ import annotations

import numpy as np
import pytest

import dhsym
from dhsym.checking import Key
from dhsym.checking.reading.answer_value import read_answer_value
from dhsym.ik.steps import BRANCH_NAMES

from .._keys import check_answer, load_key  # each key prepared once, as a grading worker does

D = "((p_x^2 + p_y^2 - a1^2 - a2^2)/(2*a1*a2))"
THETA1 = "theta1 = atan2(p_y, p_x) - atan2(a2*S2, a1 + a2*C2)"


def _key_answer(name: str, signs: dict[int, int], notation: str = "C1") -> str:
    """The derivation's own steps, one branch, as a student would copy them."""
    robot = dhsym.load(name, style=notation)
    ik = robot.inverse()
    sub = {b.symbol: signs.get(b.joint, 1) for b in ik.branches}
    return "\n".join(f"{st.lhs} = {robot.notation.text(st.rhs.xreplace(sub))}" for st in ik.steps)


@pytest.mark.parametrize("name", ["planar2r", "scara", "stanford", "puma560", "puma560_modified"])
def test_every_branch_of_the_derivation_is_right_and_named(name):
    ik = dhsym.load(name).inverse()
    key = load_key(name, "ik")
    for choice in ({}, {b.joint: -1 for b in ik.branches}):
        r = check_answer(key, _key_answer(name, choice))
        assert r.correct, r.message
        assert "sigma" not in r.message  # branches in words (issue 24: no internal symbols)
        # the branch names of the IK results (issue 24: one vocabulary), never "+ root"
        for b in ik.branches:
            if b.role in BRANCH_NAMES:
                assert any(w in r.message for w in BRANCH_NAMES[b.role]), r.message
        assert "root (θ" not in r.message, r.message


def test_the_2r_in_other_valid_forms():
    key = load_key("planar2r", "ik")
    forms = [
        f"theta2 = acos({D})\n{THETA1}",
        f"c2 = {D}; s2 = -sqrt(1 - c2^2); theta2 = atan2(s2, c2); "
        "theta1 = atan2(p_y*(a1 + a2*c2) - p_x*a2*s2, p_x*(a1 + a2*c2) + p_y*a2*s2)",
        r"\theta_2 = \arccos\left(\frac{p_x^2 + p_y^2 - a_1^2 - a_2^2}{2 a_1 a_2}\right) \\"
        r" \theta_1 = \operatorname{atan2}(p_y, p_x)"
        r" - \operatorname{atan2}(a_2 S_2, a_1 + a_2 C_2)",
        f"θ₂ = −acos({D}), θ₁ = atan2(py, px) − atan2(a2 sin θ₂, a1 + a2 cos θ₂)",
        # a half-angle form: tan(theta2/2) = ±sqrt((1 - c2)/(1 + c2))
        f"theta2 = 2*atan(sqrt((1 - {D})/(1 + {D})))\n{THETA1}",
    ]
    for form in forms:
        r = check_answer(key, form)
        assert r.correct, (form, r.message)
    assert "the branch elbow up." in check_answer(key, forms[1]).message  # s2 < 0


def test_spongs_x_and_y_are_the_position():
    """Spong writes the planar arm's target as (x, y): D = (x² + y² − a1² − a2²)/(2 a1 a2)."""
    spong = (
        "D = (x^2 + y^2 - a1^2 - a2^2)/(2 a1 a2)\ntheta2 = atan2(sqrt(1 - D^2), D)\n"
        "theta1 = atan2(y, x) - atan2(a2 sin(theta2), a1 + a2 cos(theta2))"
    )
    assert check_answer(load_key("planar2r", "ik"), spong).correct
    r = check_answer(load_key("planar2r", "ik"), spong.replace("atan2(y, x)", "atan2(x, y)"))
    assert not r.correct
    # a helper the answer defines wins over the position: x here is not p_x
    assert not check_answer(load_key("planar2r", "ik"), "x = 0\n" + spong).correct


def test_numbers_for_the_lengths_use_the_tables_values():
    key = load_key("planar2r", "ik")
    answer = (
        "theta2 = acos((p_x^2 + p_y^2 - 1.64)/1.6)\n"
        "theta1 = atan2(p_y, p_x) - atan2(0.8*S2, 1 + 0.8*C2)"
    )
    assert check_answer(key, answer).correct


def test_atan_for_atan2_is_named():
    key = load_key("planar2r", "ik")
    r = check_answer(key, f"theta2 = acos({D})\ntheta1 = atan(p_y/p_x) - atan2(a2*S2, a1 + a2*C2)")
    assert not r.correct and r.kinds == ("atan_for_atan2",)
    assert "atan(p_y/p_x) for atan2(p_y, p_x)" in r.message
    # the student's own formula with an atan, not the key's with one atan2 swapped
    y, x = "p_y*(a1 + a2*C2) - p_x*a2*S2", "p_x*(a1 + a2*C2) + p_y*a2*S2"
    own = f"theta2 = acos({D})\ntheta1 = atan(({y})/({x}))"
    r = check_answer(key, own)
    assert r.kinds == ("atan_for_atan2",) and "theta1 is 180° off" in r.message


def test_atan_in_the_puma_waist_is_named():
    answer = _key_answer("puma560", {}).replace("atan2(c_y, c_x)", "atan(c_y/c_x)")
    r = check_answer(load_key("puma560", "ik"), answer)
    assert r.kinds[0] == "atan_for_atan2"


def test_a_wrong_sign_under_the_root_is_named():
    key = load_key("planar2r", "ik")
    r = check_answer(key, f"theta2 = atan2(sqrt({D}^2 - 1), {D})\n{THETA1}")
    assert not r.correct and r.kinds == ("wrong_root_sign",)
    answer = _key_answer("puma560", {}).replace("- d3**2)", "+ d3**2)")
    assert "+ d3**2" in answer
    r = check_answer(load_key("puma560", "ik"), answer)
    assert r.kinds[0] == "wrong_root_sign" and "c_x**2 + c_y**2 + d3**2" in r.message


def test_every_branch_with_plus_minus():
    key = load_key("planar2r", "ik all")
    both = f"theta2 = atan2(±sqrt(1 - {D}^2), {D})\n{THETA1}"
    r = check_answer(key, both)
    assert r.correct and "every solution" in r.message
    assert check_answer(key, both.replace("±", r"+/-")).correct
    latex = (
        r"\theta_2 = \operatorname{atan2}\left(\pm\sqrt{1 - D^2}, D\right),"
        r" D = \frac{p_x^2 + p_y^2 - a_1^2 - a_2^2}{2 a_1 a_2} \\"
        r" \theta_1 = \operatorname{atan2}(p_y, p_x) - \operatorname{atan2}(a_2 S_2, a_1 + a_2 C_2)"
    )
    assert check_answer(key, latex).correct


def test_a_lost_branch_is_named():
    key = load_key("planar2r", "ik all")
    r = check_answer(key, f"theta2 = acos({D})\n{THETA1}")
    assert not r.correct and r.kinds == ("lost_branch",)
    assert "only the elbow down branch (θ2)" in r.message and "1 of the 2 solutions" in r.message
    puma = _key_answer("puma560", {}).replace("r = sqrt", "r = ±sqrt")  # the wrist flip lost
    r = check_answer(
        load_key("puma560", "ik all"), puma.replace("theta3 = atan2(sqrt", "theta3 = atan2(±sqrt")
    )
    assert r.kinds == ("lost_branch",) and "only the wrist not flipped branch (θ5)" in r.message
    assert "4 of the 8 solutions" in r.message


def test_one_branch_questions_accept_one_branch():
    key = load_key("puma560", "ik")
    assert check_answer(key, _key_answer("puma560", {1: -1, 5: -1})).correct


@pytest.mark.parametrize("q", [[0.3, 0.9], [2.5, -0.6], [-2.0, 1.2]])
def test_numbers_for_a_given_pose(q):
    robot = dhsym.load("planar2r")
    spec = "ik@" + ",".join(map(str, q))
    sols = robot.ik(robot.fk(q)[:3, 3])
    for name, row in zip(sols.branches, sols.q):
        r = check_answer(load_key("planar2r", spec), ", ".join(f"{x:.4f}" for x in row))
        assert r.correct and name in r.message, r.message
        degrees = ", ".join(f"{np.degrees(x):.2f}°" for x in row)
        assert check_answer(load_key("planar2r", spec), degrees).correct
    everything = "\n".join(", ".join(f"{x:.5f}" for x in row) for row in sols.q)
    assert check_answer(load_key("planar2r", "ik all@" + spec[3:]), everything).correct
    lost = check_answer(load_key("planar2r", "ik all@" + spec[3:]), everything.splitlines()[0])
    assert lost.kinds == ("lost_branch",)


def test_numbers_with_atan_or_too_few_digits():
    robot = dhsym.load("planar2r")
    q = [2.5, 0.6]  # behind the arm: p_x < 0
    px, py = robot.fk(q)[:2, 3]
    gamma = np.arctan2(0.8 * np.sin(0.6), 1 + 0.8 * np.cos(0.6))
    wrong = np.arctan(py / px) - gamma
    key = load_key("planar2r", "ik@2.5,0.6")
    r = check_answer(key, f"theta1 = {wrong:.5f}, theta2 = 0.6")
    assert r.kinds == ("atan_for_atan2",)
    assert not check_answer(key, "2.4, 0.6").correct  # 2 significant digits: not close enough
    assert check_answer(key, "2.500, 0.6000").correct


def test_the_puma_numbers_all_eight():
    robot = dhsym.load("puma560")
    q = [0.3, -0.5, 0.4, 0.2, 0.7, -1.1]
    sols = robot.ik(robot.fk(q))
    spec = "ik all@" + ",".join(map(str, q))
    text = "\n".join(", ".join(f"{x:.6f}" for x in row) for row in sols.q)
    assert check_answer(load_key("puma560", spec), text).correct
    r = check_answer(load_key("puma560", spec), "\n".join(text.splitlines()[:6]))
    assert r.kinds == ("lost_branch",) and "6 of the 8 solutions" in r.message


def test_unreadable_and_incomplete_answers():
    key = load_key("planar2r", "ik")
    assert check_answer(key, "theta1 = atan2(p_y, p_x)").kinds == ("missing_joint",)
    r = check_answer(key, "theta1 = atan2(p_y, p_x); theta2 = banana")
    assert r.kinds == ("unknown_symbol",) and "banana" in r.message
    for bad in ("__import__('os').system('ls')", "a1 = 3", "theta1 = eval(1)", "1, 2, 3"):
        assert check_answer(key, bad).verdict.value == "unreadable", bad
    r = check_answer(key, "theta1 = ±±±±±±±0")
    assert r.verdict.value == "unreadable" and "more than 6 signs" in r.message
    with pytest.raises(dhsym.DHError, match="no closed-form"):  # the key's fault, not the answer's
        load_key("planar4r", "ik")


def test_reading_statements_and_helpers():
    from dhsym.checking.judging.key import prepare
    from dhsym.checking.reading.limits import DEFAULT_ANSWER_LIMITS

    pk = prepare(Key.load("planar2r", "ik"))
    ans = read_answer_value(
        pk.form(), "c2 = D; D = 0.5\ntheta2 = acos(c2), theta1 = 1", DEFAULT_ANSWER_LIMITS
    )
    assert [h.target.name for h in ans.helpers] == ["c2", "D"]
    assert sorted(ans.solutions[0]) == [0, 1]
    ans = read_answer_value(pk.form(), "0.1, 0.2\n0.3, 0.4", DEFAULT_ANSWER_LIMITS)
    assert len(ans.solutions) == 2


def test_feedback_renders_an_ik_result():
    from dhsym.checking import render_check

    answer = f"theta2 = acos({D})\ntheta1 = atan(p_y/p_x) - atan2(a2*S2, a1 + a2*C2)"
    r = check_answer(load_key("planar2r", "ik"), answer)
    page = render_check(r)
    assert "atan instead of atan2" in page
    assert [(e.col, e.correct) for e in r.entries] == [(1, False), (2, True)]
    assert "The other entry is right." in page


def test_long_digit_runs_in_an_ik_answer_are_refused_by_the_parser():
    """The tolerance comes from the parser's literals (no text scan of its own): a long
    run of digits is refused there, in linear time."""
    key = load_key("planar2r", "ik")
    for text in ("x" + "1" * 20_000, "1" * 20_000 + ".", "a" + "1" * 20_000 + ".5"):
        assert check_answer(key, f"theta1 = {text}\ntheta2 = 0").verdict.value == "unreadable"


@pytest.mark.slow
def test_an_ik_question_on_a_general_6r_is_refused_by_the_key():
    with pytest.raises(dhsym.DHError, match="general 6R: its inverse kinematics is an"):
        load_key("jaco", "ik")
