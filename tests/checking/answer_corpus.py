"""The answer corpus in ``tests/data/answers/``: load it, check every answer, compare verdicts.

Each ``*.yaml`` file there holds defaults and a list of cases::

    robot: planar2r            # built-in robot, or a table file next to the corpus files
    question: T0_2[0,0]        # what is asked (dhsym.checking.Question)
    cases:
      - answer: '\\cos(\\theta_1 + \\theta_2)'
        verdict: correct       # correct | incorrect | unreadable
        form: latex-parens     # what the case exercises (reported by the benchmark)
        mistake: wrong_sign    # optional: a diagnosis kind the result must contain
        reason: ambiguous      # optional: text the unreadable reason must contain
        message: 4 significant # optional: text the message must contain
        rounding: digits=2     # optional: the instructor's rounding (dhsym check --rounding)
        source: Spong, ...     # optional: where the form comes from

A case may override ``robot`` and ``question``.  Used by ``tests/checking/test_answer_corpus.py``
and ``benchmarks/bench_answers.py``.
"""

from __future__ import annotations

import inspect
from dataclasses import dataclass, field
from pathlib import Path

import yaml

CORPUS = Path(__file__).resolve().parents[1] / "data" / "answers"
VERDICTS = ("correct", "incorrect", "unreadable")


@dataclass(frozen=True)
class Case:
    """One answer of the corpus and what the checker must say about it."""

    file: str
    index: int
    robot: str
    question: str
    answer: str
    verdict: str
    form: str = ""
    mistake: str | None = None
    reason: str | None = None
    message: str | None = None
    rounding: str | None = None
    source: str = field(default="", compare=False)

    @property
    def id(self) -> str:
        """``file:index:form`` (pytest id)."""
        return f"{self.file}:{self.index}:{self.form}"


def load_corpus(folder: Path = CORPUS) -> list[Case]:
    """Every case of every corpus file, in file order."""
    cases = []
    for path in sorted(folder.glob("*.yaml")):
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
        for k, raw in enumerate(data["cases"], 1):
            robot = str(raw.get("robot", data.get("robot", "")))
            local = folder / robot
            if local.suffix in (".yaml", ".yml") and local.is_file():
                robot = str(local)
            verdict = str(raw["verdict"])
            if verdict not in VERDICTS:
                raise ValueError(f"{path.name}: case {k}: verdict {verdict!r}")
            cases.append(
                Case(
                    path.stem,
                    k,
                    robot,
                    str(raw.get("question", data.get("question", ""))),
                    str(raw["answer"]),
                    verdict,
                    str(raw.get("form", data.get("form", ""))),
                    raw.get("mistake"),
                    raw.get("reason"),
                    raw.get("message"),
                    None if raw.get("rounding") is None else str(raw["rounding"]),
                    str(raw.get("source", data.get("source", ""))),
                )
            )
    return cases


@dataclass(frozen=True)
class Outcome:
    """What the checker said about one case, and whether that is what the corpus expects."""

    case: Case
    verdict: str
    ok: bool
    why: str = ""


def run_case(case: Case, keys: object = None) -> Outcome:
    """Check one case; ``ok`` when verdict, mistake, reason and message are as expected.

    ``keys``: a map of prepared keys (:class:`~dhsym.checking.judging.key.PreparedKeys`)
    that keeps each key prepared for the next cases (the tests); without it every case
    prepares its key (the benchmark's time per answer)."""
    from dhsym.checking import Key, check_answer

    kwargs: dict[str, object] = {"tool_free": False}
    if case.rounding is not None:
        if "rounding" not in inspect.signature(Key.load).parameters:
            return Outcome(case, "?", False, "this dhsym has no rounding option")
        kwargs["rounding"] = case.rounding
    shared = {} if keys is None else {"keys": keys}
    try:
        key = Key.load(case.robot, case.question, **kwargs, **shared)
        result = check_answer(key, case.answer, **shared)
    except Exception as err:  # noqa: BLE001 - the benchmark also runs older code
        return Outcome(case, "error", False, f"{type(err).__name__}: {err}")
    got = result.verdict.value
    problems = []
    if got != case.verdict:
        problems.append(f"verdict {got}, expected {case.verdict}")
    if case.mistake and case.mistake not in result.kinds:
        problems.append(f"diagnoses {result.kinds}, expected {case.mistake!r}")
    if case.reason and case.reason not in (result.reason or ""):
        problems.append(f"reason {result.reason!r} lacks {case.reason!r}")
    if case.message and case.message not in result.message:
        problems.append(f"message {result.message!r} lacks {case.message!r}")
    why = "; ".join(problems) or result.message
    return Outcome(case, got, not problems, why if problems else "")
