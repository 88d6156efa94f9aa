"""The command line room: one module per command group, listed in :mod:`.main`.

May import every other room; nothing imports it (only the ``dhsym`` entry point).
"""

from .main import build_parser, main

__all__ = ["build_parser", "main"]
