"""The closed-form derivations kept in the disk cache (:mod:`dhsym.cache`): derived once,
read back by every later process.

Deriving an arm's closed form (the family's lecture steps, each solved and tidied in
sympy) is most of the cost of a first ``robot.ik(T)`` once the solver's programs are
kept (:mod:`dhsym.ik.kept_programs`). :func:`kept_inverse` keeps the whole
:class:`~dhsym.ik.closed_form.ClosedForm`: the structure sentence, the decoupling, the
pose symbols, every step with its sentence, equation, branch and singular value, and the
branches. It is written as data: the words and numbers as JSON, every expression
through :mod:`dhsym.cache.codec` (read back without running code; the derivation's
``R_z``, ``T_x`` … of :data:`dhsym.notation.layout.WORD_FUNCTIONS` are the only
functions outside sympy's table it applies). A table without a closed form keeps its
refusal (the :class:`~dhsym.kinematics.decoupling.StructureError` is raised again, not
derived again); the general 6R's elimination is derived in each process.

The entry is named by the table's canonical form, its name (a refusal names the arm) and
the versions of dhsym and sympy (:func:`dhsym.cache.keys.entry_name`): equal tables
share it, another table or another version never reads it, and the store verifies its
content (an HMAC under this user's key) before it is read. What is read back equals
what is derived (``==``, field by field): the solver compiles the same steps, a handout
prints the same sentences.

Examples
--------
>>> from dhsym.kinematics.chain import KinematicChain
>>> from dhsym.model.library import load_table
>>> from dhsym.ik.families import inverse
>>> chain = KinematicChain(load_table("scara"))
>>> ik = inverse(chain)
>>> data = closed_form_data(ik)
>>> back = stored_closed_form(data, chain)
>>> back == ik, back.robot is chain, [st.text for st in back.steps] == [st.text for st in ik.steps]
(True, True, True)
>>> stored_closed_form(b'{"closed_form": {"steps": 7}}', chain) is None  # not what is written
True
"""

from __future__ import annotations

import json
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import sympy as sp

from dhsym.kinematics.decoupling import Decoupling, StructureError
from dhsym.notation.layout import WORD_FUNCTIONS, Sentence

from .closed_form import ClosedForm
from .steps import Branch, Step

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

    from .general6r import Elimination

__all__ = ["closed_form_data", "derivation_entry", "kept_inverse", "stored_closed_form"]

_FORMAT = "dhsym-closed-form 1"


def derivation_entry(robot: KinematicChain) -> str:
    """The disk-cache entry of ``robot``'s derivation: its table (canonical form and name)
    and the versions.

    >>> from dhsym.kinematics.chain import KinematicChain
    >>> from dhsym.model.library import load_table
    >>> derivation_entry(KinematicChain(load_table("puma560")))[:14]
    'ik_derivation-'
    """
    from dhsym.cache.keys import entry_name

    return entry_name(robot.table, "ik_derivation", f"name {robot.table.name!r}")


def kept_inverse(
    robot: KinematicChain, derive: Callable[[KinematicChain], ClosedForm | Elimination]
) -> ClosedForm | Elimination:
    """``derive(robot)`` (:func:`dhsym.ik.families.inverse`), kept in the disk cache: a
    kept closed form (or refusal) is read back instead, verified; one this version does
    not read is derived again and rewritten. With the cache off, derived.

    Raises
    ------
    StructureError
        When the table has no closed form (kept: the next process raises it at once).
    """
    from dhsym.cache.store import derived_once

    def read(data: bytes) -> ClosedForm | None:
        found = stored_closed_form(data, robot)
        return found if isinstance(found, ClosedForm) else None

    def write(ik: ClosedForm | Elimination) -> bytes | None:
        return closed_form_data(ik) if isinstance(ik, ClosedForm) else None

    return derived_once(
        lambda: derivation_entry(robot), lambda: derive(robot), write, read, StructureError
    )


def closed_form_data(ik: ClosedForm) -> bytes | None:
    """``ik`` as the data the disk cache keeps (words and indices as JSON, expressions
    through :func:`dhsym.cache.codec.write_exprs`); ``None`` when something in it cannot
    be written (then it is kept in this process only)."""
    from dhsym.cache.codec import CodecError, write_exprs

    items: list[Any] = []

    def put(e: object) -> int:
        items.append(e)
        return len(items) - 1

    def words(s: Sentence) -> dict[str, Any]:
        args: list[list[Any]] = []
        for key, value in s.args:
            if isinstance(value, str):
                args.append([key, "text", value])
            elif isinstance(value, int) and not isinstance(value, bool):
                args.append([key, "int", value])  # a joint's number
            elif isinstance(value, sp.Basic):
                args.append([key, "expr", put(value)])
            else:
                raise CodecError(f"a sentence's {type(value).__name__} is not written")
        return {"template": s.template, "args": args}

    def maybe(e: sp.Basic | None) -> int | None:
        return None if e is None else put(e)

    def branch(b: Branch) -> dict[str, Any]:
        return {
            "symbol": put(b.symbol),
            "role": b.role,
            "joint": b.joint,
            "sentence": words(b.sentence),
        }

    try:
        branches = [branch(b) for b in ik.branches]
        steps = [
            {
                "part": st.part,
                "sentence": words(st.sentence),
                "lhs": put(st.lhs),
                "rhs": put(st.rhs),
                "equation": maybe(st.equation),
                # as it is (a chain read backwards renames its branches, not its steps')
                "branch": None if st.branch is None else branch(st.branch),
                "singular": maybe(st.singular),
            }
            for st in ik.steps
        ]
        dec = ik.decoupling
        meta = {
            "format": _FORMAT,
            "structure": ik.structure,
            "family": ik.family,
            "decoupling": {
                "arm": list(dec.arm),
                "wrist": list(dec.wrist),
                "centre": dec.centre,
                "centre_in_last": put(dec.centre_in_last),
            },
            "pose": put(ik.pose),
            "branches": branches,
            "steps": steps,
        }
        exprs = write_exprs(items, WORD_FUNCTIONS)
    except (CodecError, ValueError):
        return None
    return json.dumps({"closed_form": meta, "exprs": exprs}).encode()


def stored_closed_form(data: bytes, robot: KinematicChain) -> ClosedForm | StructureError | None:
    """The :class:`ClosedForm` of :func:`closed_form_data` for ``robot``, or the
    :class:`StructureError` kept for a table that has none; ``None`` when the data is not
    what this version writes."""
    from dhsym.cache.codec import CodecError, read_exprs

    try:
        doc = json.loads(data)
        if isinstance(doc, dict) and isinstance(doc.get("refused"), str):
            return StructureError(doc["refused"])
        meta = doc["closed_form"]
        if meta["format"] != _FORMAT:
            return None
        items = read_exprs(doc["exprs"], WORD_FUNCTIONS)
        return _closed_form(meta, items, robot)
    except (CodecError, ValueError, TypeError, KeyError, IndexError, AttributeError):
        return None


def _closed_form(meta: dict[str, Any], items: list[Any], robot: KinematicChain) -> ClosedForm:
    """The closed form of a document's ``meta`` and expressions; raises ``ValueError``,
    ``TypeError``, ``KeyError`` or ``IndexError`` for what is not as written."""

    def item(k: object, kind: type | tuple[type, ...] = sp.Basic) -> Any:
        if not isinstance(k, int) or isinstance(k, bool) or not 0 <= k < len(items):
            raise ValueError(f"no expression {k!r}")
        value = items[k]
        if not isinstance(value, kind):
            raise TypeError(f"expression {k} is a {type(value).__name__}")
        return value

    def maybe(k: object, kind: type) -> Any:
        return None if k is None else item(k, kind)

    def text(value: object) -> str:
        if not isinstance(value, str):
            raise TypeError("a text is a string")
        return value

    def number(value: object) -> int:
        if not isinstance(value, int) or isinstance(value, bool):
            raise TypeError("an index is an integer")
        return value

    def words(doc: dict[str, Any]) -> Sentence:
        args: list[tuple[str, object]] = []
        for key, kind, value in doc["args"]:
            readers: dict[str, Callable[[object], object]] = {
                "text": text,
                "int": number,
                "expr": item,
            }
            args.append((text(key), readers[kind](value)))
        return Sentence(text(doc["template"]), tuple(args))

    def branch(b: dict[str, Any]) -> Branch:
        symbol = item(b["symbol"], sp.Symbol)
        return Branch(symbol, text(b["role"]), number(b["joint"]), words(b["sentence"]))

    branches = tuple(branch(b) for b in meta["branches"])
    steps = []
    for st in meta["steps"]:
        steps.append(
            Step(
                text(st["part"]),
                words(st["sentence"]),
                item(st["lhs"], sp.Symbol),
                item(st["rhs"]),
                maybe(st["equation"], sp.Eq),
                None if st["branch"] is None else branch(st["branch"]),
                maybe(st["singular"], sp.Basic),
            )
        )
    dec = meta["decoupling"]
    decoupling = Decoupling(
        tuple(number(r) for r in dec["arm"]),
        tuple(number(r) for r in dec["wrist"]),
        number(dec["centre"]),
        item(dec["centre_in_last"], sp.ImmutableMatrix),
    )
    return ClosedForm(
        robot,
        text(meta["structure"]),
        decoupling,
        item(meta["pose"], sp.ImmutableMatrix),
        tuple(steps),
        branches,
        family=text(meta["family"]),
    )
