"""The URDF model: the tree's questions (root, links below, the chain between two links) and
an origin's transforms."""

from __future__ import annotations

import pytest
import sympy as sp

from dhsym.errors import FormatError
from dhsym.formats.urdf.description import Origin, UrdfJoint, UrdfModel


def _model(*joints: tuple[str, str, str, str]) -> UrdfModel:
    links = sorted({link for _, _, parent, child in joints for link in (parent, child)})
    return UrdfModel(
        "r",
        tuple((link, None) for link in links),
        tuple(UrdfJoint(n, kind, p, c, Origin(), (0, 0, 1)) for n, kind, p, c in joints),
    )


def test_root_leaves_and_moving_joints_below() -> None:
    m = _model(
        ("j1", "revolute", "a", "b"), ("f", "fixed", "b", "c"), ("j2", "prismatic", "b", "d")
    )
    assert m.root == "a"
    assert m.leaves("a") == ["c", "d"] and m.leaves("d") == ["d"]
    assert m.below("a") == {"a": 0, "b": 1, "c": 1, "d": 2}
    assert m.parent_joint("d").name == "j2" and m.parent_joint("a") is None
    assert [j.name for j in m.chain("a", "d")] == ["j1", "j2"]


def test_chain_names_what_is_wrong() -> None:
    m = _model(("j1", "revolute", "a", "b"), ("j2", "revolute", "a", "c"))
    with pytest.raises(FormatError, match="field tip: no link named 'z' \\(links: a, b, c\\)"):
        m.chain("a", "z")
    with pytest.raises(FormatError, match="field base: link 'b' is not above link 'c'"):
        m.chain("b", "c")


def test_two_roots_and_a_joint_as_an_error_field() -> None:
    m = UrdfModel("r", (("a", None), ("b", None)), ())
    with pytest.raises(FormatError, match="links a, b are no joint's child"):
        _ = m.root
    long = UrdfJoint("x" * 300, "fixed", "a", "b", Origin(), (1, 0, 0))
    assert long.where == f"<joint name='{'x' * 80}'>"


def test_origin_word_and_exactly_orthogonal_measured_rotations() -> None:
    o = Origin((1, 0, sp.Rational(1, 2)), (sp.Rational(-9, 5), sp.pi / 2, 0))
    assert [str(e) for e in o.word] == ["Tx(1)", "Tz(1/2)", "Ry(pi/2)", "Rx(-9/5)"]
    R = o.rational_matrix[:3, :3]
    assert R.T * R == sp.eye(3) and all(v.is_rational for v in R)
    assert float((o.rational_matrix - o.matrix).norm()) < 1e-12
