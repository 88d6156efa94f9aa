"""The sum-angle identities that combine two link matrices (``C_1 C_2 - S_1 S_2 = C_{12}``).

A derivation step ``^iT_k = ^iT_{k-1} ^{k-1}T_k`` names the identities it uses;
:func:`identities` finds them by comparing the angles of the two factors with
those of the product. Used by :mod:`dhsym.derivation`.

Examples
--------
>>> import dhsym
>>> r = dhsym.load("planar2r")
>>> ids = identities(r.link_matrix(1).matrix, r.link_matrix(2).matrix,
...                  r.transform(0, 2).matrix, r.notation)
>>> [(t.sign, t.math.text) for t in ids[0].terms], ids[0].result.text
([('+', 'C1*C2'), ('-', 'S1*S2')], 'C12')
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp

from ._derivation_data import LATEX_WIDTH, Identity, Math, Term
from ._derivation_print import as_math
from .latex import TeX, math_width
from .notation import Notation

__all__ = ["identities"]


def _angles(matrix: sp.MatrixBase) -> set[sp.Expr]:
    return {f.args[0] for f in matrix.atoms(sp.sin, sp.cos)}


def _identity(
    result: sp.Expr,
    terms: Sequence[tuple[str, tuple[sp.Expr, sp.Expr]]],
    nota: Notation,
    width: float,
) -> Identity:
    """``±f(A)g(B) ± … = result``, each product printed factor by factor in textbook order."""
    ts = tuple(
        Term(sign, Math(TeX(" ".join(nota.latex(f) for f in fs)), "*".join(map(nota.text, fs))))
        for sign, fs in terms
    )
    rhs = as_math(result, nota)
    size = sum(math_width(t.math.latex) + 2.2 for t in ts) + math_width(rhs.latex)
    return Identity(ts, rhs, size > width / 2, size > width)


def identities(
    left: sp.MatrixBase,
    right: sp.MatrixBase,
    result: sp.MatrixBase,
    nota: Notation,
    width: float = LATEX_WIDTH,
) -> tuple[Identity, ...]:
    """The sum-angle identities that turn ``left · right`` into ``result``.

    An angle of ``result`` found in neither factor is ``A ± B`` with ``A`` an angle of
    ``left`` and ``B`` one of ``right`` (``θ_2 + θ_3``; ``θ_{12} - θ_4`` after a flip).
    """
    la, ra = _angles(left), _angles(right)
    trig = result.atoms(sp.sin, sp.cos)
    found = []
    for x in sorted(_angles(result) - la - ra, key=sp.default_sort_key):
        for A in sorted(la, key=sp.default_sort_key):
            B = sp.expand(x - A)
            sign = 1 if B in ra else (-1 if -B in ra else 0)
            if sign:
                break
        else:
            continue
        B = B * sign
        cA, sA, cB, sB = sp.cos(A), sp.sin(A), sp.cos(B), sp.sin(B)
        minus, plus = ("-", "+") if sign > 0 else ("+", "-")
        if sp.cos(x) in trig:
            found.append(_identity(sp.cos(x), [("+", (cA, cB)), (minus, (sA, sB))], nota, width))
        if sp.sin(x) in trig:
            found.append(_identity(sp.sin(x), [("+", (sA, cB)), (plus, (cA, sB))], nota, width))
    return tuple(found)
