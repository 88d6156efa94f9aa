"""PoE files (``*.poe.yaml``) on the command line: the commands that take a robot read them."""

from __future__ import annotations

import json
from importlib import resources

import numpy as np
import pytest

from dhsym.cli.main import main
from dhsym.screws.poefile import read_poe


@pytest.fixture
def three_r() -> str:
    with resources.as_file(resources.files("dhsym.screws") / "robots") as folder:
        return str(folder / "lynch_park_3r.poe.yaml")


def test_show_reads_a_poe_file_as_a_dh_table(three_r: str, capsys) -> None:
    assert main(["show", three_r]) == 0
    out = capsys.readouterr().out
    assert out.startswith("# 3R spatial open chain (Lynch and Park)")
    assert "| 3 | $\\theta_{3}$ |" in out


def test_fk_of_a_poe_file_is_the_products_fk(three_r: str, capsys) -> None:
    assert main(["fk", three_r, "--q", "0.4,-0.7,1.2", "--rad", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    pose = np.array(data["matrix"], dtype=float)  # printed with 12 decimals
    expected = read_poe(three_r).function("fk_space")([0.4, -0.7, 1.2])
    np.testing.assert_allclose(pose, expected, atol=1e-11)


def test_a_bad_poe_file_names_file_row_and_field(tmp_path, capsys) -> None:
    bad = tmp_path / "bad.poe.yaml"
    bad.write_text("M: [{Tx: 1}]\njoints: [{w: [0, 0, 1], v: [0, 0, 1]}]\n")
    assert main(["show", str(bad)]) != 0
    assert f"{bad}: row 1, field v: a revolute joint's axis needs omega·v = 0" in (
        capsys.readouterr().err
    )
