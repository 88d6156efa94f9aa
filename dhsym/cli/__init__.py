"""The command line room: one module per command group, listed in :mod:`.main`.

May import every other room; nothing imports it (only the ``dhsym`` entry point).
"""

from .main import build_parser, main

__all__ = ["build_parser", "main"]


def __dir__() -> list[str]:
    """What ``dir(dhsym.cli)`` shows: ``__all__``, not the command modules it imports."""
    from dhsym._lazy import public_dir

    return public_dir(__name__)
