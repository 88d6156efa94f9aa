"""Untrusted files and YAML: a read cap that trusts no file size, and YAML that cannot explode.

Every YAML text dhsym reads (table files, assignments, submissions, YAML answers)
goes through :func:`load_yaml`, and every file that may come from someone else
through :func:`read_limited`:

- :func:`read_limited` opens without blocking (a FIFO does not hang), reads only
  regular files, never follows a link where links are refused, refuses hard-linked
  files where asked (a hard link can point at any file of the same owner), and
  reads at most ``limit + 1`` bytes whatever ``st_size`` says (``/dev/zero`` and
  ``/proc`` files report 0).
- :func:`load_yaml` first walks the YAML *events* (no objects are built): the
  nesting depth, the number of values with every alias counted each time it is
  used, and the characters those values expand to are all bounded, so a
  400-byte "billion laughs" file is refused before anything is constructed or
  turned into text; an alias inside its own anchor (a list that contains
  itself) is refused too. Only then is it loaded with ``yaml.SafeLoader`` (no tags,
  no objects) under YAML 1.2's core schema (``1:30`` and ``yes`` are text, not 90 and
  True), with a key given twice in one mapping refused and integers longer than
  :attr:`YAMLLimits.max_digits` digits refused (Python refuses to convert them to
  text beyond 4300 digits anyway).

Errors are :class:`YAMLInputError` (a :class:`~dhsym.errors.DHError`) naming the
file and the line.

Examples
--------
>>> load_yaml("joints: [{type: R, theta: q1}]")
{'joints': [{'type': 'R', 'theta': 'q1'}]}
>>> bomb = "a: &a [x, x, x, x, x, x, x, x, x, x]\\n" + "".join(
...     f"{c}: &{c} [*{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}]\\n"
...     for p, c in zip("abcdefg", "bcdefgh"))
>>> len(bomb) < 500
True
>>> load_yaml(bomb, file="t.yaml")
Traceback (most recent call last):
...
dhsym.model.yamlsafe.YAMLInputError: t.yaml: line 5: the YAML is too large: ...
>>> load_yaml("[" * 200 + "]" * 200)
Traceback (most recent call last):
...
dhsym.model.yamlsafe.YAMLInputError: line 1: the YAML is nested more than 64 levels deep
>>> load_yaml("n: " + "9" * 2000)
Traceback (most recent call last):
...
dhsym.model.yamlsafe.YAMLInputError: line 1: a number with 2000 digits: at most 1000 are read
"""

from __future__ import annotations

import errno
import os
import re
import stat
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from dhsym.errors import DHError

__all__ = ["FileRefused", "YAMLInputError", "YAMLLimits", "load_yaml", "read_limited"]


class YAMLInputError(DHError):
    """YAML text that is not valid or breaks a :class:`YAMLLimits` bound."""


class FileRefused(DHError):
    """A file that is not read: ``kind`` is ``unreadable``, ``special``, ``link`` or ``large``."""

    def __init__(
        self,
        message: str,
        *,
        kind: str = "unreadable",
        file: str | None = None,
        row: int | None = None,
        field: str | None = None,
    ) -> None:
        super().__init__(message, file=file, row=row, field=field)
        self.kind = kind


@dataclass(frozen=True)
class YAMLLimits:
    """Bounds checked on the YAML events before anything is built.

    Parameters
    ----------
    max_bytes
        Size of the text (UTF-8 bytes).
    max_nodes
        Values (scalars, lists, mappings), an alias counting as many as it stands for.
    max_chars
        Characters of all scalars, aliases expanded: what ``str()`` of the result may print.
    max_depth
        Nesting of lists and mappings.
    max_digits
        Digits of one integer.
    """

    max_bytes: int = 2_000_000
    max_nodes: int = 100_000
    max_chars: int = 4_000_000
    max_depth: int = 64
    max_digits: int = 1000


DEFAULT_YAML_LIMITS = YAMLLimits()


class _Loader(yaml.SafeLoader):
    """``SafeLoader`` with YAML 1.2's core schema, integers of a bounded number of digits,
    and mappings whose keys appear once.

    YAML 1.2 reads ``1:30`` as text (YAML 1.1: the sexagesimal 90), ``yes``/``no``/``on``/
    ``off`` as text (only ``true``/``false`` are booleans), ``012`` as twelve (octal is
    ``0o12``) and dates as text.
    """

    max_digits = DEFAULT_YAML_LIMITS.max_digits
    yaml_implicit_resolvers: dict[Any, Any] = {}  # filled below with the core schema of YAML 1.2

    def construct_yaml_int(self, node: yaml.ScalarNode) -> int:
        text = str(node.value)
        digits = sum(ch.isdigit() or ch in "abcdefABCDEF" for ch in text)
        if digits > self.max_digits:
            raise YAMLInputError(
                f"line {node.start_mark.line + 1}: a number with {digits} digits: "
                f"at most {self.max_digits} are read"
            )
        if text.startswith(("0o", "0x")):  # the only octal and hexadecimal forms of YAML 1.2
            return int(text[2:], 8 if text[1] == "o" else 16)
        return int(text, 10)

    def construct_mapping(self, node: yaml.Node, deep: bool = False) -> dict[Any, Any]:
        if isinstance(node, yaml.MappingNode):
            seen: dict[object, int] = {}
            for key_node, _ in node.value:
                if key_node.tag == "tag:yaml.org,2002:merge" or not isinstance(
                    key_node, yaml.ScalarNode
                ):
                    continue
                key = self.construct_object(key_node)
                line = key_node.start_mark.line + 1
                if key in seen:
                    raise YAMLInputError(
                        f"line {line}: a key given twice in one mapping (first on line "
                        f"{seen[key]}); each field is written once"
                    )
                seen[key] = line
        return super().construct_mapping(node, deep=deep)  # type: ignore[arg-type]  # any other node: yaml's own ConstructorError


_Loader.add_constructor("tag:yaml.org,2002:int", _Loader.construct_yaml_int)
_Loader.add_constructor("tag:yaml.org,2002:map", _Loader.construct_yaml_map)  # type: ignore[type-var]  # types-PyYAML types it on SafeConstructor, a base of _Loader
# YAML 1.2 core schema: the plain scalars that are not text (no sexagesimal 1:30, no yes/no)
_BOOL = re.compile(r"^(?:true|True|TRUE|false|False|FALSE)$")
_INT = re.compile(r"^(?:[-+]?[0-9]+|0o[0-7]+|0x[0-9a-fA-F]+)$")
_FLOAT = re.compile(
    r"^(?:[-+]?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)(?:[eE][-+]?[0-9]+)?"
    r"|[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$"
)
_NULL = re.compile(r"^(?:~|null|Null|NULL|)$")
_MERGE = re.compile(r"^(?:<<)$")
for _tag, _regex, _first in (
    ("bool", _BOOL, "tTfF"),
    ("int", _INT, "-+0123456789"),
    ("float", _FLOAT, "-+.0123456789"),
    ("null", _NULL, ["~", "n", "N", ""]),
    ("merge", _MERGE, "<"),
):
    _Loader.add_implicit_resolver(f"tag:yaml.org,2002:{_tag}", _regex, list(_first))


def _line(event: yaml.Event) -> str:
    mark = getattr(event, "start_mark", None)
    return f"line {mark.line + 1}: " if mark is not None else ""


def _check_events(text: str, limits: YAMLLimits) -> None:
    """Walk the events once: depth, values and characters (aliases expanded) are bounded."""
    # each open collection accumulates (values, chars); an anchored node records its totals
    stack: list[list[int]] = [[0, 0]]
    anchors: dict[str, tuple[int, int]] = {}
    opened: list[str | None] = []
    total_nodes = total_chars = 0
    for event in yaml.parse(text, Loader=yaml.SafeLoader):
        if isinstance(event, (yaml.SequenceStartEvent, yaml.MappingStartEvent)):
            if len(opened) >= limits.max_depth:
                raise YAMLInputError(
                    f"{_line(event)}the YAML is nested more than {limits.max_depth} levels deep"
                )
            opened.append(event.anchor)
            stack.append([1, 0])
            continue
        if isinstance(event, (yaml.SequenceEndEvent, yaml.MappingEndEvent)):
            nodes, chars = stack.pop()
            anchor = opened.pop()
            if anchor is not None:
                anchors[anchor] = (nodes, chars)
            stack[-1][0] += nodes
            stack[-1][1] += chars
        elif isinstance(event, yaml.ScalarEvent):
            nodes, chars = 1, len(event.value)
            if event.anchor is not None:
                anchors[event.anchor] = (nodes, chars)
            stack[-1][0] += nodes
            stack[-1][1] += chars
            total_nodes, total_chars = total_nodes + nodes, total_chars + chars
        elif isinstance(event, yaml.AliasEvent):
            if event.anchor in opened:
                raise YAMLInputError(
                    f"{_line(event)}the alias *{event.anchor} is inside its own anchor "
                    "(a structure that contains itself)"
                )
            known = anchors.get(event.anchor) if event.anchor is not None else None
            nodes, chars = known or (1, 0)
            stack[-1][0] += nodes
            stack[-1][1] += chars
            total_nodes, total_chars = total_nodes + nodes, total_chars + chars
        else:
            continue
        if total_nodes > limits.max_nodes or stack[-1][0] > limits.max_nodes:
            raise YAMLInputError(
                f"{_line(event)}the YAML is too large: more than {limits.max_nodes} values "
                "(an alias counts as the values it repeats)"
            )
        if total_chars > limits.max_chars or stack[-1][1] > limits.max_chars:
            raise YAMLInputError(
                f"{_line(event)}the YAML is too large: its values expand to more than "
                f"{limits.max_chars} characters (an alias counts as the text it repeats)"
            )


def load_yaml(
    text: str | bytes, *, file: str | None = None, limits: YAMLLimits = DEFAULT_YAML_LIMITS
) -> object:
    """Parse untrusted YAML text within ``limits``; plain data only (``SafeLoader``).

    Raises
    ------
    YAMLInputError
        Not UTF-8, not valid YAML, or over a limit; the message names ``file`` and the line.
    """
    try:
        size = len(text) if isinstance(text, bytes) else len(text.encode("utf-8", "replace"))
        if size > limits.max_bytes:
            raise YAMLInputError(f"the YAML text is {size} bytes; at most {limits.max_bytes}")
        if isinstance(text, bytes):
            try:
                text = text.decode("utf-8")
            except UnicodeDecodeError:
                raise YAMLInputError("not UTF-8 text") from None
        try:
            _check_events(text, limits)
            loader = type("_BoundLoader", (_Loader,), {"max_digits": limits.max_digits})
            return yaml.load(text, Loader=loader)  # noqa: S506 - a SafeLoader subclass
        except yaml.YAMLError as err:
            mark = getattr(err, "problem_mark", None)
            where = f" (line {mark.line + 1}, column {mark.column + 1})" if mark else ""
            problem = getattr(err, "problem", None) or str(err)
            raise YAMLInputError(f"not valid YAML{where}: {problem}") from None
        except RecursionError:
            raise YAMLInputError("the YAML is nested too deeply") from None
    except YAMLInputError as err:
        raise err.located(file=file) from None


def _link_refused(what: str, path: Path) -> FileRefused:
    """The refusal of a file that is a symbolic link."""
    return FileRefused(
        f"{what} is not a regular file (a symbolic link: links are not read)",
        kind="link",
        file=str(path),
    )


def read_limited(
    path: str | Path,
    limit: int,
    *,
    follow_links: bool = True,
    hard_links: bool = True,
    what: str = "the file",
) -> bytes:
    """At most ``limit`` bytes of a regular file; anything else is a :class:`FileRefused`.

    The file is opened without blocking and checked on the open descriptor (no
    race between check and read): a FIFO, device, socket or directory is refused,
    so is a symbolic link unless ``follow_links`` and a file with several hard
    links unless ``hard_links``. ``limit + 1`` bytes are read: ``st_size`` is not
    trusted.

    >>> read_limited("/dev/zero", 10)
    Traceback (most recent call last):
    ...
    dhsym.model.yamlsafe.FileRefused: /dev/zero: the file is not a regular file (a device, ...)
    """
    p = Path(path)
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0)
    if not follow_links:
        flags |= getattr(os, "O_NOFOLLOW", 0)
    if not follow_links and p.is_symlink():
        raise _link_refused(what, p)
    try:
        fd = os.open(p, flags)
    except OSError as err:
        if err.errno == errno.ELOOP:
            raise _link_refused(what, p) from None
        raise FileRefused(f"cannot read {what}: {err.strerror}", file=str(p)) from None
    st = os.fstat(fd)
    if not stat.S_ISREG(st.st_mode):
        os.close(fd)
        raise FileRefused(
            f"{what} is not a regular file (a device, FIFO, socket or folder)",
            kind="special",
            file=str(p),
        )
    with os.fdopen(fd, "rb", buffering=0) as fh:
        if not hard_links and st.st_nlink > 1:
            raise FileRefused(
                f"{what} is not read: it has {st.st_nlink} hard links "
                "(a hard link can stand for any file of its owner)",
                kind="link",
                file=str(p),
            )
        if st.st_size > limit:  # believed when large; a small st_size proves nothing
            raise FileRefused(
                f"{what} is {st.st_size} bytes; at most {limit} are read", kind="large", file=str(p)
            )
        chunks, size = [], 0
        try:
            while size <= limit:
                chunk = fh.read(min(1 << 20, limit + 1 - size))
                if not chunk:
                    break
                chunks.append(chunk)
                size += len(chunk)
        except OSError as err:
            raise FileRefused(f"cannot read {what}: {err.strerror}", file=str(p)) from None
    if size > limit:
        raise FileRefused(f"{what} is larger than {limit} bytes", kind="large", file=str(p))
    return b"".join(chunks)
