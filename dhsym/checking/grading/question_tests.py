"""Question tests (as STACK has them): answers a question must grade right, and answers it
must grade wrong, with the mistake the feedback must name.

A question of the assignment may list them::

    - id: q5
      ask: T0_6[0,3]
      tests:
        right: ["C1*(a2*C2 + a3*C23 - d4*S23) + d3*S1"]
        wrong:
          - {answer: "C1*(a2*C2 + a3*C23 - d4*S23) - d3*S1", mistake: wrong_sign}
          - "a2*C2"                      # graded wrong, whatever the mistake

They are run, with the key's own answer, by
:func:`~dhsym.checking.grading.assignment_tests.run_assignment_tests`
(``dhsym check-assignment``; ``dhsym grade`` refuses an assignment whose tests fail).

Examples
--------
>>> t = QuestionTests.parse({"right": ["a1*C1"], "wrong": [{"answer": "a1", "mistake": "sign"}]})
>>> t.right, t.wrong[0].mistake, bool(t), bool(QuestionTests())
(('a1*C1',), 'wrong_sign', True, False)
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import yaml

from dhsym.errors import DHError

from ..reading.limits import echoed
from .credit import mistake_kind

__all__ = ["QuestionTests", "WrongAnswer"]

_MAX_TESTS = 100
_MAX_ANSWER = 100_000


@dataclass(frozen=True)
class WrongAnswer:
    """An answer that must be graded wrong; ``mistake`` the kind the feedback must name
    (empty: any wrong verdict passes)."""

    answer: str
    mistake: str = ""


@dataclass(frozen=True)
class QuestionTests:
    """A question's tests: answers graded right, answers graded wrong."""

    right: tuple[str, ...] = ()
    wrong: tuple[WrongAnswer, ...] = ()

    def __bool__(self) -> bool:
        return bool(self.right or self.wrong)

    @classmethod
    def parse(cls, value: object) -> QuestionTests:
        """The ``tests:`` of a question (None: no tests); errors name the field."""
        if value is None:
            return cls()
        if not isinstance(value, Mapping) or not set(value) <= {"right", "wrong"}:
            raise DHError(
                "tests: expected {right: [answers], wrong: [answers or {answer: ..., "
                f"mistake: kind}}]}}, got {echoed(value)}",
                field="tests",
            )
        right = tuple(
            _answer(a, f"tests.right[{k}]") for k, a in enumerate(_items(value, "right"), 1)
        )
        wrong = []
        for k, item in enumerate(_items(value, "wrong"), 1):
            where = f"tests.wrong[{k}]"
            if isinstance(item, Mapping):
                if "answer" not in item or not set(item) <= {"answer", "mistake"}:
                    raise DHError("expected {answer: ..., mistake: kind}", field=where)
                mistake = item.get("mistake") or ""
                try:
                    kind = mistake_kind(mistake, "mistake") if mistake else ""
                except DHError as err:
                    raise DHError(err.message, field=f"{where}.mistake") from None
                wrong.append(WrongAnswer(_answer(item["answer"], where), kind))
            else:
                wrong.append(WrongAnswer(_answer(item, where)))
        return cls(right, tuple(wrong))


def _items(value: Mapping[object, object], name: str) -> list[object]:
    items = value.get(name, []) or []
    if not isinstance(items, list):
        raise DHError(f"tests.{name}: expected a list of answers", field=f"tests.{name}")
    if len(items) > _MAX_TESTS:
        raise DHError(f"tests.{name}: at most {_MAX_TESTS} answers", field=f"tests.{name}")
    return items


def _answer(value: object, where: str) -> str:
    """An answer as text: a string, a number, or a YAML list (a matrix or a table) kept as
    the flow text a student's YAML answer would be."""
    if isinstance(value, bool) or value is None:
        raise DHError(f"expected an answer, got {echoed(value)}", field=where)
    text = value if isinstance(value, str) else _flow(value)
    if not text.strip() or len(text) > _MAX_ANSWER:
        raise DHError(f"expected an answer of 1 to {_MAX_ANSWER} characters", field=where)
    return text


def _flow(value: object) -> str:
    """A YAML value written back as the YAML a student's answer file would hold (a list
    of rows one per line: ``- {theta: theta1, d: 0, a: 0, alpha: 90}``).

    >>> print(_flow([{"theta": "theta1", "d": 0}, {"theta": "theta2", "d": "d2"}]), end="")
    - {theta: theta1, d: 0}
    - {theta: theta2, d: d2}
    """
    if not isinstance(value, (list, Mapping)):
        return str(value)
    return str(yaml.safe_dump(value, default_flow_style=None, sort_keys=False, width=10_000))
