"""``dhsym cache info|clear``: the disk cache of derived results and built libraries."""

from __future__ import annotations

import argparse
from typing import Any

from .common import add_command

__all__ = ["register"]


def _cmd_cache(args: argparse.Namespace) -> int:
    from dhsym.cache.store import Store, cache_root

    store = Store(cache_root())
    if args.action == "clear":
        count = store.clear()
        print(f"removed {count} entr{'y' if count == 1 else 'ies'} from {store.root}")
        return 0
    info = store.info()
    print(f"folder:  {info.root}")
    print(f"entries: {info.entries}")
    print(f"size:    {info.size:,} bytes")
    if not info.enabled:
        print("the cache is turned off (DHSYM_NO_CACHE)")
    return 0


def register(subparsers: Any) -> None:
    """Add ``dhsym cache info|clear``."""
    p = add_command(
        subparsers,
        "cache",
        "show or clear the cache of derived results and built libraries",
        epilog="The folder is $DHSYM_CACHE, else the user cache folder (~/.cache/dhsym on "
        "Linux). 'dhsym --no-cache COMMAND' (or DHSYM_NO_CACHE=1) runs without it.",
    )
    p.add_argument("action", choices=("info", "clear"), help="info: folder, entries, size; clear")
    p.set_defaults(func=_cmd_cache)
