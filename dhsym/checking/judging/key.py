"""The key of a question, and the key prepared once for checking many answers.

A :class:`Key` is a frozen value: a DH table and what is asked about it.
:func:`prepare` derives what every answer to it is compared with: the robot, the names
an answer may use and one prepared part per kind of question, built by that kind's own
preparer (:data:`PREPARERS`): a matrix (:mod:`~dhsym.checking.judging.matrix_key`), the
dynamics, inverse kinematics (:mod:`~dhsym.checking.judging.ik_key`), a product of
exponentials (:mod:`~dhsym.checking.judging.screw_key`) or a table (nothing to derive).
A worker keeps its prepared keys in :class:`PreparedKeys`, with those of the trajectory
and gain questions, whose key is a profile instead of a table
(:class:`~dhsym.checking.judging.trajectory_key.TrajectoryKey`; :func:`load_key` reads
either from what an assignment or a command line names).

Examples
--------
>>> key = Key.load("planar2r", "T0_2")
>>> pk = prepare(key)
>>> type(pk.part).__name__, pk.part.expected.shape, pk.form().shape
('MatrixPart', (4, 4), (4, 4))
>>> type(prepare(Key.load("planar2r", "table")).part).__name__
'TablePart'
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TypeAlias, overload

import sympy as sp

from dhsym.cache.memo import MEMO, MemoKey
from dhsym.errors import DHError
from dhsym.model.library import load_table
from dhsym.model.table import AngleUnit, Convention, DHTable, JointType
from dhsym.notation.printers import format_angle
from dhsym.robot import Robot, from_poe
from dhsym.screws.poefile import is_poe_path

from ..comparing.table_match import KeyFrames
from ..reading.answer_names import NameContext
from ..reading.answer_value import AnswerForm
from ..reading.questions import Question
from .ik_key import IKPart, prepare_ik
from .matrix_key import MatrixPart, prepare_dynamics, prepare_matrix
from .rounding import DEFAULT_ROUNDING, Rounding
from .screw_key import prepare_screw
from .trajectory_key import (
    PreparedTrajectory,
    TrajectoryKey,
    is_profile_spec,
    prepare_trajectory,
)

__all__ = [
    "PREPARERS",
    "Key",
    "AnyKey",
    "KeyPart",
    "PreparedKey",
    "PreparedKeys",
    "Preparer",
    "TablePart",
    "load_key",
    "prepare",
    "table_cells",
]


@dataclass(frozen=True)
class Key:
    """The key of one question: a DH table and what is asked about it.

    ``tool_free`` accepts another tool frame (last frame) in a table answer;
    ``rounding`` is how much rounding of decimals is accepted (:class:`Rounding`).
    """

    table: DHTable
    question: Question
    name: str = ""
    tool_free: bool = False
    rounding: Rounding = DEFAULT_ROUNDING

    @classmethod
    def load(
        cls,
        ref: str | Path | DHTable,
        question: str | Question,
        *,
        tool_free: bool = False,
        rounding: object = None,
        keys: PreparedKeys | None = None,
    ) -> Key:
        """A key from a built-in robot name, a table file (a ``*.poe.yaml`` product of
        exponentials is given its DH table, :func:`~dhsym.robot.from_poe`) or a table.

        ``rounding``: anything :meth:`Rounding.parse` reads (``"digits=4"``, ``"abs=1e-3"``,
        ``{"rel": 0.001}``, ``"off"``); None is the default (3 significant digits).
        The key is prepared once to check it (into ``keys`` when given, for later use).
        """
        if not isinstance(ref, (str, Path, DHTable)):
            raise DHError(
                "the key is a built-in robot's name, a table file or a DHTable, "
                f"got {type(ref).__name__}"
            )
        table = ref if isinstance(ref, DHTable) else _key_table(ref)
        q = question if isinstance(question, Question) else Question.parse(question, table.n)
        if q.kind == "trajectory":
            raise DHError(
                f"question {q.spec!r} asks about a profile: its key is one, like "
                "cubic(q0=0, qf=1, tf=2), lspb(q0=0, qf=1, tf=2, a=2) or gains(omega=10)",
                field="key",
            )
        name = table.name or (Path(ref).stem if not isinstance(ref, DHTable) else "")
        key = cls(table, q, name, tool_free, Rounding.parse(rounding))
        # a key that cannot be checked against (too large, wrong values) stops here
        keys.get(key) if keys is not None else prepare(key)
        return key


def _key_table(ref: str | Path) -> DHTable:
    """The table of a key given by name or file; a PoE file's robot is read through its DH
    frames (:func:`~dhsym.screws.poe_to_dh.to_dh`): the same fk, space frame and ``M``."""
    if is_poe_path(str(ref)):
        return from_poe(ref).table
    return load_table(ref)


def table_cells(
    table: DHTable, like: DHTable | None = None, printed: tuple[tuple[str, ...], ...] = ()
) -> tuple[tuple[str, ...], ...]:
    """A table as text cells, header first, in its own convention's column order.

    ``printed`` are the cells this function printed for the table ``like`` (a key's): a
    row equal to ``like``'s row at the same place, in a table of the same convention and
    angle unit, takes its printed cells (the same text) instead of being printed again.

    >>> from dhsym import load_table
    >>> key = load_table("planar2r")
    >>> cells = table_cells(key)
    >>> cells[1]
    ('1', 'theta1', '0', 'a1', '0', 'R')
    >>> table_cells(key, key, cells) == cells
    True
    >>> from dataclasses import replace
    >>> other = replace(key, rows=(key.rows[0], replace(key.rows[1], a=2 * key.rows[1].a)))
    >>> table_cells(other, key, cells)[1:] == table_cells(other)[1:] != cells[1:]
    True
    """
    deg = table.angles is AngleUnit.DEG
    same_form = (
        like is not None
        and len(printed) == len(like.rows) + 1
        and like.convention is table.convention
        and like.angles is table.angles
    )
    if table.convention is Convention.MODIFIED:
        head, order = (
            ("i", "alpha_{i-1}", "a_{i-1}", "d_i", "theta_i", "joint"),
            ("alpha", "a", "d", "theta"),
        )
    else:
        head, order = (
            ("i", "theta_i", "d_i", "a_i", "alpha_i", "joint"),
            ("theta", "d", "a", "alpha"),
        )
    rows: list[tuple[str, ...]] = [head]
    for i, row in enumerate(table.rows, 1):
        if same_form and like is not None and i <= len(like.rows) and row == like.rows[i - 1]:
            rows.append(printed[i])  # the key's row, printed once
            continue
        cells = [str(i)]
        for name in order:
            v = getattr(row, name)
            if name in ("theta", "alpha"):
                cells.append(format_angle(v, deg, latex=False))
            else:
                cells.append(
                    f"{float(v):.6g}" if v.is_Rational and not v.is_Integer else sp.sstr(v)
                )
        rows.append((*cells, row.joint.value))
    return tuple(tuple(r) for r in rows)


@dataclass(frozen=True)
class TablePart:
    """A table key's part: nothing to derive (the answer is compared with the key's table);
    ``cells`` is the key's table as the feedback shows it (:func:`table_cells`), printed
    once; ``frames`` the key's frames where answers are compared with it
    (:class:`~dhsym.checking.comparing.table_match.KeyFrames`), computed once."""

    cells: tuple[tuple[str, ...], ...] = ()
    frames: KeyFrames | None = None


#: the prepared part of a key, one type per kind of question
KeyPart: TypeAlias = MatrixPart | IKPart | TablePart
#: a kind's preparer: (table, question, robot, the table's names) → (the names an answer
#: may use, the kind's part)
Preparer: TypeAlias = Callable[[DHTable, Question, Robot, NameContext], tuple[NameContext, KeyPart]]


def _prepare_table(
    table: DHTable, question: Question, robot: Robot, names: NameContext
) -> tuple[NameContext, KeyPart]:
    """A table key: nothing to derive; its cells printed for the feedback."""
    return names, TablePart(table_cells(table), KeyFrames.of(table))


#: each kind of question's preparer (the matrix kinds share one)
PREPARERS: Mapping[str, Preparer] = {
    "table": _prepare_table,
    "ik": prepare_ik,
    "dynamics": prepare_dynamics,
    "matrix": prepare_matrix,
    "entry": prepare_matrix,
    "jacobian": prepare_matrix,
    "det": prepare_matrix,
    "screw": prepare_screw,
}


@dataclass(frozen=True, eq=False)
class PreparedKey:
    """What checking many answers to one key shares: the robot, names, the kind's part.

    Built once per worker (:class:`PreparedKeys`) before any answer's clock starts, and
    never changed after: what the mistakes of a wrong answer are recomputed from (the
    key's values under each catalogued mistake at its diagnosis samples) is built with the
    part, so the first wrong answer's diagnosis only compares.
    """

    key: Key
    robot: Robot
    names: NameContext
    part: KeyPart
    #: :meth:`form`, built with the key (it depends on the key only)
    _form: AnswerForm = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_form", self._reading_form())

    def memo_size(self) -> int:
        """The estimated size (:class:`dhsym.cache.memo.Sized`, expression nodes): a rough
        figure per prepared key (its expected values and its mistakes' variants; the
        robot is the memo's own entry)."""
        return 20_000

    def form(self) -> AnswerForm:
        """What reading an answer to this key needs: the question, the names, the key's
        shape, the joints whose Jacobian column may be missing, the convention, the joint
        variables and the lengths (built once, with the prepared key)."""
        return self._form

    def _reading_form(self) -> AnswerForm:
        table = self.key.table
        joints = [r.joint for r in table.rows if r.variable is not None]
        return AnswerForm(
            self.key.question,
            self.names,
            self.part.expected.shape if isinstance(self.part, MatrixPart) else (4, 4),
            tuple(k for k, j in enumerate(joints) if j is JointType.PRISMATIC),
            table.convention,
            tuple(self.robot.variables),
            frozenset(table.constants),
            self._nonzero_rows(),
        )

    def _nonzero_rows(self) -> tuple[int, ...]:
        """For the whole Jacobian with rows that are zero in every configuration, the others
        (a planar arm's v_x, v_y, ω_z); else ()."""
        if self.key.question.kind != "jacobian" or not isinstance(self.part, MatrixPart):
            return ()
        J = self.part.expected
        rows = tuple(i for i in range(J.rows) if any(e != 0 for e in J.row(i)))
        return rows if J.shape[0] == 6 and 0 < len(rows) < 6 else ()


#: the key of any question: a DH table's, or a profile's
AnyKey: TypeAlias = Key | TrajectoryKey


#: how many key objects :class:`PreparedKeys` recognises by identity (a class's assignment
#: has a few questions; a variant per student brings one more key object per job)
_MET = 64


class PreparedKeys:
    """A worker's prepared keys: each :class:`Key` or
    :class:`~dhsym.checking.judging.trajectory_key.TrajectoryKey` (frozen values) prepared
    once, on first use, and kept as long as this map (a grading worker's life).

    >>> keys = PreparedKeys()
    >>> k = Key.load("planar2r", "T0_2")
    >>> keys.get(k) is keys.get(Key.load("planar2r", "T0_2")), len(keys)
    (True, 1)
    """

    def __init__(self) -> None:
        self._prepared: dict[Key, PreparedKey] = {}
        self._trajectories: dict[TrajectoryKey, PreparedTrajectory] = {}
        # the key objects met last, by identity (each held, so its id is not reused): a
        # grading child unpickles its jobs' assignment once per batch, and every answer
        # asks for its key twice; hashing and comparing a key by value (its whole table)
        # cost 0.1 to 0.2 ms a time
        self._met: dict[int, tuple[AnyKey, PreparedKey | PreparedTrajectory]] = {}

    def __len__(self) -> int:
        return len(self._prepared) + len(self._trajectories)

    @overload
    def get(self, key: Key) -> PreparedKey: ...

    @overload
    def get(self, key: TrajectoryKey) -> PreparedTrajectory: ...

    def get(self, key: AnyKey) -> PreparedKey | PreparedTrajectory:
        """``key`` prepared (:func:`prepare`, or
        :func:`~dhsym.checking.judging.trajectory_key.prepare_trajectory`), the first time
        only."""
        met = self._met.get(id(key))
        if met is not None and met[0] is key:
            return met[1]
        found: PreparedKey | PreparedTrajectory
        if isinstance(key, TrajectoryKey):
            pt = self._trajectories.get(key)
            if pt is None:
                pt = self._trajectories[key] = prepare_trajectory(key)
            found = pt
        else:
            pk = self._prepared.get(key)
            if pk is None:
                pk = self._prepared[key] = prepare(key)
            found = pk
        if len(self._met) >= _MET:
            self._met.clear()
        self._met[id(key)] = (key, found)
        return found


def load_key(
    ref: str | Path | DHTable,
    question: str,
    *,
    tool_free: bool = False,
    rounding: object = None,
    keys: PreparedKeys | None = None,
) -> AnyKey:
    """The key ``ref`` names: a profile (``cubic(q0=0, qf=1, tf=2)``) gives a
    :class:`~dhsym.checking.judging.trajectory_key.TrajectoryKey`, anything else (a
    built-in robot, a table file, a table) a :class:`Key` (:meth:`Key.load`).

    >>> type(load_key("gains(omega=10)", "kp")).__name__, type(load_key("planar2r", "px")).__name__
    ('TrajectoryKey', 'Key')
    """
    if is_profile_spec(ref):
        assert isinstance(ref, str)
        key = TrajectoryKey.load(ref, question, rounding=rounding)
        if keys is not None:
            keys.get(key)
        return key
    return Key.load(ref, question, tool_free=tool_free, rounding=rounding, keys=keys)


def prepare(key: Key) -> PreparedKey:
    """Prepare a key: its robot, names and its kind's part (:data:`PREPARERS`), once per
    process for equal keys (the process's memo, :data:`dhsym.cache.memo.MEMO`, bounded):
    ``Key.load`` prepares a key to check it, and the check that follows, or the next
    ``dhsym.check`` of the same question in a notebook, finds it prepared. A grading
    worker also keeps its keys in :class:`PreparedKeys` (found by identity, faster).

    >>> prepare(Key.load("planar2r", "T0_2")) is prepare(Key.load("planar2r", "T0_2"))
    True
    """
    return MEMO.get(MemoKey(key.table, PreparedKey, key), lambda: _prepared(key))


def _prepared(key: Key) -> PreparedKey:
    """:func:`prepare`'s work, not memoised."""
    table = key.table
    robot = Robot(table)
    preparer = PREPARERS[key.question.kind]
    names, part = preparer(table, key.question, robot, NameContext.from_table(table))
    return PreparedKey(key, robot, names, part)
