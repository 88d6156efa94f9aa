"""The report folder's files: unique plain names, paths inside, atomic writes, safe CSV cells."""

from __future__ import annotations

import pytest

from dhsym.checking.grading.report_files import (
    csv_cell,
    inside,
    inside_folder,
    name_base,
    safe_name,
    write_atomic,
)
from dhsym.errors import DHError


def test_safe_names_are_unique_plain_and_never_reserved():
    used: set[str] = set()
    names = [safe_name(s, used) for s in ("a/b", "a_b", "A_B", "..", "CON", "ok", "ok")]
    assert len({n.lower() for n in names}) == len(names) and names[5] == "ok"
    assert all(n and n[0] != "." and "/" not in n for n in names)
    assert names[4].lower() != "con" and name_base("a/b") == name_base("a_b") == "a_b"


def test_a_path_outside_the_report_folder_is_refused(tmp_path):
    root = tmp_path.resolve()
    assert inside(root, "feedback", "a.md") == root / "feedback" / "a.md"
    with pytest.raises(DHError, match="outside the report folder"):
        inside(root, "..", "x")


def test_a_page_in_the_resolved_folder_is_checked_like_inside(tmp_path):
    root = (tmp_path / "report").resolve()
    folder = root / "feedback"
    folder.mkdir(parents=True)
    assert inside_folder(root, folder, "a.md") == inside(root, "feedback", "a.md")
    (folder / "in.md").symlink_to(root / "x.md")  # a link that stays inside: its target
    assert inside_folder(root, folder, "in.md") == root / "x.md"
    (folder / "out.md").symlink_to(tmp_path / "elsewhere.md")
    with pytest.raises(DHError, match="outside the report folder"):
        inside_folder(root, folder, "out.md")
    with pytest.raises(DHError, match="plain file name"):
        inside_folder(root, folder, "../x.md")


def test_writes_are_atomic_and_survive_text_that_is_not_unicode(tmp_path):
    path = tmp_path / "g.csv"
    path.write_text("old")
    write_atomic(path, "caf\udce9\n")
    assert path.read_bytes() == b"caf\\udce9\n"
    assert [p.name for p in tmp_path.iterdir()] == ["g.csv"]


@pytest.mark.parametrize("cell", ["=1+1", "+1", "-1", "@SUM(A1)", "\t=1", "\r=1"])
def test_a_cell_a_spreadsheet_would_run_is_quoted(cell):
    assert csv_cell(cell) == "'" + cell and csv_cell("Ann") == "Ann" and csv_cell(3) == "3"
