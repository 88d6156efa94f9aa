"""The keys a test process prepares once for every checking test that judges answers, as a
grading worker keeps its keys for all its answers (:class:`PreparedKeys`).

:func:`load_key` is :meth:`Key.load` with its check of the key made into the shared map (the
preparation every later answer to that key then uses), and :data:`check_answer` judges with
the shared map. A key is a frozen value and its preparation a frozen value too, so tests
that share one see what each would have prepared. The paths that prepare for themselves
(``Key.load`` without ``keys``, ``check_answer`` of one answer) stay tested where they are
the subject: ``judging/test_key.py``, ``judging/test_checker.py``, ``judging/test_rounding.py``,
``judging/test_ik_key.py`` and the doctests.
"""

from __future__ import annotations

import functools
from pathlib import Path

from dhsym.checking import Key
from dhsym.checking import check_answer as _check_answer
from dhsym.checking.judging.key import PreparedKeys
from dhsym.model.table import DHTable

__all__ = ["KEYS", "check_answer", "load_key"]

#: this process's prepared keys (an xdist worker's, shared by its test modules)
KEYS = PreparedKeys()

#: :func:`dhsym.checking.check_answer` with the keys prepared once in :data:`KEYS`
check_answer = functools.partial(_check_answer, keys=KEYS)


def load_key(
    ref: str | Path | DHTable, question: str, *, tool_free: bool = False, rounding: object = None
) -> Key:
    """:meth:`Key.load`, prepared into :data:`KEYS` (once for the whole test process)."""
    return Key.load(ref, question, tool_free=tool_free, rounding=rounding, keys=KEYS)
