"""The general 6R solver: every real solution, checked by fk, complete against a multi-start
numeric search, on the Kinova Jaco and Mico, random arms in both conventions, and the
degenerate arms (PUMA, UR5) it must either solve completely or refuse clearly."""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from dhsym.errors import DHError
from dhsym.ik.general6r import (
    EQUATIONS,
    General6R,
    elimination_matrices,
    general_6r,
    standard_chain,
)
from dhsym.kinematics.numeric import word_product
from dhsym.kinematics.transforms import chain_word
from dhsym.model.library import builtin_table
from dhsym.model.table import DHRow, DHTable, Elementary
from dhsym.model.tablefile import read_table
from dhsym.robot import Robot

from .._multistart import contains, multistart_lm, wrapped_distance

DATA = Path(__file__).resolve().parents[2] / "data" / "general6r"


@functools.cache
def _solver(name: str) -> General6R:
    if name in ("jaco", "mico", "ur5"):
        return general_6r(read_table(DATA / f"{name}.yaml"))
    return general_6r(builtin_table(name))


def _random_table(seed: int, convention: str = "standard") -> DHTable:
    rng = np.random.default_rng(seed)
    rows = [
        DHRow.revolute(
            f"q{i}",
            d=float(rng.uniform(-0.5, 0.5)),
            a=float(rng.uniform(-0.5, 0.5)),
            alpha=float(rng.uniform(-3.0, 3.0)),
        )
        for i in range(1, 7)
    ]
    return DHTable.from_rows(rows, convention=convention, snap_angles=False, name=f"arm {seed}")


@functools.cache
def _random_solver(seed: int, convention: str) -> General6R:
    return general_6r(_random_table(seed, convention))


def _check_all(solver: General6R, q: np.ndarray, fk=None) -> np.ndarray:
    """Solve fk(q): q is among the solutions, each reproduces the pose, all distinct."""
    fk = fk or solver.fk
    T = fk(q)
    Q = solver.solve(T)
    assert 1 <= len(Q) <= 16
    assert contains(Q, q), (q, Q)
    assert np.abs(fk(Q)[:, :3, :] - T[:3, :]).max() < 1e-9
    assert all(wrapped_distance(a, b) > 1e-6 for i, a in enumerate(Q) for b in Q[:i])
    assert (np.abs(Q) <= np.pi + 1e-12).all()
    return Q


# --- the Kinova arms (roboticstoolbox DH models) --------------------------------------------


@pytest.mark.parametrize("name", ["jaco", "mico"])
def test_kinova_arms_recover_every_random_configuration(name):
    solver = _solver(name)
    rng = np.random.default_rng(7)
    counts = set()
    for q in rng.uniform(-np.pi, np.pi, (150, 6)):
        counts.add(len(_check_all(solver, q)))
    assert max(counts) >= 8  # the Jaco has poses with many real solutions, not just the given one


def test_jaco_solutions_reproduce_the_pose_under_the_closed_form_fk():
    """The solver's check (the elementary word) agrees with Robot.fk_function (closed form)."""
    table = read_table(DATA / "jaco.yaml")
    robot_fk = Robot(table).fk_function()
    solver = general_6r(table, fk=robot_fk)
    rng = np.random.default_rng(3)
    for q in rng.uniform(-np.pi, np.pi, (20, 6)):
        _check_all(solver, q, fk=robot_fk)


def test_jaco_table_is_the_toolbox_model():
    """Spot values of the roboticstoolbox model: flipped joint 1, offsets, 60° wrist twists."""
    links, base, tool = standard_chain(read_table(DATA / "jaco.yaml"))
    assert [L.sign for L in links] == [-1, 1, 1, 1, 1, 1]
    assert [L.offset for L in links] == [0, -sp.pi / 2, sp.pi / 2, 0, -sp.pi, sp.pi * 5 / 9]
    assert [L.alpha for L in links] == [sp.pi / 2, sp.pi, sp.pi / 2, sp.pi / 3, sp.pi / 3, sp.pi]
    assert float(links[3].d) == pytest.approx(-(0.2073 + 0.0743 / np.sqrt(3)))
    assert base == () and tool == ()


# --- random general arms ----------------------------------------------------------------


@pytest.mark.parametrize("convention", ["standard", "modified"])
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_random_arms_recover_q(seed, convention):
    solver = _random_solver(seed, convention)
    assert solver.arrangement.project is None  # a general arm: the 12×12 pencil
    rng = np.random.default_rng(seed + 100)
    for q in rng.uniform(-np.pi, np.pi, (60, 6)):
        _check_all(solver, q)


@settings(max_examples=12, deadline=None)
@given(
    seed=st.integers(0, 10**6),
    convention=st.sampled_from(["standard", "modified"]),
    q=st.lists(st.floats(-np.pi, np.pi), min_size=6, max_size=6),
)
def test_any_random_arm_and_configuration(seed, convention, q):
    _check_all(_random_solver(seed % 40, convention), np.array(q))


@pytest.mark.slow
@pytest.mark.parametrize(
    "arm", [("random", 11), ("random", 12), ("random", 13), ("jaco", 0), ("mico", 0)]
)
def test_no_solution_found_by_a_multistart_search_is_missing(arm):
    """Completeness: 200 Levenberg–Marquardt starts never find a solution the solver lacks."""
    kind, seed = arm
    solver = _random_solver(seed, "standard") if kind == "random" else _solver(kind)
    rng = np.random.default_rng(seed + 500)
    for q in rng.uniform(-np.pi, np.pi, (2, 6)):
        T = solver.fk(q)
        Q = solver.solve(T)
        found = multistart_lm(solver.fk, T, 200, seed=seed)
        assert len(found) >= 1
        missing = [f for f in found if not contains(Q, f, 1e-5)]
        assert not missing, (missing, Q)


def test_the_multistart_reference_finds_solutions():
    """The reference itself works: on a random arm it finds the generating q or another."""
    solver = _random_solver(1, "standard")
    q = np.array([0.4, -1.0, 2.0, 0.3, -0.6, 1.4])
    found = multistart_lm(solver.fk, solver.fk(q), 40)
    assert len(found) >= 1
    assert np.abs(solver.fk(found)[:, :3, :] - solver.fk(q)[:3, :]).max() < 1e-9


# --- special poses and the eliminated joint ----------------------------------------------


@pytest.mark.parametrize("value", [np.pi, -np.pi / 2, 0.0])
def test_eliminated_joint_at_a_half_turn_and_other_special_values(value):
    """θ3 = π is x3 = ∞: the Möbius shift (or QZ) still finds it."""
    solver = _random_solver(2, "standard")
    rng = np.random.default_rng(9)
    for q in rng.uniform(-np.pi, np.pi, (5, 6)):
        q[2] = value
        _check_all(solver, q)
        q[3] = q[4] = np.pi  # x4, x5 = ∞ too
        _check_all(solver, q)


def test_solutions_are_independent_of_the_pencil_shift(monkeypatch):
    from dhsym.ik.general6r import eigenproblem as g

    solver = _random_solver(3, "modified")
    q = np.array([0.2, 1.1, -2.5, 0.7, 2.9, -1.3])
    Tp = solver.arrangement.target(solver.fk(q))

    def wrap(x):
        return np.sort(np.remainder(x + np.pi, 2 * np.pi) - np.pi)

    base = wrap(g._candidates(solver.arrangement, Tp)[:, 2])
    monkeypatch.setattr(g, "_SHIFTS", (0.9,))
    other = wrap(g._candidates(solver.arrangement, Tp)[:, 2])
    assert len(base) == len(other)
    assert np.abs(np.remainder(base - other + np.pi, 2 * np.pi) - np.pi).max() < 1e-6


def test_qz_gives_the_same_roots_as_the_companion_matrix():
    from dhsym.ik.general6r import eigenproblem as g

    solver = _random_solver(1, "standard")
    Tp = solver.arrangement.target(solver.fk(np.array([0.3, -0.2, 1.0, 2.0, -1.0, 0.5])))
    big = g._pencil(solver.arrangement, Tp, 0.0)[0]
    x1 = g._eigen(big)[0]
    x2 = g._eigen_qz(big)[0]
    real1 = np.sort(x1[np.abs(x1.imag) < 1e-8].real)
    real2 = np.sort(x2[np.abs(x2.imag) < 1e-8].real)
    assert np.allclose(real1, real2, rtol=1e-7)


def test_unreachable_pose_has_no_solution():
    solver = _random_solver(1, "standard")
    T = np.eye(4)
    T[:3, 3] = [50.0, 0.0, 0.0]
    assert solver.solve(T).shape == (0, 6)


# --- the degenerate arms: solved completely, or refused clearly -----------------------------


def test_puma_is_solved_completely_by_the_reversed_16x16_pencil():
    solver = _solver("puma560")
    assert solver.eliminated == 4 and solver.arrangement.project is not None
    rng = np.random.default_rng(4)
    for q in rng.uniform(-np.pi, np.pi, (40, 6)):
        Q = _check_all(solver, q)
        if abs(np.sin(q[4])) > 0.05:  # away from the wrist singularity: the 8 of the lecture
            assert len(Q) == 8


def test_puma_modified_table_is_solved_too():
    solver = _solver("puma560_modified")
    rng = np.random.default_rng(5)
    for q in rng.uniform(-np.pi, np.pi, (20, 6)):
        _check_all(solver, q)


def test_ur5_is_solved_with_at_most_eight_solutions():
    solver = _solver("ur5")
    rng = np.random.default_rng(6)
    for q in rng.uniform(-np.pi, np.pi, (40, 6)):
        assert len(_check_all(solver, q)) <= 8


def test_planar_arm_is_refused_with_a_clear_error():
    rows = [DHRow.revolute(f"q{i}", a=0.3 + 0.1 * i) for i in range(1, 7)]
    with pytest.raises(DHError, match="degenerates on this arm.*closed-form family"):
        general_6r(DHTable.from_rows(rows, name="planar 6R"))


def test_bad_tables_are_refused():
    with pytest.raises(DHError, match="row 3, field type: joint 3 is prismatic"):
        general_6r(builtin_table("stanford"))
    with pytest.raises(DHError, match="needs six joints"):
        general_6r(builtin_table("planar2r").with_values({"a1": 1, "a2": 1}))
    rows = [DHRow.revolute(f"q{i}", a="a1" if i == 2 else 0.2, alpha=0.5) for i in range(1, 7)]
    with pytest.raises(DHError, match="row 2, field a: a = a1 has no numeric value"):
        general_6r(DHTable.from_rows(rows, snap_angles=False))
    rows = [DHRow.revolute(f"2*q{i}", a=0.2, alpha=0.5) for i in range(1, 7)]
    with pytest.raises(DHError, match=r"row 1, field theta: theta = 2\*q1 is not ±q1"):
        general_6r(DHTable.from_rows(rows, snap_angles=False))
    solver = _random_solver(1, "standard")
    with pytest.raises(DHError, match="expected one finite 4×4 pose"):
        solver.solve(np.eye(3))


# --- the standard form and the exact matrices ----------------------------------------------


@pytest.mark.parametrize("convention", ["standard", "modified"])
def test_standard_chain_and_its_reverse_reproduce_the_table(convention):
    from dhsym.ik.general6r.elimination import _standard

    table = _random_table(5, convention)
    table = DHTable(
        table.rows,
        table.convention,
        base=(Elementary("T", "z", sp.Rational(1, 5)), Elementary("R", "y", sp.Rational(3, 10))),
        tool=(Elementary("T", "x", sp.Rational(1, 10)),),
    )
    chain = _standard(table)
    ends = (-1, table.n + 1)
    fk = lambda q: word_product(  # noqa: E731
        chain_word(table, *ends), {v: np.array([x]) for v, x in zip(table.variables, q)}, 1
    )[0]
    q = np.array([0.3, -1.1, 2.0, 0.4, -2.2, 0.9])

    def standard_fk(c):
        word = list(c.base)
        for L in c.links:
            theta = L.sign * sp.Float(q[L.joint]) + L.offset
            word += [Elementary("R", "z", theta), Elementary("T", "z", L.d)]
            word += [Elementary("T", "x", L.a), Elementary("R", "x", L.alpha)]
        return word_product(word + list(c.tool), {}, 1)[0]

    assert np.allclose(standard_fk(chain), fk(q), atol=1e-12)
    assert np.allclose(standard_fk(chain.reversed()), np.linalg.inv(fk(q)), atol=1e-12)
    solver = general_6r(table)
    _check_all(solver, q)


def test_exact_matrices_vanish_at_every_configuration():
    """P(θ3) m45 − Q m12 = 0 at a random configuration, with l, p from the pose."""
    table = read_table(DATA / "jaco.yaml")
    m = elimination_matrices(table)
    assert m.P.shape == (14, 9) and m.Q.shape == (14, 8) and len(m.equations) == 14
    assert m.equations == EQUATIONS
    assert m.Q.free_symbols <= set(m.direction) | set(m.point)
    links, _, _ = standard_chain(table)
    q = np.array([0.7, -0.4, 1.9, -2.3, 0.5, 1.2])
    theta = [float(L.sign * q[L.joint] + L.offset) for L in links]
    T = Robot(table).fk(q)
    alpha6, a6, d6 = (float(links[5].alpha), float(links[5].a), float(links[5].d))
    R = T[:3, :3]
    u = R @ [0.0, np.sin(alpha6), np.cos(alpha6)]
    p = R @ [-a6, -d6 * np.sin(alpha6), -d6 * np.cos(alpha6)] + T[:3, 3]
    th = sp.symbols("theta1:7", real=True)
    subs = dict(zip(th, theta)) | dict(zip(m.direction, u)) | dict(zip(m.point, p))
    residual = np.array(m.residual().subs(subs).evalf(), dtype=float)
    assert np.abs(residual).max() < 1e-12
    # and a wrong configuration does not satisfy them
    subs[th[2]] = theta[2] + 0.1
    assert np.abs(np.array(m.residual().subs(subs).evalf(), dtype=float)).max() > 1e-3


def test_exact_matrices_print_through_sympy():
    m = _solver("jaco").matrices()
    text = sp.latex(m.P[0, :])
    assert r"\cos{\left(\theta_{3} \right)}" in text
    assert "sqrt" not in str(m.Q) or m.Q.has(sp.sqrt(3))


_TWISTS = [sp.Integer(0), sp.pi / 2, -sp.pi / 2, sp.pi, sp.pi / 3]
_LENGTHS = [sp.Integer(0), sp.Rational(3, 10), sp.Rational(-1, 5), sp.Rational(1, 2)]


@pytest.mark.slow
@settings(max_examples=15, deadline=None)
@given(
    rows=st.lists(
        st.tuples(st.sampled_from(_LENGTHS), st.sampled_from(_LENGTHS), st.sampled_from(_TWISTS)),
        min_size=6,
        max_size=6,
    ),
    convention=st.sampled_from(["standard", "modified"]),
    seed=st.integers(0, 1000),
)
def test_lab_like_arms_are_solved_or_refused_never_silently_wrong(rows, convention, seed):
    """Arms with exact right twists and zero lengths: a DHError, or q recovered every time."""
    table = DHTable.from_rows(
        [DHRow.revolute(f"q{i}", d=d, a=a, alpha=al) for i, (d, a, al) in enumerate(rows, 1)],
        convention=convention,
    )
    try:
        solver = general_6r(table)
    except DHError as err:
        assert "degenerates on this arm" in str(err)
        return
    for q in np.random.default_rng(seed).uniform(-np.pi, np.pi, (10, 6)):
        _check_all(solver, q)


@pytest.mark.parametrize("scipy_missing", [False, True])
def test_ill_conditioned_leading_matrix_goes_to_qz_or_the_best_shift(monkeypatch, scipy_missing):
    """When every shift leaves A nearly singular: QZ, or without scipy the best companion."""
    from dhsym.ik.general6r import eigenproblem as g

    solver = _random_solver(1, "standard")
    eigen = g._eigen
    monkeypatch.setattr(g, "_eigen", lambda big: (*eigen(big)[:2], 1e12))
    if scipy_missing:

        def no_scipy(big):
            raise ImportError("scipy")

        monkeypatch.setattr(g, "_eigen_qz", no_scipy)
    rng = np.random.default_rng(12)
    for q in rng.uniform(-np.pi, np.pi, (10, 6)):
        _check_all(solver, q)


#: A random arm (d, a, α per row, standard DH) and a configuration whose pose has 16 real
#: solutions, the most a 6R can have: found by a seeded search (numpy default_rng(282) arm,
#: random perturbations of q keeping the count), not a published example.
SIXTEEN_ARM = [
    (0.24905811658648624, -0.6481798773203156, 1.3378870324620493),
    (0.4198882791648999, -0.7649114851991277, 1.5334757916983177),
    (-0.745854916017751, 0.004571845524325324, 1.7484583298120153),
    (-0.7403610230678768, 0.6322588568529004, 1.6429507728344088),
    (-0.6441019919639881, 0.06291112033039337, -1.3361058577150604),
    (-0.21279832198445248, -0.9649733094150885, -1.6263504538706948),
]
SIXTEEN_Q = [1.2246131030053473, 4.897295722694401, 3.3592513985522623, 1.2892191310844185,
             3.53638232076342, -2.3611108383310166]  # fmt: skip


def _sixteen() -> General6R:
    rows = [
        DHRow.revolute(f"q{i}", d=d, a=a, alpha=al) for i, (d, a, al) in enumerate(SIXTEEN_ARM, 1)
    ]
    return general_6r(DHTable.from_rows(rows, snap_angles=False, name="sixteen"))


def test_a_pose_with_sixteen_real_solutions_gives_all_sixteen():
    Q = _check_all(_sixteen(), np.array(SIXTEEN_Q))
    assert len(Q) == 16


@pytest.mark.slow
def test_the_multistart_search_finds_nothing_beyond_the_sixteen():
    solver = _sixteen()
    T = solver.fk(np.array(SIXTEEN_Q))
    Q = solver.solve(T)
    found = multistart_lm(solver.fk, T, 300, seed=1)
    assert len(found) >= 8
    assert all(contains(Q, f, 1e-5) for f in found)
