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
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping

__all__ = ["lazy_exports"]


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
        return sorted(set(names) | set(importlib.import_module(package).__dict__))

    return __getattr__, __dir__
