"""Names a package exports but loads on first use (PEP 562), so that imports stay cheap.

``import dhsym`` costs little more than ``import sympy``: numpy, matplotlib,
Jinja2 and the checker load only when a name that needs them is first used.

Examples
--------
>>> getattr_, dir_ = lazy_exports("dhsym.model", {"parse_expression": "parsing"})
>>> getattr_("parse_expression").__name__
'parse_expression'
>>> "parse_expression" in dir_()
True

``dir()`` of such a package lists what it exports and its dunder attributes, not
the names its ``__init__`` happens to import (``annotations``, ``lazy_exports``):

>>> "lazy_exports" in dir_(), "annotations" in dir_()
(False, False)
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Iterable, Mapping

__all__ = ["lazy_exports", "public_dir"]


def lazy_exports(
    package: str, names: Mapping[str, str]
) -> tuple[Callable[[str], object], Callable[[], list[str]]]:
    """``__getattr__`` and ``__dir__`` for ``package``: ``names`` maps a name to its module.

    Module paths are relative to ``package`` (``"parsing"``) or absolute
    (``"dhsym.plot.figures"``); a name that maps to itself (``"kinematics":
    "kinematics"``) is the submodule.
    """

    def __getattr__(name: str) -> object:
        if name not in names:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        module = names[name]
        target = module if module.startswith("dhsym") else f"{package}.{module}"
        if target == f"{package}.{name}":  # a subpackage or module of its own
            return importlib.import_module(target)
        return getattr(importlib.import_module(target), name)

    def __dir__() -> list[str]:
        return public_dir(package, names)

    return __getattr__, __dir__


def public_dir(package: str, names: Iterable[str] = ()) -> list[str]:
    """What ``dir(package)`` shows: its ``__all__``, ``names`` and its dunder attributes.

    Names the module's code imports for itself (``annotations``, ``lazy_exports``,
    ``sys``) and private ones stay out, as do submodules imported along the way.

    >>> import dhsym.model
    >>> public_dir("dhsym.model") == sorted(
    ...     {*dhsym.model.__all__, *(n for n in vars(dhsym.model) if n.startswith("__"))})
    True
    """
    namespace = vars(sys.modules[package])
    dunders = {n for n in namespace if n.startswith("__") and n.endswith("__")}
    return sorted(set(namespace.get("__all__", ())) | set(names) | dunders)
