"""Polynomials in the sines and cosines of the joint angles, in a normal form.

What the compact equations of motion are computed in (:mod:`.lagrange_euler`,
:mod:`.compact_form`): each ``sin x``, ``cos x`` of a joint-dependent angle ``x`` (the
compact ``θ2 + θ3`` included) and each bare prismatic variable is a generator; sums of the
same monomial are collected exactly by :class:`sympy.Poly`; ``sin² x → 1 − cos² x`` is the
normal form (so ``C4² + S4²`` and its relatives vanish structurally, never by ``simplify``);
derivatives follow the chain rule on the generators.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import TypeAlias

import sympy as sp

from dhsym.errors import DHError

__all__ = ["TrigRing", "lecture_form"]

Monomial: TypeAlias = tuple[int, ...]


@dataclass(frozen=True)
class TrigRing:
    """Polynomials in the sines and cosines of the joint angles (and prismatic variables).

    ``atoms[k]`` is what generator ``gens[k]`` stands for (``cos(theta2 + theta3)``, or a
    prismatic joint variable); ``pairs`` are the ``(sin, cos)`` generator indices of one
    angle; ``rates[k][j]`` is ``∂ angle_k / ∂ q_j`` (constant: angles are linear in q).

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

    @classmethod
    def of(cls, exprs: Iterable[sp.Expr], variables: Sequence[sp.Symbol]) -> TrigRing:
        """The ring of the joint-dependent sines, cosines and bare variables in ``exprs``."""
        qs = set(variables)
        angles: set[sp.Expr] = set()
        bare: set[sp.Symbol] = set()
        for e in exprs:
            for f in e.atoms(sp.sin, sp.cos):
                if f.args[0].free_symbols & qs:
                    angles.add(f.args[0])
            hidden = e.replace(lambda x: isinstance(x, (sp.sin, sp.cos)), lambda x: sp.S.One)
            bare |= hidden.free_symbols & qs
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
        gens = tuple(sp.Dummy(f"g{k}", real=True) for k in range(len(atoms)))
        return cls(tuple(variables), tuple(atoms), gens, tuple(pairs), tuple(rates))

    def poly(self, expr: sp.Expr) -> sp.Poly:
        """``expr`` as a polynomial in the generators (coefficients: the constants)."""
        e = sp.expand(expr.xreplace(dict(zip(self.atoms, self.gens))))
        if e.free_symbols & set(self.variables):
            raise DHError(f"not a polynomial in sines and cosines of the joint angles: {expr}")
        return sp.Poly(e, *self.gens) if self.gens else sp.Poly(e, sp.Dummy("one"))

    def reduce(self, p: sp.Poly) -> sp.Poly:
        """The normal form of ``p``: every ``sin² x`` replaced by ``1 − cos² x``."""
        terms = dict(p.rep.to_dict())
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
                    total = terms.get(mono, p.domain.zero) + coeff
                    if total:
                        terms[mono] = total
                    else:
                        terms.pop(mono, None)
                    if mono[s] >= 2 and mono in terms:
                        todo.append(mono)
        return sp.Poly.from_dict(terms, *p.gens, domain=p.domain)

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
