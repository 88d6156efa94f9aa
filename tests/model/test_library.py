"""Built-in robots by name, planar chains, files."""

from __future__ import annotations

import pytest

import dhsym


def test_builtin_names_cover_the_lectures():
    names = set(dhsym.builtin_names())
    assert {
        "planar2r",
        "planar4r",
        "spong2r",
        "example1_rrp",
        "example4_6dof",
        "puma260",
        "puma560",
        "puma560_modified",
        "stanford",
        "scara",
        "cylindrical",
        "cartesian",
    } <= names


def test_load_by_name_is_case_insensitive():
    assert dhsym.load("PUMA560").name == "PUMA 560"
    assert dhsym.load("Planar-2R").n == 2


def test_load_from_file(tmp_path):
    p = tmp_path / "arm.yaml"
    p.write_text("joints: [{type: R, theta: q1, d: 0, a: 1, alpha: 0}]\n")
    assert dhsym.load(p).n == 1
    assert dhsym.load(str(p)).variables[0].name == "q1"


def test_unknown_name_lists_the_choices():
    with pytest.raises(dhsym.DHError, match="no built-in robot or table file 'puma9000'"):
        dhsym.load("puma9000")
    with pytest.raises(dhsym.DHError, match="cannot read table file"):
        dhsym.load("missing.yaml")


def test_planar_chains():
    assert dhsym.load("planar8r").n == 8
    with pytest.raises(dhsym.DHError, match="1 to 60 joints"):
        dhsym.planar_chain(0)


def test_puma260_keeps_l_and_t_symbolic():
    r = dhsym.load("puma260")
    names = {s.name for s in r.table.constants}
    assert names == {"l", "t"}
    assert "l" in str(r.arm_matrix()[0, 3]) or "l" in str(r.arm_matrix()[1, 3])


def test_a_mistyped_name_gets_the_closest_built_in():
    with pytest.raises(dhsym.DHError, match=r"'stanfrod': did you mean 'stanford'\?"):
        dhsym.load("stanfrod")
    with pytest.raises(dhsym.DHError) as err:
        dhsym.load_table("nothing-like-it")
    assert "did you mean" not in str(err.value) and "built-in robots are" in str(err.value)
