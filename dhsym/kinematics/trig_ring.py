"""Polynomials in the sines and cosines of the joint angles, in a normal form.

What the compact equations of motion are computed in (:mod:`dhsym.dynamics.lagrange_euler`,
:mod:`dhsym.dynamics.compact_form`) and what two products of transforms are proven equal
in (:func:`prove_products_equal`: the product of exponentials against the DH product,
:func:`dhsym.screws.product.prove_same_fk`): each ``sin x``, ``cos x`` of a joint-dependent
angle ``x`` (the compact ``θ2 + θ3`` included) and each bare prismatic variable is a
generator; sums of the same monomial are collected exactly by :class:`sympy.Poly`;
``sin² x → 1 − cos² x`` is the normal form (so ``C4² + S4²`` and its relatives vanish
structurally, never by ``simplify``); derivatives follow the chain rule on the generators.
A ring of *constants too* (``TrigRing.of(..., constants=True)``) also makes generators of the
sines and cosines of constant angles (``cos(π/18)``) and of the square roots of integers
(``√3``, with ``(√3)² → 3``), so its coefficients are rational and its normal form
unique.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import Any, TypeAlias

import sympy as sp
from sympy.polys.rings import PolyRing

from dhsym.errors import DHError

__all__ = ["TrigRing", "lecture_form", "prove_products_equal"]

Monomial: TypeAlias = tuple[int, ...]


@dataclass(frozen=True)
class TrigRing:
    """Polynomials in the sines and cosines of the joint angles (and prismatic variables).

    ``atoms[k]`` is what generator ``gens[k]`` stands for (``cos(theta2 + theta3)``, or a
    prismatic joint variable); ``pairs`` are the ``(sin, cos)`` generator indices of one
    angle; ``rates[k][j]`` is ``∂ angle_k / ∂ q_j`` (constant: angles are linear in q);
    ``roots`` are ``(k, b)`` for a generator ``√b`` (``gens[k]² → b``) and ``radicals`` what
    each square root of an integer met is in those generators (a ring of constants only).

    >>> t1, t2 = sp.symbols("theta1 theta2", real=True)
    >>> ring = TrigRing.of([sp.cos(t1) ** 2 + sp.sin(t1) ** 2 * sp.cos(t2)], (t1, t2))
    >>> p = ring.poly(sp.sin(t1) ** 2 + sp.cos(t1) ** 2)
    >>> ring.expr(ring.reduce(p))
    1
    >>> ring.expr(ring.diff(ring.poly(sp.sin(t1) * sp.cos(t2)), 0))
    cos(theta1)*cos(theta2)
    """

    variables: tuple[sp.Symbol, ...]
    atoms: tuple[sp.Expr, ...]
    gens: tuple[sp.Symbol, ...]
    pairs: tuple[tuple[int, int], ...]
    rates: tuple[tuple[sp.Expr, ...], ...]
    roots: tuple[tuple[int, sp.Integer], ...] = ()
    radicals: tuple[tuple[sp.Expr, sp.Expr], ...] = ()

    @classmethod
    def of(
        cls, exprs: Iterable[sp.Expr], variables: Sequence[sp.Symbol], *, constants: bool = False
    ) -> TrigRing:
        """The ring of the joint-dependent sines, cosines and bare variables in ``exprs``;
        with ``constants``, of the constant angles' sines and cosines and of the square
        roots of integers too (on a coprime base of their radicands, so ``√6 = √2·√3``
        when ``√2`` or ``√3`` occurs as well).

        >>> t = sp.Symbol("t", real=True)
        >>> e = sp.sqrt(6) * sp.cos(t + sp.pi / 18) + sp.sqrt(2)
        >>> ring = TrigRing.of([sp.expand_trig(e)], (t,), constants=True)
        >>> ring.atoms
        (sin(pi/18), cos(pi/18), sin(t), cos(t), sqrt(2), sqrt(3))
        >>> ring.expr(ring.reduce(ring.poly(sp.sqrt(6) ** 3 - 6 * sp.sqrt(6))))
        0
        """
        qs = set(variables)
        angles: set[sp.Expr] = set()
        bare: set[sp.Symbol] = set()
        radicands: set[sp.Integer] = set()
        for e in exprs:
            for f in e.atoms(sp.sin, sp.cos):
                if constants or f.args[0].free_symbols & qs:
                    angles.add(f.args[0])
            hidden = e.replace(lambda x: isinstance(x, (sp.sin, sp.cos)), lambda x: sp.S.One)
            bare |= hidden.free_symbols & qs
            if constants:
                radicands |= {p.base for p in e.atoms(sp.Pow) if _is_root(p)}
        atoms: list[sp.Expr] = []
        pairs: list[tuple[int, int]] = []
        rates: list[tuple[sp.Expr, ...]] = []
        for x in sorted(angles, key=sp.default_sort_key):
            grad = tuple(sp.diff(x, q) for q in variables)
            if any(g.free_symbols & qs for g in grad):
                raise DHError(f"the angle {x} is not linear in the joint variables")
            pairs.append((len(atoms), len(atoms) + 1))
            atoms += [sp.sin(x), sp.cos(x)]
            rates += [grad, grad]
        for q in sorted(bare, key=sp.default_sort_key):
            atoms.append(q)
            rates.append(tuple(sp.Integer(int(q == v)) for v in variables))
        base = _coprime_base(radicands)
        roots = [(len(atoms) + k, b) for k, b in enumerate(base)]
        atoms += [sp.sqrt(b, evaluate=False) for b in base]
        rates += [tuple(sp.Integer(0) for _ in variables) for _ in base]
        gens = tuple(sp.Dummy(f"g{k}", real=True) for k in range(len(atoms)))
        radicals = tuple(
            (sp.sqrt(r), _in_base(r, base, gens[len(atoms) - len(base) :]))
            for r in sorted(radicands)
        )
        return cls(
            tuple(variables), tuple(atoms), gens, tuple(pairs), tuple(rates), tuple(roots), radicals
        )

    def poly(self, expr: sp.Expr) -> sp.Poly:
        """``expr`` as a polynomial in the generators (coefficients: the constants)."""
        if self.radicals:
            expr = expr.replace(lambda x: x.is_Pow and _is_root(x), self._radical)
        e = sp.expand(expr.xreplace(dict(zip(self.atoms, self.gens))))
        if e.free_symbols & set(self.variables):
            raise DHError(f"not a polynomial in sines and cosines of the joint angles: {expr}")
        return sp.Poly(e, *self.gens) if self.gens else sp.Poly(e, sp.Dummy("one"))

    def _radical(self, power: sp.Pow) -> sp.Expr:
        """``b**(k/2)`` of an integer ``b`` in the generators of the roots."""
        found: sp.Expr = dict(self.radicals)[sp.sqrt(power.base)]
        return found ** (2 * power.exp) if power.exp != sp.S.Half else found

    def reduce(self, p: sp.Poly) -> sp.Poly:
        """The normal form of ``p``: every ``sin² x`` replaced by ``1 − cos² x`` (and every
        ``(√b)²`` by ``b``)."""
        terms = self.normal_terms(dict(p.rep.to_dict()), p.domain)
        return sp.Poly.from_dict(terms, *p.gens, domain=p.domain)

    def normal_terms(
        self, terms: dict[Monomial, Any], domain: sp.polys.domains.Domain
    ) -> dict[Monomial, Any]:
        """The normal form of a polynomial given as its terms (monomial → coefficient of
        ``domain``; changed in place and returned): what :meth:`reduce` does to a
        :class:`sympy.Poly`, for a sparse polynomial of the same generators too."""
        for g, b in self.roots:
            todo = [m for m in terms if m[g] >= 2]
            while todo:
                m = todo.pop()
                k = terms.pop(m)
                lower = m[:g] + (m[g] % 2,) + m[g + 1 :]
                total = terms.get(lower, domain.zero) + k * domain.convert(b ** (m[g] // 2))
                if total:
                    terms[lower] = total
                else:
                    terms.pop(lower, None)
        for s, c in self.pairs:
            todo = [m for m in terms if m[s] >= 2]
            while todo:
                m = todo.pop()
                if m not in terms:
                    continue
                k = terms.pop(m)
                lower = m[:s] + (m[s] - 2,) + m[s + 1 :]
                swap = list(lower)
                swap[c] += 2
                for mono, coeff in ((lower, k), (tuple(swap), -k)):
                    total = terms.get(mono, domain.zero) + coeff
                    if total:
                        terms[mono] = total
                    else:
                        terms.pop(mono, None)
                    if mono[s] >= 2 and mono in terms:
                        todo.append(mono)
        return terms

    def diff(self, p: sp.Poly, j: int) -> sp.Poly:
        """``∂p/∂q_j`` by the chain rule on the generators, reduced."""
        out = p * 0
        g = self.gens
        partner = {s: c for s, c in self.pairs} | {c: s for s, c in self.pairs}
        for k, atom in enumerate(self.atoms):
            rate = self.rates[k][j]
            if rate == 0 or p.degree(g[k]) <= 0:
                continue
            d = p.diff(g[k])
            if isinstance(atom, sp.cos):
                out += d * sp.Poly(-rate * g[partner[k]], *g, domain=p.domain)
            elif isinstance(atom, sp.sin):
                out += d * sp.Poly(rate * g[partner[k]], *g, domain=p.domain)
            else:
                out += d * rate
        return self.reduce(out)

    def monomial(self, m: Monomial) -> sp.Expr:
        """The product of the atoms with exponents ``m``."""
        return sp.Mul(*(a**e for a, e in zip(self.atoms, m) if e))

    def expr(self, p: sp.Poly) -> sp.Expr:
        """``p`` written back in sines and cosines (plain, nothing named)."""
        return sp.Add(*(c * self.monomial(m) for m, c in p.terms()))


def _is_root(power: sp.Expr) -> bool:
    """Whether ``power`` is ``b**(k/2)`` of a positive integer ``b`` and an odd ``k``."""
    return bool(
        power.is_Pow
        and power.base.is_Integer
        and power.base > 1
        and power.exp.is_Rational
        and power.exp.q == 2
    )


def _coprime_base(numbers: Iterable[sp.Integer]) -> list[sp.Integer]:
    """Pairwise coprime integers > 1 whose products give each of ``numbers`` (gcds taken
    until none is left; no factoring).

    >>> _coprime_base([sp.Integer(6), sp.Integer(10)])
    [2, 3, 5]
    """
    base = sorted({int(n) for n in numbers if n > 1})
    changed = True
    while changed:
        changed = False
        for i, a in enumerate(base):
            for b in base[i + 1 :]:
                g = math.gcd(a, b)
                if g > 1:
                    rest = {a // g, b // g, g} - {1}
                    base = sorted((set(base) - {a, b}) | rest)
                    changed = True
                    break
            if changed:
                break
    return [sp.Integer(b) for b in base]


def _in_base(n: sp.Integer, base: Sequence[sp.Integer], gens: Sequence[sp.Symbol]) -> sp.Expr:
    """``√n`` in the generators ``gens`` of ``√b`` for ``b`` in ``base``."""
    out: sp.Expr = sp.Integer(1)
    rest = int(n)
    for b, g in zip(base, gens):
        k = 0
        while rest % int(b) == 0:
            rest //= int(b)
            k += 1
        out *= sp.Integer(b) ** (k // 2) * g ** (k % 2)
    return out


def _ring_products(
    ring: TrigRing, products: Sequence[Sequence[sp.MatrixBase]]
) -> list[list[list[Any]]]:
    """Each product of matrices (left to right) as sparse polynomials of ``ring`` over one
    coefficient domain (:class:`sympy.polys.rings.PolyRing`), each step reduced."""
    polys = [
        [[[ring.poly(M[i, j]) for j in range(M.cols)] for i in range(M.rows)] for M in factors]
        for factors in products
    ]
    domain = polys[0][0][0][0].domain
    for p in (p for factors in polys for P in factors for row in P for p in row):
        domain = domain.unify(p.domain)
    R = PolyRing(ring.gens, domain)

    def sparse(p: sp.Poly) -> Any:
        return R.from_dict(
            {m: domain.convert_from(c, p.domain) for m, c in p.rep.to_dict().items()}
        )

    def times(A: list[list[Any]], B: list[list[Any]]) -> list[list[Any]]:
        return [
            [
                R.from_dict(
                    ring.normal_terms(dict(sum((a * b for a, b in zip(row, col)), R.zero)), domain)
                )
                for col in zip(*B)
            ]
            for row in A
        ]

    out = []
    for factors in polys:
        sparse_factors = [[[sparse(p) for p in row] for row in P] for P in factors]
        result = sparse_factors[0]
        for B in sparse_factors[1:]:
            result = times(result, B)
        out.append(result)
    return out


def _exact(M: sp.MatrixBase) -> sp.Matrix:
    """``M`` with its floats at their exact binary values and sums of angles expanded."""
    M = sp.Matrix(M)
    floats = M.atoms(sp.Float)
    if floats:
        M = M.xreplace({f: sp.Rational(f) for f in floats})
    return M.applyfunc(lambda e: sp.expand(sp.expand_trig(e)))


#: the rounding allowed when the factors have floats (as in ``prove_equal``)
_FLOAT_TOL = 1e-12


def prove_products_equal(
    products: Sequence[Sequence[sp.MatrixBase]], variables: Sequence[sp.Symbol]
) -> bool:
    """Exact proof that the products of the matrix lists in ``products`` are all equal.

    No product is simplified, nor even multiplied out as an expression: each factor's
    entries (sums of angles expanded, floats taken at their exact binary values) become
    polynomials of one :class:`TrigRing` of constants too, in the sines and cosines of the
    joint angles, of the constant angles and in the square roots; the products are
    multiplied in the ring, each step reduced to the normal form (``sin² x → 1 − cos² x``,
    ``(√b)² → b``), and their entries must have the same normal form. When a factor has
    floats, coefficients of the difference up to 1e-12 (relative to the largest float) are
    the rounding of the same products in another order, as in
    :func:`~dhsym.kinematics.simplification.prove_equal`.

    >>> t1, t2 = sp.symbols("theta1 theta2", real=True)
    >>> from dhsym.kinematics.transforms import Rz
    >>> prove_products_equal([[Rz(t1), Rz(t2)], [Rz(t1 + t2)]], (t1, t2))
    True
    >>> prove_products_equal([[Rz(t1), Rz(t2)], [Rz(t1 - t2)]], (t1, t2))
    False
    """
    floats: set[sp.Float] = set()
    for factors in products:
        for M in factors:
            floats |= sp.Matrix(M).atoms(sp.Float)
    exact = [[_exact(M) for M in factors] for factors in products]
    ring = TrigRing.of(
        [e for factors in exact for M in factors for e in M], variables, constants=True
    )
    first, *others = _ring_products(ring, exact)
    scale = 1 + max((abs(float(f)) for f in floats), default=0.0)
    for other in others:
        for row_a, row_b in zip(first, other, strict=True):
            for a, b in zip(row_a, row_b, strict=True):
                diff = a - b
                if not diff:
                    continue
                if not floats:
                    return False
                # a coefficient may be a polynomial in the lengths: its own coefficients
                values = [diff.ring.domain.to_sympy(c) for c in diff.values()]
                coeffs = [k for v in values for k in sp.Poly(v, *v.free_symbols).coeffs()]
                if max(abs(float(k)) for k in coeffs) > _FLOAT_TOL * scale:
                    return False
    return True


def _lecture_terms(ring: TrigRing, p: sp.Poly) -> dict[Monomial, sp.Expr]:
    """The terms of a reduced ``p``, each pair ``k·m·C² − k·m`` written ``−k·m·S²``."""
    terms = {m: c for m, c in p.terms()}
    for s, c in ring.pairs:
        for m in sorted((m for m in terms if m[c] >= 2), key=lambda m: -m[c]):
            if m not in terms:
                continue
            lower = m[:c] + (m[c] - 2,) + m[c + 1 :]
            if lower in terms and sp.expand(terms[m] + terms[lower]) == 0:
                k = terms.pop(lower)
                terms.pop(m)
                sine = list(lower)
                sine[s] += 2
                terms[tuple(sine)] = k
    return terms


def lecture_form(
    ring: TrigRing, p: sp.Poly, name: Callable[[sp.Expr], sp.Expr] = lambda c: c
) -> sp.Expr:
    """A reduced ``p`` as the lecture prints it: one term per trigonometric monomial, each
    pair ``k·m·C² − k·m`` as ``−k·m·S²``, each coefficient through ``name``."""
    terms = _lecture_terms(ring, p)
    return sp.Add(*(name(sp.expand(c)) * ring.monomial(m) for m, c in sorted(terms.items())))
