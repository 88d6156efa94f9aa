"""Branch names: one vocabulary for IK results, derivations and feedback (issue 24); the
constant transform before joint 1 undone by one function."""

import numpy as np

import dhsym
from dhsym.explain.inverse_kinematics import derive_inverse
from dhsym.ik.steps import BRANCH_NAMES, branch_word


def test_every_branch_name_comes_from_the_one_list():
    words = {w for pair in BRANCH_NAMES.values() for w in pair}
    robot = dhsym.load("puma560")
    sol = robot.ik(robot.fk(np.array([0.3, -0.45, 0.6, -0.75, 0.9, -1.05])))
    assert len(sol.branches) == 8
    for name in sol.branches:
        assert set(name.split(", ")) <= words, name
    parts = {p for name in sol.branches for p in name.split(", ")}
    # both names of the arm, the elbow and the wrist occur (the shoulder's are the
    # Panda's, read backwards: below)
    assert parts == words - set(BRANCH_NAMES["shoulder"])


def test_the_derivation_names_the_branches_in_the_same_words():
    for name in ("planar2r", "puma560"):
        d = derive_inverse(name)
        for b in d.branches:
            sentence = "".join(r.words or r.math.text for r in b.sentence)
            assert all(w in sentence for w in BRANCH_NAMES[b.role]), sentence
            assert "root" not in sentence


def test_a_branch_without_a_name_of_its_own_is_named_by_its_root_in_words():
    # issue 32: "second root of the θ4 equation", not "- root for theta4"
    assert branch_word("reach", False, "d3") == "second root of the d3 equation"
    assert branch_word("sign", True, "theta4") == "first root of the θ4 equation"
    assert branch_word("wrist", True) == "wrist not flipped"


def test_the_panda_read_backwards_names_its_shoulder_and_its_roots_not_an_arm_or_a_wrist():
    robot = dhsym.load("panda")
    q = [0.3, -0.5, 0.4, -2.0, 0.2, 1.6, 0.7]
    sol = robot.ik(robot.fk(q), free={7: 0.7})
    assert len(sol) == 8
    for name, signs in zip(sol.branches, sol.signs):
        parts = name.split(", ")
        assert "root for" not in name and "wrist" not in name and "arm" not in name, name
        assert parts[-1] == ("shoulder not flipped" if signs[-1] > 0 else "shoulder flipped")
        assert parts[0] == ("first" if signs[0] > 0 else "second") + " root of the θ4 equation"
    assert len(set(sol.branches)) == 8  # the words tell the eight apart


def test_the_transform_before_joint_1_is_undone_by_one_function():
    import sympy as sp

    from dhsym.ik.steps import Builder, undo_prefix
    from dhsym.kinematics.decoupling import decouple

    robot = dhsym.load("puma560")
    b = Builder(robot, decouple(robot, 3))
    p = sp.Matrix(sp.symbols("x y z", real=True))
    assert undo_prefix(b, "position", "none", p, sp.eye(4)) is p and not b.steps
    shift = sp.eye(4)
    shift[2, 3] = sp.Rational(1, 2)
    u = undo_prefix(b, "position", "undo it", p, shift)
    assert [str(s.lhs) for s in b.steps] == ["u_x", "u_y", "u_z"]
    assert b.steps[2].rhs == p[2] - sp.Rational(1, 2) and u.shape == (3, 1)
