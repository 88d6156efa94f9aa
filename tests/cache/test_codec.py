"""Expressions and arrays as data read back without running code (dhsym.cache.codec)."""

from __future__ import annotations

import ast
import json
import re
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.cache import codec
from dhsym.cache.codec import CodecError, read_array, read_exprs, write_array, write_exprs
from dhsym.kinematics.numeric import NumericProgram


def test_round_trip_of_a_closed_form():
    M = dhsym.load("puma560").arm_matrix().matrix
    (back,) = read_exprs(write_exprs([M]))
    assert back == M and isinstance(back, sp.ImmutableMatrix)
    assert all(a == b and hash(a) == hash(b) for a, b in zip(back, M))


def test_round_trip_keeps_numbers_and_assumptions_exactly():
    x = sp.Symbol("x", positive=True)
    y = sp.Symbol("y")
    items = [
        sp.Float("0.1", 30) * x,
        sp.Rational(-7, 3) * y**2,
        sp.Integer(10) ** 40 + x,
        sp.pi / 2 - sp.atan2(y, x),
        sp.Piecewise((x, y > 0), (sp.Abs(y), True)),
        sp.sqrt(x) * sp.E + sp.I,
    ]
    back = read_exprs(write_exprs(items))
    assert back == items
    assert back[0].args[0]._prec == items[0].args[0]._prec
    assert [s.assumptions0 for s in back[0].free_symbols] == [x.assumptions0]


def test_shared_subexpressions_written_once():
    t = sp.Symbol("t")
    big = sp.cos(t) * sp.sin(t) + 1
    doc = json.loads(write_exprs([big * 2, big**2]))
    assert sum(1 for n in doc["nodes"] if n[0] == "cos") == 1


def test_a_program_round_trip():
    r = dhsym.load("planar2r")
    M = r.arm_matrix().matrix.subs({sp.Symbol("a1", real=True): 1, sp.Symbol("a2", real=True): 2})
    p = NumericProgram.of(list(M), r.variables)
    lhs = sp.Tuple(*(s for s, _ in p.assignments))
    rhs = sp.Tuple(*(e for _, e in p.assignments))
    a, b, c = read_exprs(write_exprs([lhs, rhs, sp.Tuple(*p.outputs)]))
    assert (tuple(zip(a.args, b.args)), tuple(c.args)) == (p.assignments, p.outputs)


@pytest.mark.parametrize(
    "item",
    [sp.Dummy("d"), sp.Function("f")(sp.Symbol("x")), sp.Derivative(sp.Symbol("x") ** 3)],
)
def test_what_cannot_be_written_is_refused(item):
    with pytest.raises(CodecError):
        write_exprs([item])


def test_an_undefined_function_is_written_only_as_the_class_given():
    """The derivations' non-commuting ``R_z``, ``T_x`` (dhsym.notation.layout): written and
    read back when the very class is given; one of the same name but another class is not."""
    from dhsym.model.table import Elementary
    from dhsym.notation.layout import WORD_FUNCTIONS, word_expr

    t = sp.Symbol("theta4", real=True)
    word = word_expr([Elementary("R", "z", t), Elementary("T", "x", sp.Symbol("a3"))])
    (back,) = read_exprs(write_exprs([word], WORD_FUNCTIONS), WORD_FUNCTIONS)
    assert back == word and sp.srepr(back) == sp.srepr(word) and not back.is_commutative
    with pytest.raises(CodecError):
        write_exprs([word])
    other = sp.Function("R_z")(t)
    with pytest.raises(CodecError):
        write_exprs([other], WORD_FUNCTIONS)


def _doc(nodes, roots=(0,)):
    return json.dumps({"format": "dhsym-exprs 1", "nodes": nodes, "roots": list(roots)})


@pytest.mark.parametrize(
    "text",
    [
        "not json",
        json.dumps({"format": "other"}),
        _doc([["eval", []]]),
        _doc([["__import__", []]]),
        _doc([["Symbol", ["os"]]]),  # Symbol is built from ["S", ...] only
        _doc([["cos", [1]], ["I", "1"]]),  # a reference forward
        _doc([["cos", [0]]]),  # a reference to itself
        _doc([["I", "1"]], roots=[5]),
        _doc([["I", "12_3"]]) + "x",
        _doc([["S", "x", {"real": "yes"}]]),
        _doc([["F", "0.5", "53"]]),
        _doc([["I", "1"]], roots=[{"matrix": [2, 2, [0]]}]),
        _doc([["K", "__class__"]]),
    ],
)
def test_reader_refuses_what_it_does_not_build(text):
    with pytest.raises(CodecError):
        read_exprs(text)


def test_arrays_without_pickle():
    a = np.arange(6.0).reshape(2, 3)
    assert np.array_equal(read_array(write_array(a)), a)
    with pytest.raises(CodecError):
        write_array(np.array([object()], dtype=object))
    import io

    buffer = io.BytesIO()
    np.save(buffer, np.array([{"a": 1}], dtype=object), allow_pickle=True)
    with pytest.raises(CodecError):
        read_array(buffer.getvalue())


def _code_without_docstrings(path: Path) -> str:
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if isinstance(body, list) and body and isinstance(body[0], ast.Expr):
            if isinstance(body[0].value, ast.Constant) and isinstance(body[0].value.value, str):
                body[0] = ast.Pass()
    return ast.unparse(tree)


def test_the_readers_have_no_path_to_code_execution():
    """The modules that read what the cache holds never unpickle, unmarshal, eval or exec,
    and import nothing by a name they read (their code, docstrings left out)."""
    import dhsym.cache.store as store

    for module in (codec, store):
        code = _code_without_docstrings(Path(module.__file__))
        for word in ("pickle", "marshal", "eval(", "exec(", "__import__", "importlib", "getattr("):
            hits = [m.start() for m in re.finditer(re.escape(word), code)]
            if word == "pickle":  # only np.save/np.load's allow_pickle=False
                hits = [h for h in hits if code[h - 6 : h + 12] != "allow_pickle=False"]
            assert not hits, f"{module.__name__} mentions {word}"
        assert "allow_pickle=True" not in code
