"""XML of other tools read safely: no DTD, no entities, nothing outside the text, bounded size.

Robot descriptions come from the internet. The reader is :mod:`defusedxml` (the
maintained guard around the standard library's expat parser) with every switch on:
a document type declaration, an entity declaration or an external reference is
refused before anything is expanded or fetched. On top, a document is refused when
it is larger than :data:`MAX_BYTES`, nests deeper than :data:`MAX_DEPTH` or holds
more than :data:`MAX_ELEMENTS` elements, while it is read (so a hostile file costs
at most the time to read those limits). Each refusal is one
:class:`~dhsym.errors.FormatError` naming the file and the element.

Examples
--------
>>> read_xml("<robot name='r'><link name='a'/></robot>").find("link").get("name")
'a'
>>> read_xml('<!DOCTYPE r [<!ENTITY a "aaaa">]><robot>&a;</robot>')  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
dhsym.errors.FormatError: field <!DOCTYPE>: a document type declaration (DTD) ...
"""

from __future__ import annotations

import io
import os
from pathlib import Path
from xml.etree.ElementTree import Element, ParseError

from defusedxml import (
    DefusedXmlException,
    DTDForbidden,
    EntitiesForbidden,
    ExternalReferenceForbidden,
)
from defusedxml.ElementTree import iterparse

from dhsym.errors import FormatError

__all__ = ["MAX_BYTES", "MAX_DEPTH", "MAX_ELEMENTS", "read_xml", "read_xml_file"]

#: Largest document read (bytes). Shipped URDFs are 1–250 kB.
MAX_BYTES = 8_000_000
#: Deepest nesting of elements (a URDF nests 4 deep: robot, joint, limit).
MAX_DEPTH = 40
#: Most elements in one document (a 7-joint arm with meshes, panda_collision.urdf,
#: has under 500).
MAX_ELEMENTS = 50_000


def read_xml_file(path: str | os.PathLike[str]) -> tuple[Element, str]:
    """The root element of the XML file ``path`` and the file name for messages.

    The size is checked before the file is read; nothing but ``path`` is opened.

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = Path(d, "r.urdf")
    ...     _ = p.write_text("<robot name='r'/>")
    ...     read_xml_file(p)[0].tag
    'robot'
    """
    p = Path(path)
    name = str(path)
    try:
        if not p.is_file():
            raise FormatError("no such file (or not a regular file)", file=name)
        size = p.stat().st_size
        if size > MAX_BYTES:
            raise FormatError(f"the file has {size} bytes: at most {MAX_BYTES} are read", file=name)
        with p.open("rb") as fh:
            data = fh.read(MAX_BYTES + 1)
    except OSError as err:
        raise FormatError(f"cannot read the file: {err.strerror or err}", file=name) from None
    return read_xml(data, file=name), name


def read_xml(data: str | bytes, *, file: str | None = None) -> Element:
    """The root element of an XML document given as text, with the limits of this module.

    >>> read_xml("<a><b>" * 50 + "</b></a>" * 50)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    dhsym.errors.FormatError: field <a>: the document nests deeper than 40 elements: ...
    >>> read_xml('<a><b x="1"></a>')  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    dhsym.errors.FormatError: not well-formed XML: mismatched tag: line 1, column 14
    """
    raw = data.encode("utf-8") if isinstance(data, str) else bytes(data)
    if len(raw) > MAX_BYTES:
        raise FormatError(
            f"the document has {len(raw)} bytes: at most {MAX_BYTES} are read", file=file
        )
    depth = count = 0
    root: Element | None = None
    events = iterparse(
        io.BytesIO(raw),
        events=("start", "end"),
        forbid_dtd=True,
        forbid_entities=True,
        forbid_external=True,
    )
    try:
        for event, elem in events:
            if event == "end":
                depth -= 1
                continue
            depth += 1
            count += 1
            root = elem if root is None else root
            if depth > MAX_DEPTH:
                raise FormatError(
                    f"the document nests deeper than {MAX_DEPTH} elements: not a robot description",
                    file=file,
                    field=f"<{_tag(elem)}>",
                )
            if count > MAX_ELEMENTS:
                raise FormatError(
                    f"the document has more than {MAX_ELEMENTS} elements",
                    file=file,
                    field=f"<{_tag(elem)}>",
                )
    except DTDForbidden:
        raise FormatError(
            "a document type declaration (DTD) is not allowed in a robot description "
            "(it can declare entities that expand or fetch other files); remove it",
            file=file,
            field="<!DOCTYPE>",
        ) from None
    except EntitiesForbidden as err:
        raise FormatError(
            f"entity declarations are not allowed (entity {err.name!r})",
            file=file,
            field="<!ENTITY>",
        ) from None
    except ExternalReferenceForbidden as err:
        raise FormatError(
            f"external references are not followed ({err.sysid or err.pubid!r})",
            file=file,
            field="<!ENTITY>",
        ) from None
    except DefusedXmlException as err:
        raise FormatError(f"refused XML construct: {err}", file=file) from None
    except ParseError as err:
        msg = str(err)
        if "undefined entity" in msg:
            msg += " (entities are not expanded)"
        raise FormatError(f"not well-formed XML: {msg}", file=file) from None
    if root is None:  # pragma: no cover - expat reports an empty document as ParseError
        raise FormatError("empty document", file=file)
    return root


def _tag(elem: Element) -> str:
    tag = str(elem.tag)
    return tag if len(tag) <= 40 else tag[:39] + "…"
