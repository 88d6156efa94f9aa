"""Entry names from a table's canonical form and the versions (dhsym.cache.keys)."""

from __future__ import annotations

from dataclasses import replace

from dhsym.cache.keys import code_version, entry_name
from dhsym.model.library import load_table
from dhsym.model.table import canonical_text


def test_name_and_comments_do_not_count():
    t = load_table("puma560")
    other = replace(t, name="My PUMA", source="/elsewhere/puma.yaml", notes="a comment")
    assert canonical_text(other) == canonical_text(t)
    assert entry_name(other, "transform", "0-6") == entry_name(t, "transform", "0-6")


def test_what_a_derivation_reads_counts():
    t = load_table("puma560")
    assert entry_name(t.with_values({"a2": "0.5"}), "rne") != entry_name(t, "rne")
    assert entry_name(load_table("puma560_modified"), "rne") != entry_name(t, "rne")
    assert entry_name(t, "rne", "textbook=True") != entry_name(t, "rne", "textbook=False")
    assert entry_name(t, "fk_single") != entry_name(t, "fk_batch")


def test_versions_are_part_of_the_name():
    import sympy

    text = code_version()
    assert text.startswith("dhsym ") and len(text.split()) == 3
    assert sympy.__version__  # named in every entry (see entry_name)
