"""Exact expressions and arrays as data that can be read back without running code.

An expression is written as a JSON document of nodes in topological order (each shared
subexpression once): a node is a number (``["I", "12"]``, ``["R", 1, 2]``,
``["F", "0.5", 53]``), a constant (``["K", "pi"]``), a symbol with its assumptions
(``["S", "theta1", {"real": true}]``) or a whitelisted sympy class applied to earlier
nodes (``["cos", [3]]``). The reader is :func:`json.loads` and a table of classes: a
name outside the table, a reference forward, anything else unexpected raises
:class:`CodecError` (the caller rebuilds). Nothing is imported, looked up by an
attribute name or executed from what is read. Arrays are ``.npy`` bytes read with
``allow_pickle=False``.

Examples
--------
>>> import sympy as sp
>>> t = sp.Symbol("theta1", real=True)
>>> M = sp.ImmutableMatrix([[sp.cos(t), -sp.sin(t)], [sp.Rational(1, 2) * t, sp.pi]])
>>> text = write_exprs([M, t**2 + sp.Float("0.25")])
>>> back = read_exprs(text)
>>> back[0] == M, back[1] == t**2 + sp.Float("0.25"), back[1].free_symbols == {t}
(True, True, True)
>>> read_exprs('{"format": "dhsym-exprs 1", "nodes": [["__import__", []]], "roots": [0]}')
Traceback (most recent call last):
...
dhsym.cache.codec.CodecError: node 0: __import__ is not a class the reader builds
"""

from __future__ import annotations

import io
import json
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import sympy as sp
from sympy.core.function import AppliedUndef
from sympy.functions.elementary.piecewise import ExprCondPair

__all__ = ["CodecError", "read_array", "read_exprs", "write_array", "write_exprs"]

_FORMAT = "dhsym-exprs 1"

#: The sympy classes a document may apply, by name (looked up in this table only).
CLASSES: dict[str, type] = {
    c.__name__: c
    for c in (
        sp.Add,
        sp.Mul,
        sp.Pow,
        sp.sin,
        sp.cos,
        sp.tan,
        sp.cot,
        sp.sec,
        sp.csc,
        sp.asin,
        sp.acos,
        sp.atan,
        sp.atan2,
        sp.exp,
        sp.log,
        sp.Abs,
        sp.sign,
        sp.Max,
        sp.Min,
        sp.re,
        sp.im,
        sp.floor,
        sp.ceiling,
        sp.Mod,
        sp.Heaviside,
        sp.Piecewise,
        sp.Tuple,
        sp.Eq,
        sp.Ne,
        sp.Lt,
        sp.Le,
        sp.Gt,
        sp.Ge,
        sp.And,
        sp.Or,
        sp.Not,
    )
}
CLASSES["ExprCondPair"] = ExprCondPair  # Piecewise's argument

#: Classes built from their arguments as given (no ``evaluate`` keyword).
_AS_GIVEN = {"Tuple", "ExprCondPair"}

_CONSTANTS: dict[str, sp.Basic] = {
    "pi": sp.pi,
    "E": sp.E,
    "I": sp.I,
    "oo": sp.oo,
    "-oo": -sp.oo,
    "zoo": sp.zoo,
    "nan": sp.nan,
    "true": sp.true,
    "false": sp.false,
}
_CONSTANT_NAMES = {type(v): k for k, v in _CONSTANTS.items()}


class CodecError(ValueError):
    """An expression that cannot be written, or a document that is not one this reader
    builds (the cache treats it as absent)."""


def write_exprs(items: Sequence[Any], extra: Mapping[str, type] | None = None) -> str:
    """The JSON document of ``items`` (expressions and matrices), each shared node once.

    ``extra`` names more classes (a dhsym ``Function``, or an undefined function such as
    the ``R_z`` of :data:`dhsym.notation.layout.WORD_FUNCTIONS`, given as that very class)
    the document may apply; the reader must be given the same. Raises :class:`CodecError`
    for what it cannot write (a ``Dummy``, another undefined function, a class outside the
    table).
    """
    classes = {**CLASSES, **(extra or {})}
    nodes: list[Any] = []
    index: dict[sp.Basic, int] = {}

    def visit(root: sp.Basic) -> int:
        # iterative post-order: deep expressions do not reach the recursion limit
        stack: list[tuple[sp.Basic, bool]] = [(root, False)]
        while stack:
            e, done = stack.pop()
            if e in index:
                continue
            if not done and not _is_leaf(e):
                stack.append((e, True))
                stack.extend((a, False) for a in reversed(e.args) if a not in index)
                continue
            index[e] = len(nodes)
            nodes.append(_node(e, index, classes))
        return index[root]

    def basic(value: object) -> sp.Basic:
        if not isinstance(value, sp.Basic):
            raise CodecError(f"not a sympy object: {type(value).__name__}")
        return value

    roots: list[Any] = []
    for item in items:
        if isinstance(item, sp.MatrixBase):
            cells = [visit(basic(c)) for c in item]
            roots.append({"matrix": [item.rows, item.cols, cells]})
        else:
            roots.append(visit(basic(item)))
    return json.dumps({"format": _FORMAT, "nodes": nodes, "roots": roots}, separators=(",", ":"))


def _is_leaf(e: sp.Basic) -> bool:
    return isinstance(e, (sp.Number, sp.Symbol)) or type(e) in _CONSTANT_NAMES


def _node(e: sp.Basic, index: Mapping[sp.Basic, int], classes: Mapping[str, type]) -> list[Any]:
    if type(e) in _CONSTANT_NAMES:
        return ["K", _CONSTANT_NAMES[type(e)]]
    if isinstance(e, sp.Integer):
        return ["I", str(int(e))]
    if isinstance(e, sp.Rational):
        return ["R", str(e.p), str(e.q)]
    if isinstance(e, sp.Float):
        text = sp.srepr(e)  # Float('0.25', precision=53): the exact round trip sympy defines
        digits = text[len("Float('") : text.index("'", len("Float('"))]
        return ["F", digits, int(e._prec)]
    if isinstance(e, sp.Dummy) or (
        isinstance(e, AppliedUndef) and classes.get(type(e).__name__) is not type(e)
    ):
        raise CodecError(f"{type(e).__name__} {e} cannot be written (no stable name)")
    if isinstance(e, sp.Symbol):
        if type(e) is not sp.Symbol:
            raise CodecError(f"{type(e).__name__} {e} is not a plain symbol")
        assumptions = e._assumptions_orig  # as given to Symbol (sympy >= 1.12)
        return ["S", e.name, {k: bool(v) for k, v in sorted(assumptions.items())}]
    name, args = type(e).__name__, e.args
    if classes.get(name) is not type(e):
        raise CodecError(f"{name} is not a class the reader builds")
    return [name, [index[a] for a in args]]


def read_exprs(text: str | bytes, extra: Mapping[str, type] | None = None) -> list[Any]:
    """The expressions and matrices (``ImmutableMatrix``) of a document of :func:`write_exprs`.

    Raises :class:`CodecError` when the document is not one it builds.
    """
    classes = {**CLASSES, **(extra or {})}
    try:
        doc = json.loads(text)
    except (ValueError, RecursionError) as err:
        raise CodecError(f"not a JSON document: {err}") from None
    if not isinstance(doc, dict) or doc.get("format") != _FORMAT:
        raise CodecError("not a dhsym expression document")
    raw_nodes, raw_roots = doc.get("nodes"), doc.get("roots")
    if not isinstance(raw_nodes, list) or not isinstance(raw_roots, list):
        raise CodecError("a document has a list of nodes and a list of roots")
    built: list[sp.Basic] = []
    for k, node in enumerate(raw_nodes):
        try:
            built.append(_build(node, built, classes))
        except CodecError as err:
            raise CodecError(f"node {k}: {err}") from None
        except (TypeError, ValueError, AttributeError, IndexError, KeyError) as err:
            raise CodecError(f"node {k}: {type(err).__name__}: {err}") from None

    def ref(k: object) -> sp.Basic:
        if not isinstance(k, int) or isinstance(k, bool) or not 0 <= k < len(built):
            raise CodecError(f"a root refers to no node: {k!r}")
        return built[k]

    out: list[Any] = []
    for root in raw_roots:
        if isinstance(root, dict):
            spec = root.get("matrix")
            if not (isinstance(spec, list) and len(spec) == 3 and isinstance(spec[2], list)):
                raise CodecError("a matrix is [rows, cols, cells]")
            rows, cols, cells = spec
            if not (isinstance(rows, int) and isinstance(cols, int) and rows * cols == len(cells)):
                raise CodecError("a matrix's shape does not match its cells")
            out.append(sp.ImmutableMatrix(rows, cols, [ref(c) for c in cells]))
        else:
            out.append(ref(root))
    return out


def _build(node: object, built: Sequence[sp.Basic], classes: Mapping[str, type]) -> sp.Basic:
    if not isinstance(node, list) or not node or not isinstance(node[0], str):
        raise CodecError("a node is [head, ...]")
    head = node[0]
    if head == "I" and len(node) == 2 and isinstance(node[1], str):
        return sp.Integer(int(node[1]))
    if head == "R" and len(node) == 3 and all(isinstance(v, str) for v in node[1:]):
        return sp.Rational(int(node[1]), int(node[2]))
    if head == "F" and len(node) == 3 and isinstance(node[1], str) and isinstance(node[2], int):
        return sp.Float(node[1], precision=node[2])
    if head == "K" and len(node) == 2 and node[1] in _CONSTANTS:
        return _CONSTANTS[node[1]]
    if head == "S" and len(node) == 3 and isinstance(node[1], str) and isinstance(node[2], dict):
        flags = node[2]
        if not all(isinstance(k, str) and isinstance(v, bool) for k, v in flags.items()):
            raise CodecError("a symbol's assumptions are names and booleans")
        return sp.Symbol(node[1], **flags)
    cls = classes.get(head)
    if cls is None:
        raise CodecError(f"{head} is not a class the reader builds")
    if len(node) != 2 or not isinstance(node[1], list):
        raise CodecError(f"{head} takes a list of earlier nodes")
    args = []
    for k in node[1]:
        if not isinstance(k, int) or isinstance(k, bool) or not 0 <= k < len(built):
            raise CodecError(f"{head} refers to no earlier node: {k!r}")
        args.append(built[k])
    result: sp.Basic = cls(*args) if head in _AS_GIVEN else cls(*args, evaluate=False)
    return result


def write_array(array: np.ndarray) -> bytes:
    """``.npy`` bytes of a numeric array (objects refused).

    >>> read_array(write_array(np.arange(3.0)))
    array([0., 1., 2.])
    """
    a = np.asarray(array)
    if a.dtype.hasobject:
        raise CodecError("only numeric arrays are written")
    buffer = io.BytesIO()
    np.save(buffer, a, allow_pickle=False)
    return buffer.getvalue()


def read_array(data: bytes) -> np.ndarray:
    """The array of :func:`write_array` bytes (``allow_pickle=False``: objects refused)."""
    try:
        array: np.ndarray = np.load(io.BytesIO(data), allow_pickle=False)
    except (ValueError, OSError) as err:
        raise CodecError(f"not a numeric .npy array: {err}") from None
    return array
