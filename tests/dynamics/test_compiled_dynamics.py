"""Compiled numbers against independent references: a plain-numpy Newton–Euler written
here from the textbook recursions (Luh–Walker–Paul for standard DH as in Spong §7.5 and
Corke; Craig §6.5 for modified DH), and pinocchio's ``rnea``."""

# ruff: noqa: E501  (table rows are one line each, as in a table file)
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import dhsym
from dhsym.model.tablefile import read_table_text
from dhsym.robot import Robot
from tests.conftest import _need

PARAMS = """
  - {{type: R, theta: q1, d: 0.3, a: 0.1, alpha: {al1}, m: 3.0, r: [-0.05, 0.02, 0.1], I: [0.04, 0.05, 0.03, 0.001, -0.002, 0.003], Jm: 0.0002, G: 50}}
  - {{type: R, theta: q2, d: 0.05, a: 0.45, alpha: {al2}, m: 2.5, r: [-0.2, 0.01, 0.02], I: [0.01, 0.06, 0.06, 0.002, 0.001, -0.001]}}
  - {{type: {t3}, theta: {th3}, d: {d3}, a: 0.02, alpha: {al3}, m: 1.2, r: [0.01, -0.03, 0.05], I: [0.02, 0.02, 0.01, 0, 0.001, 0]}}
  - {{type: R, theta: q4, d: 0.4, a: 0, alpha: {al4}, m: 0.6, r: [0, 0.02, -0.01], I: [0.003, 0.002, 0.003, 0, 0, 0.0005]}}
"""


def arm(convention: str, prismatic: bool = False) -> Robot:
    rows = PARAMS.format(
        al1="pi/2",
        al2="0.3" if convention == "standard" else "pi/2",
        al3="-pi/2",
        al4="pi/3",
        t3="P" if prismatic else "R",
        th3="0.4" if prismatic else "q3 + 0.2",
        d3="d3" if prismatic else "0.1",
    )
    text = (
        f"convention: {convention}\nsnap_angles: false\ngravity: [0.5, -1.0, -9.81]\njoints:{rows}"
    )
    return Robot(read_table_text(text))


# --- the textbook recursions, plain numpy -------------------------------------------------------


def _rot_x(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def _rot_z(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def _rows(robot, q):
    """Per row: kind, theta, d, a, alpha as floats; m, r, I, Jm*G^2."""
    out, k = [], 0
    for row in robot.table.rows:
        sub = {row.variable: q[k]} if row.variable is not None else {}
        k += row.variable is not None
        theta, d, a, alpha = (
            float(getattr(row, f).subs(sub)) for f in ("theta", "d", "a", "alpha")
        )
        L = row.inertia
        out.append(
            (
                row.joint.value,
                theta,
                d,
                a,
                alpha,
                float(L.m),
                np.array([float(v) for v in L.r]),
                np.array(L.I.tolist(), dtype=float),
                float(L.Jm * L.G**2),
            )
        )
    return out


def ne_standard(robot, q, qd, qdd, g):
    """Luh, Walker and Paul: z_{i-1} axes, p*_i = o_i - o_{i-1} in frame i."""
    rows = _rows(robot, q)
    n = len(rows)
    z = np.array([0.0, 0, 1])
    w, wd, vd = np.zeros(3), np.zeros(3), -np.asarray(g, float)
    store = []
    for i, (kind, th, d, a, al, m, r, J, arm_) in enumerate(rows):
        Rm = _rot_z(th) @ _rot_x(al)  # ^{i-1}R_i
        Rt = Rm.T
        pstar = np.array([a, d * np.sin(al), d * np.cos(al)])  # o_{i-1} -> o_i in frame i
        if kind == "R":
            w_new = Rt @ (w + z * qd[i])
            wd_new = Rt @ (wd + z * qdd[i] + np.cross(w, z * qd[i]))
            vd_new = np.cross(wd_new, pstar) + np.cross(w_new, np.cross(w_new, pstar)) + Rt @ vd
        else:
            w_new = Rt @ w
            wd_new = Rt @ wd
            vd_new = (
                Rt @ (z * qdd[i] + vd)
                + np.cross(wd_new, pstar)
                + 2 * np.cross(w_new, Rt @ z * qd[i])
                + np.cross(w_new, np.cross(w_new, pstar))
            )
        w, wd, vd = w_new, wd_new, vd_new
        vc = np.cross(wd, r) + np.cross(w, np.cross(w, r)) + vd
        F = m * vc
        N = J @ wd + np.cross(w, J @ w)
        store.append((Rm, pstar, r, F, N, kind, arm_))
    tau = np.zeros(n)
    f, nn = np.zeros(3), np.zeros(3)
    for i in range(n - 1, -1, -1):
        Rm, pstar, r, F, N, kind, arm_ = store[i]
        R_next = store[i + 1][0] if i + 1 < n else np.eye(3)
        nn = R_next @ (nn + np.cross(R_next.T @ pstar, f)) + np.cross(pstar + r, F) + N
        f = R_next @ f + F
        axis = Rm.T @ z  # z_{i-1} in frame i
        tau[i] = (nn @ axis if kind == "R" else f @ axis) + arm_ * qdd[i]
    return tau


def ne_modified(robot, q, qd, qdd, g):
    """Craig, Introduction to Robotics, Eqs. 6.45-6.53 (outward) and 6.49-6.51 (inward)."""
    rows = _rows(robot, q)
    n = len(rows)
    z = np.array([0.0, 0, 1])
    w, wd, vd = np.zeros(3), np.zeros(3), -np.asarray(g, float)
    Rs, ps, out = [], [], []
    for i, (kind, th, d, a, al, m, r, J, arm_) in enumerate(rows):
        Rm = _rot_x(al) @ _rot_z(th)  # ^{i-1}R_i
        p = _rot_x(al) @ np.array([a, 0, 0]) + Rm @ np.array([0, 0, d])  # ^{i-1}P_i
        Rt = Rm.T
        if kind == "R":
            w_new = Rt @ w + qd[i] * z
            wd_new = Rt @ wd + np.cross(Rt @ w, qd[i] * z) + qdd[i] * z
            vd_new = Rt @ (np.cross(wd, p) + np.cross(w, np.cross(w, p)) + vd)
        else:
            w_new = Rt @ w
            wd_new = Rt @ wd
            vd_new = (
                Rt @ (np.cross(wd, p) + np.cross(w, np.cross(w, p)) + vd)
                + 2 * np.cross(w_new, qd[i] * z)
                + qdd[i] * z
            )
        w, wd, vd = w_new, wd_new, vd_new
        vc = np.cross(wd, r) + np.cross(w, np.cross(w, r)) + vd
        out.append((m * vc, J @ wd + np.cross(w, J @ w), r, kind, arm_))
        Rs.append(Rm)
        ps.append(p)
    tau = np.zeros(n)
    f, nn = np.zeros(3), np.zeros(3)
    for i in range(n - 1, -1, -1):
        F, N, r, kind, arm_ = out[i]
        if i + 1 < n:
            R_next, p_next = Rs[i + 1], ps[i + 1]
        else:
            R_next, p_next = np.eye(3), np.zeros(3)
        f_new = R_next @ f + F
        nn = N + R_next @ nn + np.cross(r, F) + np.cross(p_next, R_next @ f)
        f = f_new
        tau[i] = (nn @ z if kind == "R" else f @ z) + arm_ * qdd[i]
    return tau


REFERENCE = {"standard": ne_standard, "modified": ne_modified}


@pytest.mark.slow
@pytest.mark.parametrize("convention", ["standard", "modified"])
@pytest.mark.parametrize("prismatic", [False, True])
def test_rne_matches_the_textbook_recursion(convention, prismatic):
    robot = arm(convention, prismatic)
    g = np.array([0.5, -1.0, -9.81])
    rng = np.random.default_rng(1)
    Q, V, A = (rng.uniform(-2, 2, (6, 4)) for _ in range(3))
    batch = robot.rne(Q, V, A)
    for q, v, a, tau in zip(Q, V, A, batch):
        expected = REFERENCE[convention](robot, q, v, a, g)
        assert np.allclose(tau, expected, atol=1e-10)
        assert np.allclose(robot.rne(q, v, a), expected, atol=1e-10)  # the one-state path


# --- pinocchio --------------------------------------------------------------------------------


def _pinocchio():
    try:
        import pinocchio
    except ImportError:
        pinocchio = None
    _need("pinocchio", pinocchio is not None, "pip install pin")
    return pinocchio


def pin_model(robot):
    """A pinocchio model built from the DH words: a joint at each elementary that holds a
    joint variable, the constant elementaries before it as its placement."""
    pin = _pinocchio()
    from dhsym.kinematics.numeric import elementary_stack, to_float

    robot = Robot(robot.table.substituted())
    model = pin.Model()
    parent, pending = 0, np.eye(4)
    armature = []
    for i, row in enumerate(robot.table.rows, start=1):
        for e in robot.link_word(i):
            var = row.variable
            if var is not None and var in e.value.free_symbols:
                pending = (
                    pending @ elementary_stack(e.kind, e.axis, [to_float(e.value.subs(var, 0))])[0]
                )
                joint = pin.JointModelRZ() if e.kind == "R" else pin.JointModelPZ()
                parent = model.addJoint(
                    parent, joint, pin.SE3(pending[:3, :3], pending[:3, 3]), f"j{i}"
                )
                pending = np.eye(4)
            else:
                pending = pending @ elementary_stack(e.kind, e.axis, [to_float(e.value)])[0]
        L = row.inertia
        inertia = pin.Inertia(
            float(L.m), np.array([float(v) for v in L.r]), np.array(L.I.tolist(), dtype=float)
        )
        model.appendBodyToJoint(parent, inertia, pin.SE3(pending[:3, :3], pending[:3, 3]))
        armature.append(to_float(L.Jm * L.G**2))
    model.armature = np.array(armature)
    model.gravity.linear = np.array([float(v) for v in robot.table.gravity])
    return model


@pytest.mark.slow
@pytest.mark.parametrize("convention", ["standard", "modified"])
@pytest.mark.parametrize("prismatic", [False, True])
def test_rne_matches_pinocchio(convention, prismatic):
    pin = _pinocchio()
    robot = arm(convention, prismatic)
    model = pin_model(robot)
    data = model.createData()
    rng = np.random.default_rng(2)
    Q, V, A = (rng.uniform(-2, 2, (5, 4)) for _ in range(3))
    ours = robot.rne(Q, V, A)
    for q, v, a, tau in zip(Q, V, A, ours):
        assert np.allclose(tau, pin.rnea(model, data, q, v, a), atol=1e-10)
        M = pin.crba(model, data, q)
        M = np.triu(M) + np.triu(M, 1).T
        assert np.allclose(robot.inertia(q), M, atol=1e-10)
        C = pin.computeCoriolisMatrix(model, data, q, v)
        assert np.allclose(robot.coriolis(q, v) @ v, C @ v, atol=1e-10)


@pytest.mark.slow
def test_puma560_against_pinocchio_and_published_gravity_load():
    pin = _pinocchio()
    robot = dhsym.load("puma560")
    qn = np.array([0, np.pi / 4, np.pi, 0, np.pi / 4, 0])
    # roboticstoolbox's Puma560().gravload(qn), from its documentation
    assert np.allclose(robot.gravload(qn), [0, 31.6399, 6.0351, 0, 0.0283, 0], atol=1e-4)
    model = pin_model(robot)
    data = model.createData()
    rng = np.random.default_rng(3)
    Q, V, A = (rng.uniform(-2, 2, (4, 6)) for _ in range(3))
    ours = robot.rne(Q, V, A) - robot.dynamics_functions().friction(V)
    for q, v, a, tau in zip(Q, V, A, ours):
        assert np.allclose(tau, pin.rnea(model, data, q, v, a), atol=1e-9)


# --- the laws ---------------------------------------------------------------------------------


@pytest.mark.slow
def test_forward_dynamics_inverts_rne_and_friction_is_motor_side():
    robot = arm("modified")
    f = robot.dynamics_functions()
    rng = np.random.default_rng(4)
    Q, V, A = (rng.uniform(-2, 2, (7, 4)) for _ in range(3))
    tau = robot.rne(Q, V, A)
    assert np.allclose(robot.accel(Q, V, tau), A, atol=1e-9)
    M = robot.inertia(Q)
    assert np.allclose(M, np.swapaxes(M, -1, -2))
    assert np.all(np.linalg.eigvalsh(M) > 0)
    h = robot.coriolis(Q, V) @ V[..., None]
    assert np.allclose(M @ A[..., None] + h + robot.gravload(Q)[..., None], tau[..., None])
    assert not f.has_friction
    assert np.isclose(M[0, 0, 0] - arm("modified").inertia(Q[0])[0, 0], 0)


def test_friction_and_motor_inertia_follow_roboticstoolbox():
    text = """
joints:
  - {type: R, theta: q1, d: 0, a: 1, alpha: 0, m: 1, r: [-0.5, 0, 0], I: [0, 0.1, 0.1], Jm: 0.001, G: -10, B: 0.01, Tc: [0.2, -0.3]}
"""
    robot = Robot(read_table_text(text))
    g = 9.81 * 0  # gravity along -z: the horizontal arm feels none
    base = 1 * 0.25 + 0.1 + 0.001 * 100  # m lc^2 + Izz + Jm G^2
    assert np.allclose(robot.inertia([0.0]), [[base]])
    assert np.allclose(robot.rne([0.0], [2.0], [0.0]), [0.01 * 100 * 2 + 10 * 0.2 + g])
    assert np.allclose(robot.rne([0.0], [-2.0], [0.0]), [-0.01 * 100 * 2 + 10 * -0.3])
    assert np.allclose(robot.rne([0.0], [0.0], [1.0]), [base])


def test_energy_is_conserved_in_a_free_swing():
    text = """
gravity: [0, -9.81, 0]
joints:
  - {type: R, theta: q1, d: 0, a: 1, alpha: 0, m: 1, r: [-0.5, 0, 0], I: [0.01, 0.1, 0.1]}
  - {type: R, theta: q2, d: 0, a: 0.8, alpha: 0, m: 0.7, r: [-0.4, 0.02, 0], I: [0.01, 0.05, 0.05]}
"""
    robot = Robot(read_table_text(text))
    f = robot.dynamics_functions()
    traj = robot.simulate([0.3, -0.2], [0.0, 1.0], 2.0, dt=1e-3)
    E = f.energy(traj.q, traj.qd)
    assert traj.q.shape == (2001, 2)
    assert np.ptp(E) < 1e-6 * max(1.0, abs(E[0]))
    assert np.ptp(traj.q[:, 0]) > 0.1  # it did swing
    batch = robot.simulate([[0.3, -0.2], [0.0, 0.0]], [[0.0, 1.0], [0.0, 0.0]], 0.1, dt=1e-2)
    assert batch.q.shape == (11, 2, 2)
    assert np.allclose(batch.q[-1, 0], traj.q[100], atol=1e-6)


def test_shapes_follow_fk():
    robot = dhsym.load("planar2r")
    values = {f"{k}{i}": v for i in (1, 2) for k, v in (("m", 1.0), ("rx", -0.3), ("ry", 0.0))}
    values |= {f"rz{i}": 0.0 for i in (1, 2)} | {f"Izz{i}": 0.1 for i in (1, 2)}
    values |= {f"{k}{i}": 0.05 for i in (1, 2) for k in ("Ixx", "Iyy")}
    values |= {f"{k}{i}": 0.0 for i in (1, 2) for k in ("Ixy", "Iyz", "Ixz")}
    assert robot.rne([0, 0], [0, 0], [0, 0], values=values).shape == (2,)
    assert robot.rne(np.zeros((3, 5, 2)), 0.0 * np.ones(2), np.ones(2), values=values).shape == (
        3,
        5,
        2,
    )
    assert robot.inertia(np.zeros((4, 2)), values=values).shape == (4, 2, 2)
    assert robot.coriolis(np.zeros((4, 2)), np.ones((4, 2)), values=values).shape == (4, 2, 2)
    with pytest.raises(dhsym.DHError, match="no numeric value"):
        robot.rne([0, 0], [0, 0], [0, 0])


def test_batches_longer_than_a_chunk_equal_their_states():
    from dhsym.kinematics.numeric import CHUNK

    robot = arm("standard")
    rng = np.random.default_rng(6)
    Q, V, A = (rng.uniform(-2, 2, (CHUNK + 3, 4)) for _ in range(3))
    tau = robot.rne(Q, V, A)
    for k in (0, CHUNK - 1, CHUNK, CHUNK + 2):
        np.testing.assert_allclose(tau[k], robot.rne(Q[k], V[k], A[k]), rtol=1e-12, atol=1e-12)


def test_a_long_run_of_small_calls_switches_to_the_compiled_program_with_the_same_numbers(
    tmp_path, monkeypatch
) -> None:
    """After COMPILE_AFTER small calls τ comes from the compiled program (kept in the disk
    cache), and agrees with the numeric recursion; batches stay on the recursion."""
    from dhsym.dynamics import compiled_dynamics as cd

    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "c"))
    monkeypatch.delenv("DHSYM_NO_CACHE", raising=False)
    monkeypatch.setattr(cd, "COMPILE_AFTER", 3)
    f = cd.dynamics_functions(arm("standard", prismatic=True))
    rng = np.random.default_rng(5)
    q, qd, qdd = rng.uniform(-1, 1, (3, 4))
    before = [f.rne(q, qd, qdd) for _ in range(3)]
    assert f._compiled._program is None  # not compiled yet
    after = f.rne(q, qd, qdd)
    assert f._compiled._program is not None
    np.testing.assert_allclose(after, before[0], rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(f.accel(q, qd, after), qdd, rtol=1e-9, atol=1e-10)
    batch = rng.uniform(-1, 1, (100, 4))
    np.testing.assert_allclose(
        f.rne(batch, batch, batch)[7], f.rne(batch[7], batch[7], batch[7]), rtol=1e-10, atol=1e-12
    )
    warm = cd.dynamics_functions(arm("standard", prismatic=True))
    monkeypatch.setattr(cd, "COMPILE_AFTER", 0)
    np.testing.assert_allclose(warm.rne(q, qd, qdd), after, rtol=1e-12, atol=1e-14)


# --- one state in C ---------------------------------------------------------------------------


def _native_rows():
    """The export room's compiler of the τ program into C (what ``Robot`` passes in)."""
    from dhsym.export.shared_library import native_compiler, native_rows

    _need("a C compiler", native_compiler() is not None, "install gcc, unset DHSYM_NO_COMPILE")
    return native_rows


def _values(robot):
    """Numbers for the inertial symbols a table leaves open (a physical arm: positive
    masses, inertia tensors with a dominant diagonal)."""
    from dhsym.dynamics.compiled_dynamics import numeric_model

    values = {}
    for k, s in enumerate(numeric_model(robot).parameters):
        name = s.name
        if name == "g":
            values[name] = 9.81
        elif name.startswith("m"):
            values[name] = 1.0 + 0.3 * k % 2.0
        elif name[:3] in ("Ixx", "Iyy", "Izz") or name[1:].isdigit():
            values[name] = 0.05 + 0.01 * (k % 5)
        elif name.startswith("I"):
            values[name] = 0.002 * ((k % 3) - 1)
        else:  # the centres of mass
            values[name] = 0.04 * ((k % 5) - 2)
    return values


def _calls(f, q, v, a):
    """Every one-state call of the numeric dynamics, by name."""
    tau = f.rne(q, v, a)
    return {
        "rne": tau,
        "rne without friction": f.rne(q, v, a, friction=False),
        "inertia": f.inertia(q),
        "gravload": f.gravload(q),
        "christoffel": f.christoffel(q),
        "coriolis": f.coriolis(q, v),
        "accel": f.accel(q, v, tau),
    }


def _agree(got, expected, rtol=1e-10):
    for name, value in expected.items():
        assert got[name].shape == value.shape, name
        scale = max(1.0, float(np.abs(value).max()))
        np.testing.assert_allclose(got[name], value, rtol=rtol, atol=rtol * scale, err_msg=name)


@pytest.mark.parametrize("name", ["puma560", "stanford", "scara", "spong2r"])
def test_one_state_in_c_gives_the_numbers_of_python_and_of_the_recursion_cold_and_warm(
    name, tmp_path, monkeypatch
):
    """After the switch, one state runs the τ program as C (the PUMA's friction with it);
    its numbers are the numeric recursion's and the Python floats' (1e-10 relative), and a
    second process-like build reads program and library from the disk cache."""
    from dhsym.dynamics import compiled_dynamics as cd
    from dhsym.export import shared_library

    native = _native_rows()
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "cache"))  # cold
    monkeypatch.delenv("DHSYM_NO_CACHE", raising=False)
    robot = dhsym.load(name)
    values = _values(robot)
    n = len(robot.variables)
    states = np.random.default_rng(7).uniform(-1.5, 1.5, (3, 3, n))
    recursion = cd.dynamics_functions(robot, values)
    expected = [_calls(recursion, *s) for s in states]  # fewer calls than COMPILE_AFTER
    assert recursion._compiled._program is None
    monkeypatch.setattr(cd, "COMPILE_AFTER", 0)
    python = cd.dynamics_functions(robot, values)  # no compiler: the program for floats
    c = cd.dynamics_functions(robot, values, native=native)
    in_c = [_calls(c, *s) for s in states]
    for s, want, got in zip(states, expected, in_c):
        _agree(got, want)
        _agree(_calls(python, *s), want)
    assert python._native is None and c._native is not None
    assert c.has_friction == (name == "puma560")

    # warm: the program and the library from the disk cache, nothing derived or built
    def refused(*args, **kwargs):
        raise AssertionError("derived or built again: the disk cache was not read")

    monkeypatch.setattr(cd, "rne_expressions", refused)
    monkeypatch.setattr(shared_library.subprocess, "run", refused)
    warm = cd.dynamics_functions(robot, values, native=native)
    for s, got in zip(states, in_c):
        again = _calls(warm, *s)
        for key, value in got.items():
            np.testing.assert_array_equal(again[key], value, err_msg=key)
    assert warm._native is not None


def test_small_batches_after_the_switch_run_in_c_row_by_row(tmp_path, monkeypatch):
    """Up to SMALL states at once go through the C program too (a state per row), with
    the numbers of the recursion; once it is built, a large batch goes through it block by
    block (more rows than its buffers hold), with the recursion's numbers."""
    from dhsym.dynamics import compiled_dynamics as cd

    native = _native_rows()
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "cache"))
    robot = arm("modified", prismatic=True)
    rng = np.random.default_rng(8)
    Q, V, A = (rng.uniform(-1, 1, (5, 4)) for _ in range(3))
    reference = cd.dynamics_functions(robot)
    want = [reference.rne(Q, V, A), reference.inertia(Q), reference.accel(Q, V, A)]
    monkeypatch.setattr(cd, "COMPILE_AFTER", 0)
    f = cd.dynamics_functions(robot, native=native)
    got = [f.rne(Q, V, A), f.inertia(Q), f.accel(Q, V, A)]
    assert f._native is not None
    for g, w in zip(got, want):
        np.testing.assert_allclose(g, w, rtol=1e-10, atol=1e-10)
    big = rng.uniform(-1, 1, (cd.SMALL + 1, 4))
    np.testing.assert_allclose(f.rne(big, big, big)[3], f.rne(big[3], big[3], big[3]), atol=1e-10)
    rows = f._native.inputs.shape[0]
    Qb, Vb, Ab = (rng.uniform(-1, 1, (2 * rows + 5, 4)) for _ in range(3))
    np.testing.assert_allclose(f.rne(Qb, Vb, Ab), reference.rne(Qb, Vb, Ab), rtol=1e-10, atol=1e-10)
    np.testing.assert_allclose(f.gravload(Qb), reference.gravload(Qb), rtol=1e-10, atol=1e-10)
    # lists and broadcast states take the general path, with the same numbers
    np.testing.assert_array_equal(f.rne(list(Q[0]), V[0], A[0]), f.rne(Q[0], V[0], A[0]))
    np.testing.assert_array_equal(f.gravload(Q[:1])[0], f.gravload(Q[0]))


def test_without_a_native_program_the_python_program_answers(tmp_path, monkeypatch):
    """A compiler that cannot build (None) is asked once; the program for Python floats
    answers with the same numbers."""
    from dhsym.dynamics import compiled_dynamics as cd

    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "cache"))
    monkeypatch.setattr(cd, "COMPILE_AFTER", 0)
    asked = []

    def cannot(program, variables, inputs, outputs):
        asked.append((len(variables), inputs.shape, outputs.shape))
        return None

    robot = arm("standard")
    f = cd.dynamics_functions(robot, native=cannot)
    q = np.array([0.1, -0.4, 0.7, 0.2])
    tau = f.rne(q, q, q)
    f.rne(q, q, q)
    assert asked == [(15, (cd.SMALL, 15), (cd.SMALL, 8))]  # q, q̇, q̈, g; τ and friction
    assert f._native is None
    np.testing.assert_allclose(tau, REFERENCE["standard"](robot, q, q, q, [0.5, -1.0, -9.81]))


def test_native_rows_refuses_what_it_cannot_run():
    """Buffers of the wrong shape, a function C has not, and rows past the buffers."""
    import sympy as sp

    from dhsym.kinematics.numeric import NumericProgram

    native = _native_rows()
    x, y = sp.symbols("x y", real=True)
    program = NumericProgram.of([x * y + sp.sin(x), x - y], (x, y))
    assert native(program, (x, y), np.zeros((2, 3)), np.zeros((2, 2))) is None
    assert native(program, (x, y), np.zeros((2, 2)), np.zeros((3, 2))) is None
    assert native(program, (x, y), np.zeros((2, 2), dtype=np.float32), np.zeros((2, 2))) is None
    mystery = NumericProgram.of([sp.Function("mystery")(x)], (x,))
    assert native(mystery, (x,), np.zeros((1, 1)), np.zeros((1, 1))) is None
    inputs, outputs = np.array([[0.5, 2.0], [1.0, -1.0]]), np.zeros((2, 2))
    run = native(program, (x, y), inputs, outputs)
    run(2)
    np.testing.assert_allclose(outputs, [[1 + np.sin(0.5), -1.5], [-1 + np.sin(1.0), 2.0]])
    with pytest.raises(dhsym.DHError, match="do not fit"):
        run(3)


def test_the_robot_passes_the_c_compiler_to_its_dynamics(monkeypatch):
    """``Robot.dynamics_functions`` gives its dynamics the export room's C compiler when
    the process has one, none with ``DHSYM_NO_COMPILE`` (no compiler found)."""
    from dhsym import robot as facade
    from dhsym.export import shared_library

    assert facade._native_rows_compiler() in (None, shared_library.native_rows)
    monkeypatch.setattr(shared_library, "native_compiler", lambda: None)
    assert facade._native_rows_compiler() is None
    monkeypatch.setattr(shared_library, "native_compiler", lambda: "cc")
    assert facade._native_rows_compiler() is shared_library.native_rows
    text = (
        "gravity: [0, -9.81, 0]\njoints: [{type: R, theta: q1, d: 0, a: 0.7, alpha: 0, "
        "m: 1.25, r: [-0.35, 0, 0], I: [0, 0.03, 0.03]}]"
    )
    f = Robot(read_table_text(text)).dynamics_functions()
    assert f._native_compiler is shared_library.native_rows


# --- a joint variable entering its cell with a rate other than 1 -------------------------------

#: the built-in Jaco's table with inertias, motor inertia and friction at joint 1, whose
#: variable enters its cell as ``theta: -theta1``
JACO = Path(__file__).resolve().parents[1] / "data" / "dynamics" / "jaco_inertial.yaml"


def _euler_lagrange(robot: Robot):
    """τ(q, q̇, q̈) without friction from the Lagrangian ``½ q̇ᵀ M(q) q̇ − P(q)``, with M
    made of Lagrange–Euler's link Jacobians (``Σ m Jvᵀ Jv + Jωᵀ I Jω + Jm G²``) and P of
    its potential energies, the Euler–Lagrange equation ``d/dt(M q̇) − ∂K/∂q + ∂P/∂q``
    taken by central differences: nothing of the Newton–Euler recursion, and ``lagrange``'s
    six-joint derivation (minutes) left out. Returns ``(τ, M, ∂P/∂q)`` functions."""
    import sympy as sp

    from dhsym.dynamics.compiled_dynamics import numeric_model
    from dhsym.dynamics.lagrange_euler import link_jacobians, potential_energies

    dm = numeric_model(robot)
    M = sp.diag(*dm.armature())
    for i, L in enumerate(dm.links, start=1):
        Jv, Jw = link_jacobians(dm, i)
        M += L.m * Jv.T * Jv + Jw.T * L.I * Jw
    inertia = sp.lambdify(dm.variables, M, "numpy")
    P = sum(potential_energies(dm), sp.Integer(0))
    dP = sp.lambdify(dm.variables, [sp.diff(P, x) for x in dm.variables], "numpy")

    def Mq(q):
        return np.array(inertia(*q), dtype=float)

    def gq(q):
        return np.array(dP(*q), dtype=float)

    def tau(q, qd, qdd, h=1e-6):
        Mdot = (Mq(q + h * qd) - Mq(q - h * qd)) / (2 * h)
        e = np.eye(len(q))
        dK = [
            (qd @ Mq(q + h * e[i]) @ qd - qd @ Mq(q - h * e[i]) @ qd) / (4 * h)
            for i in range(len(q))
        ]
        return Mq(q) @ qdd + Mdot @ qd - np.array(dK) + gq(q)

    return tau, Mq, gq


@pytest.mark.slow
def test_the_jaco_flipped_first_joint_in_the_recursion_the_compiled_program_and_c(
    tmp_path, monkeypatch
):
    """``theta: -theta1``: the numeric recursion (``robot.rne``), the compiled program for
    Python floats and its C (when a compiler is there) give the torques, M and g of the
    Euler–Lagrange equation of Lagrange–Euler's energies; the friction stays on q̇1."""
    from dhsym.dynamics import compiled_dynamics as cd
    from dhsym.export.shared_library import native_compiler, native_rows

    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "cache"))
    monkeypatch.delenv("DHSYM_NO_CACHE", raising=False)
    robot = dhsym.load(str(JACO))
    assert cd.numeric_model(robot).cell_rates == (-1, 1, 1, 1, 1, 1)
    tau, Mq, gq = _euler_lagrange(robot)
    states = np.random.default_rng(11).uniform(-1.5, 1.5, (3, 3, 6))
    recursion = cd.dynamics_functions(robot)
    monkeypatch.setattr(cd, "COMPILE_AFTER", 0)
    python = cd.dynamics_functions(robot)
    runs = [recursion, python]
    if native_compiler() is not None:
        runs.append(cd.dynamics_functions(robot, native=native_rows))
    for q, qd, qdd in states:
        want = tau(q, qd, qdd)
        scale = max(1.0, float(np.abs(want).max()))
        for f in runs:
            np.testing.assert_allclose(
                f.rne(q, qd, qdd, friction=False), want, rtol=1e-7, atol=1e-7 * scale
            )
            np.testing.assert_allclose(f.inertia(q), Mq(q), rtol=1e-10, atol=1e-12)
            np.testing.assert_allclose(f.gravload(q), gq(q), rtol=1e-10, atol=1e-12)
            friction = f.rne(q, qd, qdd) - f.rne(q, qd, qdd, friction=False)
            coulomb = 100 * (0.003 if qd[0] > 0 else -0.002)  # |G| Tc, by the sign of q̇1
            np.testing.assert_allclose(
                friction, [0.00002 * 100**2 * qd[0] + coulomb, 0, 0, 0, 0, 0], atol=1e-12
            )
    assert python._native is None
    assert len(runs) == 2 or runs[2]._native is not None
    np.testing.assert_allclose(robot.rne(*states[0]), recursion.rne(*states[0]), rtol=1e-12)
