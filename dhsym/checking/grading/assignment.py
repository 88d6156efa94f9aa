r"""The assignment file: a title, the questions with their keys and points, the time limit.

The assignment (YAML) names the key and the questions::

    title: Homework 3, forward kinematics
    key: puma560                  # built-in robot or table file (relative to this file)
    time_limit: 5                 # seconds per answer (above 0, at most 3600)
    rounding: digits=3            # accepted rounding of decimals (Rounding); per question too
    questions:
      - {id: q1, ask: table, points: 4, tool: free}   # tool: free accepts another tool frame
      - {id: q2, ask: T0_2, points: 2}
      - {id: q3, ask: A1, points: 1, key: generic_modified_link.yaml}
      - {id: q4, ask: J, points: 2, credit: entries, deduct: {wrong_sign: 25%}}
      - {id: q5, ask: px, tests: {right: [a2*C1*C2], wrong: [{answer: -a2*C1*C2, mistake: sign}]}}
      - {id: q6, ask: traj a2, key: "cubic(q0=0, qf=1, tf=T)"}   # a profile's key: T is drawn
    variants: {d3: [0.1, 0.15, 0.2], T: [2, 3, 4]}   # drawn per student (with secret: FILE)
    secret: hw3.secret

Partial credit is :mod:`~dhsym.checking.grading.credit`'s (all or nothing by default),
question tests :mod:`~dhsym.checking.grading.question_tests`', variants
:mod:`~dhsym.checking.grading.variants`' (:meth:`Assignment.for_variant` is one student's).
Every key is described in the assignment-file reference of the documentation.

Examples
--------
>>> import tempfile
>>> from pathlib import Path
>>> folder = Path(tempfile.mkdtemp())
>>> _ = (folder / "hw.yaml").write_text(
...     "title: HW 1\nkey: planar2r\nquestions:\n"
...     "  - {id: q1, ask: T0_2, points: 2}\n  - {id: q2, ask: table}\n"
... )
>>> a = Assignment.load(folder / "hw.yaml")
>>> a.title, [q.id for q in a.questions], a.max_score
('HW 1', ['q1', 'q2'], 3.0)
"""

from __future__ import annotations

import hashlib
import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, replace
from pathlib import Path

from dhsym.errors import DHError
from dhsym.model.yamlsafe import FileRefused, YAMLInputError, load_yaml, read_limited

from ..judging.key import AnyKey, Key, PreparedKeys
from ..judging.trajectory_key import TrajectoryKey, is_profile_spec, spec_names
from ..reading.limits import check_seconds
from ..reading.questions import Question
from .credit import Credit
from .question_tests import QuestionTests
from .variants import Variant, VariantSpec, read_secret

__all__ = ["Assignment", "AssignmentQuestion"]

_ID = re.compile(r"^[A-Za-z0-9_-]{1,40}$")
_MAX_ASSIGNMENT = 1_000_000
_MAX_POINTS = 1e6


@dataclass(frozen=True)
class AssignmentQuestion:
    """One question: its id, what is asked, points, the key (with whether the tool frame is
    free and the rounding; a trajectory or gain question's key is a profile,
    :class:`~dhsym.checking.judging.trajectory_key.TrajectoryKey`), its partial credit
    (:class:`~.credit.Credit`: all or nothing unless the question says otherwise) and its
    tests (:class:`~.question_tests.QuestionTests`).  With variants, ``key`` is the key as
    written (the table's symbols, an ``ik@`` question at the first value of each drawn joint
    value, a profile with the first value of each drawn name)."""

    id: str
    ask: str
    points: float
    key: AnyKey
    credit: Credit = Credit()
    tests: QuestionTests = QuestionTests()


@dataclass(frozen=True)
class Assignment:
    """A title and questions; ``seconds`` is the time limit of one answer."""

    title: str
    questions: tuple[AssignmentQuestion, ...]
    seconds: float = 5.0
    fingerprint: str = ""
    #: the quantities drawn per student (``variants:``), None when everyone has the same
    variants: VariantSpec | None = None
    #: the student's values when this is one student's assignment (:meth:`for_variant`)
    variant: Variant | None = None

    @property
    def max_score(self) -> float:
        """Sum of the points."""
        return sum(q.points for q in self.questions)

    def for_variant(self, variant: Variant) -> Assignment:
        """The assignment of the student who drew ``variant``: each key with their values
        (the table's symbols replaced by the numbers, the joint values of ``ik@``
        questions put in, a profile's drawn names given their values); its fingerprint
        covers the values.  Keys are not prepared here (a grading worker prepares each
        distinct one once)."""
        values = dict(variant.values)
        questions = []
        for q in self.questions:
            if isinstance(q.key, TrajectoryKey):
                drawn = {n: values[n] for n in spec_names(q.key.spec, q.ask) if n in values}
                questions.append(replace(q, key=q.key.with_drawn(drawn)) if drawn else q)
                continue
            own = variant.values_for(q.key.table)
            asked = _ask_with(q.ask, values)
            if not own and asked == q.ask:  # untouched: the same objects (pickled once a batch)
                questions.append(q)
                continue
            table = q.key.table.with_values(own).substituted() if own else q.key.table
            key = replace(q.key, table=table, question=Question.parse(asked, table.n))
            questions.append(replace(q, key=key))
        text = self.fingerprint + "\n" + repr(variant.values)
        fp = hashlib.sha256(text.encode()).hexdigest()[:16]
        return replace(
            self, questions=tuple(questions), fingerprint=fp, variants=None, variant=variant
        )

    @classmethod
    def load(cls, path: str | Path, keys: PreparedKeys | None = None) -> Assignment:
        """Read an assignment YAML file (keys given as files are relative to it).

        Each key is prepared once to check it, into ``keys`` when given.  Every problem
        is a :class:`~dhsym.errors.DHError` naming the file and the question (row) or field.
        """
        p = Path(path)
        try:
            raw = read_limited(p, _MAX_ASSIGNMENT, what="the assignment")
            text = raw.decode("utf-8")
            data = load_yaml(text)
        except (FileRefused, YAMLInputError) as err:
            raise DHError(err.message, file=str(p)) from None
        except UnicodeDecodeError:
            raise DHError("the assignment is not UTF-8 text", file=str(p)) from None
        if not isinstance(data, Mapping) or not isinstance(data.get("questions"), list):
            raise DHError("expected 'questions: [...]' (and 'key:') in the assignment", file=str(p))
        seconds = check_seconds(data.get("time_limit", 5.0), "time_limit", file=str(p))
        default = data.get("key")
        spec = _variant_spec(data, p)
        sample = dict(spec.sample().values) if spec is not None else {}
        used: set[str] = set()
        questions, seen, digest = [], set(), [text]
        for k, q in enumerate(data["questions"], 1):
            if not isinstance(q, Mapping) or "ask" not in q or "id" not in q:
                raise DHError("each question needs 'id' and 'ask'", file=str(p), row=k)
            qid = str(q["id"]) if isinstance(q["id"], (str, int)) else ""
            if not _ID.match(qid) or qid in seen or qid in ("student", "name"):
                raise DHError(
                    f"question id {str(q['id'])[:60]!r}: use letters, digits, '_' or '-', once",
                    file=str(p),
                    row=k,
                    field="id",
                )
            seen.add(qid)
            points = _points(q.get("points", 1), p, k)
            ref = q.get("key", default)
            if not isinstance(ref, str) or not ref.strip():
                raise DHError(
                    "no key: give 'key:' (a robot name or table file) for the assignment "
                    "or the question",
                    file=str(p),
                    row=k,
                    field="key",
                )
            local = p.parent / ref
            where: str | Path = (
                local if local.suffix.lower() in (".yaml", ".yml") or local.exists() else ref
            )
            tool = str(q.get("tool", "fixed")).lower() in ("free", "any", "true")
            ask = q["ask"]
            if not isinstance(ask, (str, int)):
                raise DHError("'ask' must be text like T0_2", file=str(p), row=k, field="ask")
            rounding = q.get("rounding", data.get("rounding"))
            asked = _ask_with(str(ask), sample)  # the sample variant's, checked here
            key: AnyKey
            try:
                if is_profile_spec(ref):  # a trajectory or gain question: a profile's key
                    drawn = {n: sample[n] for n in spec_names(ref, asked) if n in sample}
                    key = TrajectoryKey.load(ref, asked, rounding=rounding, drawn=drawn)
                    if keys is not None:
                        keys.get(key)
                    used.update(drawn)
                else:
                    key = Key.load(where, asked, tool_free=tool, rounding=rounding, keys=keys)
                    used.update(str(s) for s in key.table.constants if str(s) in sample)
            except DHError as err:
                raise DHError(err.message, file=str(p), row=k, field=err.field or "ask") from None
            used.update(n for n in sample if _ask_with(str(ask), {n: sample[n]}) != str(ask))
            try:
                credit = Credit.parse(q)
            except DHError as err:
                raise DHError(err.message, file=str(p), row=k, field="credit") from None
            try:
                tests = QuestionTests.parse(q.get("tests"))
            except DHError as err:
                raise DHError(err.message, file=str(p), row=k, field=err.field or "tests") from None
            digest.append(repr(key) + (repr(credit) if credit != Credit() else ""))
            questions.append(AssignmentQuestion(qid, str(ask), points, key, credit, tests))
        if spec is not None:
            unused = [n for n in spec.names if n not in used]
            if unused:
                raise DHError(
                    f"{unused[0]!r} is drawn but used by no question: a variant is a symbol "
                    "of a question's key table (a2, d3, ...), a name in an ik@ question "
                    '(ask: "ik@q1,q2") or a transform at joint values (ask: "T0_2@q1,q2") '
                    'or a name in a profile key (key: "cubic(q0=0, qf=1, tf=T)")',
                    file=str(p),
                    field=f"variants.{unused[0]}",
                )
        fp = hashlib.sha256("\n".join(digest).encode()).hexdigest()[:16]
        return cls(_title(data, p), tuple(questions), seconds, fp, spec)


def _title(data: Mapping[str, object], path: Path) -> str:
    title = data.get("title")
    return " ".join(str(title).split())[:200] if isinstance(title, (str, int)) else path.stem


def _variant_spec(data: Mapping[str, object], path: Path) -> VariantSpec | None:
    """The ``variants:`` of the assignment with its secret (the file ``secret:`` names,
    beside the assignment), or None; variants without a secret are refused."""
    if "variants" not in data:
        return None
    ref = data.get("secret")
    if not isinstance(ref, str) or not ref.strip():
        raise DHError(
            "variants are drawn with a secret only the instructor keeps: add "
            "'secret: <file>' (a file beside the assignment; dhsym variants "
            f"{path.name} --new-secret writes one). Without it anyone with the assignment "
            "could compute every student's values",
            file=str(path),
            field="secret",
        )
    secret = read_secret(path.parent / ref.strip(), assignment=str(path))
    return VariantSpec.parse(data["variants"], secret, _title(data, path), file=str(path))


#: a question at joint values: ``ik@…``, or a transform there (``T0_6@…``, ``fk@…``)
_IK_AT = re.compile(
    r"^(?P<head>\s*(?:ik|inverse|fk|arm|\^|[TAH]_?\{?\d|p_?[xyz])[^@]*@)(?P<values>.*)$",
    re.IGNORECASE,
)


def _ask_with(ask: str, values: Mapping[str, object]) -> str:
    """``ask`` with the drawn joint values put in: ``ik@q1,q2`` becomes ``ik@pi/6,9/20``
    when ``q1`` and ``q2`` are drawn (and ``T0_2@q1,q2``, ``fk@q1,q2``: a transform at
    them); any other question is left as it is.

    >>> import sympy as sp
    >>> _ask_with("ik@q1, 0.5", {"q1": sp.pi / 6}), _ask_with("T0_2", {"q1": 1})
    ('ik@pi/6,0.5', 'T0_2')
    >>> _ask_with("T0_2@q1,q2", {"q1": 1, "q2": sp.pi}), _ask_with("q@T", {"T": 2})
    ('T0_2@1,pi', 'q@T')
    """
    m = _IK_AT.match(ask)
    parts = [v.strip() for v in m["values"].split(",")] if m is not None else []
    if m is None or not any(v in values for v in parts):
        return ask
    return m["head"] + ",".join(str(values[v]) if v in values else v for v in parts)


def _points(value: object, path: Path, row: int) -> float:
    """Points of a question: a finite number, at least 0."""
    number = None
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        number = float(value)
    elif isinstance(value, str):
        try:
            number = float(value)
        except ValueError:
            number = None
    if number is None or not math.isfinite(number) or not 0 <= number <= _MAX_POINTS:
        shown = value if isinstance(value, (int, float)) else repr(value)[:60]
        raise DHError(
            f"expected a number of points from 0 to {_MAX_POINTS:g}, got {shown}",
            file=str(path),
            row=row,
            field="points",
        )
    return number
