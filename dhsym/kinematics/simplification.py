"""Textbook-compact products of elementary transforms, by construction.

No ``simplify``/``trigsimp``/``fu`` runs over a whole product. Instead:

1. **Normalise the word**: drop identities, move each ``Tx`` left past an
   ``Rx`` (they commute), merge neighbours of the same kind and axis.
2. **Planar segments**: a maximal run of ``Rz``, ``Tz``, ``Tx``, ``Ty`` and
   half-turn flips ``Rx(π)``, ``Ry(π)`` keeps the z axis (up to sign), so its
   rotation is ``Rz(φ)`` (times a flip) with φ the *sum* of the joint angles
   (a difference after a flip) and its translation is ``Σ a_k (cos φ_k, sin φ_k)``
   — this is where ``C12`` and ``a1 C1 + a2 C12`` come from, exactly.
3. **Nesting**: segments and the remaining twists are multiplied right to left
   without expanding, which keeps the textbook nesting (arm part times wrist
   part): ``c1[c23(c4c5c6 − s4s6) − s23s5c6] + s1(s4c5c6 + c4s6)``.
4. **Targeted identities**: in each sum, pairs ``cAcB ∓ sAsB``, ``sAcB ± cAsB``
   and ``cA² + sA²`` are folded (:func:`fold_sum_angles`).

:func:`prove_equal` checks a result against the plain product exactly
(polynomial reduction modulo ``s² + c² − 1``); :func:`numeric_equal` at random
points.

Examples
--------
>>> from dhsym.model.table import Elementary as E
>>> t1, t2, a1, a2 = sp.symbols("theta1 theta2 a1 a2", real=True)
>>> T = compose([E("R", "z", t1), E("T", "x", a1), E("R", "z", t2), E("T", "x", a2)])
>>> T[0, 0], T[0, 3]
(cos(theta1 + theta2), a1*cos(theta1) + a2*cos(theta1 + theta2))
"""

from __future__ import annotations

import random
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import Any, TypeAlias

import sympy as sp
from sympy.polys.domains import QQ
from sympy.polys.polyerrors import BasePolynomialError, CoercionFailed
from sympy.polys.rings import PolyRing

from dhsym.errors import DHError
from dhsym.model.table import Elementary

from .numeric import compile_exprs
from .transforms import cos_sin, plain_product
from .trig_ring import TrigRing

__all__ = [
    "Segment",
    "closed_form_size",
    "compose",
    "fold_sum_angles",
    "normalize_word",
    "numeric_equal",
    "prove_equal",
    "split_segments",
    "tidy_signs",
    "trig_coefficients",
]

Matrix: TypeAlias = sp.ImmutableMatrix
_FLOAT_TOL = 1e-12


def _is_zero_turn(e: Elementary) -> bool:
    if e.kind == "T":
        return bool(e.value == 0)
    v = e.value
    return v == 0 or (not v.free_symbols and (v / (2 * sp.pi)).is_integer is True)


def _is_half_turn(e: Elementary) -> bool:
    v = e.value
    return (
        e.kind == "R"
        and e.axis in ("x", "y")
        and not v.free_symbols
        and ((v - sp.pi) / (2 * sp.pi)).is_integer is True
    )


def normalize_word(word: Sequence[Elementary]) -> tuple[Elementary, ...]:
    """Drop identities, move translations left past rotations about their own axis, merge.

    >>> from dhsym.model.table import Elementary as E
    >>> a = sp.Symbol("a")
    >>> normalize_word([E("R", "z", 1), E("T", "z", 0), E("R", "x", 1), E("T", "x", a),
    ...                 E("R", "z", 2)])
    (Rz(1), Tx(a), Rx(1), Rz(2))
    >>> normalize_word([E("R", "z", 1), E("R", "z", -1)])
    ()
    """
    out: list[Elementary] = []
    for e in word:
        if _is_zero_turn(e):
            continue
        out.append(e)
        # bubble a translation left past rotations about the same axis
        k = len(out) - 1
        while (
            k > 0
            and out[k].kind == "T"
            and out[k - 1].kind == "R"
            and out[k - 1].axis == out[k].axis
        ):
            out[k - 1], out[k] = out[k], out[k - 1]
            k -= 1
        # merge with the left neighbour of the same kind and axis
        while k > 0 and out[k - 1].kind == out[k].kind and out[k - 1].axis == out[k].axis:
            merged = Elementary(out[k].kind, out[k].axis, out[k - 1].value + out[k].value)
            del out[k - 1 : k + 1]
            k -= 1
            if _is_zero_turn(merged):
                break
            out.insert(k, merged)
        del k
    return tuple(out)


@dataclass(frozen=True)
class Segment:
    """A run of elementaries that keeps the z axis, or one other elementary.

    ``planar`` segments compose by angle addition; others are single factors.
    """

    word: tuple[Elementary, ...]
    planar: bool

    @property
    def angle(self) -> sp.Expr:
        """The accumulated angle φ of a planar segment (sum/difference of its Rz)."""
        return _planar(self.word)[0]

    def matrix(self) -> Matrix:
        """The segment's 4×4 matrix in closed form."""
        if not self.planar:
            return plain_product(self.word)
        phi, sigma, p = _planar(self.word)
        c, s = cos_sin(phi)
        return Matrix(
            [
                [c, -sigma * s, 0, p[0]],
                [s, sigma * c, 0, p[1]],
                [0, 0, sigma, p[2]],
                [0, 0, 0, 1],
            ]
        )


def _is_planar(e: Elementary) -> bool:
    return e.axis == "z" or e.kind == "T" or _is_half_turn(e)


def _planar(word: Sequence[Elementary]) -> tuple[sp.Expr, int, list[sp.Expr]]:
    """Angle φ, flip sign σ and translation p of a planar run: ``Rz(φ)·diag(1,σ,σ)``."""
    phi: sp.Expr = sp.Integer(0)
    sigma = 1
    p: list[sp.Expr] = [sp.Integer(0)] * 3
    for e in word:
        if e.kind == "R" and e.axis == "z":
            phi += sigma * e.value
        elif e.kind == "R":  # half turn about x, or about y = Rz(pi) Rx(pi)
            if e.axis == "y":
                phi += sigma * sp.pi
            sigma = -sigma
        elif e.axis == "z":
            p[2] += sigma * e.value
        elif e.axis == "x":
            c, s = cos_sin(phi)
            p[0] += e.value * c
            p[1] += e.value * s
        else:
            c, s = cos_sin(phi)
            p[0] += -sigma * e.value * s
            p[1] += sigma * e.value * c
    return phi, sigma, p


def split_segments(word: Sequence[Elementary]) -> tuple[Segment, ...]:
    """Split a normalised word into planar runs and single non-planar factors.

    >>> from dhsym.model.table import Elementary as E
    >>> [s.planar for s in split_segments([E("R", "z", 1), E("R", "x", sp.pi / 2),
    ...                                    E("R", "z", 2), E("T", "x", 3)])]
    [True, False, True]
    """
    segs: list[Segment] = []
    run: list[Elementary] = []
    for e in word:
        if _is_planar(e):
            run.append(e)
            continue
        if run:
            segs.append(Segment(tuple(run), True))
            run = []
        segs.append(Segment((e,), False))
    if run:
        segs.append(Segment(tuple(run), True))
    return tuple(segs)


def compose(word: Sequence[Elementary]) -> Matrix:
    """The product of ``word`` in textbook-compact closed form.

    Exact: equal to :func:`dhsym.kinematics.transforms.plain_product` of the same word.

    >>> from dhsym.model.table import Elementary as E
    >>> t1, t2 = sp.symbols("theta1 theta2", real=True)
    >>> compose([E("R", "z", t1), E("R", "x", sp.pi), E("R", "z", t2)])[:2, :2]
    Matrix([
    [cos(theta1 - theta2),  sin(theta1 - theta2)],
    [sin(theta1 - theta2), -cos(theta1 - theta2)]])
    """
    segs = split_segments(normalize_word(word))
    if not segs:
        return Matrix(sp.eye(4))
    result = segs[-1].matrix()
    for seg in reversed(segs[:-1]):
        result = seg.matrix() * result
    return Matrix(result.applyfunc(lambda e: tidy_signs(fold_sum_angles(e))))


def _nodes(expr: sp.Expr) -> int:
    return sum(1 for _ in sp.preorder_traversal(expr))


def _segment_sizes(seg: Segment) -> list[list[int]]:
    """Expression sizes of a segment's 16 entries (0: the entry is zero), without building them."""
    eye = [[int(i == j) for j in range(4)] for i in range(4)]
    if not seg.planar:
        (e,) = seg.word
        n = _nodes(e.value)
        axis = "xyz".index(e.axis)
        if e.kind == "T":
            eye[axis][3] = n
            return eye
        const = not e.value.free_symbols
        c = 0 if const and sp.cos(e.value) == 0 else n + 1
        si = 0 if const and sp.sin(e.value) == 0 else n + 1
        b, d = (k for k in range(3) if k != axis)
        eye[b][b] = eye[d][d] = c
        eye[b][d], eye[d][b] = si + 1 if si else 0, si
        return eye
    phi, rot, p_xy, terms, p_z = 0, False, 0, 0, 0
    for e in seg.word:
        if e.kind == "R":
            phi, rot = phi + (_nodes(e.value) if e.axis == "z" else 1), True
        elif e.axis == "z":
            p_z += _nodes(e.value) + 1
        else:
            p_xy += _nodes(e.value) + (phi + 2 if rot else 0) + 1
            terms += 1
    trig = phi + 2 if rot else 0
    return [
        [trig or 1, trig + 1 if rot else 0, 0, p_xy + terms],
        [trig if rot else 0, trig or 1, 0, p_xy + terms],
        [0, 0, 1, p_z],
        [0, 0, 0, 1],
    ]


def closed_form_size(word: Sequence[Elementary]) -> int:
    """An estimate (from above) of the expression size of :func:`compose` of ``word``.

    Counted without building anything, in microseconds: the sizes of each segment's
    entries, multiplied through as :func:`compose` multiplies (a sum of products per
    entry).  It is close for planar chains and about 3× above the result for spatial
    ones, whose closed form grows exponentially with the number of twisted joints.

    >>> from dhsym.model.table import Elementary as E
    >>> t1, t2, a1, a2 = sp.symbols("theta1 theta2 a1 a2", real=True)
    >>> word = [E("R", "z", t1), E("T", "x", a1), E("R", "z", t2), E("T", "x", a2)]
    >>> closed_form_size(word), sum(_nodes(e) for e in compose(word))
    (45, 50)
    """
    segs = split_segments(normalize_word(word))
    if not segs:
        return 16
    result = _segment_sizes(segs[-1])
    for seg in reversed(segs[:-1]):
        left = _segment_sizes(seg)
        product = [[0] * 4 for _ in range(4)]
        for i in range(4):
            for j in range(4):
                terms = [
                    left[i][k] + result[k][j] + 1 for k in range(4) if left[i][k] and result[k][j]
                ]
                product[i][j] = sum(terms) + max(0, len(terms) - 1)
        result = product
    return sum(map(sum, result))


def tidy_signs(expr: sp.Expr) -> sp.Expr:
    """Move minus signs out of inner sums where that saves operations.

    ``-(-a - b)*c`` becomes ``(a + b)*c``; ``(-a - b)*c`` becomes ``-(a + b)*c``
    when it prints shorter. The value never changes.

    >>> a, b, c = sp.symbols("a b c", real=True)
    >>> tidy_signs(c * (-a - b) + 1)
    -c*(a + b) + 1
    """
    if expr.is_Atom or not isinstance(expr, sp.Expr):
        return expr
    args = [tidy_signs(a) for a in expr.args]
    node = expr.func(*args) if args != list(expr.args) else expr
    if not node.is_Add:
        return node
    terms = list(node.args)
    best = sp.count_ops(node)
    for k, term in enumerate(terms):
        if not term.is_Mul:
            continue
        factors = list(term.args)
        for m, f in enumerate(factors):
            if not f.is_Add:
                continue
            flipped = sp.Mul(
                -1, *factors[:m], sp.Add(*[-t for t in f.args]), *factors[m + 1 :], evaluate=True
            )
            trial = sp.Add(*terms[:k], flipped, *terms[k + 1 :])
            ops = sp.count_ops(trial)
            if ops < best:
                best, terms[k] = ops, flipped
                break
    return sp.Add(*terms)


# --- targeted sum-angle identities ------------------------------------------------


def _trig_pairs(term: sp.Expr) -> list[tuple[tuple[object, ...], sp.Expr, sp.Expr]]:
    """Every way to read ``term`` as ``coeff * rest * f(A) * g(B)`` with f, g in {sin, cos}.

    Returns ``(signature, coeff, rest)`` triples; the signature names the pair.
    """
    coeff, body = term.as_coeff_Mul()
    factors: list[sp.Expr] = []
    for f in sp.Mul.make_args(body):
        base, exp = f.as_base_exp()
        if isinstance(base, (sp.sin, sp.cos)) and exp.is_Integer and 0 < exp <= 4:
            factors.extend([base] * int(exp))
        else:
            factors.append(f)
    out = []
    n = len(factors)
    for i in range(n):
        for j in range(i + 1, n):
            f, g = factors[i], factors[j]
            if not (isinstance(f, (sp.sin, sp.cos)) and isinstance(g, (sp.sin, sp.cos))):
                continue
            rest = sp.Mul(*(factors[k] for k in range(n) if k not in (i, j)))
            A, B = f.args[0], g.args[0]
            if isinstance(f, sp.cos) and isinstance(g, sp.cos):
                sig: tuple[object, ...] = ("cc", frozenset((A, B)), A == B)
            elif isinstance(f, sp.sin) and isinstance(g, sp.sin):
                sig = ("ss", frozenset((A, B)), A == B)
            elif isinstance(f, sp.sin):
                sig = ("sc", A, B)
            else:
                sig = ("sc", B, A)
            out.append((sig, coeff, rest))
    return out


def _fold_pair(terms: list[sp.Expr]) -> list[sp.Expr] | None:
    """Fold one matching pair of terms of a sum, or return None."""
    reads = [_trig_pairs(t) for t in terms]
    index: dict[tuple[object, ...], list[tuple[int, sp.Expr]]] = {}
    for i, rs in enumerate(reads):
        for sig, coeff, rest in rs:
            index.setdefault((sig, rest), []).append((i, coeff))
    for i, rs in enumerate(reads):
        for sig, coeff, rest in rs:
            kind = sig[0]
            if kind == "cc":
                partner_sig: tuple[object, ...] = ("ss", sig[1], sig[2])
            elif kind == "sc" and sig[1] != sig[2]:
                partner_sig = ("sc", sig[2], sig[1])
            else:
                continue
            for j, c2 in index.get((partner_sig, rest), []):
                if j == i:
                    continue
                new = _combine(kind, sig, coeff, c2)
                if new is None:
                    continue
                kept = [t for k, t in enumerate(terms) if k not in (i, j)]
                return [*kept, coeff * rest * new]
    return None


def _combine(kind: str, sig: tuple[Any, ...], c1: sp.Expr, c2: sp.Expr) -> sp.Expr | None:
    if kind == "cc":
        A, B = (list(sig[1]) * 2)[:2] if sig[2] else sorted(sig[1], key=sp.default_sort_key)
        if c2 == -c1:
            return sp.cos(A + B)
        if c2 == c1:
            return sp.cos(A - B)
        return None
    A, B = sig[1], sig[2]
    if c2 == c1:
        return sp.sin(A + B)
    if c2 == -c1:
        return sp.sin(A - B)
    return None


def fold_sum_angles(expr: sp.Expr) -> sp.Expr:
    """Apply the sum-angle and Pythagorean identities to pairs of terms, bottom up.

    >>> a, b, r = sp.symbols("a b r", real=True)
    >>> fold_sum_angles(r * sp.cos(a) * sp.cos(b) - r * sp.sin(a) * sp.sin(b))
    r*cos(a + b)
    >>> fold_sum_angles(sp.sin(a) * sp.cos(b) - sp.cos(a) * sp.sin(b) + 2)
    sin(a - b) + 2
    >>> fold_sum_angles(3 * sp.cos(a)**2 + 3 * sp.sin(a)**2)
    3
    """
    if expr.is_Atom or not isinstance(expr, sp.Expr):
        return expr
    args = [fold_sum_angles(a) for a in expr.args]
    if not expr.is_Add:
        return expr.func(*args) if args != list(expr.args) else expr
    terms = list(args)
    while len(terms) > 1:
        folded = _fold_pair(terms)
        if folded is None:
            break
        terms = list(sp.Add.make_args(sp.Add(*folded)))
    return sp.Add(*terms)


def trig_coefficients(expr: sp.Expr, x: sp.Symbol) -> tuple[sp.Expr, sp.Expr, sp.Expr] | None:
    """``(A, B, C)`` with ``expr = A cos x + B sin x + C`` after expanding sum angles, or None.

    >>> x, a, b = sp.symbols("x a b", real=True)
    >>> trig_coefficients(a * sp.cos(x + b) + 2, x)
    (a*cos(b), -a*sin(b), 2)
    >>> trig_coefficients(sp.cos(x) ** 2, x) is None
    True
    """
    e = sp.expand(sp.expand_trig(expr))
    c, s = sp.Dummy("c"), sp.Dummy("s")
    e = e.xreplace({sp.cos(x): c, sp.sin(x): s})
    if x in e.free_symbols:
        return None
    poly = sp.Poly(e, c, s)
    if poly.total_degree() > 1:
        return None
    return poly.coeff_monomial(c), poly.coeff_monomial(s), poly.coeff_monomial(1)


# --- checking ---------------------------------------------------------------------


def _trig_polynomial(expr: sp.Expr) -> tuple[sp.Expr, list[sp.Expr], list[sp.Symbol]]:
    """Rewrite ``expr`` as a polynomial in c_x = cos x, s_x = sin x of its symbols."""
    expanded = sp.expand(sp.expand_trig(expr))
    subs: dict[sp.Expr, sp.Symbol] = {}
    relations: list[sp.Expr] = []
    gens: list[sp.Symbol] = []
    for f in sorted(expanded.atoms(sp.sin, sp.cos), key=sp.default_sort_key):
        x = f.args[0]
        if sp.cos(x) not in subs:
            c = sp.Dummy(f"c_{x}")
            s = sp.Dummy(f"s_{x}")
            subs[sp.cos(x)] = c
            subs[sp.sin(x)] = s
            relations.append(c**2 + s**2 - 1)
            gens.extend([s, c])
    return sp.expand(expanded.xreplace(subs)), relations, gens


def _remainder_by_division(diff: sp.Expr) -> tuple[sp.Expr, list[sp.Expr]]:
    """The remainder of ``diff`` (no floats) modulo ``sin² x + cos² x − 1`` by generic
    polynomial division (:func:`sympy.reduced`, lex order: ``sin x`` first), and the
    generators it is a polynomial of: the general way, for what :func:`_ring_of` refuses."""
    poly, relations, gens = _trig_polynomial(diff)
    if poly == 0:
        return sp.Integer(0), []
    others = sorted(poly.free_symbols - set(gens), key=sp.default_sort_key)
    if relations:
        _, rem = sp.reduced(poly, relations, *gens, *others, order="lex")
    else:
        rem = poly
    return sp.expand(rem), [*gens, *others]


def _polynomial_node(e: sp.Basic) -> bool:
    """Whether ``e`` is a sum, a product or a positive integer power (what :func:`_in_ring`
    builds from its arguments)."""
    return bool(e.is_Add or e.is_Mul or (e.is_Pow and e.exp.is_Integer and e.exp > 0))


def _subtrees(exprs: Iterable[sp.Basic], into: Callable[[sp.Basic], bool]) -> set[sp.Basic]:
    """The subexpressions of ``exprs``, each visited once however often it is shared (the
    equations of a recursion share most of their subtrees; ``atoms`` would walk each
    copy), entering the arguments only of those for which ``into`` holds."""
    seen: set[sp.Basic] = set()
    todo = list(exprs)
    while todo:
        e = todo.pop()
        if e in seen:
            continue
        seen.add(e)
        if into(e):
            todo.extend(e.args)
    return seen


def _leaves(exprs: Iterable[sp.Basic], *, opened: bool = False) -> list[sp.Basic]:
    """The subexpressions of ``exprs`` that are no sum, product or positive integer power
    (the symbols, numbers, sines and cosines a polynomial is made of); ``opened``: of
    ``exprs`` with their sums of angles expanded (:func:`sympy.expand_trig`, which changes
    only the leaves)."""
    if opened:
        exprs = [sp.expand_trig(e) for e in exprs]
    return [e for e in _subtrees(exprs, _polynomial_node) if not _polynomial_node(e)]


def _ring_of(exprs: Sequence[sp.Expr]) -> tuple[TrigRing, PolyRing] | None:
    """The :class:`~dhsym.kinematics.trig_ring.TrigRing` of ``exprs`` over the rationals
    (sums of angles expanded by :func:`sympy.expand_trig`, as :func:`_in_ring` does): the
    sines and cosines of each angle, each symbol met outside them and the square roots of
    integers are its generators; with the sparse ring
    (:class:`sympy.polys.rings.PolyRing`) their polynomials are computed in. None when an
    angle is not linear in the symbols or not written as :func:`sympy.expand` writes it
    (its sine would be another generator there)."""
    leaves = _leaves(_leaves(exprs), opened=True)
    for f in leaves:
        if isinstance(f, (sp.sin, sp.cos)) and sp.expand(f.args[0]) != f.args[0]:
            return None
    symbols = sorted(set().union(*(e.free_symbols for e in leaves)), key=sp.default_sort_key)
    try:
        ring = TrigRing.of(leaves, symbols, constants=True)
    except DHError:  # an angle not linear in the symbols
        return None
    return ring, PolyRing(ring.gens or (sp.Dummy("one"),), QQ)


def _in_ring(expr: sp.Expr, ring: TrigRing, R: PolyRing, known: dict[sp.Expr, Any]) -> Any:
    """``expr`` as a polynomial of ``R`` in the normal form of ``ring`` (``sin² x → 1 −
    cos² x``, ``(√b)² → b``), built from its tree: sums added, each product and power
    reduced as it is made, each leaf with its sums of angles expanded
    (:func:`sympy.expand_trig`: all it changes are the leaves), so nothing is expanded as
    an expression; ``known`` holds the generators and the subexpressions already built
    (shared subtrees are built once). Raises :class:`~sympy.polys.polyerrors.CoercionFailed`
    when ``expr`` is no polynomial with rational coefficients in the generators (``π``,
    ``1/x``, ``tan x``)."""
    found = known.get(expr)
    if found is not None:
        return found

    def normal(p: Any) -> Any:
        return R.from_dict(ring.normal_terms(dict(p), QQ))

    if expr.is_Add:
        out = R.zero
        for arg in expr.args:
            out += _in_ring(arg, ring, R, known)
    elif expr.is_Mul:
        out = R.one
        for arg in expr.args:
            out = normal(out * _in_ring(arg, ring, R, known))
    elif _polynomial_node(expr):  # a positive integer power, by squaring
        square, k = _in_ring(expr.base, ring, R, known), int(expr.exp)
        out = R.one
        while k:
            if k & 1:
                out = normal(out * square)
            k >>= 1
            if k:
                square = normal(square * square)
    elif expr.is_Rational:
        out = R(QQ(int(expr.p), int(expr.q)))
    elif (opened := sp.expand_trig(expr)) != expr:
        out = _in_ring(opened, ring, R, known)
    else:  # a square root of an integer (in the ring's roots), or nothing of the ring
        try:
            leaf = ring.poly(expr)
        except (BasePolynomialError, DHError) as e:
            raise CoercionFailed(str(e)) from e
        if not (leaf.domain.is_ZZ or leaf.domain.is_QQ):
            raise CoercionFailed(f"{expr} is not a rational polynomial")
        terms = {m: QQ.convert_from(c, leaf.domain) for m, c in leaf.rep.to_dict().items()}
        out = normal(R.from_dict(terms))
    known[expr] = out
    return out


def _within_rounding(coeffs: Sequence[sp.Expr], scale: float) -> bool:
    """Whether coefficients of a remainder are the rounding of products of floats."""
    return max(abs(float(c)) for c in coeffs) <= _FLOAT_TOL * scale


def prove_equal(A: sp.MatrixBase, B: sp.MatrixBase) -> bool:
    """Exact proof that two trigonometric matrices are equal.

    Each entry of ``A − B`` is expanded into a polynomial in ``cos x``, ``sin x``
    and reduced modulo ``sin² x + cos² x − 1``; all remainders must vanish.
    Floats (the cosine and sine of a measured twist, see
    :func:`~dhsym.kinematics.transforms.cos_sin`) are taken at their exact binary
    values; then remainder coefficients up to 1e-12 (float rounding of the
    same products in another order) are allowed.

    The relations of different angles share no variable, so they are a Gröbner basis
    and the remainder is the normal form ``sin^k x → sin^(k mod 2) x (1 − cos² x)^(k//2)``
    (:meth:`~dhsym.kinematics.trig_ring.TrigRing.normal_terms`): the entries are built in
    the sparse polynomial ring of the sines, cosines and symbols of both matrices, each
    product reduced as it is made (:func:`_in_ring`), never expanded as expressions. An
    entry with coefficients outside the rationals and their square roots of integers
    (``π``), or with floats and square roots at once, is reduced by polynomial division
    (:func:`sympy.reduced`) instead; both give the same remainder.

    >>> t = sp.Symbol("t", real=True)
    >>> prove_equal(sp.Matrix([sp.cos(2 * t)]), sp.Matrix([1 - 2 * sp.sin(t)**2]))
    True
    >>> prove_equal(sp.Matrix([sp.cos(t)]), sp.Matrix([sp.sin(t)]))
    False
    >>> prove_equal(sp.Matrix([sp.sqrt(6) * sp.sin(t + sp.pi / 4)]),
    ...             sp.Matrix([sp.sqrt(3) * (sp.sin(t) + sp.cos(t))]))
    True
    >>> prove_equal(sp.Matrix([sp.pi * sp.sin(t) ** 2]),
    ...             sp.Matrix([sp.pi - sp.pi * sp.cos(t) ** 2]))
    True
    """
    if A.shape != B.shape:
        return False
    # each entry that is not 0 at sight: its sides, difference (floats at their exact
    # values) and the difference's floats
    entries: list[tuple[sp.Expr, sp.Expr, sp.Expr, set[sp.Basic]]] = []
    for a, b in zip(A, B):
        diff = a - b
        if diff == 0:
            continue
        floats = {e for e in _subtrees([diff], lambda e: True) if e.is_Float}
        if floats:  # cos/sin of a measured twist: exact arithmetic on the floats' values
            diff = diff.xreplace({f: sp.Rational(f) for f in floats})
        entries.append((a, b, diff, floats))
    if not entries:
        return True
    ringed = _ring_of([diff for _, _, diff, _ in entries])
    known: dict[sp.Expr, Any] = dict(zip(ringed[0].atoms, ringed[1].gens)) if ringed else {}
    for a, b, diff, floats in entries:
        try:
            # with floats, the coefficients whose rounding is allowed are those of division
            if ringed is None or (floats and ringed[0].roots):
                raise CoercionFailed("reduced by division")
            rem = _in_ring(diff, *ringed, known)
            if not rem:
                continue
            if not floats:
                return False
            coeffs = [QQ.to_sympy(c) for c in rem.values()]
        except CoercionFailed:
            remainder, gens = _remainder_by_division(diff)
            if remainder == 0:
                continue
            if not floats:
                return False
            coeffs = sp.Poly(remainder, *gens).coeffs() if gens else [remainder]
        # the two sides multiplied the same floats in another order: allow their rounding
        scale = 1 + max(abs(float(f)) for f in (a.atoms(sp.Float) | b.atoms(sp.Float) | floats))
        if not _within_rounding(coeffs, scale):
            return False
    return True


def numeric_equal(
    A: sp.MatrixBase, B: sp.MatrixBase, *, points: int = 20, tol: float = 1e-12, seed: int = 0
) -> bool:
    """Compare two symbolic matrices at ``points`` random values of their symbols.

    >>> t = sp.Symbol("t", real=True)
    >>> numeric_equal(sp.Matrix([sp.sin(t)**2]), sp.Matrix([1 - sp.cos(t)**2]))
    True
    >>> huge = sp.sqrt(sp.Integer(10) ** 40 + 1)  # evaluated once, as a float
    >>> numeric_equal(sp.Matrix([huge * t]), sp.Matrix([10**20 * t]))
    True
    """
    if A.shape != B.shape:
        return False
    syms = sorted(A.free_symbols | B.free_symbols, key=sp.default_sort_key)
    fa = compile_exprs(list(A), syms, floats=True)
    fb = compile_exprs(list(B), syms, floats=True)
    rng = random.Random(seed)
    for _ in range(points):
        vals = [rng.uniform(-3.0, 3.0) for _ in syms]
        for x, y in zip(fa(*vals), fb(*vals)):
            if abs(x - y) > tol * max(1.0, abs(x)):
                return False
    return True
