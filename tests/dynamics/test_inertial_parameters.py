"""τ = Y π exactly, and the base parameters reproduce τ."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

import dhsym
from dhsym.dynamics import base_parameters, lagrange, regressor
from dhsym.dynamics.inertial_parameters import standard_values
from dhsym.kinematics.simplification import prove_equal


@pytest.mark.parametrize("name", ["planar2r", "example1_rrp"])
def test_Y_times_pi_is_tau_exactly(name):
    robot = dhsym.load(name)
    reg = regressor(robot)
    tau = reg.Y * sp.Matrix(reg.parameters)
    assert prove_equal(tau.subs(standard_values(reg.model)), lagrange(robot).tau)


def test_standard_values_use_the_parallel_axis_theorem():
    v = standard_values(lagrange(dhsym.load("planar2r")).model)
    S = {n: sp.Symbol(n, real=True) for n in ("ZZ2", "Izz2", "m2", "rx2", "ry2", "MX2")}
    assert sp.expand(v[S["ZZ2"]] - (S["Izz2"] + S["m2"] * (S["rx2"] ** 2 + S["ry2"] ** 2))) == 0
    assert v[S["MX2"]] == S["m2"] * S["rx2"]


def test_base_parameters_of_the_planar_arm():
    base = base_parameters(dhsym.load("planar2r"))
    assert len(base.combinations) == 4  # Khalil: 4 base parameters for a planar 2R arm
    names = {str(s) for s in base.unidentifiable}
    assert {"XX1", "YY1", "XX2", "MZ2"} <= names
    assert any("ZZ2" in line and "16*M2/25" in line for line in base.lines())  # a2 = 0.8


@settings(max_examples=10, deadline=None)
@given(st.lists(st.floats(-3, 3), min_size=6, max_size=6))
def test_base_regressor_reproduces_tau(state):
    base = _base()
    reg = base.regressor
    rng = np.random.default_rng(0)
    pi = {s: sp.Float(rng.uniform(0.1, 1.0)) for s in reg.parameters}
    args = dict(zip((*reg.model.variables, *reg.model.rates, *reg.model.accelerations), state))
    values = dhsym.load("planar2r").table.value_map
    full = (reg.Y * sp.Matrix(reg.parameters)).subs(values).subs(args).subs(pi)
    reduced = (base.Y * sp.Matrix(base.combinations)).subs(values).subs(args).subs(pi)
    assert np.allclose(np.array(full, dtype=float), np.array(reduced, dtype=float), atol=1e-8)


_CACHE: list = []


def _base():
    if not _CACHE:
        _CACHE.append(base_parameters(dhsym.load("planar2r")))
    return _CACHE[0]
