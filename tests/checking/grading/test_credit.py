"""Partial credit per question: credit: entries, deduct per named mistake, floor."""

from __future__ import annotations

import csv

import pytest

from dhsym.checking import Assignment, grade
from dhsym.errors import DHError

ASSIGNMENT = """key: planar2r
questions:
  - {id: q1, ask: T0_2, points: 2, credit: entries}
  - {id: q2, ask: "T0_2[0,3]", points: 1, deduct: {sign: 25%}}
  - {id: q3, ask: T0_2, points: 2}
  - {id: q4, ask: "T0_2[0,3]", points: 1, deduct: {sign: 90%}, floor: 20%}
"""
ONE_WRONG = "[[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 - a2*S12], [0, 0, 1, 0]]"


def test_partial_credit_per_question(tmp_path):
    """Issue 34, item 1: the points per part and why; the default stays all or nothing."""
    (tmp_path / "hw.yaml").write_text(ASSIGNMENT, encoding="utf-8")
    ann = tmp_path / "subs" / "ann"
    ann.mkdir(parents=True)
    for qid, text in (("q1", ONE_WRONG), ("q2", "a1*C1 - a2*C12"), ("q3", ONE_WRONG)):
        (ann / f"{qid}.txt").write_text(text, encoding="utf-8")
    (ann / "q4.txt").write_text("a1*C1 - a2*C12", encoding="utf-8")
    out = tmp_path / "out"
    grade(tmp_path / "hw.yaml", tmp_path / "subs", out, workers=0, progress=False)
    (row,) = csv.DictReader((out / "gradebook.csv").open(encoding="utf-8"))
    assert (row["q1"], row["q2"], row["q3"], row["q4"]) == ("1.875", "0.75", "0", "0.2")
    assert row["total"] == "2.825"
    page = (out / row["feedback"]).read_text(encoding="utf-8")
    assert "(1.875 / 2 points)" in page
    assert "Partial credit: 15 of 16 entries right, 1.875 of 2 points." in page
    assert "Partial credit: wrong sign (25% deducted), 0.75 of 1 points." in page


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        ("credit: some", "credit: expected 'all' or 'entries'"),
        ("deduct: {sine: 10%}", "deduct: unknown mistake 'sine'"),
        ("deduct: {wrong_sign: 125%}", "expected a share like 25%"),
        ("deduct: [wrong_sign]", "deduct: expected a mapping"),
    ],
)
def test_bad_credit_rules_are_refused_naming_the_question(tmp_path, extra, message):
    (tmp_path / "hw.yaml").write_text(
        f"key: planar2r\nquestions:\n  - {{id: q1, ask: T0_2, {extra}}}\n", encoding="utf-8"
    )
    with pytest.raises(DHError, match=message) as err:
        Assignment.load(tmp_path / "hw.yaml")
    assert err.value.row == 1


IK_ASSIGNMENT = """key: planar2r
questions:
  - {id: q1, ask: ik all, points: 3, credit: entries}
  - {id: q2, ask: ik all, points: 3}
"""
#: the 2R's inverse kinematics, the elbow-down branch only (no ± on theta2)
ONE_BRANCH = (
    "D = (p_x**2 + p_y**2 - a1**2 - a2**2)/(2*a1*a2)\n"
    "theta2 = atan2(sqrt(1 - D**2), D)\n"
    "theta1 = atan2(p_y, p_x) - atan2(a2*sin(theta2), a1 + a2*cos(theta2))"
)


def test_ik_all_with_credit_entries_gives_points_per_branch(tmp_path):
    """Each key branch is a part: one of the 2R's two branches earns half the points, in
    the gradebook and the feedback; without credit: entries it stays all or nothing."""
    (tmp_path / "hw.yaml").write_text(IK_ASSIGNMENT, encoding="utf-8")
    ann = tmp_path / "subs" / "ann"
    ann.mkdir(parents=True)
    for qid in ("q1", "q2"):
        (ann / f"{qid}.txt").write_text(ONE_BRANCH, encoding="utf-8")
    out = tmp_path / "out"
    grade(tmp_path / "hw.yaml", tmp_path / "subs", out, workers=0, progress=False)
    (row,) = csv.DictReader((out / "gradebook.csv").open(encoding="utf-8"))
    assert (row["q1"], row["q2"], row["total"]) == ("1.5", "0", "1.5")
    page = (out / row["feedback"]).read_text(encoding="utf-8")
    assert "Partial credit: 1 of 2 branches right (not given: elbow up), 1.5 of 3 points." in page


def test_ik_all_branches_of_the_puma_count_each_branch_once():
    """The PUMA 560's derivation with the shoulder sign fixed (σ1 = +1) gives 4 of its 8
    branches: each is named, and credit: entries gives half the points."""
    import dhsym
    from dhsym.checking.grading.credit import Credit

    from .._keys import check_answer, load_key  # the key prepared once, as a worker does

    robot = dhsym.load("puma560")
    steps = robot.inverse().steps
    text = "\n".join(
        f"{robot.notation.text(st.lhs)} = {robot.notation.text(st.rhs)}" for st in steps
    ).replace("sigma_1*", "")
    result = check_answer(load_key("puma560", "ik all"), text)
    assert result.verdict.value == "incorrect"
    assert len(result.branches) == 8 and sum(ok for _, ok in result.branches) == 4
    assert len({name for name, _ in result.branches}) == 8
    score, why = Credit("entries").award(2.0, result)
    assert score == 1.0 and why.startswith("partial credit: 4 of 8 branches right (not given: ")
    assert result.to_json()["branches"][0] == {"name": result.branches[0][0], "given": True}
    assert type(result).from_json(result.to_json()).branches == result.branches


TRAJECTORY = """title: Trajectories
questions:
  - id: t1
    ask: traj a2
    key: "cubic(q0=q0, qf=qf, tf=tf)"
    points: 2
    deduct: {tf_for_tf_squared: 25%}
  - {id: t2, ask: kd, key: "gains(omega=10)", points: 1, deduct: {kd_without_two: 50%}}
  - {id: t3, ask: kp, key: "gains(omega=10)", points: 1, deduct: {kd_without_two: 50%}}
  - {id: t4, ask: tb, key: "lspb(q0=0, qf=1, tf=2, a=2)", points: 1, credit: entries}
"""


def test_deductions_name_the_trajectory_mistakes(tmp_path):
    """Issue 35, item 5: a trajectory mistake of the catalogue costs what deduct says; another
    mistake, or none, costs everything."""
    (tmp_path / "hw.yaml").write_text(TRAJECTORY, encoding="utf-8")
    ann = tmp_path / "subs" / "ann"
    ann.mkdir(parents=True)
    answers = {"t1": "3*(qf-q0)/tf", "t2": "10", "t3": "10", "t4": "1 + sqrt(2)/2"}
    for qid, text in answers.items():
        (ann / f"{qid}.txt").write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    grade(tmp_path / "hw.yaml", tmp_path / "subs", out, workers=0, progress=False)
    (row,) = csv.DictReader((out / "gradebook.csv").open(encoding="utf-8"))
    assert (row["t1"], row["t2"], row["t3"], row["t4"]) == ("1.5", "0.5", "0", "0")
    page = (out / row["feedback"]).read_text(encoding="utf-8")
    assert r"Partial credit: t\_f for t\_f² (25% deducted), 1.5 of 2 points." in page
    assert r"Partial credit: K\_d without the factor 2 (50% deducted), 0.5 of 1 points." in page
    assert r"Most likely: K\_p = ω." in page and "blend time from the wrong limit" in page
