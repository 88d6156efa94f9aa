"""The compact equations of motion: grouped constants (Armstrong, Khatib and Burdick 1986),
proven equal to the plain Lagrange–Euler sums, short, and never half symbolic."""

from __future__ import annotations

import pytest
import sympy as sp

import dhsym
from dhsym.dynamics.compact_form import compact_dynamics, symbolic_links
from dhsym.dynamics.model import dynamic_model
from dhsym.kinematics.simplification import prove_equal


def test_spong_two_link_arm_with_its_constants_and_proof():
    cd = compact_dynamics(dhsym.load("spong2r"))
    names = [str(k.symbol) for k in cd.constants]
    assert names == ["Ig1", "Ig2", "gamma1"]  # the table has an I1 of its own
    assert cd.g[0] != 0 and cd.g[1] != 0
    assert cd.proven()
    assert not cd.values  # the table's inertias are symbols already


def test_a_wrong_constant_breaks_the_proof():
    cd = compact_dynamics(dhsym.load("spong2r"))
    first = cd.constants[0]
    broken = type(first)(first.symbol, first.value + sp.Symbol("m2", real=True))
    assert not type(cd)(
        cd.model, cd.M, cd.C, cd.g, cd.tau, cd.christoffel, (broken, *cd.constants[1:]), ()
    ).proven()


def test_numeric_inertias_become_symbols_with_their_values_kept():
    dm, values = symbolic_links(dynamic_model(dhsym.load("puma560")))
    link2 = dm.links[1]
    assert link2.m == sp.Symbol("m2", real=True)
    assert values[link2.m] == sp.Rational(87, 5)
    assert link2.I[0, 1] == 0  # zero products of inertia stay zero
    assert all(s.is_Symbol for L in dm.links for s in (L.m, *L.r) if s != 0)


@pytest.fixture(scope="module")
def puma() -> object:
    return compact_dynamics(dhsym.load("puma560"))


@pytest.mark.slow
def test_puma_m11_has_at_most_thirty_terms_once_the_constants_are_named(puma):
    assert puma.terms(1, 1) <= 30
    constant_names = {k.symbol for k in puma.constants}
    assert puma.M[0, 0].free_symbols & constant_names
    # lengths and inertias both symbolic: no number other than small integers
    assert all(n.is_Integer for n in puma.M.atoms(sp.Number))


@pytest.mark.slow
def test_puma_compact_equations_are_proven_equal_to_the_expanded_ones(puma):
    assert puma.proven()


@pytest.mark.slow
def test_puma_symbolic_with_values_equals_the_numeric_derivation(puma):
    numeric = compact_dynamics(dhsym.load("puma560"), symbolic=False)
    assert not numeric.constants  # every coefficient a number
    assert numeric.M.free_symbols <= set(numeric.model.variables)
    values = dict(puma.values) | dhsym.load("puma560").table.value_map
    for part in ("M", "g"):
        assert prove_equal(puma.expanded(part).xreplace(values), getattr(numeric, part))
