"""The kinds a DH table is made of: convention, angle unit, joint type.

Each is an Enum whose ``parse`` reads the names people write (``craig``,
``degrees``, ``revolute``) and raises a :class:`~dhsym.errors.TableError`
naming the field otherwise.

>>> Convention.parse("Craig"), AngleUnit.parse("degrees"), JointType.parse("prismatic")
(<Convention.MODIFIED: 'modified'>, <AngleUnit.DEG: 'deg'>, <JointType.PRISMATIC: 'P'>)
"""

from __future__ import annotations

from enum import Enum
from typing import TypeVar

from dhsym.errors import TableError

__all__ = ["AngleUnit", "Convention", "JointType"]

_E = TypeVar("_E", bound=Enum)


def _lookup(
    cls: type[_E], value: object, synonyms: dict[str, str], what: str, field: str, expected: str
) -> _E:
    """Find the member of ``cls`` that ``value`` names, through ``synonyms`` (name -> value)."""
    if isinstance(value, cls):
        return value
    key = str(value).strip().lower()
    if key not in synonyms:
        raise TableError(f"unknown {what} {value!r}: expected {expected}", field=field)
    return cls(synonyms[key])


class Convention(str, Enum):
    """Which DH convention a table uses: standard (distal) or modified (proximal, Craig)."""

    STANDARD = "standard"
    MODIFIED = "modified"

    @classmethod
    def parse(cls, value: object) -> Convention:
        """Read ``standard``/``distal``/``std`` or ``modified``/``proximal``/``craig``."""
        synonyms = dict.fromkeys(("standard", "distal", "std"), "standard")
        synonyms.update(
            dict.fromkeys(("modified", "proximal", "craig", "non-standard"), "modified")
        )
        return _lookup(cls, value, synonyms, "convention", "convention", "'standard' or 'modified'")


class AngleUnit(str, Enum):
    """Unit in which the angles of a table file are written."""

    DEG = "deg"
    RAD = "rad"

    @classmethod
    def parse(cls, value: object) -> AngleUnit:
        """Read ``deg``/``degrees`` or ``rad``/``radians``."""
        synonyms = dict.fromkeys(("deg", "degree", "degrees"), "deg")
        synonyms.update(dict.fromkeys(("rad", "radian", "radians"), "rad"))
        return _lookup(cls, value, synonyms, "angle unit", "angles", "'deg' or 'rad'")


class JointType(str, Enum):
    """Revolute (θ variable), prismatic (d variable) or fixed (no variable)."""

    REVOLUTE = "R"
    PRISMATIC = "P"
    FIXED = "F"

    @classmethod
    def parse(cls, value: object) -> JointType:
        """Read ``R``/``revolute``, ``P``/``prismatic`` or ``F``/``fixed``."""
        synonyms = dict.fromkeys(("r", "revolute", "rotary"), "R")
        synonyms.update(dict.fromkeys(("p", "prismatic", "sliding"), "P"))
        synonyms.update(dict.fromkeys(("f", "fixed"), "F"))
        return _lookup(
            cls, value, synonyms, "joint type", "type", "R (revolute), P (prismatic) or F (fixed)"
        )
