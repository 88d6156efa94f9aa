"""Every mistake kind, recognised by recomputing the key under it, with its diagnosis."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest
import sympy as sp

import dhsym
from dhsym.kinematics.transforms import link_word, plain_product
from dhsym.model.table import Convention

from .._keys import check_answer, load_key  # each key prepared once, as a grading worker does

ROOT = Path(__file__).resolve().parents[3]
SEED002 = ROOT / "tests" / "data" / "seeds" / "002_8d4894e47f2048cf.txt"
GENERIC = ROOT / "examples" / "homework" / "generic_modified_link.yaml"
PUMA = dhsym.load("puma560")


def text(M) -> str:
    return str(sp.Matrix(M).tolist())


def product(rows, convention, reverse=False):
    links = [list(link_word(r, convention)) for r in rows]
    return plain_product([e for link in (links[::-1] if reverse else links) for e in link])


def check(robot, question, answer):
    return check_answer(load_key(robot, question), answer)


def test_seed_002_slide_is_wrong_at_entry_2_4_with_the_sign_diagnosis():
    lines = SEED002.read_text(encoding="utf-8").splitlines()
    slide = next(ln for ln in lines if r"& d_i \sin \alpha_{i-1} \\" in ln)
    r = check(GENERIC, "A1", slide)
    assert r.verdict.value == "incorrect"
    assert [e for e in r.entries if not e.correct][0].row == 2
    assert [(e.row, e.col) for e in r.entries if not e.correct] == [(2, 4)]
    assert r.kinds == ("wrong_sign",) and r.diagnoses[0].entries == ((2, 4),)
    assert "Entry (2,4) has the wrong sign" in r.message
    fixed = slide.replace(r"& d_i \sin \alpha_{i-1} \\", r"& -d_i \sin \alpha_{i-1} \\")
    assert check(GENERIC, "A1", fixed).correct


def test_wrong_sign_of_one_term():
    T = sp.Matrix(PUMA.transform(0, 2).matrix)
    T[1, 3] = T[1, 3] - 2 * T[1, 3].args[0] if T[1, 3].is_Add else -T[1, 3]
    r = check("puma560", "T0_2", text(T))
    assert r.kinds == ("wrong_sign",) and r.diagnoses[0].entries == ((2, 4),)


def test_sin_cos_swapped():
    t1 = sp.Symbol("theta1", real=True)
    T = sp.Matrix(PUMA.transform(0, 1).matrix)
    T[0, 0] = sp.sin(t1)
    r = check("puma560", "T0_1", text(T))
    assert r.kinds == ("sin_cos_swapped",) and r.diagnoses[0].entries == ((1, 1),)


def test_degrees_read_as_radians():
    rows = [replace(rw, alpha=rw.alpha * 180 / sp.pi) for rw in PUMA.table.rows[:2]]
    r = check("puma560", "T0_2", text(product(rows, Convention.STANDARD)))
    assert r.kinds == ("degrees_as_radians",)


def test_index_shift_in_a_modified_table():
    from dhsym.checking.mistakes._row_mistakes import shifted as _shifted

    m = dhsym.load("puma560_modified")
    rows = _shifted(m.table.rows, 1, ("alpha", "a"))[:3]
    r = check("puma560_modified", "T0_3", text(product(rows, Convention.MODIFIED)))
    assert r.kinds == ("index_shift",)


def test_index_shift_in_the_generic_link_matrix():
    lines = SEED002.read_text(encoding="utf-8").splitlines()
    standard = next(ln for ln in lines if r"-\sin \theta_i \cos \alpha_i" in ln)
    r = check(GENERIC, "A1", standard)
    assert r.kinds[0] == "index_shift" and "alpha_i for alpha_im1" in r.diagnoses[0].detail
    assert "other_convention" in r.kinds


def test_offset_missing():
    ex4 = dhsym.load("example4_6dof")
    rows = [replace(rw, theta=rw.variable) for rw in ex4.table.rows[:3]]
    r = check("example4_6dof", "T0_3", text(product(rows, Convention.STANDARD)))
    assert r.kinds == ("offset_missing",) and "theta3 + pi/2" in r.message


@pytest.mark.parametrize(
    ("change", "kind", "row"),
    [
        ("| 2 | θ2 | 0 | a2 | 0 |", "single_wrong_row", 2),
        ("| 3 | θ3 | d3 | a3 | 90° |", "wrong_sign", 3),
    ],
)
def test_table_single_wrong_row_and_wrong_sign(change, kind, row):
    table = (
        "| j | θ | d | a | α |\n|---|---|---|---|---|\n| 1 | θ1 | 0 | 0 | 90° |\n"
        "| 2 | θ2 | 0 | a2 | 0 |\n| 3 | θ3 | d3 | a3 | -90° |\n| 4 | θ4 | d4 | 0 | 90° |\n"
        "| 5 | θ5 | 0 | 0 | -90° |\n| 6 | θ6 | 0 | 0 | 0 |"
    )
    assert check("puma560", "table", table).correct
    n = row + 1  # header and separator lines
    lines = table.splitlines()
    lines[n] = change if kind == "wrong_sign" else change.replace("a2", "0.5")
    r = check("puma560", "table", "\n".join(lines))
    assert r.kinds == (kind,) and r.diagnoses[0].rows == (row,)


def test_table_offset_missing_and_other_convention():
    ex4 = (
        "| i | a | alpha | d | theta |\n| 1 | 0 | pi/2 | d1 | θ1 |\n| 2 | a2 | 0 | 0 | θ2 |\n"
        "| 3 | 0 | pi/2 | 0 | θ3 |\n| 4 | 0 | -pi/2 | d4 | θ4 |\n| 5 | 0 | pi/2 | 0 | θ5 |\n"
        "| 6 | 0 | 0 | d6 | θ6 |"
    )
    r = check("example4_6dof", "table", ex4)
    assert r.kinds == ("offset_missing",) and r.diagnoses[0].rows == (3,)
    craig = dhsym.dump_table(dhsym.load_table("puma560_modified"))
    r = check("puma560", "table", craig)
    assert r.kinds == ("other_convention",)


def test_table_degrees_as_radians():
    table = (
        "| θ | d | a | α (deg) |\n| θ1 | 0 | 0 | 1.5708 |\n| θ2 | 0 | a2 | 0 |\n"
        "| θ3 | d3 | a3 | -1.5708 |\n| θ4 | d4 | 0 | 1.5708 |\n| θ5 | 0 | 0 | -1.5708 |\n"
        "| θ6 | 0 | 0 | 0 |"
    )
    r = check("puma560", "table", table)
    assert r.kinds == ("degrees_as_radians",)
