"""A homogeneous transform ``^iT_j`` as a value that prints in lecture notation.

Examples
--------
>>> import sympy as sp
>>> from dhsym.notation.printers import Notation
>>> t1 = sp.Symbol("theta1", real=True)
>>> from dhsym.kinematics.transforms import Rz
>>> P = Pose(Rz(t1), 0, 1, Notation.from_variables([t1]))
>>> P.label_latex
'{}^{0}T_{1}'
>>> print(P.text())
Matrix([
[C1, -S1, 0, 0],
[S1,  C1, 0, 0],
[ 0,   0, 1, 0],
[ 0,   0, 0, 1]])
>>> P.a
Matrix([
[0],
[0],
[1]])
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp

from dhsym.notation.printers import Notation

__all__ = ["Pose"]


@dataclass(frozen=True)
class Pose:
    """``^{frm}T_{to}``: pose of frame ``to`` in frame ``frm``, an exact 4×4 matrix.

    Indexing, ``rotation``, ``position`` and the n, s, a columns (normal,
    sliding, approach; seed 004) read the matrix; printing goes through
    :class:`~dhsym.notation.Notation`.
    """

    matrix: sp.ImmutableMatrix
    frm: int | str
    to: int | str
    notation: Notation = field(default_factory=Notation, compare=False)
    symbol: str = "T"

    def __getitem__(self, key: object) -> object:
        return self.matrix[key]  # type: ignore[index]

    @property
    def rotation(self) -> sp.ImmutableMatrix:
        """The 3×3 rotation ``R``."""
        return self.matrix[:3, :3]

    @property
    def position(self) -> sp.ImmutableMatrix:
        """The origin ``p`` of frame ``to`` in frame ``frm`` (3×1)."""
        return self.matrix[:3, 3]

    @property
    def n(self) -> sp.ImmutableMatrix:
        """Normal vector: the x axis of frame ``to``."""
        return self.matrix[:3, 0]

    @property
    def s(self) -> sp.ImmutableMatrix:
        """Sliding vector: the y axis of frame ``to``."""
        return self.matrix[:3, 1]

    @property
    def a(self) -> sp.ImmutableMatrix:
        """Approach vector: the z axis of frame ``to``."""
        return self.matrix[:3, 2]

    @property
    def label_latex(self) -> str:
        """``{}^{i}T_{j}`` for headings and equations."""
        return f"{{}}^{{{self.frm}}}{self.symbol}_{{{self.to}}}"

    @property
    def label_text(self) -> str:
        """``T0_2`` style label for plain text."""
        return f"{self.symbol}{self.frm}_{self.to}"

    def count_ops(self) -> int:
        """``sympy.count_ops`` over the entries (a size measure)."""
        return int(sum(sp.count_ops(e) for e in self.matrix))

    def subs(self, values: dict) -> Pose:
        """A copy with values substituted (symbols to numbers or expressions)."""
        return Pose(
            sp.ImmutableMatrix(self.matrix.subs(values)),
            self.frm,
            self.to,
            self.notation,
            self.symbol,
        )

    def evalf(self, values: dict | None = None) -> sp.ImmutableMatrix:
        """Numerical matrix (sympy floats) at ``values``."""
        return sp.ImmutableMatrix(self.matrix.evalf(subs=values or {}))

    def latex(self) -> str:
        """The matrix in LaTeX (``bmatrix``) in this pose's notation."""
        return self.notation.latex(self.matrix)

    def text(self) -> str:
        """The matrix in plain text in this pose's notation."""
        return self.notation.text(self.matrix)

    def _latex(self, printer: object) -> str:
        return self.latex()

    def _sympystr(self, printer: object) -> str:
        return self.text()

    def _repr_latex_(self) -> str:
        return f"$${self.label_latex} = {self.latex()}$$"

    def _repr_markdown_(self) -> str:
        return self._repr_latex_()

    def __str__(self) -> str:
        return f"{self.label_text} = {self.text()}"
