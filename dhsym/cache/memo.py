"""One memo per process: derived state shared by every object of an equal frozen table.

A :class:`~dhsym.kinematics.chain.KinematicChain` or a :class:`~dhsym.robot.Robot` asks
the memo for its derived state (the closed forms, the compiled functions, the inverse
kinematics, the equations of motion) by a :class:`MemoKey`: the frozen
:class:`~dhsym.model.table.DHTable` value, the type of the state (a class, not a
string) and what else changes it (the notation its poses print in). A second
``load("puma560")`` gets the first one's state and derives nothing.

:data:`MEMO` is the one documented exception to "no process-wide mutable state": the
memo is process-wide by its nature. It is a typed object (a bounded LRU, not a dict keyed
by strings), safe under threads (a lock guards its table; a key being built has its own
lock, so threads asking for the same table build it once), and bounded by an estimate
of its size: the least recently used entries are dropped when the sum of their sizes
passes :attr:`Memo.budget`.

Examples
--------
>>> from dhsym.model.library import load_table
>>> memo = Memo(budget=10)
>>> key = MemoKey(load_table("planar2r"), list)
>>> state = memo.get(key, list)
>>> memo.get(MemoKey(load_table("planar2r"), list), list) is state
True
>>> len(memo), memo.size
(1, 1)
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable
from dataclasses import dataclass
from typing import Any, Protocol, TypeVar, cast, runtime_checkable

from dhsym.model.table import DHTable

__all__ = ["MEMO", "DEFAULT_BUDGET", "Memo", "MemoKey", "Sized"]

T = TypeVar("T")

#: Estimated size the process-wide memo keeps (expression nodes, see :class:`Sized`): a
#: PUMA 560's kinematics, inverse kinematics and dynamics are a few hundred thousand.
DEFAULT_BUDGET = 5_000_000


@runtime_checkable
class Sized(Protocol):
    """A derived state that estimates its own size (expression nodes; a compiled function
    counts as its expressions), read again each time the memo accounts for it."""

    def memo_size(self) -> int:
        """The estimated size now."""
        ...


@dataclass(frozen=True)
class MemoKey:
    """What a derived state is shared by: the table (by value), the state's type and
    what else changes it (``extra``: e.g. the notation its poses print in)."""

    table: DHTable
    kind: type
    extra: Hashable = None


class Memo:
    """A bounded, thread-safe LRU of derived states (see the module's docstring).

    Parameters
    ----------
    budget
        Largest sum of the entries' estimated sizes (:class:`Sized`; 1 for other
        states). The entry just asked for is always kept.
    """

    def __init__(self, budget: int = DEFAULT_BUDGET) -> None:
        self.budget = budget
        self._lock = threading.Lock()
        self._entries: OrderedDict[MemoKey, object] = OrderedDict()
        self._building: dict[MemoKey, threading.Lock] = {}

    def get(self, key: MemoKey, build: Callable[[], T]) -> T:
        """The state of ``key``, built by ``build()`` the first time (once, across threads)."""
        with self._lock:
            if key in self._entries:
                self._entries.move_to_end(key)
                return cast(T, self._entries[key])
            gate = self._building.setdefault(key, threading.Lock())
        with gate:  # one builder per key; others wait for it
            with self._lock:
                if key in self._entries:
                    self._entries.move_to_end(key)
                    return cast(T, self._entries[key])
            state = build()
            with self._lock:
                self._entries[key] = state
                self._building.pop(key, None)
                self._evict(keep=key)
        return state

    def _evict(self, keep: MemoKey) -> None:
        total = sum(_size(v) for v in self._entries.values())
        for key in list(self._entries):
            if total <= self.budget:
                break
            if key == keep:
                continue
            total -= _size(self._entries.pop(key))

    @property
    def size(self) -> int:
        """The estimated size of what the memo keeps now."""
        with self._lock:
            return sum(_size(v) for v in self._entries.values())

    def __len__(self) -> int:
        with self._lock:
            return len(self._entries)

    def __contains__(self, key: object) -> bool:
        with self._lock:
            return key in self._entries

    def clear(self) -> None:
        """Forget every state (objects holding one keep theirs)."""
        with self._lock:
            self._entries.clear()

    def __repr__(self) -> str:
        return f"Memo({len(self)} entries, size {self.size} of {self.budget})"


def _size(state: Any) -> int:
    return max(1, int(state.memo_size())) if isinstance(state, Sized) else 1


#: The process-wide memo (the documented exception: see the module's docstring).
MEMO = Memo()
