"""Link matrices entry by entry against the seeds (001, 000, 002)."""

from __future__ import annotations

import sympy as sp

import dhsym
from dhsym.kinematics.transforms import (
    Rx,
    Rz,
    Tx,
    Tz,
    chain_word,
    link_matrix,
    plain_product,
    rigid_inverse,
)
from dhsym.model.table import Convention, DHRow, DHTable, Elementary

th, d, a, al = sp.symbols("theta_i d_i a_i alpha_i", real=True)
alm, am = sp.symbols("alpha_im1 a_im1", real=True)
c, s = sp.cos, sp.sin


def test_standard_link_matrix_is_seed_001_and_002():
    # seed 001 "Example 4" general matrix; seed 002 "Arm Matrix for the Standard DH"
    row = DHRow(dhsym.JointType.REVOLUTE, th, d, a, al)
    A = link_matrix(row, Convention.STANDARD)
    expected = sp.Matrix(
        [
            [c(th), -s(th) * c(al), s(th) * s(al), a * c(th)],
            [s(th), c(th) * c(al), -c(th) * s(al), a * s(th)],
            [0, s(al), c(al), d],
            [0, 0, 0, 1],
        ]
    )
    assert sp.expand(A - expected) == sp.zeros(4)
    assert A == Rz(th) * Tz(d) * Tx(a) * Rx(al)


def test_modified_link_matrix_is_seed_000_eq10_with_the_correct_sign():
    # seed 000 eq. (10) and seed 002; one slide of seed 002 prints +d_i sin(alpha_{i-1})
    row = DHRow(dhsym.JointType.REVOLUTE, th, d, am, alm)
    T = link_matrix(row, Convention.MODIFIED)
    expected = sp.Matrix(
        [
            [c(th), -s(th), 0, am],
            [s(th) * c(alm), c(th) * c(alm), -s(alm), -s(alm) * d],
            [s(th) * s(alm), c(th) * s(alm), c(alm), c(alm) * d],
            [0, 0, 0, 1],
        ]
    )
    assert sp.expand(T - expected) == sp.zeros(4)
    assert T[1, 3] == -d * s(alm)  # entry (2,4): minus, not the slide's plus
    assert T[1, 3] != d * s(alm)


def test_modified_factors_are_seed_002_transformations_1_to_4():
    r = dhsym.Robot(
        DHTable.from_rows([DHRow(dhsym.JointType.REVOLUTE, th, d, am, alm)], convention="modified")
    )
    f = [p.matrix for p in r.link_factors(1)]
    assert f == [Rx(alm), Tx(am), Rz(th), Tz(d)]
    assert f[0] * f[1] * f[2] * f[3] == link_matrix(r.table.rows[0], Convention.MODIFIED)


def test_elementary_rotations_are_proper():
    t = sp.Symbol("t", real=True)
    for R in (Rx(t), Rz(t), dhsym.kinematics.transforms.Ry(t)):
        assert sp.simplify(R[:3, :3].T * R[:3, :3]) == sp.eye(3)
        assert sp.simplify(R[:3, :3].det()) == 1


def test_rigid_inverse_is_exact():
    t, x = sp.symbols("t x", real=True)
    T = Rz(t) * Tx(x) * Rx(sp.pi / 2) * Tz(3)
    assert sp.simplify(rigid_inverse(T) * T) == sp.eye(4)


def test_chain_word_inverse_reverses_and_inverts():
    table = dhsym.planar_chain(2)
    fwd = plain_product(chain_word(table, 0, 2))
    back = plain_product(chain_word(table, 2, 0))
    assert sp.simplify(fwd * back) == sp.eye(4)


def test_chain_word_includes_base_and_tool():
    table = DHTable.from_rows(
        [DHRow.revolute("q1")], base=(Elementary("T", "z", 1),), tool=(Elementary("T", "x", 2),)
    )
    assert chain_word(table, -1, 2)[0] == Elementary("T", "z", 1)
    assert chain_word(table, -1, 2)[-1] == Elementary("T", "x", 2)
    assert chain_word(table, 0, 1) == chain_word(table, 0, 1)[:4]
