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

import sympy as sp

import dhsym
from dhsym.export.c import CPrinter, NativePrinter, SinCos, SinCosGroup, sincos_pairs
from dhsym.export.program import fk_program

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


def test_the_ik_takes_the_sines_of_one_level_together():
    """The UR5's innermost level: q2 + q3 and q2 in one call (two at a time), after q2."""
    files = dhsym.export(dhsym.load("ur5"), "c", what="ik", prefix="arm")
    ik = files["arm.c"].split("int arm_ik")[1]
    after_q2 = ik.split("const double q2 =")[1]
    assert "const double angle[2] = {q2 + q3, q2};" in after_q2.split("const double q4 =")[0]
    assert "continue; /* no real value" in ik  # a branch with no real joint value ends there


def test_the_native_solver_keeps_libm():
    x, y = sp.symbols("x y", real=True)
    e = sp.atan2(sp.sin(x), sp.cos(y))
    assert CPrinter().doprint(e) == "dh_atan2(dh_sin(x), dh_cos(y))"
    assert NativePrinter().doprint(e) == "atan2(sin(x), cos(y))"
