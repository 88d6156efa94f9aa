"""The README's Python examples run and print what it says."""

from __future__ import annotations

import doctest
import re
from pathlib import Path

README = Path(__file__).resolve().parent.parent / "README.md"


def test_readme_examples_run():
    result = doctest.testfile(
        str(README), module_relative=False, optionflags=doctest.NORMALIZE_WHITESPACE
    )
    assert result.attempted >= 8
    assert result.failed == 0


def test_readme_gives_exactly_two_commands():
    text = README.read_text()
    block = text.split("## Two commands")[1].split("```sh")[1].split("```")[0]
    commands = [line.split("#")[0].strip() for line in block.strip().splitlines()]
    assert commands == ["make demo", "make test"]
    assert "make test" in (README.parent / ".ci" / "run").read_text()


def test_readme_is_a_five_minute_read():
    assert len(README.read_bytes()) <= 15_000


def test_readme_shows_a_handout_page_and_the_arm_with_its_frames():
    text = README.read_text()
    for picture in ("docs/handout-puma560-result.png", "docs/puma560-frames.png"):
        assert f"]({picture})" in text
        assert (README.parent / picture).is_file()


def test_readme_links_point_to_files_that_exist():
    text = README.read_text()
    links = re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", text)
    local = [link for link in links if "://" not in link]
    assert len(local) >= 20
    missing = [link for link in local if not (README.parent / link).exists()]
    assert missing == []
