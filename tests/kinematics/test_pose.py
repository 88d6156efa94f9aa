"""Pose is a sympy matrix where it matters: every sympy call the issue names, and the labels."""

from __future__ import annotations

import copy
import pickle

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.kinematics.pose import Pose
from dhsym.kinematics.simplification import prove_equal
from dhsym.kinematics.transforms import Rz, Tx, rigid_inverse
from dhsym.notation.printers import Notation


@pytest.fixture(scope="module")
def planar():
    return dhsym.load("planar2r")


@pytest.fixture(scope="module")
def puma():
    return dhsym.load("puma560")


def test_matrix_of_a_pose_is_the_4x4(puma):
    T = puma.arm_matrix()
    M = sp.Matrix(T)
    assert M.shape == (4, 4)
    assert M == T.matrix
    assert sp.ImmutableMatrix(T).shape == (4, 4)
    assert isinstance(T, sp.ImmutableMatrix) and isinstance(T, sp.MatrixBase)


def test_link_matrices_compose_to_the_transform(planar, puma):
    for robot in (planar, puma):
        A1, A2 = robot.link_matrix(1), robot.link_matrix(2)
        for product in (A1 * A2, A1 @ A2):
            assert isinstance(product, Pose)
            assert product == robot.transform(0, 2)
            assert (product.frm, product.to, product.label_latex) == (0, 2, "{}^{0}T_{2}")
    arm = puma.link_matrix(1)
    for k in range(2, puma.n + 1):
        arm = arm * puma.link_matrix(k)
    assert arm == puma.arm_matrix() and arm.label_text == "T0_6"


def test_composition_is_the_matrix_product(puma):
    A2, A3 = puma.link_matrix(2), puma.link_matrix(3)
    assert prove_equal(A2 * A3, A2.matrix * A3.matrix)


def test_frames_that_do_not_chain_give_a_plain_matrix(planar):
    A1, A2 = planar.link_matrix(1), planar.link_matrix(2)
    for product in (A2 * A1, A1 @ A1):
        assert type(product) is sp.ImmutableDenseMatrix
    assert A2 * A1 == A2.matrix * A1.matrix


def test_poses_without_a_word_fold_sum_angles():
    t1, t2, a1, a2 = sp.symbols("theta1 theta2 a1 a2", real=True)
    nota = Notation.from_variables([t1, t2])
    P = Pose(Rz(t1) * Tx(a1), 0, 1, nota)
    Q = Pose(Rz(t2) * Tx(a2), 1, 2, nota)
    PQ = P * Q
    assert isinstance(PQ, Pose) and PQ.label_text == "T0_2"
    assert PQ[0, 0] == sp.cos(t1 + t2)
    assert PQ[0, 3] == a1 * sp.cos(t1) + a2 * sp.cos(t1 + t2)
    assert PQ.text().splitlines()[1] == "[C12, -S12, 0, a1*C1 + a2*C12],"


def test_pose_times_a_plain_matrix_and_back(planar):
    A1 = planar.link_matrix(1)
    M = sp.Matrix(sp.eye(4))
    for product in (A1 * M, M * A1, A1 @ M, M @ A1, A1 * sp.eye(4)):
        assert not isinstance(product, Pose)
        assert product == A1.matrix
    x = sp.Symbol("x")
    assert not isinstance(x * A1, Pose) and (x * A1)[0, 3] == x * A1[0, 3]
    assert not isinstance(2 * A1, Pose)


def test_inv_is_the_exact_rigid_inverse(planar, puma):
    for robot in (planar, puma):
        T = robot.arm_matrix()
        inv = T.inv()
        assert isinstance(inv, Pose) and (inv.frm, inv.to) == (robot.n, 0)
        assert inv == robot.transform(robot.n, 0)
        assert prove_equal(inv, rigid_inverse(T.matrix))
    T = planar.arm_matrix()
    assert T.inv()[0, 3] == -planar.table.constants[0] * sp.cos(planar.variables[1]) - sp.Symbol(
        "a2", real=True
    )
    assert (T * T.inv()).label_text == "T0_0"
    assert T * T.inv() == sp.eye(4)


def test_inv_without_a_word():
    t = sp.Symbol("t", real=True)
    P = Pose(Rz(t) * Tx(1), "W", "base")
    inv = P.inv()
    assert inv.label_text == "Tbase_W"
    assert inv * P == sp.eye(4)
    assert inv == rigid_inverse(P.matrix).applyfunc(sp.simplify)


def test_shape_indexing_slicing_iteration(planar):
    T = planar.arm_matrix()
    assert T.shape == (4, 4) and T.rows == 4 and T.cols == 4 and len(T) == 16
    assert T[0, 3] == T.matrix[0, 3] and T[3] == T.matrix[3]
    assert T[:3, 3] == T.position and T[:3, :3] == T.rotation
    assert not isinstance(T[:3, :3], Pose)
    assert list(T) == list(T.matrix)
    assert T.T == T.matrix.T and not isinstance(T.T, Pose)
    assert T.tolist() == T.matrix.tolist()
    assert np.array(T).shape == (4, 4)


def test_free_symbols_and_subs(planar):
    T = planar.arm_matrix()
    t1, t2 = planar.variables
    a1, a2 = planar.table.constants
    assert T.free_symbols == {t1, t2, a1, a2}
    S = T.subs({t1: 0, t2: 0})
    assert isinstance(S, Pose) and S.label_text == "T0_2" and S[0, 3] == a1 + a2
    assert T.subs(t1, 0)[0, 3] == a1 + a2 * sp.cos(t2)
    assert T.subs([(a1, 1), (a2, 2)]).free_symbols == {t1, t2}
    assert not isinstance(T.xreplace({a1: 1}), Pose)


def test_simplify_lambdify_latex_pprint_accept_a_pose(planar, capsys):
    T = planar.arm_matrix()
    assert sp.simplify(T) == T.matrix
    assert sp.trigsimp(T) == T.matrix
    assert float(sp.N(T.subs({s: 0 for s in T.free_symbols}))[0, 0]) == 1.0
    f = sp.lambdify([*planar.variables, *planar.table.constants], T, "numpy")
    np.testing.assert_allclose(f(0.0, 0.0, 1.0, 0.8)[:3, 3], [1.8, 0.0, 0.0])
    g = sp.lambdify([*planar.variables, *planar.table.constants], T)  # default modules
    assert g(0.0, 0.0, 1.0, 0.8)[0, 3] == pytest.approx(1.8)
    h = sp.lambdify([*planar.variables, *planar.table.constants], T, "sympy")
    assert h(0, 0, 1, 2)[0, 3] == 3
    assert sp.latex(T).startswith(r"\begin{bmatrix}C_{12} & -S_{12} & 0 & a_{1} C_{1}")
    sp.pprint(T, use_unicode=True)
    out = capsys.readouterr().out
    assert "C₁₂" in out and "S₁⋅a₁ + S₁₂⋅a₂" in out and "cos" not in out
    assert sp.sstr(T).startswith("Matrix([\n[C12, -S12, 0, a1*C1 + a2*C12],")
    assert str(T).startswith("T0_2 = Matrix([")
    assert eval(sp.srepr(T), vars(sp)) == T.matrix  # noqa: S307 - sympy's own repr


def test_equality_and_hash_are_the_matrix(planar):
    T = planar.arm_matrix()
    assert T == T.matrix and T.matrix == T
    assert hash(T) == hash(T.matrix)
    assert {T.matrix: 1}[T] == 1


def test_pickle_and_copy_keep_the_labels(puma):
    T = puma.transform(2, 5)
    for other in (pickle.loads(pickle.dumps(T)), copy.deepcopy(T), copy.copy(T)):
        assert isinstance(other, Pose) and other == T
        assert (other.frm, other.to, other.word) == (2, 5, T.word)
        assert other.text() == T.text()


def test_existing_api(puma):
    T = puma.arm_matrix()
    assert T.label_latex == "{}^{0}T_{6}" and T.label_text == "T0_6"
    assert T.n == T.matrix[:3, 0] and T.s == T.matrix[:3, 1] and T.a == T.matrix[:3, 2]
    assert T.position == T.matrix[:3, 3] and T.rotation == T.matrix[:3, :3]
    assert T.count_ops() == sum(sp.count_ops(e) for e in T.matrix)
    assert T.latex() == puma.notation.latex(T.matrix)
    assert T.text() == puma.notation.text(T.matrix)
    vals = {s: 0 for s in T.free_symbols}
    assert T.evalf(vals) == sp.ImmutableMatrix(T.matrix.evalf(subs=vals))
    assert float(T.evalf(3, subs=vals)[0, 0]) == 1.0
    assert T._repr_latex_().startswith("$${}^{0}T_{6} = \\begin{bmatrix}")


def test_a_pose_must_be_4x4():
    with pytest.raises(ValueError, match="4×4"):
        Pose(sp.eye(3), 0, 1)


def test_latex_of_table_robot_and_derivation(planar):
    from dhsym.notation.tables import table_latex

    assert sp.latex(planar.table) == table_latex(planar.table)
    assert sp.latex(planar) == table_latex(planar.table)
    d = dhsym.derive("planar2r")
    assert sp.latex(d) == d.to_latex()
    assert r"\begin{array}" in sp.latex(planar.table)


def test_merged_notation_keeps_both_labels_and_the_style():
    from dhsym.kinematics.pose import _merge
    from dhsym.notation.printers import TrigStyle

    t1, t2 = sp.symbols("theta1 theta2", real=True)
    a = Notation.from_variables([t1], ["1"], style=TrigStyle.LOWER)
    b = Notation.from_variables([t2], ["2"])
    merged = _merge(a, b)
    assert dict(merged.labels) == {t1: "1", t2: "2"}
    assert merged.style is TrigStyle.LOWER and merged.compact == a.compact
