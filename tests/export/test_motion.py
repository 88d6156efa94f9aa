# ruff: noqa: E501
"""The exported profiles (``<prefix>_cubic``, ``<prefix>_quintic``) and computed torque
(``<prefix>_computed_torque``) in every language, built and run: the profiles against
``dhsym.trajectory.cubic``/``quintic(...).sample(t)`` (and at rest outside ``[0, tf]``),
computed torque against ``robot.rne`` at the commanded acceleration and against
``dhsym.control.ComputedTorque``, for the PUMA 560 (published parameters) and Spong's
two-link arm with numbers for its masses and inertias."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

import dhsym
from dhsym.errors import DHError
from dhsym.trajectory import cubic, quintic

from ..conftest import _need
from . import _harness as h

SPONG = {"m1": 1.0, "m2": 0.8, "I1": 0.1, "I2": 0.05, "g": 9.81}
NAMES = ["puma560", "spong2r"]


def _robot(name: str) -> dhsym.Robot:
    robot = dhsym.load(name)
    if name == "spong2r":  # its masses and inertias are symbols: numbers for them
        robot = dhsym.Robot(robot.table.with_values(SPONG))
    return robot


def _export(name: str, lang: str) -> tuple[dhsym.Robot, dict[str, str]]:
    robot = _robot(name)
    return robot, dhsym.export(robot, lang, what="trajectory,control", prefix="arm")


def _profile_cases(n: int, m: int = 7) -> list[tuple[np.ndarray, ...]]:
    """(q0, qf, v0, vf, a0, af, tf, t): times inside [0, tf], at both ends and outside."""
    rng = np.random.default_rng(35)
    cases = []
    for k in range(m):
        q0, qf, v0, vf, a0, af = rng.uniform(-2, 2, (6, n))
        tf = float(rng.uniform(0.5, 3.0))
        t = [0.0, tf, -0.5, tf + 1.0][k] if k < 4 else float(rng.uniform(0, tf))
        cases.append((q0, qf, v0, vf, a0, af, np.array([tf]), np.array([t])))
    return cases


def _want_profiles(case) -> np.ndarray:
    """q, qd, qdd of the quintic, then of the cubic (as dhsym.trajectory samples them)."""
    q0, qf, v0, vf, a0, af, (tf,), (t,) = case
    out = []
    for profile in (
        quintic(list(q0), list(qf), tf, list(v0), list(vf), list(a0), list(af)),
        cubic(list(q0), list(qf), tf, list(v0), list(vf)),
    ):
        inside = min(max(t, 0.0), tf)
        q, qd, qdd = (x[0] for x in profile.sample([inside]))
        if not 0.0 <= t <= tf:  # at rest outside [0, tf]: at q0 before, at qf after
            qd, qdd = np.zeros(len(q0)), np.zeros(len(q0))
        out += [q, qd, qdd]
    return np.concatenate(out)


def _torque_cases(n: int, m: int = 6) -> list[tuple[np.ndarray, ...]]:
    """(q, qd, q_ref, qd_ref, qdd_ref, kp, kd)."""
    rng = np.random.default_rng(10)
    cases = []
    for _ in range(m):
        q, q_ref = rng.uniform(-np.pi, np.pi, (2, n))
        qd, qd_ref, qdd_ref = rng.uniform(-2, 2, (3, n))
        kp, kd = rng.uniform(10, 100, n), rng.uniform(2, 20, n)
        cases.append((q, qd, q_ref, qd_ref, qdd_ref, kp, kd))
    return cases


def _want_torque(robot: dhsym.Robot, case) -> np.ndarray:
    q, qd, q_ref, qd_ref, qdd_ref, kp, kd = case
    return robot.rne(q, qd, qdd_ref + kd * (qd_ref - qd) + kp * (q_ref - q))


def _stdin(robot: dhsym.Robot) -> str:
    n = len(robot.variables)
    profiles, torques = _profile_cases(n), _torque_cases(n)
    rows = [str(len(profiles))]
    rows += [" ".join(repr(float(v)) for v in np.concatenate(c)) for c in profiles]
    rows.append(str(len(torques)))
    rows += [" ".join(repr(float(v)) for v in np.concatenate(c)) for c in torques]
    return "\n".join(rows) + "\n"


def _check(robot: dhsym.Robot, out: np.ndarray) -> None:
    """``out``: for each profile case q, qd, qdd of the quintic and of the cubic, then
    the torque of each computed-torque case."""
    n = len(robot.variables)
    profiles, torques = _profile_cases(n), _torque_cases(n)
    want_p = np.array([_want_profiles(c) for c in profiles])
    want_t = np.array([_want_torque(robot, c) for c in torques])
    assert out.size == want_p.size + want_t.size
    got_p = out[: want_p.size].reshape(want_p.shape)
    got_t = out[want_p.size :].reshape(want_t.shape)
    assert np.allclose(got_p, want_p, rtol=1e-12, atol=1e-11)
    scale = np.abs(want_t).max(axis=1, keepdims=True)
    assert np.all(np.abs(got_t - want_t) <= 1e-9 * np.maximum(scale, 1.0))


_C_MAIN = """
#include <stdio.h>
#include "arm.{ext}"
#define N {n}
static int read(double *x, int k)
{{
    int j;
    for (j = 0; j < k; ++j) if (scanf("%lf", &x[j]) != 1) return 0;
    return 1;
}}
static void put(const double *x)
{{
    int j;
    for (j = 0; j < N; ++j) printf("%.17g\\n", x[j]);
}}
int main(void)
{{
    int m, i;
    double b[6 * N + 2], s[7 * N], q[N], qd[N], qdd[N], tau[N];
    if (scanf("%d", &m) != 1) return 1;
    for (i = 0; i < m; ++i) {{
        if (!read(b, 6 * N + 2)) return 1;
        {ns}quintic(b, b + N, b + 2 * N, b + 3 * N, b + 4 * N, b + 5 * N, b[6 * N], b[6 * N + 1], q, qd, qdd);
        put(q); put(qd); put(qdd);
        {ns}cubic(b, b + N, b + 2 * N, b + 3 * N, b[6 * N], b[6 * N + 1], q, qd, qdd);
        put(q); put(qd); put(qdd);
    }}
    if (scanf("%d", &m) != 1) return 1;
    for (i = 0; i < m; ++i) {{
        if (!read(s, 7 * N)) return 1;
        {ns}computed_torque(s, s + N, s + 2 * N, s + 3 * N, s + 4 * N, s + 5 * N, s + 6 * N, tau);
        put(tau);
    }}
    return 0;
}}
"""

_RUST_MAIN = h.rust_main(
    """\
    let mut at = 1;
    for _ in 0..(v[0] as usize) {
        let b = &v[at..at + 6 * N + 2];
        let (tf, t) = (b[6 * N], b[6 * N + 1]);
        let x: Vec<[f64; N]> = (0..6).map(|k| arr(&b[k * N..])).collect();
        let (q, qd, qdd) = arm::quintic(&x[0], &x[1], &x[2], &x[3], &x[4], &x[5], tf, t);
        let (c, cd, cdd) = arm::cubic(&x[0], &x[1], &x[2], &x[3], tf, t);
        for a in [q, qd, qdd, c, cd, cdd].iter() { for y in a.iter() { println!("{:e}", y); } }
        at += 6 * N + 2;
    }
    let m = v[at] as usize;
    at += 1;
    for _ in 0..m {
        let x: Vec<[f64; N]> = (0..7).map(|k| arr(&v[at + k * N..])).collect();
        let tau = arm::computed_torque(&x[0], &x[1], &x[2], &x[3], &x[4], &x[5], &x[6]);
        for y in tau.iter() { println!("{:e}", y); }
        at += 7 * N;
    }
""",
    items="""\
const N: usize = arm::NJOINTS;
fn arr(v: &[f64]) -> [f64; N] {
    let mut a = [0.0; N];
    a.copy_from_slice(&v[..N]);
    a
}
""",
)

_OCTAVE = """
fid = fopen('in.txt'); v = fscanf(fid, '%f'); fclose(fid);
n = arm_njoints(); at = 2;
for i = 1:v(1)
  b = v(at:at + 6 * n + 1); x = reshape(b(1:6 * n), n, 6); tf = b(6 * n + 1); t = b(6 * n + 2);
  [q, qd, qdd] = arm_quintic(x(:, 1), x(:, 2), x(:, 3), x(:, 4), x(:, 5), x(:, 6), tf, t);
  printf('%.17g\\n', q, qd, qdd);
  [q, qd, qdd] = arm_cubic(x(:, 1), x(:, 2), x(:, 3), x(:, 4), tf, t);
  printf('%.17g\\n', q, qd, qdd);
  at = at + 6 * n + 2;
end
m = v(at); at = at + 1;
for i = 1:m
  x = reshape(v(at:at + 7 * n - 1), n, 7);
  printf('%.17g\\n', arm_computed_torque(x(:, 1), x(:, 2), x(:, 3), x(:, 4), x(:, 5), x(:, 6), x(:, 7)));
  at = at + 7 * n;
end
"""


def _c_like(name: str, tmp_path: Path, cpp: bool) -> None:
    robot, files = _export(name, "cpp" if cpp else "c")
    main = _C_MAIN.format(
        ext="hpp" if cpp else "h", n=len(robot.variables), ns="arm::" if cpp else "arm_"
    )
    prog = h.build_c(files, tmp_path, main, cpp)
    _check(robot, h.numbers([str(prog)], tmp_path, _stdin(robot)))


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_c(name, tmp_path):
    _need("gcc", shutil.which("gcc") is not None, "apt-get install gcc")
    _c_like(name, tmp_path, cpp=False)


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_cpp(name, tmp_path):
    _need("g++", shutil.which("g++") is not None, "apt-get install g++")
    _c_like(name, tmp_path, cpp=True)


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_rust(name, tmp_path):
    rustc = h.rustc()
    _need("rustc", rustc is not None, "apt-get install rustc (or rustup)")
    robot, files = _export(name, "rust")
    prog = h.build_rust(files, tmp_path, _RUST_MAIN)
    _check(robot, h.numbers([str(prog)], tmp_path, _stdin(robot)))


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_octave(name, tmp_path):
    _need("octave", shutil.which("octave") is not None, "apt-get install octave")
    robot, files = _export(name, "matlab")
    (tmp_path / "in.txt").write_text(_stdin(robot))
    _check(robot, h.octave(files, tmp_path, _OCTAVE))


@pytest.mark.parametrize("name", [pytest.param("puma560", marks=pytest.mark.slow), "spong2r"])
def test_python(name, tmp_path):
    robot, files = _export(name, "python")
    module = h.load_python(files, "arm", tmp_path)
    n = len(robot.variables)
    out = []
    for q0, qf, v0, vf, a0, af, (tf,), (t,) in _profile_cases(n):
        out += module.quintic(q0, qf, v0, vf, a0, af, tf, t)
        out += module.cubic(q0, qf, v0, vf, tf, t)
    out += [module.computed_torque(*c) for c in _torque_cases(n)]
    _check(robot, np.concatenate(out))


def test_python_samples_a_batch_of_times(tmp_path):
    """``t`` of shape (N, 1) gives (N, n), the samples of ``quintic(...).sample``."""
    _, files = _export("spong2r", "python")
    module = h.load_python(files, "arm", tmp_path)
    ts = np.linspace(0.0, 1.5, 31)
    got = module.quintic(
        [0.0, 0.5], [1.0, -0.8], [0.2, 0.0], 0.0, 0.0, [0.0, 1.0], 1.5, ts[:, None]
    )
    want = quintic([0, 0.5], [1, -0.8], 1.5, [0.2, 0], 0, 0, [0, 1]).sample(ts)
    for g, w in zip(got, want):
        assert g.shape == (31, 2)
        assert np.allclose(g, w, rtol=1e-12, atol=1e-12)


def test_computed_torque_is_the_control_rooms_law(tmp_path):
    """The exported law, fed the exported quintic as reference, gives the torque of
    ``dhsym.control.ComputedTorque`` on the same reference (two independent codes)."""
    from dhsym.control import ComputedTorque

    robot, files = _export("spong2r", "python")
    module = h.load_python(files, "arm", tmp_path)
    ends = ([0.0, 0.0], [1.0, -0.8], 1.5)
    law = ComputedTorque(
        [64.0, 49.0], [16.0, 14.0], quintic(*ends), model=robot.dynamics_functions()
    )
    rng = np.random.default_rng(3)
    for t in (0.0, 0.4, 1.1, 1.5):
        q, qd = rng.uniform(-1, 1, (2, 2))
        q_ref, qd_ref, qdd_ref = module.quintic(ends[0], ends[1], 0, 0, 0, 0, ends[2], t)
        got = module.computed_torque(q, qd, q_ref, qd_ref, qdd_ref, [64.0, 49.0], [16.0, 14.0])
        assert np.allclose(got, law(t, q, qd), rtol=1e-10, atol=1e-10)


def test_parts_and_files():
    robot = _robot("spong2r")
    c = dhsym.export(robot, "c", what="trajectory", prefix="arm", command="x")
    assert "void arm_quintic(const double q0[ARM_NJOINTS]" in c["arm.h"]
    assert "void arm_cubic(" in c["arm.c"] and "arm_rne" not in c["arm.c"]
    assert "computed_torque" not in c["arm.c"]
    # control brings the rne it calls along
    a = dhsym.export(robot, "c", what="control", prefix="arm", command="x")
    b = dhsym.export(robot, "c", what="control,dynamics", prefix="arm", command="x")
    assert a == b
    assert "    arm_rne(q, qd, v, tau);" in a["arm.c"]
    assert sorted(dhsym.export(robot, "matlab", what="trajectory,control", prefix="arm")) == [
        "arm_computed_torque.m",
        "arm_cubic.m",
        "arm_fk.m",
        "arm_njoints.m",
        "arm_quintic.m",
        "arm_rne.m",
    ]
    # the default parts stay as they were: no profile, no controller
    plain = dhsym.export(dhsym.load("planar2r"), "c", prefix="arm")
    assert "quintic" not in plain["arm.c"] and "computed_torque" not in plain["arm.h"]
    # the trajectory needs no dynamics: a robot without inertial numbers exports it
    files = dhsym.export(dhsym.load("planar2r"), "python", what="trajectory", prefix="arm")
    assert "def quintic(" in files["arm.py"] and "def rne(" not in files["arm.py"]


def test_control_refused_without_numbers():
    with pytest.raises(DHError, match="numeric inertial parameters; no number for .*m1"):
        dhsym.export(dhsym.load("spong2r"), "c", what="control")


def test_cli_exports_trajectory_and_control(tmp_path):
    from dhsym.cli.main import main

    args = ["export", "puma560", "--lang", "c", "--what", "trajectory,control", "--prefix", "puma"]
    assert main([*args, "-o", str(tmp_path)]) == 0
    header = (tmp_path / "puma.h").read_text()
    assert "void puma_quintic(" in header and "void puma_computed_torque(" in header
    assert "void puma_rne(" in header
