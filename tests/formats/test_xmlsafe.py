"""Hostile XML: each refused with one FormatError naming the element, nothing outside read."""

from __future__ import annotations

from pathlib import Path

import pytest

from dhsym.errors import FormatError
from dhsym.formats.xmlsafe import MAX_BYTES, MAX_DEPTH, MAX_ELEMENTS, read_xml, read_xml_file

BOMB = """<?xml version="1.0"?>
<!DOCTYPE robot [
 <!ENTITY a "aaaaaaaaaaaaaaaaaaaa">
 <!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">
 <!ENTITY c "&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;">
 <!ENTITY d "&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;">
 <!ENTITY e "&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;">
 <!ENTITY f "&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;">
 <!ENTITY g "&f;&f;&f;&f;&f;&f;&f;&f;&f;&f;">
 <!ENTITY h "&g;&g;&g;&g;&g;&g;&g;&g;&g;&g;">
 <!ENTITY i "&h;&h;&h;&h;&h;&h;&h;&h;&h;&h;">
]>
<robot name="&i;"><link name="a"/></robot>"""


def test_entity_bomb_is_refused_at_the_doctype() -> None:
    with pytest.raises(FormatError, match="<!DOCTYPE>.*DTD"):
        read_xml(BOMB)


def test_external_entity_is_never_fetched(tmp_path: Path) -> None:
    secret = tmp_path / "secret.txt"
    secret.write_text("SECRET")
    text = f'<!DOCTYPE r [<!ENTITY x SYSTEM "file://{secret}">]><robot name="&x;"/>'
    with pytest.raises(FormatError) as err:
        read_xml(text)
    assert "DTD" in str(err.value) and "SECRET" not in str(err.value)


def test_plain_dtd_is_refused() -> None:
    with pytest.raises(FormatError, match="<!DOCTYPE>"):
        read_xml('<!DOCTYPE robot SYSTEM "http://example.com/robot.dtd"><robot/>')


def test_undeclared_entity_is_not_expanded() -> None:
    with pytest.raises(FormatError, match="entities are not expanded"):
        read_xml('<robot name="&x;"/>')


def test_deep_document_is_refused_early() -> None:
    depth = 1_000_000
    with pytest.raises(FormatError, match=f"field <b>: the document nests deeper than {MAX_DEPTH}"):
        read_xml("<robot>" + "<b>" * depth + "</b>" * depth + "</robot>")


def test_many_elements_are_refused() -> None:
    with pytest.raises(FormatError, match=f"more than {MAX_ELEMENTS} elements"):
        read_xml("<robot>" + "<link/>" * (MAX_ELEMENTS + 10) + "</robot>")


def test_huge_text_and_file_are_refused_before_parsing(tmp_path: Path) -> None:
    with pytest.raises(FormatError, match="at most 8000000"):
        read_xml("<robot>" + " " * MAX_BYTES + "</robot>")
    big = tmp_path / "big.urdf"
    with big.open("wb") as fh:  # sparse: 10 GB that take no room and are never read
        fh.truncate(10 * 1024**3)
    with pytest.raises(FormatError, match="big.urdf: the file has 10737418240 bytes"):
        read_xml_file(big)


def test_not_a_file(tmp_path: Path) -> None:
    with pytest.raises(FormatError, match="no such file"):
        read_xml_file(tmp_path / "missing.urdf")
    with pytest.raises(FormatError, match="not a regular file"):
        read_xml_file(tmp_path)


def test_malformed_xml_names_the_place() -> None:
    with pytest.raises(FormatError, match="not well-formed XML: .*line 1"):
        read_xml("<robot><link></robot>")
