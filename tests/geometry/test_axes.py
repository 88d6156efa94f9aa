"""Joint axes and line geometry: exact normalisation, common normals, classification."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from dhsym.errors import GeometryError
from dhsym.geometry.axes import (
    Frame,
    JointAxis,
    Relation,
    Tool,
    classify,
    common_normal,
    exact_number,
    norm,
    sign_of,
    unit_direction,
    vector,
)

S = lambda n: sp.Symbol(n, real=True)  # noqa: E731


def test_directions_are_normalised_exactly():
    ax = JointAxis((0, 0, 0), (1, 2, 2), "P", "3")
    assert tuple(ax.direction) == (sp.Rational(1, 3), sp.Rational(2, 3), sp.Rational(2, 3))
    assert tuple(JointAxis((0, 0, 0), (0, 3, -3)).direction) == (0, sp.sqrt(2) / 2, -sp.sqrt(2) / 2)
    assert ax.joint == "P" and ax.name == "3"
    assert JointAxis((0, 0, 0), (0, 0, 1), "revolute").joint == "R"


def test_floats_become_the_exact_numbers_they_stand_for():
    assert exact_number(0.4318) == sp.Rational(2159, 5000)
    assert exact_number(np.float64(-0.7071067811865476)) == -sp.sqrt(2) / 2
    assert exact_number(0.5773502691896258) == sp.sqrt(3) / 3
    assert exact_number(1e-17) == 0
    assert exact_number(0.1 + 0.2) == sp.Rational(3, 10)
    with pytest.raises(GeometryError, match="non-finite"):
        exact_number(float("nan"))


def test_bad_axes_are_refused_with_the_joint_named():
    with pytest.raises(GeometryError, match="joint 4: the direction of the axis has zero length"):
        JointAxis((1, 2, 3), (0, 0.0, 0), "R", "4")
    with pytest.raises(GeometryError, match="joint 2: unknown joint type 'Q'"):
        JointAxis((0, 0, 0), (0, 0, 1), "Q", "2")
    with pytest.raises(GeometryError, match="direction must be numbers"):
        JointAxis((0, 0, 0), (0, "a", 1), "R", "1")
    with pytest.raises(GeometryError, match="three components"):
        vector([1, 2])
    with pytest.raises(GeometryError, match="not R or P|R or P, not fixed"):
        JointAxis((0, 0, 0), (0, 0, 1), "F", "1")


def test_common_normal_of_skew_lines_with_its_feet():
    l1 = JointAxis((0, 0, 0), (0, 0, 1))
    l2 = JointAxis((2, -5, 3), (0, 1, 0))
    cn = common_normal(l1, l2)
    assert cn.relation is Relation.SKEW
    assert tuple(cn.foot1) == (0, 0, 3) and tuple(cn.foot2) == (2, 0, 3)
    assert tuple(cn.direction) == (1, 0, 0) and cn.length == 2


def test_common_normal_of_oblique_skew_lines_is_exact():
    l1 = JointAxis((0, 0, 0), (1, 0, 0))
    l2 = JointAxis((0, 1, 1), (0, 1, 1))  # through (0, 0, 0)+... meets plane x = 0 along a line
    cn = common_normal(l1, l2)
    assert cn.relation is Relation.INTERSECTING  # (0,1,1) + t(0,1,1) passes the origin
    l3 = JointAxis((0, 1, 0), (1, 0, 1))
    cn3 = common_normal(l1, l3)
    assert cn3.relation is Relation.SKEW
    assert cn3.length == 1 and tuple(cn3.direction) == (0, 1, 0)


def test_parallel_lines_take_the_normal_through_a_chosen_point():
    l1 = JointAxis((0, 0, 0), (0, 0, 1))
    l2 = JointAxis((3, 4, 10), (0, 0, -1))
    cn = common_normal(l1, l2, through=(0, 0, 7))
    assert cn.relation is Relation.PARALLEL
    assert tuple(cn.foot1) == (0, 0, 7) and tuple(cn.foot2) == (3, 4, 7)
    assert cn.length == 5 and tuple(cn.direction) == (sp.Rational(3, 5), sp.Rational(4, 5), 0)


def test_classification_of_the_four_cases():
    z = JointAxis((0, 0, 0), (0, 0, 1))
    assert classify(z, JointAxis((0, 0, 9), (0, 0, -2))) is Relation.COINCIDENT
    assert classify(z, JointAxis((1, 1, 0), (0, 0, 1))) is Relation.PARALLEL
    assert classify(z, JointAxis((0, 0, 2), (1, 1, 0))) is Relation.INTERSECTING
    assert classify(z, JointAxis((0, 1, 2), (1, 0, 0))) is Relation.SKEW


def test_symbolic_points_are_decided_with_values():
    a2, d3 = S("a2"), S("d3")
    l1 = JointAxis((0, 0, 0), (0, 0, 1))
    l2 = JointAxis((a2, 0, 0), (0, 0, 1))
    cn = common_normal(l1, l2, values={a2: 0.4})
    assert cn.length == a2 and tuple(cn.direction) == (1, 0, 0)
    cn_neg = common_normal(l1, JointAxis((-d3, 0, 0), (0, 0, 1)), values={d3: 0.1})
    assert cn_neg.length == d3 and tuple(cn_neg.direction) == (-1, 0, 0)
    with pytest.raises(GeometryError, match="give values for a2"):
        common_normal(l1, l2)
    assert norm(vector([3, 4, 0])) == 5
    assert sign_of(sp.sqrt(3) - sp.Rational(17, 10)) == 1


def test_motion_about_and_along_an_axis():
    r = JointAxis((1, 0, 0), (0, 0, 1), "R")
    M = r.motion(np.pi / 2)
    assert np.allclose(M @ [2, 0, 0, 1], [1, 1, 0, 1])
    p = JointAxis((1, 0, 0), (0, 3, 4), "P")
    assert np.allclose(p.motion(5.0)[:3, 3], [0, 3, 4])
    assert r.contains((1, 0, -3)) and not r.contains((1, 1, 0))
    assert tuple(r.foot((5, 0, 2))) == (1, 0, 2)


def test_frames_and_tools_are_validated():
    f = Frame.from_matrix(np.eye(4), 0)
    assert f.matrix == sp.eye(4)
    with pytest.raises(GeometryError, match="not a rotation"):
        Frame.from_matrix(np.diag([1, 1, -1, 1]), 0)
    with pytest.raises(GeometryError, match="frame 2: x and z must be orthogonal unit vectors"):
        Frame(2, (0, 0, 0), (1, 0, 0), (1, 1, 0))
    t = Tool((0, 0, 1), (0, 0, 2), (0, 3, 0))
    assert tuple(t.frame.x) == (1, 0, 0)  # n = s × a
    with pytest.raises(GeometryError, match="approach vector must be non-zero"):
        Tool((0, 0, 0), (0, 0, 0), (0, 1, 0))
    with pytest.raises(GeometryError, match="must be orthogonal; got a·s = sqrt\\(2\\)/2"):
        Tool((0, 0, 0), (0, 0, 1), (0, 1, 1))


# --- directions: exact where cheap, rational unit vectors otherwise ---------------------------


@pytest.mark.parametrize(
    ("given", "expected"),
    [
        ((0.6, 0, 0.8), (sp.Rational(3, 5), 0, sp.Rational(4, 5))),
        ((2, 2, 0), (sp.sqrt(2) / 2, sp.sqrt(2) / 2, 0)),
        ((0, 0, -7), (0, 0, -1)),
        ((sp.sqrt(3) / 2, sp.Rational(1, 2), 0), (sp.sqrt(3) / 2, sp.Rational(1, 2), 0)),
    ],
)
def test_small_integer_directions_stay_exact(given: tuple, expected: tuple) -> None:
    assert tuple(unit_direction(vector(given))) == expected


@pytest.mark.parametrize(
    "given",
    [
        ("3", "1e-40", "7"),
        ("1e300", "1e-300", "1"),
        ("0.3", "1e-17", "0.95"),
        ("-0.101", "0.2", "-0.97"),
        ("0.123", "0.4567", "0.89"),
        ("0.123456789", "0.987654321", "-0.5"),
    ],
)
def test_measured_directions_are_rational_unit_vectors_near_the_float_one(given: tuple) -> None:
    # once: minutes in sympy's factorint; now floats, then the nearest rational unit vector
    exact = [sp.Rational(v) for v in given]
    u = unit_direction(vector(exact))
    assert all(c.is_Rational for c in u) and u.dot(u) == 1
    big = max(abs(v) for v in exact)
    f = np.array([float(v / big) for v in exact])
    assert np.abs(np.array([float(c) for c in u]) - f / np.linalg.norm(f)).max() < 1e-11
    assert JointAxis((0, 0, 0), exact).direction == u
