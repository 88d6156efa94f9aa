"""Tests of the whitelist expression parser ``dhsym.model.parsing``."""

from __future__ import annotations

import ast
import builtins
import dataclasses
import importlib
import inspect
import time

import pytest
import sympy
import sympy.parsing.sympy_parser
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st

from dhsym.errors import DHError, ParseError
from dhsym.model import parsing
from dhsym.model.parsing import (
    DEFAULT_LIMITS,
    ParseLimits,
    normalize_name,
    parse_expression,
    symbol,
)

x, y, a, a1, a2 = (symbol(n) for n in ("x", "y", "a", "a1", "a2"))
theta1, theta2, alpha = symbol("theta1"), symbol("theta2"), symbol("alpha")


# --- ordinary expressions ----------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("theta1 + pi/2", theta1 + sympy.pi / 2),
        (
            "a1*cos(theta1) + a2*cos(theta1 + theta2)",
            a1 * sympy.cos(theta1) + a2 * sympy.cos(theta1 + theta2),
        ),
        ("-x^2", -(x**2)),
        ("-x**2", -(x**2)),
        ("2^3^2", sympy.Integer(512)),
        ("2**3**2", sympy.Integer(512)),
        ("(x+1)(x-1)", (x + 1) * (x - 1)),
        ("2a", 2 * a),
        ("2a1", 2 * a1),
        ("2 pi", 2 * sympy.pi),
        ("a1 cos(theta1)", a1 * sympy.cos(theta1)),
        ("c1 c2", symbol("c1") * symbol("c2")),
        ("x^2 y", x**2 * y),
        ("x^-2", x**-2),
        ("8^(2/3)", sympy.Integer(4)),
        ("--x", x),
        ("+x", x),
        ("sqrt(2)/2", sympy.sqrt(2) / 2),
        ("atan2(y, x)", sympy.atan2(y, x)),
        ("tan(theta1)", sympy.tan(theta1)),
        ("θ1 + α", theta1 + alpha),
        ("θ_1", symbol("theta_1")),
        ("π/4", sympy.pi / 4),
        ("  x\t+\ny  ", x + y),
    ],
)
def test_ordinary_expressions(text: str, expected: sympy.Expr) -> None:
    assert parse_expression(text) == expected


def test_unary_minus_binds_looser_than_power() -> None:
    assert parse_expression("-x^2") != x**2
    assert parse_expression("-2^2") == -4


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("0.15005", sympy.Rational(15005, 100000)),
        ("0.4318", sympy.Rational(4318, 10000)),
        ("1e-3", sympy.Rational(1, 1000)),
        (".5", sympy.Rational(1, 2)),
        ("2.5E2", sympy.Integer(250)),
        ("1E+2", sympy.Integer(100)),
        ("5.", sympy.Integer(5)),
        ("007", sympy.Integer(7)),
    ],
)
def test_decimals_are_exact_rationals(text: str, expected: sympy.Rational) -> None:
    value = parse_expression(text)
    assert value == expected
    assert value.is_Rational
    assert not value.atoms(sympy.Float)


def test_exponent_letter_without_digits_is_a_symbol() -> None:
    assert parse_expression("2e") == 2 * symbol("e")
    assert parse_expression("2e-3x") == x / 500


def test_symbols_are_real() -> None:
    value = parse_expression("a1*cos(theta1) + d_2 + θ1")
    assert value.free_symbols == {a1, theta1, symbol("d_2")}
    assert all(s.is_real is True for s in value.free_symbols)


def test_e_and_capital_e_are_plain_symbols() -> None:
    assert parse_expression("E") == symbol("E")
    assert parse_expression("e") == symbol("e")
    assert parse_expression("E") != sympy.E
    assert parse_expression("e**2").has(sympy.E) is False


def test_normalize_name_and_symbol() -> None:
    assert normalize_name("θ1") == "theta1"
    assert normalize_name("α") == "alpha"
    assert normalize_name("π") == "pi"
    assert normalize_name("Θ") == "theta"
    greek = [normalize_name(c) for c in "φψβγδλμω"]
    assert greek == "phi psi beta gamma delta lambda mu omega".split()
    assert normalize_name("q_2") == "q_2"
    assert symbol("θ1") == symbol("theta1") == sympy.Symbol("theta1", real=True)
    assert symbol("θ1") != sympy.Symbol("theta1")  # not the assumption-free symbol


@pytest.mark.parametrize("name", ["", "1a", "a b", "__x", "a__b", "nan", "exec", "x+1"])
def test_symbol_rejects_invalid_names(name: str) -> None:
    with pytest.raises(ParseError):
        symbol(name)


def test_resolve_hook_substitutes_names() -> None:
    seen: list[str] = []

    def resolve(name: str) -> sympy.Expr | None:
        seen.append(name)
        return sympy.cos(theta1) if name == "C1" else None

    value = parse_expression("a1*C1 + C1 + θ1 + pi + sin(x)", resolve=resolve)
    assert value == a1 * sympy.cos(theta1) + sympy.cos(theta1) + theta1 + sympy.pi + sympy.sin(x)
    assert sorted(seen) == ["C1", "a1", "theta1", "x"]  # once per name; never pi or sin


def test_resolved_name_before_parenthesis_multiplies() -> None:
    value = parse_expression("a1(x + 1)", resolve=lambda n: a1 if n == "a1" else None)
    assert value == a1 * (x + 1)
    with pytest.raises(ParseError, match="unknown function 'a1'"):
        parse_expression("a1(x + 1)")


def test_resolve_must_return_an_expression() -> None:
    with pytest.raises(TypeError, match="resolve"):
        parse_expression("x", resolve=lambda n: 3)  # type: ignore[arg-type,return-value]


def test_unknown_function_lists_the_allowed_ones() -> None:
    with pytest.raises(ParseError) as info:
        parse_expression("foo(x)")
    assert "unknown function 'foo'" in str(info.value)
    assert "allowed: atan2, cos, sin, sqrt, tan" in str(info.value)


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("sin x", "expected '(' after function 'sin'"),
        ("sin(x, y)", "sin() with 2 argument(s)"),
        ("atan2(x)", "atan2() with 1 argument(s)"),
        ("2 3", "unexpected number '3' at column 3"),
        ("1.2.3", "unexpected number '.3' at column 4"),
        ("(x", "unexpected end of text at column 3"),
        ("x)", "unexpected ')' at column 2"),
        ("x, y", "unexpected ',' at column 2"),
        ("x^y", "non-numeric exponent"),
    ],
)
def test_grammar_errors(text: str, fragment: str) -> None:
    with pytest.raises(ParseError) as info:
        parse_expression(text)
    assert fragment in str(info.value)


# --- round trip ---------------------------------------------------------------------------

_LEAVES = st.one_of(
    st.integers(-12, 12).map(sympy.Integer),
    st.sampled_from([x, y, theta1, symbol("a_2"), sympy.pi]),
)


def _extend(children: st.SearchStrategy[sympy.Expr]) -> st.SearchStrategy[sympy.Expr]:
    pairs = st.tuples(children, children)
    return st.one_of(
        pairs.map(lambda p: p[0] + p[1]),
        pairs.map(lambda p: p[0] - p[1]),
        pairs.map(lambda p: p[0] * p[1]),
        pairs.map(lambda p: p[0] / p[1]),
        st.tuples(children, st.integers(-3, 3)).map(lambda p: p[0] ** p[1]),
        children.map(sympy.sin),
        children.map(sympy.cos),
    )


def _within_default_limits(expr: sympy.Expr) -> bool:
    exponents = [p.exp for p in expr.atoms(sympy.Pow)]
    numbers = expr.atoms(sympy.Rational)
    return all(e.is_Rational and max(abs(e.p), e.q) <= 64 for e in exponents) and all(
        max(abs(r.p), r.q) < 10**300 for r in numbers
    )


@settings(
    max_examples=300, deadline=None, database=None, suppress_health_check=[HealthCheck.too_slow]
)
@given(st.recursive(_LEAVES, _extend, max_leaves=10))
@example(sympy.sin(1 / (2 * (x + 1))))
def test_printed_expressions_parse_back_to_the_same_tree(expr: sympy.Expr) -> None:
    assume(not expr.has(sympy.zoo, sympy.nan, sympy.oo, -sympy.oo))
    assume(_within_default_limits(expr))
    parsed = parse_expression(sympy.sstr(expr))
    # Structurally equal almost always; sympy's printer can show a product that evaluation
    # would distribute, e.g. 1/(2*(x + 1)) reads back as 1/(2*x + 2): then compare values.
    assert parsed == expr or sympy.simplify(parsed - expr) == 0


@pytest.mark.parametrize(
    "expr",
    [-(x + 1) * sympy.sin(x - 1), y - (x - 1) * (x + 1), -((x + 1) ** 2) * y, (1 - x) / (x + 1)],
)
def test_sign_in_front_of_a_product_round_trips(expr: sympy.Expr) -> None:
    assert parse_expression(sympy.sstr(expr)) == expr


_PIECES = [*"0123456789.eE+-*/^(),_ xyθπ'[;=\\\x00", "sin", "atan2", "pi", "**", "nan", "__", "1e"]


@settings(max_examples=300, deadline=None, database=None)
@given(
    st.one_of(st.text(max_size=40), st.lists(st.sampled_from(_PIECES), max_size=40).map("".join))
)
def test_any_text_gives_an_expression_or_parse_error(text: str) -> None:
    start = time.process_time()
    try:
        assert isinstance(parse_expression(text), sympy.Expr)
    except ParseError as err:
        assert "\n" not in str(err)
    assert time.process_time() - start < 2.0  # a hang guard, not a speed figure


# --- hostile input ------------------------------------------------------------------------

HOSTILE = {
    "import": "__import__('os').system('ls')",
    "dunder": "().__class__",
    "lambda": "lambda: 0",
    "big exponent": "x**9999999",
    "big power": "10**400",
    "power tower": "2**2**2**2**2**2",
    "nested parens": "(" * 100_000 + "x" + ")" * 100_000,
    "many signs": "-" * 100_000 + "x",
    "10 MB": "x" * 10_000_000,
    "control bytes": "\x00\x01",
    "exec": "exec",
    "eval call": "eval(1)",
    "open call": "open('f')",
    "nan": "nan",
    "inf": "inf",
    "Infinity": "Infinity",
    "division by zero": "1/0",
    "statement": "x; y",
    "assignment": "a = 1",
    "empty": "",
    "blank": "  \t ",
    "subscript": "a[1]",
    "dict": "{x}",
    "backslash": "x\\y",
    "attribute": "x.y",
    "decorator": "@x",
    "backtick": "`x`",
    "dollar": "$x",
    "keyword": "import",
    "too many digits": "1" * 41,
    "huge literal": "1e999",
    "tan(pi/2)": "tan(pi/2)",
    "atan2(0, 0)": "atan2(0, 0)",
    "zero to minus one": "0^-1",
    "power of a big number": "(10^60)^60",
    "merged powers": "((10^(64/63))^64)^64",
    "many factors": "*".join(["10^60"] * 8),
    "merged radicals": "*".join(f"sqrt({10**39 + 2 * k + 1})" for k in range(120)),
    "merged roots": "*".join(f"{10**39 + 2 * k + 1}^(1/64)" for k in range(120)),
    "sum of fractions": "+".join(f"1/{10_001 + 2 * k}" for k in range(300)),
    "too many tokens": "x" + "+x" * 2_600,
}


@pytest.mark.parametrize("text", list(HOSTILE.values()), ids=list(HOSTILE))
def test_hostile_input_raises_parse_error_quickly(text: str) -> None:
    start = time.process_time()  # CPU time: the load of other processes does not count
    with pytest.raises(ParseError):
        parse_expression(text)
    assert time.process_time() - start < 2.0  # a hang guard, not a speed figure


@pytest.mark.parametrize("value", [b"x + 1", None, 3, ["x"]])
def test_non_text_input_raises_parse_error(value: object) -> None:
    with pytest.raises(ParseError, match="expected text"):
        parse_expression(value)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    "text",
    [
        "(" * 100_000 + "x" + ")" * 100_000,
        "-" * 100_000 + "x",
        "2^" * 50_000 + "2",
        "sin(" * 1000 + "x",
    ],
    ids=["parens", "signs", "power tower", "calls"],
)
def test_deep_nesting_is_refused_by_max_depth_not_recursion(text: str) -> None:
    roomy = ParseLimits(max_length=10**6, max_nodes=10**6)
    start = time.process_time()
    with pytest.raises(ParseError, match="max_depth=60"):
        parse_expression(text, limits=roomy)
    assert time.process_time() - start < 2.0  # mostly tokenizing 200,000 characters


def test_recursion_limit_is_turned_into_parse_error() -> None:
    reckless = ParseLimits(max_length=10**6, max_nodes=10**6, max_depth=10**6)
    with pytest.raises(ParseError, match="too deeply nested"):
        parse_expression("(" * 50_000 + "x" + ")" * 50_000, limits=reckless)


@pytest.mark.parametrize(
    ("text", "limit"),
    [
        ("x**9999999", "max_exponent=64"),
        ("10**400", "max_exponent=64"),
        ("(x^64)^2", "max_exponent=64"),
        ("x^(1/65)", "max_exponent=64"),
        ("(10^60)^60", "max_result_digits=400"),
        ("1" * 41, "max_digits=40"),
        ("x" * 20_001, "max_length=20000"),
        ("x" + "+x" * 2_600, "max_nodes=5000"),
        (" + ".join(f"x{i}" for i in range(101)), "max_symbols=100"),
    ],
    ids=lambda value: value if len(value) < 30 else f"{value[:10]}...({len(value)} chars)",
)
def test_limit_errors_name_the_limit(text: str, limit: str) -> None:
    with pytest.raises(ParseError, match=limit):
        parse_expression(text)


def test_inputs_just_within_the_limits_parse_in_linear_time() -> None:
    text = " + ".join(f"x{i % 100}*cos(q{i % 50})" for i in range(400))
    assert len(text) < DEFAULT_LIMITS.max_length
    start = time.process_time()
    parse_expression(text, limits=ParseLimits(max_symbols=200))
    assert time.process_time() - start < 2.0


def test_parse_limits_are_frozen_and_validated() -> None:
    with pytest.raises(dataclasses.FrozenInstanceError):
        DEFAULT_LIMITS.max_depth = 1000  # type: ignore[misc]
    with pytest.raises(ValueError, match="max_depth"):
        ParseLimits(max_depth=0)
    with pytest.raises(ValueError, match="max_length"):
        ParseLimits(max_length=2.5)  # type: ignore[arg-type]
    with pytest.raises(ParseError, match="max_depth=3"):
        parse_expression("((((x))))", limits=ParseLimits(max_depth=3))


def test_parsing_never_evaluates_text(monkeypatch: pytest.MonkeyPatch) -> None:
    def forbidden(*args: object, **kwargs: object) -> None:
        raise AssertionError("text was evaluated")

    # the module itself: the attribute sympy.core.sympify is the function of that name
    sympify_module = importlib.import_module("sympy.core.sympify")
    real_sympify = sympify_module.sympify

    def sympify_without_text(a: object, *args: object, **kwargs: object) -> object:
        if isinstance(a, str):
            raise AssertionError("sympify was given text")
        return real_sympify(a, *args, **kwargs)

    monkeypatch.setattr(builtins, "eval", forbidden)
    monkeypatch.setattr(builtins, "exec", forbidden)
    monkeypatch.setattr(builtins, "compile", forbidden)
    monkeypatch.setattr(sympy, "sympify", forbidden)
    monkeypatch.setattr(sympy, "parse_expr", forbidden)
    monkeypatch.setattr(sympy.parsing.sympy_parser, "parse_expr", forbidden)
    monkeypatch.setattr(sympify_module, "sympify", sympify_without_text)
    for text in [
        "a1*cos(theta1) + a2*cos(theta1 + theta2)",
        "-x^2 + 2^3^2 + (x+1)(x-1)",
        "0.4318 + 1e-3 + θ1 + α",
        "sqrt(2)*atan2(y, x) - tan(q)/3",
    ]:
        assert isinstance(parse_expression(text), sympy.Expr)
    for text in ["__import__('os')", "eval(1)", "1/0"]:
        with pytest.raises(ParseError):
            parse_expression(text)


def test_module_source_calls_no_evaluator() -> None:
    tree = ast.parse(inspect.getsource(parsing))
    calls = [node.func for node in ast.walk(tree) if isinstance(node, ast.Call)]
    names = {func.id for func in calls if isinstance(func, ast.Name)}
    attributes = {func.attr for func in calls if isinstance(func, ast.Attribute)}
    assert not names & {"eval", "exec", "compile", "__import__", "sympify", "parse_expr", "S"}
    assert not attributes & {"eval", "exec", "sympify", "parse_expr", "S", "lambdify", "N"}
    assert "Symbol" in attributes and "Rational" in attributes  # the walk does see sympy calls


# --- error messages -----------------------------------------------------------------------


def test_error_message_carries_location() -> None:
    with pytest.raises(ParseError) as info:
        parse_expression("q1 + )", file="arm.yaml", row=2, field="theta")
    err = info.value
    assert isinstance(err, DHError)
    assert (err.file, err.row, err.field) == ("arm.yaml", 2, "theta")
    message = str(err)
    assert message.startswith("arm.yaml: row 2, field theta:")
    assert "column 6" in message
    assert "'q1 + )'" in message
    assert "expected a number, name or '('" in message
    assert "\n" not in message


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("sin(x) + 'abc'", 'unexpected character "\'" at column 10'),
        ('x + "y"', "unexpected character '\"' at column 5"),
        ("x; y", "unexpected character ';' at column 2"),
        ("a = 1", "unexpected character '=' at column 3"),
        ("\x00\x01", "unexpected character U+0000 at column 1"),
        ("x\\y", "unexpected character '\\' at column 2"),
        ("__import__('os')", "names with double underscores are not allowed"),
        ("nan", "non-finite number 'nan'"),
        ("1/0", "division by zero at column 2"),
        ("", "empty expression"),
        ("   ", "empty expression"),
    ],
)
def test_error_messages_say_what_and_where(text: str, fragment: str) -> None:
    with pytest.raises(ParseError) as info:
        parse_expression(text)
    assert fragment in str(info.value)
    assert "\n" not in str(info.value)


def test_long_text_is_shortened_in_messages() -> None:
    text = "x + " * 100 + "$"
    with pytest.raises(ParseError) as info:
        parse_expression(text, field="theta")
    message = str(info.value)
    assert f"column {len(text)}" in message
    assert "…" in message
    assert len(message) < 200


# --- bounded numerals ---------------------------------------------------------------------


@pytest.mark.parametrize(
    "text",
    ["0e99999999999", "0E+99999999999", "0.0e-99999999999", "00.000e99999", "x + 0e9999999"],
)
@pytest.mark.parametrize("textbook", [False, True])
def test_zero_mantissa_with_a_huge_exponent_is_refused_before_any_arithmetic(
    text: str, textbook: bool
) -> None:
    start = time.process_time()
    with pytest.raises(ParseError, match="exponent .*max_result_digits=400"):
        parse_expression(text, textbook=textbook)
    assert time.process_time() - start < 1.0  # a hang guard: this used to never return


def test_numeral_problem_is_the_one_rule_for_every_literal() -> None:
    assert parsing.numeral_problem("0.4318") is None
    assert parsing.numeral_problem("1e-390") is None  # 391 digits: within 400
    assert "exponent" in parsing.numeral_problem("1e-400")[0]
    assert "max_digits" in parsing.numeral_problem("1" * 41)[1]
    small = ParseLimits(max_digits=5, max_result_digits=10)
    assert parsing.numeral_problem("1e12", small) and not parsing.numeral_problem("1e8", small)


# --- textbook mode (answers) -------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("90°", sympy.pi / 2),
        ("sin 90°", sympy.Integer(1)),
        ("x/90°", 2 * x / sympy.pi),  # the sign binds to its number only
        ("-90° + x", x - sympy.pi / 2),
        ("(x + 30)°", (x + 30) * sympy.pi / 180),
        ("sin x cos y", sympy.sin(x) * sympy.cos(y)),
        ("cos 2θ1", sympy.cos(2 * theta1)),
        ("sin^2 x + cos^2(x)", sympy.Integer(1)),
        ("sin^(2)(x)", sympy.sin(x) ** 2),
        ("sqrt 2/2", sympy.sqrt(2) / 2),
        ("a1cos(theta1)", a1 * sympy.cos(theta1)),
        ("2a1cos(x)", 2 * a1 * sympy.cos(x)),
        ("sin(x)^2", sympy.sin(x) ** 2),
        ("cos^-1(x)", sympy.acos(x)),  # textbooks' inverse functions
        ("sin^-1 x", sympy.asin(x)),
        ("tan^-1(x)", sympy.atan(x)),
        ("Atan2(x, 1)", sympy.atan2(x, 1)),  # Craig
        ("arctan2(x, 1)", sympy.atan2(x, 1)),  # numpy
    ],
)
def test_textbook_forms(text: str, expected: sympy.Expr) -> None:
    assert sympy.simplify(parse_expression(text, textbook=True) - expected) == 0


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("sin^-2(x)", "expected a positive whole power"),
        ("sin^x(y)", "unknown function 'x'"),
        ("sin", "expected '(' or an argument after 'sin'"),
        ("sin + x", "expected '(' or an argument after 'sin'"),
        ("cos cos x", "expected '(' or an argument after 'cos'"),
    ],
)
def test_textbook_refusals(text: str, fragment: str) -> None:
    with pytest.raises(ParseError, match=fragment.replace("(", r"\(").replace("'", "'")):
        parse_expression(text, textbook=True)


def test_textbook_forms_are_off_by_default() -> None:
    with pytest.raises(ParseError, match="unexpected character '°'"):
        parse_expression("90°")
    assert parse_expression("acos1") == symbol("acos1")  # only a digit before 'cos' splits


def test_literal_hook_sees_every_number_outside_exponents() -> None:
    seen: list[tuple[str, sympy.Rational]] = []

    def hook(text: str, value: sympy.Rational) -> sympy.Expr:
        seen.append((text, value))
        return symbol(f"n{len(seen)}")

    value = parse_expression("0.7071*x^2 + 1.5°", literal=hook, textbook=True)
    assert seen == [("0.7071", sympy.Rational(7071, 10000)), ("1.5", sympy.Rational(3, 2))]
    assert value == symbol("n1") * x**2 + symbol("n2") * sympy.pi / 180


def test_inverse_functions_for_inverse_kinematics_answers():
    x, y = sympy.symbols("x y", real=True)
    assert parse_expression("atan(y/x) + arctan(1)") == sympy.atan(y / x) + sympy.pi / 4
    assert parse_expression("acos(x) - arcsin(x)") == sympy.acos(x) - sympy.asin(x)
    assert parse_expression("atan y", textbook=True) == sympy.atan(y)
