"""The compact composition is exactly the plain product (hypothesis) and is compact."""

from __future__ import annotations

import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dhsym.kinematics.simplification import (
    compose,
    fold_sum_angles,
    normalize_word,
    numeric_equal,
    prove_equal,
    split_segments,
    tidy_signs,
)
from dhsym.kinematics.transforms import chain_word, plain_product
from dhsym.model.table import Elementary

from ..strategies import dh_tables

SLOW = settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])

x, y, z, r = sp.symbols("x y z r", real=True)


@SLOW
@given(dh_tables(max_rows=5))
def test_compact_equals_plain_product_numerically(table):
    word = chain_word(table, 0, table.n)
    assert numeric_equal(compose(word), plain_product(word), points=20, tol=1e-11)


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(dh_tables(max_rows=3))
def test_compact_equals_plain_product_exactly(table):
    word = chain_word(table, 0, table.n)
    assert prove_equal(compose(word), plain_product(word))


@SLOW
@given(dh_tables(max_rows=4))
def test_inverse_word_composes_to_identity(table):
    fwd = compose(chain_word(table, 0, table.n))
    back = compose(chain_word(table, table.n, 0))
    assert numeric_equal(fwd * back, sp.eye(4), tol=1e-11)


@SLOW
@given(dh_tables(min_rows=2, max_rows=5), st.data())
def test_transforms_chain(table, data):
    i = data.draw(st.integers(0, table.n))
    j = data.draw(st.integers(0, table.n))
    T0i = compose(chain_word(table, 0, i))
    Tij = compose(chain_word(table, i, j))
    T0j = compose(chain_word(table, 0, j))
    assert numeric_equal(T0i * Tij, T0j, tol=1e-11)


@given(
    st.sampled_from([x, x + y, x - y, 2 * x, x + sp.pi / 3]),
    st.sampled_from([y, z, y + z, -z, y - sp.pi / 7]),
    st.sampled_from([1, r, -2 * r, sp.Rational(1, 3)]),
)
def test_fold_sum_angles_keeps_value(A, B, k):
    e = k * (sp.cos(A) * sp.cos(B) - sp.sin(A) * sp.sin(B)) + k * sp.sin(A) * sp.cos(B)
    folded = fold_sum_angles(sp.expand(e))
    assert numeric_equal(sp.Matrix([folded]), sp.Matrix([e]))


def test_fold_sum_angles_recognises_the_four_identities():
    assert fold_sum_angles(sp.cos(x) * sp.cos(y) - sp.sin(x) * sp.sin(y)) == sp.cos(x + y)
    assert fold_sum_angles(sp.cos(x) * sp.cos(y) + sp.sin(x) * sp.sin(y)) == sp.cos(x - y)
    assert fold_sum_angles(sp.sin(x) * sp.cos(y) + sp.cos(x) * sp.sin(y)) == sp.sin(x + y)
    assert fold_sum_angles(sp.sin(x) * sp.cos(y) - sp.cos(x) * sp.sin(y)) == sp.sin(x - y)
    assert fold_sum_angles(r * sp.cos(x) ** 2 + r * sp.sin(x) ** 2) == r
    assert fold_sum_angles(sp.cos(x) * sp.cos(y) + 2 * sp.sin(x) * sp.sin(y)) == (
        sp.cos(x) * sp.cos(y) + 2 * sp.sin(x) * sp.sin(y)
    )


def test_tidy_signs_keeps_value_and_saves_operations():
    e = -z * (-x - y) + 1
    t = tidy_signs(e)
    assert sp.expand(t - e) == 0
    assert sp.count_ops(t) < sp.count_ops(e)


def test_normalize_word_moves_tx_left_of_rx_and_merges():
    a, b = sp.symbols("a b", real=True)
    word = [
        Elementary("R", "x", x),
        Elementary("T", "x", a),
        Elementary("T", "x", b),
        Elementary("R", "z", 0),
        Elementary("R", "z", y),
        Elementary("R", "z", z),
    ]
    assert normalize_word(word) == (
        Elementary("T", "x", a + b),
        Elementary("R", "x", x),
        Elementary("R", "z", y + z),
    )


def test_split_segments_keeps_half_turns_planar():
    word = normalize_word(
        [
            Elementary("R", "z", x),
            Elementary("R", "x", sp.pi),
            Elementary("R", "z", y),
            Elementary("R", "x", sp.pi / 2),
        ]
    )
    segs = split_segments(word)
    assert [s.planar for s in segs] == [True, False]
    assert segs[0].angle == x - y


def test_prove_equal_rejects_a_wrong_sign():
    A = sp.Matrix([[sp.cos(x + y), -sp.sin(x + y) * z]])
    B = sp.Matrix([[sp.cos(x) * sp.cos(y) - sp.sin(x) * sp.sin(y), sp.sin(x + y) * z]])
    assert not prove_equal(A, B)
    assert prove_equal(A[:, :1], B[:, :1])


# --- the normal form of prove_equal against polynomial division --------------------

#: the leaves of the random trigonometric polynomials: sines and cosines of angles (sums,
#: multiples and constant offsets expanded by prove_equal), symbols, square roots
_TRIG_LEAVES = [
    sp.sin(x),
    sp.cos(x),
    sp.sin(y),
    sp.cos(y),
    sp.sin(x + y),
    sp.cos(x - y),
    sp.sin(2 * x),
    sp.cos(y + sp.pi / 3),
    sp.cos(sp.pi / 18),
    z,
    r,
    sp.sqrt(2),
    sp.sqrt(6),
]


@st.composite
def trig_polynomials(draw: st.DrawFn) -> sp.Expr:
    """A random sum of products of leaves (:data:`_TRIG_LEAVES`), nested once, with
    squares."""

    def term() -> sp.Expr:
        coeff = sp.Rational(draw(st.integers(-5, 5)), draw(st.integers(1, 4)))
        factors = draw(st.lists(st.sampled_from(_TRIG_LEAVES), max_size=2))
        power = draw(st.integers(1, 2))
        return coeff * sp.Mul(*factors) ** power

    inner = sp.Add(*(term() for _ in range(draw(st.integers(1, 2)))))
    outer = sp.Add(*(term() for _ in range(draw(st.integers(0, 2)))))
    return inner * term() + outer


def _division_remainder(e: sp.Expr) -> sp.Expr:
    """The remainder of ``e`` modulo ``sin² + cos² − 1`` by :func:`sympy.reduced`, lex
    order with each sine before its cosine, written back in sines and cosines."""
    expanded = sp.expand(sp.expand_trig(e))
    angles = sorted({f.args[0] for f in expanded.atoms(sp.sin, sp.cos)}, key=sp.default_sort_key)
    s = [sp.Dummy(f"s{k}") for k in range(len(angles))]
    c = [sp.Dummy(f"c{k}") for k in range(len(angles))]
    forward = {sp.sin(a): s[k] for k, a in enumerate(angles)}
    forward |= {sp.cos(a): c[k] for k, a in enumerate(angles)}
    poly = sp.expand(expanded.xreplace(forward))
    if not angles or poly == 0:
        return poly
    gens = [g for k in range(len(angles)) for g in (s[k], c[k])]
    others = sorted(poly.free_symbols - set(gens), key=sp.default_sort_key)
    relations = [s[k] ** 2 + c[k] ** 2 - 1 for k in range(len(angles))]
    _, rem = sp.reduced(poly, relations, *gens, *others, order="lex")
    return sp.expand(rem.xreplace({v: k for k, v in forward.items()}))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(trig_polynomials())
def test_the_normal_form_is_the_remainder_of_division(e):
    from sympy.polys.domains import QQ

    from dhsym.kinematics.simplification import _in_ring, _ring_of

    ringed = _ring_of([e])
    assert ringed is not None  # rational coefficients, square roots, linear angles
    ring, R = ringed
    p = _in_ring(e, ring, R, dict(zip(ring.atoms, R.gens)))
    fast = sp.Add(*(QQ.to_sympy(k) * ring.monomial(m) for m, k in p.items()))
    assert sp.expand(fast - _division_remainder(e)) == 0


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(trig_polynomials(), trig_polynomials(), st.sampled_from([0, 1, sp.sqrt(3), sp.pi]))
def test_prove_equal_answers_as_division_does(e, other, k):
    # e against itself rewritten (sin² → 1 − cos², sums of angles expanded), and against
    # itself plus a multiple of another polynomial (often not 0 modulo sin² + cos² − 1);
    # k = π leaves the rationals and their roots: prove_equal divides as the reference does
    rewritten = sp.expand(sp.expand_trig(e)).replace(
        lambda f: f.is_Pow and isinstance(f.base, sp.sin) and f.exp == 2,
        lambda f: 1 - sp.cos(f.base.args[0]) ** 2,
    )
    assert prove_equal(sp.Matrix([k * e]), sp.Matrix([k * rewritten]))
    changed = e + k * other
    expected = _division_remainder(k * other) == 0
    assert prove_equal(sp.Matrix([e, changed]), sp.Matrix([rewritten, e])) is expected
