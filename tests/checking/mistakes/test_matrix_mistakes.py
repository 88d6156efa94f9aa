"""Mistakes of a whole matrix: transposed, reverse order, the other convention."""

from __future__ import annotations

import sympy as sp

import dhsym
from dhsym.checking.mistakes._matrix_mistakes import BlockTransposed
from dhsym.kinematics.transforms import link_word, plain_product
from dhsym.model.table import Convention

from .._keys import check_answer, load_key  # each key prepared once, as a grading worker does

PUMA = dhsym.load("puma560")


def text(M) -> str:
    return str(sp.Matrix(M).tolist())


def product(rows, convention, reverse=False):
    links = [list(link_word(r, convention)) for r in rows]
    return plain_product([e for link in (links[::-1] if reverse else links) for e in link])


def check(robot, question, answer):
    return check_answer(load_key(robot, question), answer)


def test_transposed():
    r = check("puma560", "T0_2", text(PUMA.transform(0, 2).matrix.T))
    assert r.kinds == ("transposed",)


def test_rotation_part_transposed():
    T = sp.Matrix(PUMA.transform(0, 2).matrix)
    T[:3, :3] = T[:3, :3].T
    r = check("puma560", "T0_2", text(T))
    assert r.kinds == ("transposed",) and "rotation part" in r.diagnoses[0].detail


def test_other_convention():
    rows = PUMA.table.rows[:2]
    r = check("puma560", "T0_2", text(product(rows, Convention.MODIFIED)))
    assert r.kinds == ("other_convention",) and "modified link matrix" in r.message


def test_product_in_reverse_order():
    r = check("puma560", "T0_3", text(product(PUMA.table.rows[:3], Convention.STANDARD, True)))
    assert r.kinds == ("reverse_order",) and "reverse order" in r.message


def test_one_block_of_the_jacobian_transposed():
    J = sp.Matrix(dhsym.load("planar3r").jacobian().matrix)
    J[:3, :3] = J[:3, :3].T
    r = check("planar3r", "J", text(J))
    assert r.kinds == ("transposed",) and r.diagnoses[0].title == BlockTransposed.title
