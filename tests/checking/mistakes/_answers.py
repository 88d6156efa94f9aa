"""What the tests of the mistakes share: a matrix written as a student types it, the
plain product of rows, and one answer checked against a built-in key."""

from __future__ import annotations

import sympy as sp

import dhsym
from dhsym.kinematics.transforms import link_word, plain_product

from .._keys import check_answer, load_key  # each key prepared once, as a grading worker does

PUMA = dhsym.load("puma560")


def text(M) -> str:
    return str(sp.Matrix(M).tolist())


def product(rows, convention, reverse=False):
    links = [list(link_word(r, convention)) for r in rows]
    return plain_product([e for link in (links[::-1] if reverse else links) for e in link])


def check(robot, question, answer):
    return check_answer(load_key(robot, question), answer)
