"""The PoE mistakes (issue 36, item 5): each named in the feedback, for every question it
belongs to, with wrong answers written the way a student makes the mistake."""

from __future__ import annotations

from importlib import resources

import pytest
import sympy as sp

import dhsym
from dhsym.checking import Key, check_answer
from dhsym.checking.comparing.equivalence import Sample, values
from dhsym.checking.comparing.verdict import Verdict
from dhsym.checking.grading.credit import Credit, mistake_kinds
from dhsym.checking.mistakes._screw_mistakes import (
    _flipped,
    _flipped_jacobian,
    _from_body,
    _with_space,
)
from dhsym.checking.mistakes.registry import SCREW_MISTAKES
from dhsym.screws.algebra import matrix_exp

from .._keys import KEYS  # each key prepared once, as a grading worker does

ROBOTS = resources.files("dhsym.screws") / "robots"
UR5 = str(ROBOTS / "lynch_park_ur5.poe.yaml")
THREE_R = str(ROBOTS / "lynch_park_3r.poe.yaml")
th1, th2 = sp.symbols("theta1 theta2", real=True)
a1, a2 = sp.symbols("a1 a2", real=True)

#: Lynch and Park's UR5 axes with v = omega x q (each revolute v negated), one per row
UR5_S_SIGN = (
    "[[0, 0, 1, 0, 0, 0], [0, 1, 0, H1, 0, 0], [0, 1, 0, H1, 0, -L1],"
    " [0, 1, 0, H1, 0, -L1 - L2], [0, 0, -1, W1, -L1 - L2, 0], [0, 1, 0, H1 - H2, 0, -L1 - L2]]"
)
UR5_B = (
    "[[0, 1, 0, W1 + W2, 0, L1 + L2], [0, 0, 1, H2, -L1 - L2, 0], [0, 0, 1, H2, -L2, 0],"
    " [0, 0, 1, H2, 0, 0], [0, -1, 0, -W2, 0, 0], [0, 0, 1, 0, 0, 0]]"
)
UR5_S = (
    "[[0, 0, 1, 0, 0, 0], [0, 1, 0, -H1, 0, 0], [0, 1, 0, -H1, 0, L1],"
    " [0, 1, 0, -H1, 0, L1 + L2], [0, 0, -1, -W1, L1 + L2, 0], [0, 1, 0, H2 - H1, 0, L1 + L2]]"
)


def check(ref: object, question: str, answer: str):
    return check_answer(Key.load(ref, question, keys=KEYS), answer, keys=KEYS)


def diagnosed(ref: object, question: str, answer: str) -> str:
    """The mistake the feedback names first; the answer is graded wrong."""
    r = check(ref, question, answer)
    assert r.verdict is Verdict.INCORRECT, r.message
    first = r.diagnoses[0]
    assert f"Most likely: {first.title}." in r.message
    return first.kind


def _text(M: sp.MatrixBase) -> str:
    return str(sp.Matrix(M).tolist())


def _planar(axes: list[list[object]], home: sp.Matrix | None = None, order: str = "") -> str:
    """``e^[A1]θ1 e^[A2]θ2 M`` of the planar 2R arm (``order``: ``reverse`` or ``M first``)."""
    M = (
        home
        if home is not None
        else sp.Matrix([[1, 0, 0, a1 + a2], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    )
    E = [matrix_exp(a, q) for a, q in zip(axes, (th1, th2), strict=True)]
    if order == "reverse":
        E = E[::-1]
    P = E[0] * E[1]
    return _text(M * P if order == "M first" else P * M)


S2R = [[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, -a1, 0]]
B2R = [[0, 0, 1, 0, a1 + a2, 0], [0, 0, 1, 0, a2, 0]]


@pytest.mark.parametrize(
    ("ref", "question", "answer", "kind"),
    [
        # v = omega x q for v = -omega x q
        ("planar2r", "S", "[[0,0,1,0,0,0],[0,0,1,0,a1,0]]", "omega_cross_q"),
        ("planar2r", "S2", "[0,0,1,0,a1,0]", "omega_cross_q"),
        ("planar2r", "B", "[[0,0,1,0,-a1-a2,0],[0,0,1,0,-a2,0]]", "omega_cross_q"),
        (UR5, "S", UR5_S_SIGN, "omega_cross_q"),
        (
            "planar2r",
            "T(theta)",
            _planar([[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, a1, 0]]),
            "omega_cross_q",
        ),
        # the body axes where the space axes are asked, and the reverse
        (UR5, "S", UR5_B, "body_for_space"),
        (UR5, "B", UR5_S, "space_for_body"),
        ("planar2r", "S1", "[0,0,1,0,a1+a2,0]", "body_for_space"),
        ("planar2r", "T(theta)", _planar(B2R), "body_for_space"),
        ("planar2r", "T(theta)", _planar(S2R, order="M first"), "space_for_body"),
        # rows [v; omega]
        ("planar2r", "S", "[[0,0,0,0,0,1],[0,-a1,0,0,0,1]]", "rows_swapped"),
        (UR5, "B2", "[H2, -L1 - L2, 0, 0, 0, 1]", "rows_swapped"),
        # M at the wrong configuration: another link's frame, or where the entries are zero
        ("planar2r", "Mhome", "[[1,0,0,a1],[0,1,0,0],[0,0,1,0]]", "wrong_home"),
        ("example1_rrp", "M0", "[[1,0,0,a2+a4],[0,-1,0,0],[0,0,-1,a1+a3]]", "wrong_home"),
        ("planar2r", "B", "[[0,0,1,0,a1,0],[0,0,1,0,0,0]]", "wrong_home"),
        (
            "planar2r",
            "T(theta)",
            _planar(S2R, sp.Matrix([[1, 0, 0, a1], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])),
            "wrong_home",
        ),
        # the product in reverse order, M transposed
        ("planar2r", "T(theta)", _planar(S2R, order="reverse"), "reverse_order"),
        (
            UR5,
            "Mhome",
            "[[-1, 0, 0, 0], [0, 0, 1, 0], [0, 1, 0, 0], [L1 + L2, W1 + W2, H1 - H2, 1]]",
            "transposed",
        ),
    ],
)
def test_each_mistake_is_named(ref, question, answer, kind):
    assert diagnosed(ref, question, answer) == kind


def test_jacobians_of_the_other_frame_and_of_the_wrong_sign():
    robot = dhsym.load(THREE_R)
    poe = robot.poe()
    Js, Jb = robot.jacobian_space().matrix, robot.jacobian_body().matrix
    assert diagnosed(THREE_R, "Jb", _text(Js)) == "space_for_body"  # J_s given for J_b
    assert diagnosed(THREE_R, "Js", _text(Jb)) == "body_for_space"
    assert diagnosed(THREE_R, "Js", _text(sp.Matrix.vstack(Js[3:, :], Js[:3, :]))) == "rows_swapped"
    # derived from the flipped axes by the screws room, not by the shortcut
    flipped_s = _with_space(poe, _flipped(poe.space)).jacobian_space().matrix
    flipped_b = _from_body(poe, _flipped(poe.body)).jacobian_body().matrix
    assert diagnosed(THREE_R, "Js", _text(flipped_s)) == "omega_cross_q"
    assert diagnosed(THREE_R, "Jb", _text(flipped_b)) == "omega_cross_q"


@pytest.mark.parametrize("name", ["planar2r", THREE_R, "stanford"])
def test_the_flipped_jacobian_shortcut_equals_the_derivation(name):
    """All revolute: J built on the flipped axes is J with its v rows negated (the point
    reflection through the origin); with a prismatic joint it is derived again."""
    robot = dhsym.load(name)
    poe = robot.poe()
    sample = Sample.random(set(robot.table.variables) | set(robot.table.constants))
    for part, J, derived in (
        (
            "Js",
            robot.jacobian_space().matrix,
            lambda: _with_space(poe, _flipped(poe.space)).jacobian_space(),
        ),
        (
            "Jb",
            robot.jacobian_body().matrix,
            lambda: _from_body(poe, _flipped(poe.body)).jacobian_body(),
        ),
    ):
        got = values(_flipped_jacobian(poe, part, J), sample)
        want = values(derived().matrix, sample)
        assert abs(got - want).max() < 1e-9, (name, part)


def test_a_sign_in_one_axis_is_named_with_its_entries_and_earns_entry_credit():
    # S2 of the UR5 with v = omega x q, the other five right: one column wrong
    answer = UR5_S.replace("[0, 1, 0, -H1, 0, 0]", "[0, 1, 0, H1, 0, 0]")
    r = check(UR5, "S", answer)
    assert r.verdict is Verdict.INCORRECT
    (d,) = r.diagnoses
    assert d.kind == "omega_cross_q" and d.entries == ((4, 2),)
    assert d.detail.startswith("The v of the axis S_2 has the wrong sign")
    assert Credit("entries").award(3.0, r) == (
        2.916667,
        "partial credit: 35 of 36 entries right, 2.91667 of 3 points",
    )
    assert Credit(deduct=(("omega_cross_q", 0.5),)).award(3.0, r)[0] == 1.5


def test_the_catalogue_names_every_screw_mistake():
    kinds = {m.kind for m in SCREW_MISTAKES}
    assert kinds == {
        "omega_cross_q",
        "body_for_space",
        "space_for_body",
        "wrong_home",
        "rows_swapped",
        "reverse_order",
        "transposed",
    }
    assert kinds <= mistake_kinds()
    assert all(m.title for m in SCREW_MISTAKES)
