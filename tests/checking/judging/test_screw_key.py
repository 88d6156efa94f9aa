"""PoE questions judged: the keys are the screws room's, right answers in every equivalent
form are right (Lynch and Park's UR5 of Example 4.5 and 3R arm of Example 4.1, with their
symbols and their numbers), and wrong answers are never graded right."""

from __future__ import annotations

from importlib import resources

import pytest
import sympy as sp

import dhsym
from dhsym.checking import Key, check_answer
from dhsym.checking.judging.key import prepare
from dhsym.checking.judging.screw_key import ScrewPart, screw_key_matrix
from dhsym.screws.poefile import read_poe

from .._keys import KEYS  # each key prepared once, as a grading worker does

ROBOTS = resources.files("dhsym.screws") / "robots"
UR5 = str(ROBOTS / "lynch_park_ur5.poe.yaml")
THREE_R = str(ROBOTS / "lynch_park_3r.poe.yaml")

#: Lynch and Park, Example 4.5: the UR5's M, S_i and B_i as the book prints them
UR5_M = "[[-1, 0, 0, L1 + L2], [0, 0, 1, W1 + W2], [0, 1, 0, H1 - H2], [0, 0, 0, 1]]"
UR5_S = (
    "[[0, 0, 1, 0, 0, 0], [0, 1, 0, -H1, 0, 0], [0, 1, 0, -H1, 0, L1],"
    " [0, 1, 0, -H1, 0, L1 + L2], [0, 0, -1, -W1, L1 + L2, 0], [0, 1, 0, H2 - H1, 0, L1 + L2]]"
)
UR5_B = (
    "[[0, 1, 0, W1 + W2, 0, L1 + L2], [0, 0, 1, H2, -L1 - L2, 0], [0, 0, 1, H2, -L2, 0],"
    " [0, 0, 1, H2, 0, 0], [0, -1, 0, -W2, 0, 0], [0, 0, 1, 0, 0, 0]]"
)
#: the same with the book's numbers (W1 = 0.109, W2 = 0.082, L1 = 0.425, L2 = 0.392,
#: H1 = 0.089, H2 = 0.095 m)
UR5_M_NUMBERS = "[[-1, 0, 0, 0.817], [0, 0, 1, 0.191], [0, 1, 0, -0.006]]"
UR5_S_NUMBERS = (
    "[[0, 0, 1, 0, 0, 0], [0, 1, 0, -0.089, 0, 0], [0, 1, 0, -0.089, 0, 0.425],"
    " [0, 1, 0, -0.089, 0, 0.817], [0, 0, -1, -0.109, 0.817, 0], [0, 1, 0, 0.006, 0, 0.817]]"
)


def check(ref: str, question: str, answer: str):
    return check_answer(Key.load(ref, question, keys=KEYS), answer, keys=KEYS)


def _text(M: sp.MatrixBase, robot: dhsym.Robot) -> str:
    nota = robot.notation
    return (
        "["
        + ", ".join("[" + ", ".join(nota.text(x) for x in M.row(i)) + "]" for i in range(M.rows))
        + "]"
    )


def test_the_keys_are_the_screws_rooms():
    robot = dhsym.load("planar2r")
    poe = robot.poe()
    assert screw_key_matrix(robot, "S") == poe.screw_matrix("space")
    assert screw_key_matrix(robot, "B") == poe.screw_matrix("body")
    assert screw_key_matrix(robot, "Mhome") == poe.home
    assert screw_key_matrix(robot, "Js") == robot.jacobian_space().matrix
    assert screw_key_matrix(robot, "Jb") == robot.jacobian_body().matrix
    assert screw_key_matrix(robot, "T") == poe.fk_space().matrix
    part = prepare(Key.load("planar2r", "S2")).part
    assert isinstance(part, ScrewPart) and part.expected == poe.screw_matrix("space")[:, 1]


def test_a_poe_file_is_a_key_with_the_books_axes():
    book = read_poe(UR5)
    pk = KEYS.get(Key.load(UR5, "S", keys=KEYS))
    assert sp.simplify(pk.part.expected - book.screw_matrix("space")) == sp.zeros(6, 6)
    pk = KEYS.get(Key.load(UR5, "Mhome", keys=KEYS))
    assert sp.simplify(pk.part.expected - book.home) == sp.zeros(4, 4)


@pytest.mark.parametrize(
    ("question", "answer"),
    [
        ("S", UR5_S),  # the axes one per row, as the book lists them
        ("S", UR5_S_NUMBERS),  # with the book's numbers
        ("B", UR5_B),
        ("Mhome", UR5_M),
        ("M0", UR5_M_NUMBERS),  # the top three rows, numbers
        ("S6", "[0, 1, 0, H2 - H1, 0, L1 + L2]"),
        ("S5", r"\begin{pmatrix} 0 \\ 0 \\ -1 \\ -W_1 \\ L_1 + L_2 \\ 0 \end{pmatrix}"),
        ("B2[3,0]", "H2"),
    ],
)
def test_lynch_and_parks_ur5_as_the_book_prints_it_is_right(question, answer):
    r = check(UR5, question, answer)
    assert r.correct, r.message


def test_the_ur5_with_numbers_rounded_as_the_key_allows_is_right():
    answer = "[[-1, 0, 0, 0.82], [0, 0, 1, 0.19], [0, 1, 0, -0.006]]"  # two digits
    key = Key.load(UR5, "Mhome", rounding="digits=2", keys=KEYS)
    r = check_answer(key, answer, keys=KEYS)
    assert r.correct and "up to rounding" in r.message, r.message
    assert not check(UR5, "Mhome", answer).correct  # the default asks for three digits


def test_the_3r_arm_in_every_form():
    robot = dhsym.load(THREE_R)
    poe = robot.poe()
    # Example 4.1: S1 = (0,0,1,0,0,0), S2 = (0,-1,0,0,0,-L1), S3 = (1,0,0,0,-L2,0)
    assert check(THREE_R, "S", "[[0,0,1,0,0,0],[0,-1,0,0,0,-L1],[1,0,0,0,-L2,0]]").correct
    assert check(
        THREE_R,
        "Mhome",
        r"\begin{bmatrix} 0&0&1&L_1 \\ 0&1&0&0 \\ -1&0&0&-L_2 \\ 0&0&0&1 \end{bmatrix}",
    ).correct
    for question, matrix in (
        ("Js", robot.jacobian_space().matrix),
        ("Jb", robot.jacobian_body().matrix),
        ("T(theta)", poe.fk_space().matrix),
    ):
        r = check(THREE_R, question, _text(matrix, robot))
        assert r.correct, (question, r.message)
        expanded = matrix.applyfunc(lambda e: sp.expand(sp.expand_trig(e)))
        assert check(THREE_R, question, str(expanded.tolist())).correct, question


def test_the_body_form_of_the_fk_is_the_same_answer():
    """T(theta) is the fk: written from the body form M e^[B1]θ1 ⋯ it is as right."""
    robot = dhsym.load("planar2r")
    body = robot.poe().fk_body().matrix
    r = check("planar2r", "T(theta)", _text(body, robot))
    assert r.correct
    latex = (
        r"\begin{bmatrix} \cos(\theta_1+\theta_2) & -\sin(\theta_1+\theta_2) & 0 & "
        r"a_1\cos\theta_1 + a_2\cos(\theta_1+\theta_2) \\ \sin(\theta_1+\theta_2) & "
        r"\cos(\theta_1+\theta_2) & 0 & a_1\sin\theta_1 + a_2\sin(\theta_1+\theta_2) \\ "
        r"0&0&1&0 \end{bmatrix}"
    )
    assert check("planar2r", "T(theta)", latex).correct


@pytest.mark.parametrize(
    ("ref", "question", "answer"),
    [
        ("planar2r", "S", "[[0,0],[0,0],[1,1],[0,0],[0,-a2],[0,0]]"),
        ("planar2r", "S", "[[0,0],[0,0],[1,1],[0,0],[0,0],[0,0]]"),
        ("planar2r", "Mhome", "[[1,0,0,a1+a2],[0,1,0,0],[0,0,1,1]]"),
        ("planar2r", "Jb", "[[0,0],[0,0],[1,1],[a1*S2,0],[a1*C2+a2,a1],[0,0]]"),
        ("planar2r", "T(theta)", "[[C12,-S12,0,a1*C1+a2*C2],[S12,C12,0,a1*S1+a2*S12],[0,0,1,0]]"),
        (UR5, "S", UR5_B),
        (UR5, "Mhome", "[[-1, 0, 0, 0.817], [0, 0, 1, 0.191], [0, 1, 0, 0.006]]"),
    ],
)
def test_wrong_answers_are_never_graded_right(ref, question, answer):
    r = check(ref, question, answer)
    assert r.verdict.value == "incorrect", r.message
    assert r.diagnoses and r.message.startswith(tuple("0123456789") + ("The entry",))


def test_an_answer_that_evaluates_text_is_unreadable():
    r = check("planar2r", "S", "[[__import__('os').getcwd(),0],[0,0],[1,1],[0,0],[0,-a1],[0,0]]")
    assert r.verdict.value == "unreadable"
