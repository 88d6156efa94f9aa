"""Mistakes of a whole matrix: transposed, multiplied in reverse order, the other convention.

Each recomputes the full key matrix the way the student did (all of it, or one 3×3 block
of a Jacobian). The public names are re-exported by
:mod:`dhsym.checking.mistakes.registry`.

Examples
--------
>>> Transposed().kind, ReverseOrder().title
('transposed', 'product in reverse order')
>>> _other(Convention.STANDARD).value
'modified'
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from dhsym.model.table import Convention, DHTable

from ..comparing.table_match import Chain, compare_tables
from ..comparing.verdict import Diagnosis
from ._mistake_base import MatrixCase, Mistake, TableCase

__all__ = ["BlockTransposed", "OtherConvention", "ReverseOrder", "Transposed"]

_FORMULA = {
    Convention.STANDARD: "A_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i)",
    Convention.MODIFIED: "^{i-1}T_i = Rx(α_{i-1}) Tx(a_{i-1}) Rz(θ_i) Tz(d_i)",
}


class Transposed(Mistake):
    """The matrix (or its rotation part) written transposed."""

    kind, title = "transposed", "matrix transposed"

    def matrix_variants(self, case: MatrixCase) -> Iterator[tuple[np.ndarray, str]]:
        full = np.asarray(case.cache.setdefault(("full", case.sample.origin), _full(case)))
        yield (
            case.project(np.swapaxes(full, 1, 2)),
            (
                "Rows and columns are exchanged: the columns of ^iT_j are the axes n, s, a of "
                "frame j and its position p, written in frame i."
            ),
        )
        rot = full.copy()
        rot[:, :3, :3] = np.swapaxes(full[:, :3, :3], 1, 2)
        yield (
            case.project(rot),
            (
                "The rotation part is transposed (that is the inverse rotation, R^T = R^-1); "
                "the columns of R are the axes of the new frame in the old one."
            ),
        )


class BlockTransposed(Mistake):
    """One 3×3 block of a 6×n Jacobian written transposed (the rotation block of ^iT_j
    is the mistake ``transposed`` of a whole matrix)."""

    kind, title = "transposed", "one 3×3 block transposed"

    def matrix_variants(self, case: MatrixCase) -> Iterator[tuple[np.ndarray, str]]:
        vals = np.asarray(case.key_values)
        if vals.ndim != 3 or vals.shape[1] != 6:
            return
        for r in (0, 3):
            for c in range(0, vals.shape[2] - 2, 3):
                out = vals.copy()
                out[:, r : r + 3, c : c + 3] = np.swapaxes(vals[:, r : r + 3, c : c + 3], 1, 2)
                rows = "linear" if r == 0 else "angular"
                yield (
                    out,
                    (
                        f"The {rows} block of columns {c + 1} to {c + 3} is transposed: column "
                        "i of J holds the contribution of joint i."
                    ),
                )


def _full(case: MatrixCase) -> np.ndarray:
    """Values of the full 4×4 key matrix at the sample (also for entry questions)."""
    return case.full_values(case.rows, case.convention)


class ReverseOrder(Mistake):
    """Link matrices (or the four elementary factors) multiplied in reverse order."""

    kind, title = "reverse_order", "product in reverse order"

    def matrix_variants(self, case: MatrixCase) -> Iterator[tuple[np.ndarray, str]]:
        if abs(case.to - case.frm) > 1:
            yield (
                case.chain_values(case.rows, case.convention, "links"),
                (
                    f"The link matrices are multiplied in reverse order: ^{case.frm}T_{case.to} = "
                    f"A_{min(case.frm, case.to) + 1} ⋯ A_{max(case.frm, case.to)}, first link on "
                    "the left (each factor is expressed in the frame before it)."
                ),
            )
        yield (
            case.chain_values(case.rows, case.convention, "factors"),
            (
                "The elementary transforms are multiplied in reverse order: for this convention "
                f"{_FORMULA[case.convention]}, left to right."
            ),
        )


class OtherConvention(Mistake):
    """The other DH convention's link matrix (or table) used."""

    kind, title = "other_convention", "other DH convention"

    def matrix_variants(self, case: MatrixCase) -> Iterator[tuple[np.ndarray, str]]:
        other = _other(case.convention)
        yield (
            case.chain_values(case.rows, other),
            (
                f"This is the {other.value} link matrix ({_FORMULA[other]}); the question uses "
                f"the {case.convention.value} convention: {_FORMULA[case.convention]}."
            ),
        )

    def explain_table(self, case: TableCase) -> Diagnosis | None:
        key_conv, other = case.key.convention, _other(case.key.convention)
        declared = case.answer.convention is not key_conv
        valid = (
            f"Your table is a valid {other.value}-convention table of this robot, but the "
            f"question asks for the {key_conv.value} convention ({_FORMULA[key_conv]})."
        )
        tries: list[tuple[DHTable | Chain, str]] = [(Chain(case.answer.rows, other), valid)]
        if declared:
            tries = [
                (case.answer, valid),
                (
                    Chain(case.answer.rows, key_conv),
                    (
                        f"The columns are labelled for the {other.value} convention, "
                        "but the values "
                        f"are those of the {key_conv.value} convention ({_FORMULA[key_conv]})."
                    ),
                ),
            ]
        for target, detail in tries:
            m = compare_tables(case.key, target, tool_free=case.tool_free, values=case.values)
            if m.same_robot:
                return Diagnosis(self.kind, self.title, detail)
        return None


def _other(c: Convention) -> Convention:
    return Convention.MODIFIED if c is Convention.STANDARD else Convention.STANDARD
