"""Via points: roboticstoolbox 1.5.0's ``mstraj`` numbers recorded (no runtime dependency),
and cubic splines with continuous acceleration."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from dhsym.errors import DHError
from dhsym.trajectory import mstraj, spline, via_cubic

# roboticstoolbox.mstraj(array([[0, 0], [1, 2], [2, 2]]), dt=0.1, tacc=0.2, qdmax=[1, 1]):
# 33 rows, every fourth kept (rows 0, 4, …, 32)
RTB_MSTRAJ_Q = [
    [0.04761904761904767, 0.09523809523809534],
    [0.23809523809523808, 0.47619047619047616],
    [0.42857142857142855, 0.8571428571428571],
    [0.6190476190476191, 1.2380952380952381],
    [0.8095238095238095, 1.619047619047619],
    [1.0066964285714286, 1.9821428571428572],
    [1.3333333333333335, 2.0],
    [1.6666666666666667, 2.0],
    [2.0, 2.0],
]
RTB_MSTRAJ_QD = [
    [4.7619047619047783e-01, 9.5238095238095566e-01],
    [4.7619047619047616e-01, 9.5238095238095233e-01],
    [4.7619047619047616e-01, 9.5238095238095233e-01],
    [4.7619047619047616e-01, 9.5238095238095233e-01],
    [4.7619047619047616e-01, 9.5238095238095233e-01],
    [6.5476190476190432e-01, 4.7619047619047716e-01],
    [8.3333333333333337e-01, 0.0],
    [8.3333333333333337e-01, 0.0],
    [3.0531133177191805e-15, 0.0],
]


def test_mstraj_equals_roboticstoolbox() -> None:
    dt = sp.Rational(1, 10)
    p = mstraj([[0, 0], [1, 2], [2, 2]], dt=dt, tacc=0.2, qdmax=[1, 1])
    assert p.duration == sp.Rational(33, 10)  # 33 samples of roboticstoolbox
    rows = np.arange(0, 33, 4)
    q, qd, _ = p.sample((rows + 1) * 0.1)  # its row k is the time (k + 1) dt
    np.testing.assert_allclose(q, RTB_MSTRAJ_Q, atol=1e-12)
    np.testing.assert_allclose(qd, RTB_MSTRAJ_QD, atol=1e-12)
    assert p.derivation().solution == (sp.Rational(21, 10), sp.Rational(6, 5))


def test_mstraj_arguments() -> None:
    with pytest.raises(DHError, match="one of the two"):
        mstraj([[0], [1]], 0.1, 0.2)
    with pytest.raises(DHError, match="shorter than its blends"):
        mstraj([[0], [1]], 0.1, 1, tsegment=[0.5])
    p = mstraj([[0], [1]], 0.1, 0.2, tsegment=[2])
    q, qd, _ = p.sample([0.0, 2.0])
    np.testing.assert_allclose(q[:, 0], [0, 1], atol=1e-15)


def test_spline_passes_through_with_continuous_acceleration() -> None:
    via, times = [0, 1, 3, 2], [0, 1, 2, 4]
    p = spline(via, times)
    for k, t in enumerate(times):
        assert p.at(t) == (via[k],)
    for t in times[1:-1]:
        left, right = p.joints[0][times.index(t) - 1], p.joints[0][times.index(t)]
        x = sp.Symbol("t", nonnegative=True)
        for order in (1, 2):
            assert sp.diff(left.position(), x, order).subs(x, t) == sp.diff(
                right.position(), x, order
            ).subs(x, t)
    assert p.derivation().matrix is not None and p.derivation().check()
    # the end velocities as given
    _, qd, _ = spline([[0, 0], [1, 1], [0, 2]], [0, 1, 2], v0=[0, 1], vf=0).sample([0.0, 2.0])
    np.testing.assert_allclose(qd, [[0, 1], [0, 0]], atol=1e-15)


def test_spline_symbolic_inner_velocity() -> None:
    q0, q1, q2, h = sp.symbols("q0 q1 q2 h", positive=True)
    p = spline([q0, q1, q2], [0, h, 2 * h])
    (v1,) = p.derivation().solution
    assert sp.simplify(v1 - 3 * (q2 - q0) / (4 * h)) == 0


def test_spline_arguments() -> None:
    with pytest.raises(DHError, match="times must increase"):
        spline([0, 1, 2], [0, 2, 1])
    with pytest.raises(DHError, match="3 via points but 2 times"):
        spline([0, 1, 2], [0, 1])


def test_craig_via_blends() -> None:
    from dhsym.trajectory import via_blends

    via, durations, acc = [0, 1, 3, 2], [1, 1, 1.5], 8
    p = via_blends(via, durations, acc)
    segs = p.joints[0]
    assert len(segs) == 7  # four blends, three lines
    times = [0, 1, 2, sp.Rational(7, 2)]
    lines = segs[1::2]
    for k, line in enumerate(lines):  # each line runs through its via point at its time
        anchor = 1 if k == 0 else k
        x = sp.Symbol("t", nonnegative=True)
        assert sp.simplify(line.position(x).subs(x, times[anchor]) - via[anchor]) == 0
    for seg in segs[0::2]:  # blends of the given acceleration, lines of none
        assert abs(seg.coefficients[2]) == sp.Rational(acc, 2)
    for seg in segs[1:]:  # position and velocity continuous at every joint of pieces
        t0 = float(seg.start)
        before, after = p.sample([t0 - 1e-10]), p.sample([t0 + 1e-10])
        assert abs(before[0] - after[0]).max() < 1e-8 and abs(before[1] - after[1]).max() < 1e-8
    q, qd, _ = p.sample([0.0, 3.5])
    np.testing.assert_allclose(q, [0, 2], atol=1e-12)
    np.testing.assert_allclose(qd, [0, 0], atol=1e-12)
    assert p.derivation().check()
    with pytest.raises(DHError, match="acceleration is too small"):
        via_blends(via, durations, 0.5)
    with pytest.raises(DHError, match="at least three via points"):
        via_blends([0, 1], [1], 8)


# --- the via-point rule: cubics with the via velocities chosen by the slopes ------------
def _cubic_by_hand(q0, q1, v0, v1, h):
    """Craig's closed form of the cubic between two via points (an independent method)."""
    D = q1 - q0
    return (q0, v0, 3 * D / h**2 - (2 * v0 + v1) / h, -2 * D / h**3 + (v0 + v1) / h**2)


def test_via_cubic_worked_example() -> None:
    # via points 10, 30, 40, 20 (degrees) at 0, 2, 3, 5 s: slopes 10, 10, -10
    p = via_cubic([10, 30, 40, 20], [0, 2, 3, 5])
    d = p.derivation()
    assert d.pairs == (
        (sp.Symbol("d_1", real=True), 10),
        (sp.Symbol("d_2", real=True), 10),
        (sp.Symbol("d_3", real=True), -10),
        (sp.Symbol("v_1", real=True), 10),  # same sign: (10 + 10)/2
        (sp.Symbol("v_2", real=True), 0),  # the sign changes: at rest
    )
    assert d.check()
    R = sp.Rational
    want = [
        _cubic_by_hand(R(10), R(30), R(0), R(10), R(2)),
        _cubic_by_hand(R(30), R(40), R(10), R(0), R(1)),
        _cubic_by_hand(R(40), R(20), R(0), R(0), R(2)),
    ]
    assert [s.coefficients for s in p.joints[0]] == want
    assert want[0] == (10, 0, 10, -5 / R(2)) and want[1] == (30, 10, 10, -10)
    assert "same sign" in d.labels[3] and "sign changes" in d.labels[4]
    assert str(d).splitlines()[:5] == [
        "d_1 = 20/2",
        "d_2 = 10",
        "d_3 = -20/2",
        "v_1 = (d_1 + d_2)/2",
        "v_2 = 0",
    ]


def test_via_cubic_is_continuous_in_position_and_velocity() -> None:
    via = [[0, 1], [1, 3], [3, 2], [2, 2], [-1, 0]]
    times = [0, 1, sp.Rational(5, 2), 3, 5]
    p = via_cubic(via, times, v0=[0, 1], vf=[1, 0])
    t = sp.Symbol("t")
    for j, segs in enumerate(p.joints):
        assert segs[0].position(sp.Integer(0)) == via[0][j]
        assert sp.diff(segs[0].position(t), t).subs(t, 0) == [0, 1][j]
        assert sp.diff(segs[-1].position(t), t).subs(t, 5) == [1, 0][j]
        for k in range(len(segs) - 1):
            a, b = segs[k], segs[k + 1]
            assert a.end == b.start == times[k + 1]
            assert a.position(a.end) == b.position(b.start) == via[k + 1][j]
            va = sp.diff(a.position(t), t).subs(t, a.end)
            vb = sp.diff(b.position(t), t).subs(t, b.start)
            assert va == vb
    # joint 2: slopes 2, -2/3, 0, -1: a sign change, a zero slope, a zero slope
    assert p.derivation(2).solution[-3:] == (0, 0, 0)
    # joint 1: slopes 1, 4/3, -2, -3/2: the average, a sign change, same sign
    assert p.derivation(1).solution[-3:] == (sp.Rational(7, 6), 0, sp.Rational(-7, 4))
    q, qd, _ = p.sample(np.linspace(0, 5, 501))
    assert np.all(np.isfinite(q))
    at = p.sample([1 - 1e-9, 1 + 1e-9])[1]
    np.testing.assert_allclose(at[0], at[1], atol=1e-6)


def test_via_cubic_differs_from_the_spline_in_acceleration() -> None:
    via, times = [0, 1, 3, 2], [0, 1, 2, 3]
    rule, smooth = via_cubic(via, times), spline(via, times)
    jump = rule.sample([1 - 1e-9, 1 + 1e-9])[2]
    assert abs(jump[0] - jump[1]) > 1  # the rule: acceleration jumps at the via point
    cont = smooth.sample([1 - 1e-9, 1 + 1e-9])[2]
    assert abs(cont[0] - cont[1]) < 1e-6  # the spline: continuous


def test_via_cubic_arguments() -> None:
    with pytest.raises(DHError, match="times must increase"):
        via_cubic([0, 1, 2], [0, 2, 1])
    with pytest.raises(DHError, match="3 via points but 2 times"):
        via_cubic([0, 1, 2], [0, 1])
    a, b = sp.symbols("a b", real=True)
    with pytest.raises(DHError, match="have the same sign: give numbers"):
        via_cubic([0, a, b], [0, 1, 2])
    two = via_cubic([0, 1], [0, 2])  # no via point: one cubic
    assert two.joints[0][0].coefficients == (0, 0, sp.Rational(3, 4), sp.Rational(-1, 4))
