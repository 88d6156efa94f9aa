"""The seeds' matrices, reproduced by KinematicChain (entry by entry)."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.errors import DHError
from dhsym.kinematics.chain import KinematicChain
from dhsym.model.table import DHRow, DHTable

S = lambda n: sp.Symbol(n, real=True)  # noqa: E731
t1, t2, t3, t4, t5, t6 = (S(f"theta{i}") for i in range(1, 7))
a1, a2, a3, a4 = (S(f"a{i}") for i in range(1, 5))
d1, d3, d4, d6 = (S(n) for n in ("d1", "d3", "d4", "d6"))
c, s = sp.cos, sp.sin


def test_planar_2r_matches_seed_001():
    r = dhsym.load("planar2r")
    H01 = sp.Matrix(
        [[c(t1), -s(t1), 0, a1 * c(t1)], [s(t1), c(t1), 0, a1 * s(t1)], [0, 0, 1, 0], [0, 0, 0, 1]]
    )
    H12 = sp.Matrix(
        [[c(t2), -s(t2), 0, a2 * c(t2)], [s(t2), c(t2), 0, a2 * s(t2)], [0, 0, 1, 0], [0, 0, 0, 1]]
    )
    T02 = sp.Matrix(
        [
            [c(t1 + t2), -s(t1 + t2), 0, a1 * c(t1) + a2 * c(t1 + t2)],
            [s(t1 + t2), c(t1 + t2), 0, a1 * s(t1) + a2 * s(t1 + t2)],
            [0, 0, 1, 0],
            [0, 0, 0, 1],
        ]
    )
    assert r.link_matrix(1).matrix == H01
    assert r.link_matrix(2).matrix == H12
    assert r.arm_matrix().matrix == T02  # structurally identical, not just equal
    assert r.arm_matrix().text().splitlines()[1:3] == [
        "[C12, -S12, 0, a1*C1 + a2*C12],",
        "[S12,  C12, 0, a1*S1 + a2*S12],",
    ]


def test_example_4_link_matrices_match_seed_001():
    r = dhsym.load("example4_6dof")
    expected = [
        [[c(t1), 0, s(t1), 0], [s(t1), 0, -c(t1), 0], [0, 1, 0, d1]],
        [[c(t2), -s(t2), 0, a2 * c(t2)], [s(t2), c(t2), 0, a2 * s(t2)], [0, 0, 1, 0]],
        [
            [c(t3 + sp.pi / 2), 0, s(t3 + sp.pi / 2), 0],
            [s(t3 + sp.pi / 2), 0, -c(t3 + sp.pi / 2), 0],
            [0, 1, 0, 0],
        ],
        [[c(t4), 0, -s(t4), 0], [s(t4), 0, c(t4), 0], [0, -1, 0, d4]],
        [[c(t5), 0, s(t5), 0], [s(t5), 0, -c(t5), 0], [0, 1, 0, 0]],
        [[c(t6), -s(t6), 0, 0], [s(t6), c(t6), 0, 0], [0, 0, 1, d6]],
    ]
    for i, rows in enumerate(expected, start=1):
        M = sp.Matrix([*rows, [0, 0, 0, 1]])
        assert r.link_matrix(i).matrix == M, f"T_{i}^{i - 1}"
    # cos(theta3 + pi/2) is -sin(theta3): the offset is carried exactly
    assert r.link_matrix(3)[0, 0] == -s(t3)


def test_puma560_at_zero_is_the_toolbox_value_of_seed_001():
    r = dhsym.load("puma560")
    T = r.fk([0, 0, 0, 0, 0, 0])
    expected = np.array([[1, 0, 0, 0.4521], [0, 1, 0, -0.15005], [0, 0, 1, 0.4318], [0, 0, 0, 1]])
    np.testing.assert_allclose(T, expected, atol=1e-12)
    # the printout rounds -0.15005 to -0.15
    assert round(T[1, 3], 2) == -0.15


def test_puma560_reaches_the_nested_c23_form():
    r = dhsym.load("puma560")
    T = r.arm_matrix()
    assert r.verify()
    text = T.text()
    assert "C23" in text and "S23" in text
    assert T.count_ops() <= 277  # what trigsimp reaches on the same table


# Craig, Introduction to Robotics, eq. 3.14 (the textbook's printed closed form)
c1, s1, c23, s23 = c(t1), s(t1), c(t2 + t3), s(t2 + t3)
c2, s2 = c(t2), s(t2)
c4, s4, c5, s5, c6, s6 = c(t4), s(t4), c(t5), s(t5), c(t6), s(t6)
CRAIG = sp.Matrix(
    [
        [
            c1 * (c23 * (c4 * c5 * c6 - s4 * s6) - s23 * s5 * c6) + s1 * (s4 * c5 * c6 + c4 * s6),
            c1 * (c23 * (-c4 * c5 * s6 - s4 * c6) + s23 * s5 * s6) + s1 * (c4 * c6 - s4 * c5 * s6),
            -c1 * (c23 * c4 * s5 + s23 * c5) - s1 * s4 * s5,
            c1 * (a2 * c2 + a3 * c23 - d4 * s23) - d3 * s1,
        ],
        [
            s1 * (c23 * (c4 * c5 * c6 - s4 * s6) - s23 * s5 * c6) - c1 * (s4 * c5 * c6 + c4 * s6),
            s1 * (c23 * (-c4 * c5 * s6 - s4 * c6) + s23 * s5 * s6) - c1 * (c4 * c6 - s4 * c5 * s6),
            -s1 * (c23 * c4 * s5 + s23 * c5) + c1 * s4 * s5,
            s1 * (a2 * c2 + a3 * c23 - d4 * s23) + d3 * c1,
        ],
        [
            -s23 * (c4 * c5 * c6 - s4 * s6) - c23 * s5 * c6,
            -s23 * (-c4 * c5 * s6 - s4 * c6) + c23 * s5 * s6,
            s23 * c4 * s5 - c23 * c5,
            -a3 * s23 - a2 * s2 - d4 * c23,
        ],
        [0, 0, 0, 1],
    ]
)


def test_modified_puma560_equals_craigs_printed_closed_form():
    r = dhsym.load("puma560_modified")
    T = r.arm_matrix()
    assert dhsym.kinematics.simplification.prove_equal(T.matrix, CRAIG)
    assert r.verify()
    craig_ops = sum(sp.count_ops(e) for e in CRAIG)
    assert T.count_ops() <= craig_ops
    assert T.count_ops() <= 277


@pytest.mark.parametrize("n", [1, 2, 3, 4, 5, 8, 20])
def test_planar_nr_closed_form(n):
    r = dhsym.Robot(dhsym.planar_chain(n))
    T = r.arm_matrix().matrix
    th = [S(f"theta{k}") for k in range(1, n + 1)]
    a = [S(f"a{k}") for k in range(1, n + 1)]
    assert T[0, 0] == c(sum(th))
    assert T[0, 3] == sum(a[k] * c(sum(th[: k + 1])) for k in range(n))
    assert T[1, 3] == sum(a[k] * s(sum(th[: k + 1])) for k in range(n))


def test_planar_4r_prints_c1234():
    r = dhsym.load("planar4r")
    assert "C1234" in r.arm_matrix().text()
    assert r.arm_matrix().text().count("a4*C1234") == 1


def test_example_i_twist_180_standard_and_modified():
    r = dhsym.load("example1_rrp")
    T = r.arm_matrix().matrix
    # standard: the 180 twist lies between joints 2 and 3; theta1 + theta2 combine, z flips
    assert T[:3, :3] == sp.Matrix(
        [[c(t1 + t2), s(t1 + t2), 0], [s(t1 + t2), -c(t1 + t2), 0], [0, 0, -1]]
    )
    assert r.verify()
    # read as a modified table the twist sits between joints 1 and 2: theta1 - theta2
    mod = dhsym.Robot(dhsym.DHTable(r.table.rows, dhsym.Convention.MODIFIED))
    M = mod.arm_matrix()
    assert M.matrix[0, 0] == c(t1 - t2)
    assert "C[1-2]" in M.text()
    assert mod.verify()


def test_scara_joint_4_enters_with_a_minus_sign():
    r = dhsym.load("scara")
    assert "C[12-4]" in r.arm_matrix().text()
    assert r.verify()


def test_transform_any_pair_and_inverse():
    r = dhsym.load("puma560")
    T02 = r.transform(0, 2).matrix
    T25 = r.transform(2, 5).matrix
    T05 = r.transform(0, 5).matrix
    assert dhsym.kinematics.simplification.numeric_equal(T02 * T25, T05)
    T50 = r.transform(5, 0).matrix
    assert dhsym.kinematics.simplification.numeric_equal(T50 * T05, sp.eye(4))


def test_inverse_of_2r_is_compact():
    r = dhsym.load("planar2r")
    assert r.transform(2, 0)[0, 3] == -a1 * c(t2) - a2


@pytest.mark.parametrize("name", dhsym.builtin_names())
def test_every_builtin_is_exactly_its_plain_product(name):
    r = dhsym.load(name)
    assert r.verify()
    for i in range(1, r.n + 1):
        assert r.verify(i - 1, i)


def test_fk_batch_equals_single():
    r = dhsym.load("puma560")
    rng = np.random.default_rng(1)
    Q = rng.uniform(-3, 3, size=(50, 6))
    batch = r.fk(Q)
    assert batch.shape == (50, 4, 4)
    for k in (0, 17, 49):
        np.testing.assert_allclose(batch[k], r.fk(Q[k]), atol=1e-14)


def test_fk_degrees():
    r = dhsym.load("planar2r")
    np.testing.assert_allclose(r.fk([90, 0], deg=True)[:2, 3], [0, 1.8], atol=1e-12)


def test_fk_needs_values_for_symbols():
    r = dhsym.Robot(dhsym.planar_chain(2))
    with pytest.raises(dhsym.DHError, match="no numeric value for a1, a2"):
        r.fk([0, 0])
    np.testing.assert_allclose(r.fk([0, 0], values={"a1": 1, "a2": 2})[0, 3], 3)


def _dh(theta: float, d: float, a: float, alpha: float) -> np.ndarray:
    ct, st, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
    return np.array(
        [
            [ct, -st * ca, st * sa, a * ct],
            [st, ct * ca, -ct * sa, a * st],
            [0, sa, ca, d],
            [0, 0, 0, 1],
        ]
    )


def test_sixty_twisted_joints_fk_without_a_closed_form():
    """The closed form of ^0T_60 would be astronomically large: fk multiplies small parts."""
    n = 60
    rows = [
        DHRow.revolute(f"q{k}", d=0.1, a=0.2, alpha=(-1) ** k * sp.pi / 2) for k in range(1, n + 1)
    ]
    robot = KinematicChain(DHTable.from_rows(rows, name="snake"))
    assert robot.transform_size(0, n) > 10**12
    with pytest.raises(DHError, match="too large to write out in closed form"):
        robot.transform(0, n)
    q = np.linspace(-1.0, 1.0, n)
    expected = np.eye(4)
    for k in range(n):
        expected = expected @ _dh(q[k], 0.1, 0.2, (-1) ** (k + 1) * np.pi / 2)
    assert np.allclose(robot.fk(q), expected, atol=1e-12)
    assert np.allclose(robot.fk(np.stack([q, q]))[1], expected, atol=1e-12)
    assert np.allclose(robot.fk_function(n, 0)(q) @ expected, np.eye(4), atol=1e-12)


def test_measured_constants_take_the_float_path_with_the_same_numbers() -> None:
    # issue 32 (e): a skewed measured axis read as huge exact rationals; its closed form
    # compiled huge radicals on the first fk, the elementary transforms as floats do not
    from dhsym.kinematics.constants import measured
    from dhsym.kinematics.transforms import chain_word, plain_product

    big = sp.Rational(123456789123456789123, 10**21)
    twist = sp.atan(sp.Rational(987654321987654321987, 10**21) / big)
    rows = [
        DHRow.revolute("theta1", d=big, alpha=twist),
        DHRow.revolute(sp.Symbol("theta2", real=True) + twist, a=sp.sqrt(big)),
        DHRow.revolute("theta3", a=sp.Rational(3, 10)),
    ]
    chain = KinematicChain(DHTable.from_rows(rows))
    assert measured(rows[0].d) and not measured(rows[2].a)
    q = [0.3, -0.7, 1.1]
    exact = plain_product(chain_word(chain.table, 0, 3))
    at = dict(zip(chain.variables, map(sp.Float, q)))
    want = np.array(exact.xreplace(at).evalf(30), dtype=float)
    assert np.abs(chain.fk(q) - want).max() < 1e-12
