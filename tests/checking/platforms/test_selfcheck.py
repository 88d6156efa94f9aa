"""Self-check in a notebook: the rich result and the widget (without a browser)."""

from __future__ import annotations

import pytest

from dhsym.checking import Key, SelfCheck, TrajectoryKey, assert_answer, check, check_widget
from dhsym.checking.platforms.selfcheck import read_answer
from dhsym.errors import DHError

RIGHT = "[[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 + a2*S12], [0, 0, 1, 0]]"
WRONG = RIGHT.replace("a1*C1 + a2*C12", "a1*C1 - a2*C12")


def test_correct_incorrect_unreadable():
    assert check(RIGHT, key="planar2r", question="T0_2").verdict == "correct"
    r = check(WRONG, key="planar2r", question="T0_2")
    assert r.verdict == "incorrect"
    html, md = r._repr_html_(), r._repr_markdown_()
    for page in (html, md):
        assert "INCORRECT" in page and "Most likely mistake" in page and "wrong sign" in page
        assert "(1,4)" in page and "a_{1} C_{1} - a_{2} C_{12}" in page  # typeset, as read
        assert "a_{1} C_{1} + a_{2} C_{12}" not in page  # the key stays hidden
    shown = check(WRONG, key="planar2r", question="T0_2", show_key=True)
    assert "a_{1} C_{1} + a_{2} C_{12}" in shown._repr_html_()
    bad = check("__import__('os').system('ls')", key="planar2r", question="T0_2")
    assert bad.verdict == "unreadable"


def test_student_text_is_escaped():
    r = check("<script>alert(1)</script> | x |", key="planar2r", question="table")
    assert "<script>" not in r._repr_html_() and "<script>" not in r._repr_markdown_()


def test_assert_correct_for_notebook_graders():
    check(RIGHT, key="planar2r", question="T0_2").assert_correct()
    with pytest.raises(AssertionError, match="wrong sign"):
        check(WRONG, key="planar2r", question="T0_2").assert_correct()


def test_read_answer_is_the_live_preview():
    key = Key.load("planar2r", "T0_2")
    assert read_answer(key, "").error == "" and read_answer(key, "").latex == ""
    assert read_answer(key, RIGHT).latex.startswith(r"\begin{bmatrix}C_{12} & -S_{12}")
    assert "expected a 4×4 matrix" in read_answer(key, "C1 S1").error
    table = read_answer(
        Key.load("planar2r", "table"),
        "| θ | d | a | α |\n|--|--|--|--|\n| θ1 | 0 | a1 | 0 |\n| θ2 | 0 | a2 | 0 |",
    )
    assert table.table[1][1] == "theta1"


def test_the_preview_reads_as_the_check_does():
    """The preview is the check's own reading: a Jacobian 6×n, a determinant, IK statements."""
    jac = Key.load("planar2r", "J")
    rows = "; ".join(
        ", ".join(["-a1*S1 - a2*S12", "-a2*S12"] if i == 0 else ["0", "0"]) for i in range(6)
    )
    assert read_answer(jac, rows).latex.startswith(r"\begin{bmatrix}")
    assert read_answer(jac, rows).error == ""
    assert read_answer(Key.load("planar2r", "det J"), "a1*a2*S2").latex == r"a_{1} a_{2} S_{2}"
    ik = read_answer(Key.load("planar2r", "ik"), "theta1 = atan2(py, px); theta2 = 0")
    assert ik.error == ""
    assert r"\theta_{1} = \operatorname{atan2}\left(p_{y}, p_{x}\right)" in ik.latex


def test_bad_key_or_question_is_the_teachers_error():
    with pytest.raises(DHError):
        check("1", key="planar2r", question="T0_9")
    with pytest.raises(DHError):
        check("1", key="no-such-robot", question="T0_1")
    with pytest.raises(DHError, match="give the key"):
        check("1")
    with pytest.raises(DHError, match="give the question"):
        check("1", key="planar2r")


def test_widget_previews_and_checks(need_ipywidgets):
    box = check(key="planar2r", question="T0_2")
    area, preview, button, verdict = box.children[1:]
    assert "dhsym-answer" in area._dom_classes and "dhsym-check" in button._dom_classes
    assert "Type your answer" in preview.value
    area.value = WRONG
    assert "dhsym reads" in preview.value and "a_{1} C_{1} - a_{2} C_{12}" in preview.value
    button.click()
    assert "INCORRECT" in verdict.value and "wrong sign" in verdict.value
    area.value = RIGHT
    button.click()
    assert "CORRECT" in verdict.value and "INCORRECT" not in verdict.value
    assert isinstance(check(RIGHT, key="planar2r", question="T0_2"), SelfCheck)
    assert check_widget("planar2r", "px", answer="a1*C1").children[2].value.count("dhsym reads")


def test_a_profile_key_in_a_notebook():
    r = check("3*(qf - q0)/tf", key="cubic(q0=q0, qf=qf, tf=tf)", question="traj a2")
    assert r.verdict == "incorrect" and r"t\_f for t\_f²" in r._repr_markdown_()
    assert check("3 (q_f-q_0)/t_f^2", key="cubic(q0=q0, qf=qf, tf=tf)", question="traj a2").correct
    with pytest.raises(AssertionError, match="K_p = ω"):
        assert_answer("10", key="gains(omega=10)", question="kp")
    preview = read_answer(TrajectoryKey.load("gains(omega=omega)", "kd"), r"2\zeta\omega")
    assert preview.latex == r"2 \omega \zeta" and not preview.error
    assert read_answer(TrajectoryKey.load("gains(omega=10)", "kd"), "2 +").error
    with pytest.raises(DHError, match="asks about a profile"):
        check("1", key="planar2r", question="traj a2")
