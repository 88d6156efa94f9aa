"""``dhsym cache info|clear|trim``: the disk cache of derived results and built libraries."""

from __future__ import annotations

import argparse
from typing import Any

from .common import add_command

__all__ = ["register"]


def _cmd_cache(args: argparse.Namespace) -> int:
    from dhsym.cache.store import Store, cache_root, parse_size

    store = Store(cache_root())
    if args.action == "clear":
        count = store.clear()
        print(f"removed {count} entr{'y' if count == 1 else 'ies'} from {store.root}")
        return 0
    if args.action == "trim":
        limit = parse_size(args.max_size, "--max-size") if args.max_size else store.bound()
        done = store.trim(limit)
        print(
            f"removed {done.entries} entr{'y' if done.entries == 1 else 'ies'} "
            f"({done.freed:,} bytes) from {store.root}; {done.size:,} bytes left "
            f"(at most {limit:,})"
        )
        return 0
    info = store.info()
    print(f"folder:  {info.root}")
    print(f"entries: {info.entries}")
    print(f"size:    {info.size:,} bytes")
    print(f"limit:   {info.limit:,} bytes (least recently used entries deleted beyond it)")
    if not info.enabled:
        print("the cache is turned off (DHSYM_NO_CACHE)")
    return 0


def register(subparsers: Any) -> None:
    """Add ``dhsym cache info|clear|trim``."""
    p = add_command(
        subparsers,
        "cache",
        "show, clear or trim the cache of derived results and built libraries",
        epilog="The folder is DHSYM_CACHE, else the user cache folder (~/.cache/dhsym on "
        "Linux); its entries take at most DHSYM_CACHE_SIZE (default 512M), the least "
        "recently used deleted first. 'dhsym --no-cache COMMAND' (or DHSYM_NO_CACHE=1) "
        "runs without it.",
    )
    p.add_argument(
        "action",
        choices=("info", "clear", "trim"),
        help="info: folder, entries, size, limit; clear: delete every entry; trim: delete the "
        "least recently used entries until the rest fit the limit",
    )
    p.add_argument(
        "--max-size",
        metavar="SIZE",
        help="with trim: the size to trim to (200M, 1G, 64k or bytes; default the limit)",
    )
    p.set_defaults(func=_cmd_cache)
