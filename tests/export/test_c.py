# ruff: noqa: E501
"""The C printer's own functions: the exported C and C++ take sine, cosine and atan2 from
dhsym's own ``dh_sincos_n`` and ``dh_atan2`` (no libm call on the fk's and IK's path).

Compared with libm on 10^6 arguments each, built under the strict flags: within 2 ulp
inside the range of the reduction (random angles up to ±1024, angles near multiples of
pi/2 and of pi/4, small angles; pairs of every size, near the axes and the diagonals), and
the very bits of libm outside it (±0, beyond ±1024, ±inf, NaN, subnormal). The fk's
sines and cosines of the PUMA come from one call for all its angles."""

from __future__ import annotations

import shutil

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.export import c as c_language
from dhsym.export.c import (
    CPrinter,
    Direction,
    NativePrinter,
    SinCos,
    SinCosGroup,
    ik_trig,
    sincos_pairs,
)
from dhsym.export.program import Assign, fk_program, ik_program

from ..conftest import _need
from . import _harness as h

_DRIVER = r"""
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#ifdef __cplusplus
#include "arm.hpp"
#define OWN(f) arm::detail::f
#else
#include "arm.c"
#define OWN(f) f
#endif

static uint64_t state = 88172645463325252u;

static double uniform(void) /* xorshift64, [0, 1) */
{
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return (double)(state >> 11) * (1.0 / 9007199254740992.0);
}

static double ulps(double a, double b) /* how many doubles apart; 0 for two NaNs */
{
    int64_t i, j;
    if (a == b || (a != a && b != b)) {
        return 0.0;
    }
    if (a != a || b != b) {
        return 1e300;
    }
    memcpy(&i, &a, 8);
    memcpy(&j, &b, 8);
    i = i < 0 ? INT64_MIN - i : i;
    j = j < 0 ? INT64_MIN - j : j;
    return i > j ? (double)(i - j) : (double)(j - i);
}

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, 8) == 0 || (a != a && b != b);
}

#define N 1000000
#define BLOCK 8
int main(void)
{
    double worst_sincos = 0.0, worst_atan2 = 0.0, x[BLOCK], s[BLOCK], c[BLOCK];
    int outside = 0, i, k;
    const double edge[] = {0.0, -0.0, 1024.0000000000002, -1024.0000000000002, 1e300, -1e300,
                           INFINITY, -INFINITY, NAN, 4.9406564584124654e-324, -2.2250738585072014e-308};
    const double pairs[][2] = {{0.0, 0.0}, {-0.0, 0.0}, {0.0, -0.0}, {-0.0, -0.0}, {1.0, 0.0},
                               {-1.0, -0.0}, {0.0, -1.0}, {-0.0, -1.0}, {INFINITY, 1.0},
                               {1.0, -INFINITY}, {INFINITY, -INFINITY}, {NAN, 1.0}, {1.0, NAN},
                               {1e-300, 1.0}, {-1.0, 1e300}, {0.0, 2.5}, {-0.0, 2.5}, {0.0, -2.5},
                               {-0.0, -2.5}, {2.5, 0.0}, {-2.5, -0.0}, {0.0, 1e-310}, {-1e-310, -0.0}};
    for (i = 0; i < N; i += BLOCK) {
        for (k = 0; k < BLOCK; ++k) {
            const int kind = (i / BLOCK + k) % 4;
            const double turn = (double)(long)((2.0 * uniform() - 1.0) * 1300.0);
            const double near = nextafter(turn * 0.78539816339744828, uniform() < 0.5 ? -INFINITY : INFINITY);
            x[k] = kind == 0 ? (2.0 * uniform() - 1.0) * 1024.0
                 : kind == 1 ? (2.0 * uniform() - 1.0) * 4.0
                 : kind == 2 ? (turn == 0.0 ? 1e-9 : near)
                 : (2.0 * uniform() - 1.0) * 1e-6;
        }
        OWN(dh_sincos_n)(BLOCK, x, s, c);
        for (k = 0; k < BLOCK; ++k) {
            double s1, c1;
            OWN(dh_sincos)(x[k], &s1, &c1);
            worst_sincos = fmax(worst_sincos, fmax(ulps(s[k], sin(x[k])), ulps(c[k], cos(x[k]))));
            outside += !same_bits(s1, s[k]) || !same_bits(c1, c[k]);
        }
    }
    for (i = 0; i < N; ++i) {
        const int kind = i % 4;
        const double scale = kind == 3 ? ldexp(1.0, (int)(uniform() * 400.0) - 200) : 1.0;
        const double angle = (2.0 * uniform() - 1.0) * 4.0, r = 1.0 + uniform();
        const double y = kind == 0 ? 2.0 * uniform() - 1.0 : kind == 1 ? r * sin(angle)
                       : kind == 2 ? (2.0 * uniform() - 1.0) * 1e-6 : (2.0 * uniform() - 1.0) * scale;
        const double xx = kind == 0 ? 2.0 * uniform() - 1.0 : kind == 1 ? r * cos(angle)
                        : 2.0 * uniform() - 1.0;
        worst_atan2 = fmax(worst_atan2, ulps(OWN(dh_atan2)(y, xx), atan2(y, xx)));
    }
    for (i = 0; i < (int)(sizeof edge / sizeof edge[0]); ++i) {
        double s1, c1;
        OWN(dh_sincos)(edge[i], &s1, &c1);
        outside += !same_bits(s1, sin(edge[i])) || !same_bits(c1, cos(edge[i]));
        OWN(dh_sincos_n)(1, &edge[i], &s1, &c1);
        outside += !same_bits(s1, sin(edge[i])) || !same_bits(c1, cos(edge[i]));
    }
    for (i = 0; i < (int)(sizeof pairs / sizeof pairs[0]); ++i) {
        outside += !same_bits(OWN(dh_atan2)(pairs[i][0], pairs[i][1]), atan2(pairs[i][0], pairs[i][1]));
    }
    printf("%.17g %.17g %d\n", worst_sincos, worst_atan2, outside);
    return 0;
}
"""


def _compare_with_libm(tmp_path, cpp: bool) -> None:
    files = dhsym.export(dhsym.load("planar2r"), "cpp" if cpp else "c", prefix="arm")
    if not cpp:  # the driver includes arm.c for its static functions: build it alone
        files = {"arm.h": files["arm.h"], "arm.c.inc": files["arm.c"]}
        driver = _DRIVER.replace('#include "arm.c"', '#include "arm.c.inc"')
    else:
        driver = _DRIVER
    prog = h.build_c(files, tmp_path, driver, cpp=cpp)
    worst_sincos, worst_atan2, outside = h.numbers([str(prog)], tmp_path)
    assert worst_sincos <= 2.0, f"sin/cos {worst_sincos} ulp from libm"
    assert worst_atan2 <= 2.0, f"atan2 {worst_atan2} ulp from libm"
    assert outside == 0  # libm's own bits outside the range; one angle as in a block


def test_own_sine_cosine_and_atan2_against_libm_in_c(tmp_path):
    _need("gcc", shutil.which("gcc") is not None, "apt-get install gcc")
    _compare_with_libm(tmp_path, cpp=False)


def test_own_sine_cosine_and_atan2_against_libm_in_cpp(tmp_path):
    _need("g++", shutil.which("g++") is not None, "apt-get install g++")
    _compare_with_libm(tmp_path, cpp=True)


def test_the_fk_takes_every_angle_in_one_call():
    files = dhsym.export(dhsym.load("puma560"), "c", what="fk", prefix="arm")
    fk = files["arm.c"].split("void arm_fk")[1]
    assert fk.count("dh_sincos_n(6, angle, sine, cosine);") == 1
    assert "const double angle[6] = {q1, q2, q2 + q3, q4, q5, q6};" in fk
    # the library's own: no call of libm's sin or cos on the fk's path
    assert " sin(" not in fk.split("}")[0] and " cos(" not in fk.split("}")[0]


def test_pairs_keep_an_angle_alone_and_the_order():
    body = fk_program(dhsym.load("planar2r")).body
    items = sincos_pairs(body)
    assert isinstance(items[0], SinCosGroup) and all(isinstance(p, SinCos) for p in items[0].pairs)
    assert [(p.sin, p.cos) for p in items[0].pairs] == [("s1", "c1"), ("s12", "c12")]
    assert not any(isinstance(a, SinCosGroup) for a in items[1:])
    q = sp.Symbol("q1", real=True)
    alone = [a for a in sincos_pairs(body[:1]) if not isinstance(a, SinCosGroup)]
    assert [a.name for a in alone] == ["c1"] and str(alone[0].expr) == str(sp.cos(q))


def test_the_ik_takes_sines_from_the_atan2_arguments_where_nothing_is_decided():
    """The UR5's innermost level: the sines and cosines of q2, q2 + q3 and q2 + q3 + q4 from
    the atan2 arguments and the angle-sum formulas (no atan2, sin, cos in a row); those of
    q1, q5, q6, which a square root's radicand further on reads, stay the angles' own."""
    files = dhsym.export(dhsym.load("ur5"), "c", what="ik", prefix="arm")
    ik = files["arm.c"].split("int arm_ik")[1]
    inner = ik.split("const double q3_y =")[1]
    assert "dh_direction(q3_y, d_3, q3, &s3, &c3);" in inner
    assert "const double s23 = c2*s3 + c3*s2;" in inner
    assert "const double s234 = c23*sq4 + cq4*s23;" in inner
    assert "dh_sincos" not in inner.split("const double F[12]")[0]
    for q in ("q1", "q5", "q6"):
        assert f"dh_sincos({q}, &s{q[1]}, &c{q[1]});" in ik
    assert "sol[2] = q3;" in ik and "sol[1] = wrap(q2);" in ik  # an atan2 is in [-pi, pi]
    assert "continue; /* no real value" in ik  # a branch with no real joint value ends there


def test_ik_trig_leaves_what_decides_a_branch():
    """Only pairs no radicand or singular guard reads are derived, and a call is split
    only when it gets shorter: the PUMA's s23 (read by its wrist's radicand) and s4
    (beside s5, guarded) keep their calls whole; the UR5's s5 and s6 (read by its elbow's
    radicand) stay, its s2, s23, s234 are derived."""
    items = ik_trig(ik_program(dhsym.load("puma560")).body)
    assert not any(isinstance(a, Direction) for a in items)
    kept = {p.sin for a in items if isinstance(a, SinCosGroup) for p in a.pairs}
    assert {"s1", "s2", "s23", "s3", "s4", "s5", "s6"} <= kept
    items = ik_trig(ik_program(dhsym.load("ur5")).body)
    kept = {p.sin for a in items if isinstance(a, SinCosGroup) for p in a.pairs}
    derived = {a.name for a in items if isinstance(a, Assign) and a.name[0] == "s"}
    assert kept == {"s1", "s5", "s6"} and {"s2", "s23", "s234"} <= derived


@pytest.mark.slow
@pytest.mark.parametrize("name", ["ur5", "puma560"])
def test_ik_at_singular_poses_as_with_the_angles_sines(name, tmp_path, monkeypatch):
    """Lecture poses: the home pose and joints at multiples of pi/2 (a wrist, an elbow, a
    shoulder on a singularity: radicands exactly 0 in exact arithmetic, where a rounding
    decides a branch): the exported C IK finds the branches the same C finds with every
    sine and cosine the angle's own (:func:`sincos_pairs` instead of :func:`ik_trig`),
    the same values ≤ 1e-12 (angles across the cut at ±pi as one)."""
    _need("gcc", shutil.which("gcc") is not None, "apt-get install gcc")
    robot = dhsym.load(name)
    rng = np.random.default_rng(3)
    q = np.vstack([np.zeros(6), rng.integers(-2, 3, (60, 6)) * (np.pi / 2)])
    q[20:40] += rng.uniform(-2.5, 2.5, (20, 6)) * (rng.random((20, 6)) < 0.5)
    poses = robot.fk(q)
    files = dhsym.export(robot, "c", what=("fk", "jacobian", "ik"), prefix="arm")
    monkeypatch.setitem(c_language.LANGUAGE.extra, "ik_trig", sincos_pairs)
    plain = dhsym.export(robot, "c", what=("fk", "jacobian", "ik"), prefix="arm")
    assert plain["arm.c"] != files["arm.c"] or name == "puma560"
    (tmp_path / "plain").mkdir()
    iks = h.run_c(files, "arm", q[:0], poses, 6, True, True, tmp_path)[2]
    want = h.run_c(plain, "arm", q[:0], poses, 6, True, True, tmp_path / "plain")[2]
    assert sum(len(Q) for Q in want) > 4 * len(poses)
    for Q, W in zip(iks, want):
        assert Q.shape == W.shape
        d = np.remainder(Q - W + np.pi, 2 * np.pi) - np.pi
        assert np.abs(d).max(initial=0.0) <= 1e-12


def test_the_native_solver_keeps_libm():
    x, y = sp.symbols("x y", real=True)
    e = sp.atan2(sp.sin(x), sp.cos(y))
    assert CPrinter().doprint(e) == "dh_atan2(dh_sin(x), dh_cos(y))"
    assert NativePrinter().doprint(e) == "atan2(sin(x), cos(y))"
