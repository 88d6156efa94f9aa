"""The cache room: what dhsym derives, kept so that it is derived once.

Two layers, one idea each: :mod:`.memo` shares derived state between the objects of one
process that hold an equal table (bounded, thread-safe, invisible in the API);
:mod:`.store` keeps exact results and built libraries on disk between processes,
written atomically, owner- and mode-checked and verified by an HMAC before use;
:mod:`.codec` turns expressions into text and back through a restricted reader (no
pickle, no ``eval``), and :mod:`.keys` names an entry by a table's canonical form and
the versions of dhsym and sympy.

May import :mod:`dhsym.errors`, :mod:`dhsym._version` and :mod:`dhsym.model` only; the
rooms above use it.
"""

from dhsym._lazy import lazy_exports

__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "MEMO": "memo",
        "Memo": "memo",
        "MemoKey": "memo",
        "Store": "store",
        "cache_root": "store",
        "default_store": "store",
        "read_expr": "codec",
        "write_expr": "codec",
        "entry_name": "keys",
    },
)
