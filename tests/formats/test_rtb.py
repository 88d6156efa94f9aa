"""roboticstoolbox both ways: recorded numbers always; the real toolbox when installed."""

from __future__ import annotations

import math
import sys
from types import SimpleNamespace as Obj

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.errors import FormatError
from dhsym.formats.rtb import table_from_rtb, to_rtb
from dhsym.kinematics.chain import KinematicChain

# roboticstoolbox-python 1.5.0, rtb.models.DH.Puma560(): the links' documented attributes
# (sigma, theta, d, a, alpha, offset, qlim, isflip) and fkine([0.1, ..., 0.6]).A, recorded
# once with the toolbox installed outside the project's environment.
PUMA_LINKS = [
    (
        0,
        0.0,
        0.6718299999999999,
        0,
        1.5707963267948966,
        0.0,
        [-2.792526803190927, 2.792526803190927],
    ),
    (0, 0.0, 0, 0.4318, 0.0, 0.0, [-0.7853981633974483, 3.9269908169872414]),
    (0, 0.0, 0.15005, 0.0203, -1.5707963267948966, 0.0, [-3.9269908169872414, 0.7853981633974483]),
    (0, 0.0, 0.4318, 0, 1.5707963267948966, 0.0, [-1.9198621771937625, 2.9670597283903604]),
    (0, 0.0, 0, 0, -1.5707963267948966, 0.0, [-1.7453292519943295, 1.7453292519943295]),
    (0, 0.0, 0, 0, 0.0, 0.0, [-4.642575810304916, 4.642575810304916]),
]
PUMA_FKINE = [
    [0.12169768141653306, -0.6066717260175295, -0.7855820079334506, 0.2478027469236375],
    [0.8183638247039288, 0.5091974688455275, -0.2664556025631021, -0.1259401814515313],
    [0.561667450324298, -0.6104648675986358, 0.5584463453851071, 1.1462879056952355],
    [0.0, 0.0, 0.0, 1.0],
]


def puma() -> Obj:
    keys = ("sigma", "theta", "d", "a", "alpha", "offset", "qlim")
    links = [Obj(**dict(zip(keys, row, strict=True)), isflip=False) for row in PUMA_LINKS]
    return Obj(links=links, mdh=False, base=np.eye(4), tool=np.eye(4), name="Puma 560")


def test_from_rtb_reproduces_recorded_fkine() -> None:
    r = KinematicChain(table_from_rtb(puma()))
    assert r.table.rows[2].d == sp.Rational("0.15005")
    assert r.table.rows[0].alpha == sp.pi / 2 and r.table.rows[1].limits == (
        -sp.pi / 4,
        5 * sp.pi / 4,
    )
    assert np.abs(r.fk([0.1, 0.2, 0.3, 0.4, 0.5, 0.6]) - np.array(PUMA_FKINE)).max() < 1e-12


def _link_A(sigma: int, theta: float, d: float, a: float, alpha: float, q: float) -> np.ndarray:
    """The toolbox's standard DH link transform (DHLink.A), written out."""
    th, dd = (q, d) if sigma == 0 else (theta, q)
    ct, st, ca, sa = math.cos(th), math.sin(th), math.cos(alpha), math.sin(alpha)
    return np.array(
        [
            [ct, -st * ca, st * sa, a * ct],
            [st, ct * ca, -ct * sa, a * st],
            [0, sa, ca, dd],
            [0, 0, 0, 1],
        ]
    )


def test_flipped_joints_keep_the_meaning_of_q() -> None:
    links = [
        Obj(sigma=0, theta=0.0, d=0.3, a=0.2, alpha=0.5, offset=0.25, qlim=None, isflip=True),
        Obj(sigma=1, theta=0.4, d=0.0, a=0.1, alpha=0.0, offset=0.1, qlim=[0, 1], isflip=True),
    ]
    base = np.eye(4)
    base[:3, 3] = [0.0, 0.0, 0.7]
    r = KinematicChain(
        table_from_rtb(Obj(links=links, mdh=False, base=base, tool=None, name="flip"))
    )
    assert r.table.rows[0].offset == sp.Rational(1, 4) and r.table.base
    for q in ([0.3, 0.2], [-1.0, 0.6]):
        A1 = _link_A(0, 0, 0.3, 0.2, 0.5, -q[0] + 0.25)
        A2 = _link_A(1, 0.4, 0, 0.1, 0.0, -q[1] + 0.1)
        assert np.abs(r.fk(q) - base @ A1 @ A2).max() < 1e-12


def test_bad_attributes_are_refused() -> None:
    with pytest.raises(FormatError, match="links"):
        table_from_rtb(Obj(links=[], mdh=False))
    bad = Obj(sigma=0, theta=0.0, d="x", a=0, alpha=0, offset=0, qlim=None, isflip=False)
    with pytest.raises(FormatError, match=r"links\[0\].d: expected a number"):
        table_from_rtb(Obj(links=[bad], mdh=False, base=None, tool=None, name="b"))


def test_to_rtb_says_what_to_install(monkeypatch) -> None:
    monkeypatch.setitem(sys.modules, "roboticstoolbox", None)
    with pytest.raises(FormatError, match="pip install roboticstoolbox-python"):
        to_rtb(dhsym.load("planar2r"))


def test_both_ways_with_the_toolbox() -> None:
    rtb = pytest.importorskip("roboticstoolbox")  # not a dhsym dependency: runs where installed
    rng = np.random.default_rng(0)
    for model in (rtb.models.DH.Puma560(), rtb.models.DH.Panda(), rtb.models.DH.Stanford()):
        q = rng.uniform(-1, 1, model.n)
        r = KinematicChain(table_from_rtb(model))
        assert np.abs(r.fk(q) - model.fkine(q).A).max() < 1e-12
        assert np.abs(to_rtb(r).fkine(q).A - model.fkine(q).A).max() < 1e-12
    for table in (
        dhsym.load("stanford").table,
        dhsym.convert(dhsym.load("scara").table, "modified"),
    ):
        table = table.with_values({s: 0.3 for s in table.constants if s not in table.value_map})
        r = dhsym.Robot(table)
        q = rng.uniform(-1, 1, table.n)
        assert np.abs(r.to_rtb().fkine(q).A - r.fk(q)).max() < 1e-12
