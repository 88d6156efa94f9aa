"""The inverse-kinematics derivation: every step and branch of the core, printed in each format."""

from __future__ import annotations

import numpy as np
import pytest

import dhsym
from dhsym.explain.inverse_kinematics import default_configuration, derive_inverse

ROBOTS = ["planar2r", "scara", "stanford", "puma560", "puma560_modified", "cylindrical"]


def _say(runs) -> str:
    return "".join(r.words if r.math is None else r.math.text for r in runs)


@pytest.mark.parametrize("name", ROBOTS)
def test_every_step_of_the_core_is_in_the_document(name):
    robot = dhsym.load(name)
    ik = robot.inverse()
    d = derive_inverse(robot)
    results = [(r.name.text, r.text_lines) for p in d.parts for s in p.steps for r in s.results]
    assert [n for n, _ in results] == [robot.notation.text(s.lhs) for s in ik.steps]
    for (_, lines), step in zip(results, ik.steps, strict=True):
        whole = robot.notation.text(step.rhs)
        assert " ".join(x.strip() for x in lines).replace("( ", "(") == whole or len(lines) > 1
    assert [b.symbol.text for b in d.branches] == [str(b.symbol) for b in ik.branches]
    assert d.count == ik.count
    text = d.to_text()
    for b in ik.branches:
        assert str(b.symbol) in text
    assert text.count("atan2") >= sum("atan2" in str(s.rhs) for s in ik.steps)


def test_the_puma_derivation_reads_like_the_lecture():
    d = derive_inverse("puma560")
    assert [p.title for p in d.parts] == [
        "The wrist centre",
        "Position: joints 1–3",
        "Orientation: joints 4–6",
    ]
    wrist = d.parts[0].steps
    assert len(wrist) == 1 and [r.name.text for r in wrist[0].results] == ["c_x", "c_y", "c_z"]
    text = " ".join(d.to_text().split())
    assert "theta1 = atan2(c_y, c_x) - atan2(-d3, r)" in text
    assert "r = sigma_1*sqrt(c_x**2 + c_y**2 - d3**2)" in text
    assert "(the law of cosines): a3*C3 - d4*S3 = K_3 with" in text
    assert "theta3 = atan2(sigma_3*sqrt(a3**2 - K_3**2 + d4**2), K_3) + atan2(-d4, a3)" in text
    assert "sigma_5 = 1: wrist not flipped (S5 > 0); sigma_5 = -1: wrist flipped" in text
    assert "If the wrist is singular (S5 = 0)" in text and "theta4 = 0" in text
    tex = d.to_latex()
    assert r"\theta_{1} &= \operatorname{atan2}\left(c_{y}, c_{x}\right)" in tex
    assert r"\item $\sigma_{3} = 1$ and $\sigma_{3} = -1$: the two elbow configurations" in tex
    assert tex.isascii()
    md = d.to_markdown()
    assert "- $\\sigma_{1} = 1$: right arm" in md


def test_the_2r_elbow_and_its_two_solutions():
    d = derive_inverse("planar2r", check=True)
    assert d.check.position  # a positioning arm: the position of the pose is solved
    names = [_say(n) for n, _ in d.check.solutions]
    assert sorted(names) == ["elbow down", "elbow up"]
    text = d.to_text()
    assert "D_2 = (p_x**2 + p_y**2 - a1**2 - a2**2)/(2*a1*a2)" in text
    assert "theta2 = atan2(sigma_2*sqrt(1 - D_2**2), D_2)" in text


def test_the_check_lists_every_solution_and_each_reproduces_the_pose():
    robot = dhsym.load("puma560")
    q = default_configuration(robot)
    d = derive_inverse(robot, check=q)
    assert len(d.check.solutions) == 8
    assert len({_say(n) for n, _ in d.check.solutions}) == 8
    T = robot.fk(q)
    for _, values in d.check.solutions:
        shown = np.radians([float(v.text) for v in values])
        assert np.abs(robot.fk(shown) - T).max() < 1e-3  # printed to 0.01°
    assert [x.text for _, x in d.check.q] == [f"{np.degrees(v):.2f}" for v in q]
    assert "right arm, elbow down, wrist not flipped" in d.to_text()


def test_a_prismatic_branch_is_named_by_its_root():
    d = derive_inverse("stanford", check=True)
    names = [_say(n) for n, _ in d.check.solutions]
    assert "right arm, first root of the d3 equation, wrist not flipped" in names
    assert all("√" not in n for n in names)
    assert d.to_latex().isascii()


def test_no_closed_form_is_a_clear_error():
    with pytest.raises(dhsym.DHError, match="no closed-form inverse kinematics"):
        derive_inverse("planar4r")


def test_the_check_needs_numbers():
    rows = [dhsym.DHRow.revolute("theta1", a="a1"), dhsym.DHRow.revolute("theta2", a="a2")]
    robot = dhsym.Robot(dhsym.DHTable.from_rows(rows, name="2R without numbers"))
    assert derive_inverse(robot).check is None
    with pytest.raises(dhsym.DHError, match="needs values for a1, a2"):
        derive_inverse(robot, check=True)
