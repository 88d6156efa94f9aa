"""Every regular expression that reads user text is linear: 1 MB worst cases finish at once.

A pattern with two neighbouring parts that match the same characters (``\\s*\\|?\\s*``)
backtracks quadratically: 100 kB of spaces before a table cost 85 s in one worker
thread, which nothing could interrupt.  The patterns are collected from the modules
(compiled ones and the literal patterns of ``re.*`` calls) with the functions the
module calls on them (``search``, ``fullmatch`` …); each one's worst inputs are searched
among texts built from its own parts (a prefix that matches the start of the pattern or
of one of its groups, then a long run of one character, or a repeated unit), and the
two slowest are run at 1 MB in a killable worker process: a pattern that does not
finish within the deadline fails.
"""

from __future__ import annotations

import ast
import importlib
import inspect
import re

import pytest

from dhsym.checking.grading.sandbox import JobFailure, Sandbox

from .checking._jobs import regex_worst_case

try:  # Python 3.11+
    import re._constants as C  # noqa: N812
    import re._parser as sre_parse
except ImportError:  # pragma: no cover - Python 3.10
    import sre_constants as C  # noqa: N812
    import sre_parse

MODULES = [
    "dhsym.checking.mistakes._ik_mistakes",
    "dhsym.checking.comparing.ik_values",
    "dhsym.checking.mistakes._jacobian_mistakes",
    "dhsym.checking.grading.report",
    "dhsym.checking.grading.submissions",
    "dhsym.checking.reading._table_text",
    "dhsym.checking.reading.answers",
    "dhsym.checking.platforms.autograder",
    "dhsym.checking.grading.feedback",
    "dhsym.checking.platforms.gradebooks",
    "dhsym.checking.grading.batch",
    "dhsym.checking.judging.ik_check",
    "dhsym.checking.reading.latex_input",
    "dhsym.checking.reading.answer_names",
    "dhsym.checking.reading.questions",
    "dhsym.checking.judging.rounding",
    "dhsym.checking.platforms.selfcheck",
    "dhsym.cli.common",
    "dhsym.explain.derivation",
    "dhsym.explain.documents",
    "dhsym.explain.inverse_kinematics",
    "dhsym.explain.velocity_kinematics",
    "dhsym.explain.latex",
    "dhsym.explain.rendering",
    "dhsym.model.angles",
    "dhsym.model.entries",
    "dhsym.model.library",
    "dhsym.model.parsing",
    "dhsym.model.table",
    "dhsym.model.tablefile",
    "dhsym.model.yamlsafe",
    "dhsym.notation.escape",
    "dhsym.notation.printers",
]
_CALLS = {"compile", "search", "match", "fullmatch", "sub", "subn", "split", "findall", "finditer"}
MEGABYTE = 1_000_000


def _literal(node: ast.AST, namespace: dict) -> str | None:
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if isinstance(node, (ast.JoinedStr, ast.BinOp)):  # f-strings of module constants
        try:
            value = eval(compile(ast.Expression(node), "<pattern>", "eval"), namespace)  # noqa: S307
        except Exception:  # noqa: BLE001
            return None
        return value if isinstance(value, str) else None
    return None


def collect() -> tuple[dict[str, tuple[re.Pattern, tuple[str, ...]]], list[str]]:
    """Patterns by name (``module.NAME`` or ``module:line``) with the functions called on
    them, and the calls whose pattern could not be read."""
    found: dict[str, tuple[re.Pattern, tuple[str, ...]]] = {}
    unread: list[str] = []
    for name in MODULES:
        mod = importlib.import_module(name)
        namespace = vars(mod)
        tree = ast.parse(inspect.getsource(mod))
        used: dict[str, set[str]] = {}
        for node in ast.walk(tree):  # NAME.search(…), NAME.sub(…) …
            if (
                isinstance(node, ast.Attribute)
                and isinstance(node.value, ast.Name)
                and node.attr in _CALLS - {"compile"}
            ):
                used.setdefault(node.value.id, set()).add(node.attr)
        for attr, value in namespace.items():
            if isinstance(value, re.Pattern):
                ops = used.get(attr) or _CALLS - {"compile"}  # passed around: every function
                found[f"{name}.{attr}"] = (value, tuple(sorted(ops)))
        for node in ast.walk(tree):
            if not (
                isinstance(node, ast.Call)
                and isinstance(node.func, ast.Attribute)
                and isinstance(node.func.value, ast.Name)
                and node.func.value.id == "re"
                and node.func.attr in _CALLS
                and node.args
            ):
                continue
            if node.func.attr == "compile" and any(
                isinstance(v, re.Pattern) for v in namespace.values()
            ):
                pattern = _literal(node.args[0], namespace)
                if pattern is not None:  # compiled at module level: already collected
                    continue
            pattern = _literal(node.args[0], namespace)
            if pattern is None:
                unread.append(f"{name}:{node.lineno}")
                continue
            flags = 0
            flag_nodes = [k.value for k in node.keywords if k.arg == "flags"]
            position = {"sub": 4, "subn": 4, "split": 3}.get(node.func.attr, 2)
            if len(node.args) > position:
                flag_nodes.append(node.args[position])
            for f in flag_nodes:
                flags |= eval(compile(ast.Expression(f), "<flags>", "eval"), {"re": re})  # noqa: S307
            found[f"{name}:{node.lineno}"] = (re.compile(pattern, flags), (node.func.attr,))
    return found, unread


PATTERNS, UNREAD = collect()


def _char_of_set(items: list) -> str:
    negate = any(op is C.NEGATE for op, _ in items)
    inside: set[str] = set()
    reps = []
    for op, av in items:
        if op is C.LITERAL:
            inside.add(chr(av))
            reps.append(chr(av))
        elif op is C.RANGE:
            inside.update(chr(c) for c in range(av[0], min(av[1], av[0] + 300) + 1))
            reps.append(chr(av[0]))
        elif op is C.CATEGORY:
            name = str(av)
            rep = " " if "SPACE" in name else "1" if "DIGIT" in name else "a"
            if "NOT" in name:
                rep = "a" if "SPACE" in name else " "
            reps.append(rep)
            inside.add(rep)
    if negate:
        return next(c for c in "ax0 -_\\(\x01" if c not in inside)
    return reps[0] if reps else "a"


def _sample(items: list) -> str:
    """A short text matched by the sequence ``items`` (repeats taken at least once)."""
    out = []
    for op, av in items:
        if op is C.LITERAL:
            out.append(chr(av))
        elif op is C.NOT_LITERAL:
            out.append("a" if chr(av) != "a" else "b")
        elif op is C.ANY:
            out.append("a")
        elif op is C.IN:
            out.append(_char_of_set(av))
        elif op is C.BRANCH:
            out.append(_sample(av[1][0]))
        elif op is C.SUBPATTERN:
            out.append(_sample(av[-1]))
        elif op in (C.MAX_REPEAT, C.MIN_REPEAT) or str(op) == "POSSESSIVE_REPEAT":
            lo, hi, item = av
            out.append(_sample(item) * (max(lo, 1) if hi else 0))
        elif str(op) == "ATOMIC_GROUP":
            out.append(_sample(av))
    return "".join(out)


def _sequences(items: list) -> list[list]:
    """The pattern and every alternative and group inside it, as item sequences."""
    seqs = [list(items)]
    for op, av in items:
        if op is C.BRANCH:
            for alt in av[1]:
                seqs += _sequences(alt)
        elif op is C.SUBPATTERN:
            seqs += _sequences(av[-1])
        elif op in (C.MAX_REPEAT, C.MIN_REPEAT) or str(op) == "POSSESSIVE_REPEAT":
            seqs += _sequences(av[2])
    return seqs


def cases(pattern: re.Pattern) -> list[tuple[str, str, str]]:
    """(prefix, filler, kind) triples: prefixes matching a start of the pattern or a part."""
    tree = list(sre_parse.parse(pattern.pattern, pattern.flags))
    prefixes, fillers = {""}, set(" a1\n\\({$|-_.,:=^&")
    for seq in _sequences(tree):
        for k in range(1, len(seq) + 1):
            prefixes.add(_sample(seq[:k]))
        fillers.update(_sample(seq[k : k + 1]) for k in range(len(seq)))
    fillers = {f for f in fillers if len(f) == 1}
    out = []
    for prefix in sorted(prefixes):
        for filler in sorted(fillers):
            out.append((prefix, filler, "run"))
            out.append((prefix, filler, "pairs"))
        if prefix:
            out.append((prefix, "", "repeat"))
    return out


def _seconds(pattern: re.Pattern, ops: tuple[str, ...], case: tuple[str, str, str]) -> float:
    return regex_worst_case((pattern.pattern, pattern.flags, ops, *case, 1500))


def test_every_regex_on_user_text_is_collected():
    assert UNREAD == []
    assert len(PATTERNS) >= 40
    assert {"dhsym.checking.reading.latex_input._MATRIX", "dhsym.model.parsing._TOKEN"} <= set(
        PATTERNS
    )


@pytest.fixture(scope="module")
def sandbox():
    with Sandbox(preload=()) as box:
        yield box


@pytest.mark.parametrize("name", sorted(PATTERNS))
def test_one_megabyte_worst_cases_finish_at_once(name, sandbox):
    pattern, ops = PATTERNS[name]
    timed = sorted(cases(pattern), key=lambda c: -_seconds(pattern, ops, c))
    for case in timed[:2]:
        job = (pattern.pattern, pattern.flags, ops, *case, MEGABYTE)
        result = sandbox.call(regex_worst_case, job, deadline=30.0)
        assert not isinstance(result, JobFailure), f"{name} on {case!r}: {result}"
