"""The facade: Robot is a KinematicChain with the rooms above it, cached in typed fields."""

from __future__ import annotations

from types import SimpleNamespace as Obj

import numpy as np
import pytest

import dhsym
from dhsym.errors import DHError
from dhsym.formats.urdf import chain_from_urdf
from dhsym.ik.choices import IKCache
from dhsym.kinematics.chain import KinematicChain
from dhsym.robot import Robot, from_rtb, from_urdf, inverse, load

SLIDE = """<robot name="slide"><link name="a"/><link name="b"/>
  <joint name="s" type="prismatic"><parent link="a"/><child link="b"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="0.5" effort="1" velocity="1"/></joint>
</robot>"""


def test_the_public_names_are_the_facade():
    r = dhsym.load("planar2r")
    assert type(r) is Robot and isinstance(r, KinematicChain)
    assert dhsym.Robot is Robot and dhsym.load is load and dhsym.inverse is inverse
    assert dhsym.from_urdf is from_urdf and dhsym.from_rtb is from_rtb
    assert dhsym.KinematicChain is KinematicChain
    assert repr(r) == "Robot('Planar 2R', RR, standard)"
    assert repr(KinematicChain(r.table)) == "KinematicChain('Planar 2R', RR, standard)"


def test_the_inverse_is_derived_once_and_kept():
    r = load("planar2r")
    assert r.inverse() is r.inverse() is r.ik_cache().inverse()
    assert inverse(r) is r.inverse()
    assert [b.role for b in inverse("planar2r").branches] == ["elbow"]


def test_ik_with_a_joint_given_derives_the_sub_chain_once():
    r = load("panda")
    q = [0.3, -0.5, 0.4, -2.0, 0.2, 1.6, 0.7]
    T = r.fk(q)
    first = r.ik(T, free={7: 0.7})
    given = r.ik_cache().given(7)
    assert type(given.cache.chain) is KinematicChain and given.row == r.n
    second = r.ik(T, free={7: 0.7})
    assert r.ik_cache().given(7) is given
    assert np.array_equal(first.q, second.q)
    assert np.abs(first.q - q).max(axis=1).min() < 1e-9


def test_ik_on_a_chain_with_its_own_cache_matches_the_robot():
    from dhsym.ik.choices import solve

    r = load("puma560")
    chain = KinematicChain(r.table)
    T = r.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    cache = IKCache(chain)
    mine = solve(chain, T, cache=cache)
    assert cache.inverse() is cache.inverse()
    assert np.array_equal(mine.q, r.ik(T).q)


def test_the_equations_of_motion_are_kept_per_method():
    r = load("planar2r")
    lag = r.dynamics()
    assert r.dynamics("lagrange") is lag and r.dynamics(" Lagrange ") is lag
    ne = r.dynamics("newton-euler")
    assert r.dynamics("ne") is ne and r.dynamics("newton_euler") is ne and ne is not lag
    assert (lag.M - ne.M).applyfunc(lambda e: e.expand()).is_zero_matrix
    with pytest.raises(DHError, match="unknown dynamics method 'euler'"):
        r.dynamics("euler")


def test_the_compiled_dynamics_are_kept_per_values():
    r = load("planar2r")
    values = {"a1": 1, "a2": 0.5, "m1": 2, "m2": 1, "Izz1": 0.1, "Izz2": 0.05}
    values |= {"rx1": -0.5, "rx2": -0.25, "ry1": 0, "ry2": 0}
    f = r.dynamics_functions(values)
    assert r.dynamics_functions(dict(values)) is f
    assert r.dynamics_functions({**values, "a1": 2}) is not f
    q = np.array([0.3, -0.4])
    assert np.allclose(r.rne(q, 0 * q, 0 * q, values=values), r.gravload(q, values=values))


def test_from_urdf_and_load_give_robots_the_formats_room_a_chain():
    r = from_urdf(SLIDE, convention="modified")
    c = chain_from_urdf(SLIDE, convention="modified")
    assert type(r) is Robot and type(c) is KinematicChain
    assert r.table == c.table and float(r.fk([0.2])[0, 3]) == pytest.approx(0.2)
    assert type(load(SLIDE, convention="modified")) is Robot


def test_from_rtb_gives_a_robot():
    link = Obj(sigma=0, theta=0.0, d=0.5, a=0.0, alpha=1.5707963267948966, offset=0.0)
    r = from_rtb(Obj(links=[link], mdh=False, base=None, tool=None, name="one"), name="uno")
    assert type(r) is Robot and r.name == "uno" and r.n == 1


def test_the_rooms_below_build_chains():
    from tests.geometry.test_frames import MEASURED

    assert type(dhsym.assign_frames(MEASURED).chain()) is KinematicChain
    assert type(dhsym.formats.urdf.import_urdf(SLIDE).chain()) is KinematicChain
