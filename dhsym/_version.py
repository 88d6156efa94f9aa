"""The installed version, read from the package metadata on first use (``dhsym.__version__``).

>>> isinstance(__version__, str)
True
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

__all__ = ["__version__"]

try:
    __version__ = version("dhsym")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0.0.0"
