r"""A homogeneous transform ``^iT_j``: a sympy ``ImmutableMatrix`` that prints in lecture notation.

Why a subclass of :class:`sympy.ImmutableMatrix` rather than a wrapper that implements
the sympy protocols (``_sympy_``, ``__array__``, ``_latex``, ``_sympystr``, ``_pretty``):
sympy decides many things by ``isinstance``. :func:`sympy.lambdify` prints only
``Basic``/``MatrixBase`` objects and refuses any other iterable; ``sympy.Matrix(x)``
reads a wrapper through ``__array__`` (numpy) or else as a flat sequence (the 16×1
column of old); equality, hashing, ``free_symbols``, slicing, iteration, ``.T``,
``.det()``, ``simplify`` and every other matrix function would each need a delegate.
As a subclass, a pose *is* the 4×4 matrix to all of sympy, and only what makes it a
pose is added: the frames ``frm``/``to``, the notation it prints in, and (when it
comes from a DH table) the word of elementary transforms it is the product of.

The rules that follow from that choice:

* Anything sympy computes from a pose (``simplify``, ``pose.T``, ``pose[:3, :3]``,
  ``2 * pose``, ``xreplace``) is a plain ``ImmutableMatrix``: a label would be a
  guess there.
* ``P * Q`` and ``P @ Q`` of two poses whose frames chain (``P.to == Q.frm``, both
  named, same symbol) is the pose ``^{P.frm}T_{Q.to}``, in compact form: two poses of
  a robot compose their words (so ``A1 * A2`` is *identical* to ``robot.transform(0,
  2)``), other poses fold the sum-angle pairs of the product. Frames that do not chain
  give the plain matrix product (a product of unrelated transforms is still a
  matrix, but not a pose with a meaningful label).
* ``P.inv()`` is the exact rigid inverse ``^{to}T_{frm}`` (``Rᵀ``, ``−Rᵀp``).
* ``P == M`` compares the 4×4 entries only (as for any sympy matrix), and the hash
  is the plain matrix's: a pose and its matrix are interchangeable as dict keys.
* ``P.subs(...)`` keeps the labels; ``P.evalf(values)`` gives numbers.
* ``sympy.latex``, ``sympy.pprint`` and ``str`` print the lecture notation
  (``C_{12}``, ``a_{1} C_{1}``); code printers (``lambdify``) print the plain matrix.

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
>>> P.shape, sp.Matrix(P).shape, P.inv().label_text
((4, 4), (4, 4), 'T1_0')
>>> sp.latex(P[0, 0]), sp.latex(P)[:29]
('\\cos{\\left(\\theta_{1} \\right)}', '\\begin{bmatrix}C_{1} & -S_{1}')
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import Any, TypeAlias, TypeGuard

import sympy as sp
from sympy.core.basic import Basic

from dhsym.model.table import Elementary, symbol_values
from dhsym.notation.printers import Notation

__all__ = ["Pose"]

_Matrix: TypeAlias = sp.ImmutableDenseMatrix


class Pose(_Matrix):
    """``^{frm}T_{to}``: pose of frame ``to`` in frame ``frm``, an exact 4×4 ``ImmutableMatrix``.

    Parameters
    ----------
    matrix
        The 4×4 homogeneous transform (anything ``sympy.ImmutableMatrix`` accepts).
    frm, to
        The frames (numbers, or names such as ``"W"``, ``"tool"``, ``"table"``).
    notation
        How it prints (:class:`~dhsym.notation.Notation`: which angles are joints).
    symbol
        The letter of its label (``T``; ``R_z`` for a factor).
    word
        The elementary transforms whose product it is, when known (poses of a
        :class:`~dhsym.kinematics.chain.KinematicChain`): products and inverses are then
        rebuilt in the same compact form as ``robot.transform``.

    Notes
    -----
    ``rotation``, ``position`` and the n, s, a columns (normal, sliding, approach)
    read the matrix; ``matrix`` is the plain ``ImmutableMatrix``.

    Examples
    --------
    >>> import dhsym, sympy as sp
    >>> robot = dhsym.load("planar2r")
    >>> A1, A2 = robot.link_matrix(1), robot.link_matrix(2)
    >>> (A1 * A2).label_text, A1 * A2 == robot.transform(0, 2), (A1 @ A2).inv()[0, 3]
    ('T0_2', True, -a1*cos(theta2) - a2)
    >>> robot.table.constants
    (a1, a2)
    >>> f = sp.lambdify([*robot.variables, *robot.table.constants], A1 * A2)
    >>> f(0, 0, 1.0, 0.8)[0, 3]
    np.float64(1.8)
    """

    _op_priority = 10.02  # above Matrix (10.01): M * pose and pose * M come here

    # the pose's own attributes, set in __new__ (declared: sympy's base class is untyped)
    _plain: sp.ImmutableMatrix
    _frm: int | str
    _to: int | str
    _notation: Notation
    _symbol: str
    _word: tuple[Elementary, ...] | None

    def __new__(
        cls,
        matrix: Iterable[Iterable[object]],
        frm: int | str = "",
        to: int | str = "",
        notation: Notation | None = None,
        symbol: str = "T",
        word: Sequence[Elementary] | None = None,
    ) -> Pose:
        if isinstance(matrix, sp.MatrixBase):
            plain = _Matrix(matrix)
        else:  # rows of numbers or sympy objects; text is refused, never sympified
            from .constants import as_basic

            plain = _Matrix([[as_basic(x) for x in row] for row in matrix])
        if plain.shape != (4, 4):
            raise ValueError(f"a pose is a 4×4 homogeneous transform, got shape {plain.shape}")
        obj: Pose = Basic.__new__(cls, *plain.args)
        obj._rows, obj._cols, obj._rep = 4, 4, plain._rep
        obj._plain = plain
        obj._frm, obj._to, obj._symbol = frm, to, symbol
        obj._notation = notation if notation is not None else Notation()
        obj._word = tuple(word) if word is not None else None
        return obj

    # -- what sympy builds from a pose is a plain matrix ---------------------------------
    @classmethod
    def _new(cls, *args: object, **kwargs: object) -> _Matrix:
        return _Matrix._new(*args, **kwargs)

    @classmethod
    def _fromrep(cls, rep: object) -> _Matrix:
        return _Matrix._fromrep(rep)

    @property
    def func(self) -> type:
        """sympy rebuilds ``func(*args)``: a plain ``ImmutableMatrix``."""
        matrix_type: type = _Matrix
        return matrix_type

    def __hash__(self) -> int:
        return hash(self._plain)

    __eq__ = _Matrix.__eq__

    def __reduce__(self) -> tuple[object, ...]:
        return (Pose, (self._plain, self._frm, self._to, self._notation, self._symbol, self._word))

    # -- the pose ------------------------------------------------------------------------
    @property
    def matrix(self) -> sp.ImmutableMatrix:
        """The plain 4×4 ``ImmutableMatrix``."""
        return self._plain

    @property
    def frm(self) -> int | str:
        """The reference frame ``i`` of ``^iT_j``."""
        return self._frm

    @property
    def to(self) -> int | str:
        """The frame ``j`` of ``^iT_j`` whose pose this is."""
        return self._to

    @property
    def notation(self) -> Notation:
        """How the entries print (``C12``, ``S1``, …)."""
        return self._notation

    @property
    def symbol(self) -> str:
        """The letter of the label (``T``)."""
        return self._symbol

    @property
    def word(self) -> tuple[Elementary, ...] | None:
        """The elementary transforms whose product this is, when known."""
        return self._word

    @property
    def rotation(self) -> sp.ImmutableMatrix:
        """The 3×3 rotation ``R``."""
        return self._plain[:3, :3]

    @property
    def position(self) -> sp.ImmutableMatrix:
        """The origin ``p`` of frame ``to`` in frame ``frm`` (3×1)."""
        return self._plain[:3, 3]

    @property
    def n(self) -> sp.ImmutableMatrix:
        """Normal vector: the x axis of frame ``to`` (``sympy.N(pose)`` still evaluates)."""
        return self._plain[:3, 0]

    @property
    def s(self) -> sp.ImmutableMatrix:
        """Sliding vector: the y axis of frame ``to``."""
        return self._plain[:3, 1]

    @property
    def a(self) -> sp.ImmutableMatrix:
        """Approach vector: the z axis of frame ``to``."""
        return self._plain[:3, 2]

    @property
    def label_latex(self) -> str:
        """``{}^{i}T_{j}`` for headings and equations."""
        return f"{{}}^{{{self.frm}}}{self.symbol}_{{{self.to}}}"

    @property
    def label_text(self) -> str:
        """``T0_2`` style label for plain text."""
        return f"{self.symbol}{self.frm}_{self.to}"

    def count_ops(self, visual: bool | None = None) -> int | sp.Expr:
        """``sympy.count_ops`` summed over the 16 entries (a size measure).

        With ``visual`` the count is sympy's expression of the operations (``2*ADD + ...``).
        """
        if visual:
            ops: sp.Expr = sp.count_ops(self._plain, visual=True)
            return ops
        return int(sum(sp.count_ops(e) for e in self._plain))

    def subs(self, *args: object, **kwargs: object) -> Pose:
        """A copy with values substituted (symbols to numbers or expressions), labels kept.

        Takes what ``sympy.Matrix.subs`` takes: a dict, pairs, or ``old, new``; names may be
        text and values text or numbers (read by the whitelist parser, never sympified).

        >>> from dhsym import load
        >>> load("planar2r").link_matrix(1).subs({"a1": "0.5"})[0, 3]
        cos(theta1)/2
        """
        return Pose(
            self._plain.subs(*_safe_subs(args), **kwargs),
            self.frm,
            self.to,
            self.notation,
            self.symbol,
        )

    def evalf(
        self, values: Mapping[Any, object] | int | None = None, *args: object, **kwargs: object
    ) -> sp.ImmutableMatrix:
        """Numerical matrix (sympy floats) at ``values`` (a dict of symbol values).

        ``sympy.N(pose, 5)`` and ``pose.evalf(5, subs=…)`` work as for any matrix.
        """
        subs = kwargs.get("subs")
        if isinstance(subs, Mapping):
            kwargs["subs"] = symbol_values(subs)
        if isinstance(values, Mapping) or values is None:
            kwargs.setdefault("subs", symbol_values(values))
            return _Matrix(self._plain.evalf(*args, **kwargs))
        return _Matrix(self._plain.evalf(values, *args, **kwargs))

    # -- composition -----------------------------------------------------------------------
    def _chains_with(self, other: object) -> TypeGuard[Pose]:
        return (
            isinstance(other, Pose)
            and other.symbol == self.symbol
            and self.to not in ("", None)
            and self.to == other.frm
        )

    def __mul__(self, other: object) -> object:
        if self._chains_with(other):
            return self._compose(other)
        if isinstance(other, Pose):
            return self._plain * other._plain
        return _Matrix.__mul__(self, other)

    def __matmul__(self, other: object) -> object:
        if isinstance(other, Pose):
            return self * other
        return _Matrix.__matmul__(self, other)

    def __rmul__(self, other: object) -> object:
        return _Matrix.__rmul__(self, other)

    def __rmatmul__(self, other: object) -> object:
        return _Matrix.__rmatmul__(self, other)

    def _compose(self, other: Pose) -> Pose:
        from .simplification import compose

        notation = _merge(self.notation, other.notation)
        if self.word is not None and other.word is not None:
            word = self.word + other.word
            return Pose(compose(word), self.frm, other.to, notation, self.symbol, word)
        product = self._plain * other._plain
        return Pose(_tidy(product), self.frm, other.to, notation, self.symbol)

    def inv(self, *args: object, **kwargs: object) -> Pose:
        """``^{to}T_{frm}``, the exact rigid inverse ``[Rᵀ, −Rᵀp; 0 0 0 1]``.

        (Arguments of ``sympy.Matrix.inv`` are accepted and not needed: no generic
        matrix inverse is computed.)
        """
        from .simplification import compose
        from .transforms import inverse_word, rigid_inverse

        if self.word is not None:
            word = inverse_word(self.word)
            return Pose(compose(word), self.to, self.frm, self.notation, self.symbol, word)
        return Pose(
            _tidy(rigid_inverse(self._plain)), self.to, self.frm, self.notation, self.symbol
        )

    # -- printing --------------------------------------------------------------------------
    def latex(self) -> str:
        """The matrix in LaTeX (``bmatrix``) in this pose's notation."""
        return self.notation.latex(self._plain)

    def text(self) -> str:
        """The matrix in plain text in this pose's notation."""
        return self.notation.text(self._plain)

    def _latex(self, printer: object) -> str:
        return self.latex()

    def _sympystr(self, printer: object) -> str:
        from sympy.printing.codeprinter import CodePrinter

        if isinstance(printer, CodePrinter):  # code must evaluate: cos(theta1), not C1
            return str(printer._print(self._plain))
        return self.text()

    def _sympyrepr(self, printer: Any) -> str:  # a sympy printer (untyped)
        return str(printer._print(self._plain))

    def _pretty(self, printer: Any) -> object:  # a sympy printer (untyped)
        """``sympy.pprint``: the matrix with the abbreviations as symbols (C₁₂, S₁)."""
        short = {}
        for f in self._plain.atoms(sp.cos, sp.sin):
            name = self.notation.text(f)
            if name != sp.sstr(f):
                short[f] = sp.Symbol(name)
        return printer._print(self._plain.xreplace(short))

    def _repr_latex_(self) -> str:
        return f"$${self.label_latex} = {self.latex()}$$"

    def _repr_markdown_(self) -> str:
        return self._repr_latex_()

    def __str__(self) -> str:
        return f"{self.label_text} = {self.text()}"

    def __repr__(self) -> str:
        return self.text()


def _merge(a: Notation, b: Notation) -> Notation:
    """The notation of a product: the joint labels of both factors."""
    if a == b or not b.labels:
        return a
    labels = dict(a.labels)
    for sym, lab in b.labels:
        labels.setdefault(sym, lab)
    return Notation(tuple(labels.items()), compact=a.compact, style=a.style)


def _tidy(M: sp.MatrixBase) -> sp.ImmutableMatrix:
    """Fold the sum-angle pairs of a product (``C1C2 − S1S2`` → ``C12``): exact."""
    from .simplification import fold_sum_angles, tidy_signs

    return _Matrix(M.applyfunc(lambda e: tidy_signs(fold_sum_angles(sp.expand(e)))))


def _safe_subs(args: tuple[object, ...]) -> tuple[object, ...]:
    """``subs`` arguments with names and values read safely (:func:`symbol_values`)."""
    if len(args) == 2:  # old, new
        return tuple(symbol_values({args[0]: args[1]}).items())[0]
    if len(args) == 1 and isinstance(args[0], Mapping):
        return (symbol_values(args[0]),)
    if len(args) == 1 and isinstance(args[0], (list, tuple)):  # pairs
        return (list(symbol_values(dict(args[0])).items()),)
    return args
