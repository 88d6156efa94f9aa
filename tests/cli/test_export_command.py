"""``dhsym export`` writes only where told: a prefix is a name, and no link in the ``-o``
folder is followed (the campaign overwrote a file outside through one)."""

from __future__ import annotations

import os

import pytest

from dhsym.cli.main import main

#: the file each language writes first for ``--prefix arm``
FIRST = {
    "c": "arm.h",
    "cpp": "arm.hpp",
    "matlab": "arm_fk.m",
    "rust": "arm.rs",
    "python": "arm.py",
    "urdf": "arm.urdf",
}


def _export(lang: str, out, *extra: str) -> int:
    return main(["export", "planar2r", "--lang", lang, "--prefix", "arm", "-o", str(out), *extra])


@pytest.mark.parametrize("lang", sorted(FIRST))
def test_a_planted_link_is_refused_and_its_target_kept(lang, tmp_path, capsys):
    outside = tmp_path / "outside.txt"
    outside.write_text("keep me\n")
    folder = tmp_path / "gen"
    folder.mkdir()
    (folder / FIRST[lang]).symlink_to(outside)
    assert _export(lang, folder) == 2
    err = capsys.readouterr().err
    assert str(folder / FIRST[lang]) in err and "symbolic link" in err
    assert outside.read_text() == "keep me\n"
    assert sorted(p.name for p in folder.iterdir()) == [FIRST[lang]]  # nothing else written


def test_a_link_among_the_files_stops_all_of_them(tmp_path, capsys):
    outside = tmp_path / "outside.txt"
    outside.write_text("keep me\n")
    folder = tmp_path / "gen"
    folder.mkdir()
    (folder / "arm.c").symlink_to(outside)  # the second file C writes
    assert _export("c", folder) == 2
    assert "arm.c is a symbolic link" in capsys.readouterr().err
    assert not (folder / "arm.h").exists() and outside.read_text() == "keep me\n"


def test_a_hard_link_is_refused(tmp_path, capsys):
    outside = tmp_path / "outside.txt"
    outside.write_text("keep me\n")
    folder = tmp_path / "gen"
    folder.mkdir()
    os.link(outside, folder / "arm.py")
    assert _export("python", folder) == 2
    assert "hard link" in capsys.readouterr().err and outside.read_text() == "keep me\n"


def test_a_urdf_file_named_by_o_is_not_followed(tmp_path, capsys):
    outside = tmp_path / "outside.txt"
    outside.write_text("keep me\n")
    (tmp_path / "arm.urdf").symlink_to(outside)
    assert main(["export", "planar2r", "--lang", "urdf", "-o", str(tmp_path / "arm.urdf")]) == 2
    assert "symbolic link" in capsys.readouterr().err and outside.read_text() == "keep me\n"


@pytest.mark.parametrize("lang", sorted(FIRST))
@pytest.mark.parametrize("prefix", ["../../escaped", "/tmp/abs"])
def test_a_prefix_that_is_a_path_is_refused(lang, prefix, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    argv = ["export", "planar2r", "--lang", lang, "--prefix", prefix, "-o", "gen/sub"]
    assert main(argv) == 2
    assert f"prefix {prefix!r} is not a name" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.rglob("*")) == []  # nothing written, no folder


def test_existing_files_are_rewritten_and_a_linked_folder_is_used(tmp_path):
    real = tmp_path / "real"
    real.mkdir()
    (real / "arm.c").write_text("old\n")
    (tmp_path / "gen").symlink_to(real, target_is_directory=True)  # -o itself: the user's
    assert _export("c", tmp_path / "gen") == 0
    assert "void arm_fk" in (real / "arm.c").read_text()
    assert (real / "arm.c").stat().st_mode & 0o777 in (0o644, 0o600, 0o640, 0o664)


def test_reserved_prefixes_are_suffixed_on_the_command_line(tmp_path):
    assert (
        main(["export", "planar2r", "--lang", "cpp", "--prefix", "log", "-o", str(tmp_path)]) == 0
    )
    assert (
        main(["export", "planar2r", "--lang", "python", "--prefix", "os", "-o", str(tmp_path)]) == 0
    )
    assert sorted(p.name for p in tmp_path.iterdir()) == ["log_.hpp", "os_.py"]
