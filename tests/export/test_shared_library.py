"""The exported C built into a shared library and loaded back (dhsym.export.shared_library)."""

from __future__ import annotations

import os
import shutil
import stat
import subprocess
import sys
from dataclasses import replace

import numpy as np
import pytest

import dhsym
from dhsym.export import shared_library as shared_library
from dhsym.export.shared_library import compiled
from dhsym.ik.choices import IKCache, solve
from dhsym.kinematics.chain import KinematicChain

from ..conftest import _need


def test_compiled_matches_robot(tmp_path, monkeypatch):
    _need("a C compiler", shutil.which("cc") or shutil.which("gcc"), "apt-get install gcc")
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path))
    r = dhsym.load("puma560")
    fast = compiled(r)
    assert (
        fast.backend == "c" and fast.library is not None and fast.library.parent.parent == tmp_path
    )
    q = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    assert np.abs(fast.fk(q) - r.fk(q)).max() <= 1e-12
    assert np.abs(fast.jacobian(q) - r.jacob0(q)).max() <= 1e-12
    assert np.abs(fast.ik(r.fk(q)).q - r.ik(r.fk(q)).q).max() <= 1e-9
    again = dhsym.load("puma560").compiled("c")  # the cache: the same library, not rebuilt
    assert again.library == fast.library


def test_compiled_without_a_compiler(monkeypatch, tmp_path):
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path))
    monkeypatch.setenv("CC", "")
    monkeypatch.setattr(shutil, "which", lambda name: None)
    r = dhsym.load("planar2r")
    slow = compiled(r)
    assert slow.backend == "numpy"
    assert np.abs(slow.fk([0.1, 0.2]) - r.fk([0.1, 0.2])).max() == 0
    T = r.fk([0.4, 0.9])
    assert np.array_equal(slow.ik(T).q, r.ik(T).q)


def test_compiled_derives_in_the_cache_it_is_given(monkeypatch, tmp_path):
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path))
    monkeypatch.setenv("CC", "")
    monkeypatch.setattr(shutil, "which", lambda name: None)
    r = dhsym.load("planar2r")
    cache = IKCache(KinematicChain(r.table))
    compiled(cache.chain, cache=cache)
    derived = cache.inverse()
    assert derived is cache.inverse()  # derived once, by compiled, and kept
    assert r.compiled().backend == "numpy" and r.ik_cache().inverse() is r.inverse()


def test_compiled_ik_at_a_singular_wrist(tmp_path, monkeypatch):
    _need("a C compiler", shutil.which("cc") or shutil.which("gcc"), "apt-get install gcc")
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path))
    r = dhsym.load("puma560")
    fast = r.compiled("c")
    for q5 in (0.0, 1e-7):  # sin θ5 = 0 (θ4 = 0 and θ6 from the whole rotation) and near it
        T = r.fk([0.3, -0.5, 0.4, 0.2, q5, -1.1])
        got, want = fast.ik(T).q, r.ik(T)
        assert got.shape == want.q.shape
        assert np.abs(np.angle(np.exp(1j * (got - want.q)))).max() <= 1e-9


_PLANTED = r"""
#include <stdio.h>
#include <string.h>
__attribute__((constructor)) static void planted(void) {
    FILE *f = fopen("%(marker)s", "w");
    if (f) { fputs("ran", f); fclose(f); }
}
void dhsym_arm_fk(const double *q, double *out) { for (int i = 0; i < 16; i++) out[i] = 42; }
void dhsym_arm_jacobian(const double *q, double *out) { out[0] = 42; }
int dhsym_arm_ik(const double *T, double *out) { return 0; }
"""


def _plant(tmp_path, target):
    """The campaign's library: a constructor that leaves a marker file, fk that returns 42s,
    built with gcc to ``target`` (mode 0600, owned by this user: only the HMAC stops it)."""
    cc = shutil.which("gcc") or shutil.which("cc")
    marker = tmp_path / "constructor-ran"
    src = tmp_path / "planted.c"
    src.write_text(_PLANTED % {"marker": marker})
    target.parent.mkdir(parents=True, exist_ok=True)
    subprocess.run([cc, "-shared", "-fPIC", "-o", str(target), str(src)], check=True)
    os.chmod(target, 0o600)
    return marker


def test_planted_library_is_refused_and_rebuilt(tmp_path, monkeypatch):
    _need("a C compiler", shutil.which("cc") or shutil.which("gcc"), "apt-get install gcc")
    cache = tmp_path / "cache"
    monkeypatch.setenv("DHSYM_CACHE", str(cache))
    r = dhsym.load("planar2r")
    from dhsym.export import export

    source = export(r, "c", what=("fk", "jacobian", "ik"), prefix="dhsym_arm", cache=r.ik_cache())
    cc = shared_library._compiler()
    name = shared_library.library_name(source, cc)
    # planted at the predictable name, with an HMAC file of its own (it cannot know the key)
    marker = _plant(tmp_path, cache / "entries" / name)
    (cache / "entries" / f"{name}.hmac").write_text("0" * 64)
    # and where the old cache kept its libraries (never read now)
    _plant(tmp_path, cache / "compiled" / "planted.so")
    os.chmod(cache, 0o700)
    fast = compiled(r)
    q = np.array([0.4, 0.9])
    assert not marker.exists()  # its constructor never ran
    assert np.abs(fast.fk(q) - r.fk(q)).max() <= 1e-12  # rebuilt: the right numbers
    assert fast.library == cache / "entries" / name
    assert b"planted" not in fast.library.read_bytes()


def test_modified_library_is_refused_and_rebuilt(tmp_path, monkeypatch):
    _need("a C compiler", shutil.which("cc") or shutil.which("gcc"), "apt-get install gcc")
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "cache"))
    r = dhsym.load("planar2r")
    first = compiled(r)
    assert first.library is not None and stat.S_IMODE(first.library.stat().st_mode) == 0o600
    assert stat.S_IMODE(first.library.parent.stat().st_mode) == 0o700
    marker = _plant(tmp_path, first.library)  # replaced in place; its HMAC file kept
    again = compiled(r)
    q = np.array([0.4, 0.9])
    assert not marker.exists()
    assert np.abs(again.fk(q) - r.fk(q)).max() <= 1e-12
    assert again.library == first.library


def test_without_the_cache_nothing_is_kept(tmp_path, monkeypatch):
    _need("a C compiler", shutil.which("cc") or shutil.which("gcc"), "apt-get install gcc")
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "cache"))
    monkeypatch.setenv("DHSYM_NO_CACHE", "1")
    r = dhsym.load("planar2r")
    fast = compiled(r)
    q = np.array([0.4, 0.9])
    assert fast.library is None and np.abs(fast.fk(q) - r.fk(q)).max() <= 1e-12
    assert not (tmp_path / "cache").exists()


# -- robot.ik's program for one pose in C (native_program) ----------------------------------
def _fields_agree(a, b):
    """Two solutions of one pose say the same: every field, the joint values to rounding."""
    assert a.branches == b.branches
    assert a.q.shape == b.q.shape and np.abs(a.q - b.q).max(initial=0.0) <= 1e-10
    assert np.abs(a.residual - b.residual).max(initial=0.0) <= 1e-12
    assert (a.valid == b.valid).all() and (a.near == b.near).all()
    assert (a.signs == b.signs).all() and a.factor_kinds == b.factor_kinds
    assert (a.method, a.reason) == (b.method, b.reason)


@pytest.mark.parametrize("name", ["puma560", "ur5", "stanford", "planar2r"])
def test_native_program_agrees_with_the_numpy_path(name):
    _need("a C compiler", shared_library.native_compiler(), "apt-get install gcc")
    robot = dhsym.load(name)
    solver = robot.ik_cache().solver()
    built = solver.native(now=True)
    assert built is not None
    served = []

    def counted(inner, pose, stretch):
        served.append(stretch)
        return built.run(inner, pose, stretch)

    def around(pose, tol, base_inv, tool_inv):
        served.append("given")
        return built.given(pose, tol, base_inv, tool_inv)

    # the C, counted: it serves every pose below
    solver._native_program = replace(built, run=counted, given=around)
    numpy_only = IKCache(robot)  # no native compiler: the program for floats, and numpy
    rng = np.random.default_rng(7)
    n = len(robot.variables)
    for q in rng.uniform(-3.0, 3.0, (12, n)):
        T = robot.fk(q)
        for pose in (T, np.round(T, 6), np.round(T, 3)):
            _fields_agree(robot.ik(pose), solve(robot, pose, cache=numpy_only))
        _fields_agree(
            robot.ik(T, limits=True, near=q), solve(robot, T, cache=numpy_only, limits=True, near=q)
        )
    far = robot.fk(np.zeros(n))
    far[:3, 3] *= 100.0  # out of reach: no solution, the same reason
    _fields_agree(robot.ik(far), solve(robot, far, cache=numpy_only))
    # every pose asks the rule around the program first (the few it leaves to robot.ik's
    # own path, a singular wrist or a branch to refine, are solved by the program again)
    assert served.count("given") == 12 * 4 + 1


@pytest.mark.parametrize("name", ["puma560", "ur5", "stanford"])
def test_a_rounded_pose_gets_the_same_solutions_from_the_native_rule(name):
    """A pose as it comes (rounded to 6, 4 or 3 decimals, or typed: a few entries off by a
    unit of the last decimal) is answered by one call of the native program with the rule
    around it (``given``): the same branches, joint values and residuals (to rounding:
    the nearest rigid pose by Newton's iteration, not by an SVD) as robot.ik's own path
    of dhsym.ik.choices, and the same empty answers with the same reason, which the own
    path gives (as it refines the branches near the pose as given, not on it)."""
    _need("a C compiler", shared_library.native_compiler(), "apt-get install gcc")
    robot = dhsym.load(name)
    solver = robot.ik_cache().solver()
    built = solver.native(now=True)
    assert built is not None and built.given is not None
    answered = []
    own_answer = solver.solve_given

    def spied(*args, **kwargs):
        got = own_answer(*args, **kwargs)
        answered.append(got is not None)
        return got

    solver.solve_given = spied  # robot.ik asks it first, for every pose below
    numpy_only = IKCache(robot)  # no native compiler: robot.ik's own path, all in Python
    rng = np.random.default_rng(30)
    n = len(robot.variables)
    checked = 0
    for q in rng.uniform(-3.0, 3.0, (40, n)):
        T = robot.fk(q)
        typed = np.round(T, 4)
        typed[rng.integers(0, 3), rng.integers(0, 4)] += 1e-4  # one entry mistyped
        for pose in (np.round(T, 6), np.round(T, 4), np.round(T, 3), typed):
            fast, own = robot.ik(pose), solve(robot, pose, cache=numpy_only)
            assert set(fast.branches) == set(own.branches)
            _fields_agree(fast, own)
            assert fast.note == own.note
            checked += 1
    # the native rule answered most poses itself (the rest: a branch to refine, none)
    assert len(answered) == checked and sum(answered) >= 0.8 * checked


def test_native_program_shared_by_threads_gives_each_its_own_answer():
    """Each thread copies the poses into buffers of its own and gets a new array of the
    outputs: threads that call the program at once each get the outputs of their own pose,
    as one thread calling in turn, and a later call never changes an array returned."""
    from concurrent.futures import ThreadPoolExecutor

    _need("a C compiler", shared_library.native_compiler(), "apt-get install gcc")
    robot = dhsym.load("puma560")
    solver = robot.ik_cache().solver()
    built = solver.native(now=True)
    assert built is not None
    poses = robot.fk(np.random.default_rng(11).uniform(-3.0, 3.0, (64, 6)))
    inner = [np.ascontiguousarray(solver._inner(T)) for T in poses]
    rounded = [np.round(T, 3) for T in poses]  # another pose given: the second buffer
    calls = [(a, a, False) for a in inner] + [(a, b, True) for a, b in zip(inner, rounded)]
    arrays = [built.run(*c) for c in calls]
    assert all(type(v) is np.ndarray and v.dtype == np.float64 for v in arrays)
    assert not any(np.shares_memory(a, b) for a, b in zip(arrays, arrays[1:]))
    serial = [v.tolist() for v in arrays]  # read after every call: none was overwritten
    assert len({tuple(v) for v in serial}) == len(calls)  # each pose its own outputs
    assert serial == [built.run(*c).tolist() for c in calls]
    with ThreadPoolExecutor(4) as pool:
        for _ in range(5):
            assert [v.tolist() for v in pool.map(lambda c: built.run(*c), calls)] == serial


def test_no_compile_forces_the_numpy_path(tmp_path):
    env = dict(os.environ, DHSYM_NO_COMPILE="1", DHSYM_CACHE=str(tmp_path))
    code = (
        "import dhsym; from dhsym.export.shared_library import native_compiler; "
        "r = dhsym.load('planar2r'); s = r.ik_cache().solver(); "
        "print(native_compiler(), r.ik_cache().native, s.native(now=True))"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
    )
    assert done.stdout.split() == ["None", "None", "None"]


def test_native_source_builds_under_strict_flags(tmp_path):
    cc = shared_library.native_compiler()
    _need("a C compiler", cc, "apt-get install gcc")
    solver = dhsym.load("puma560").ik_cache().solver()
    from dhsym.ik.kept_programs import kept_program

    args, program, outputs = kept_program(
        lambda: solver._entry("scalar"), lambda: solver._rewritten("scalar")
    )
    (tmp_path / "p.c").write_text(shared_library.native_source(args, program, outputs))
    done = subprocess.run(
        [cc, "-std=c99", "-Wall", "-Wextra", "-Werror", "-c", "p.c"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == 0, done.stderr
