"""Table files: the documented format, round trips, and every bad input with its message."""

from __future__ import annotations

import os

import pytest
import sympy as sp

import dhsym
from dhsym.errors import TableError
from dhsym.model.tablefile import dump_table, read_table, read_table_text

GOOD = """
name: Planar 2R
convention: standard
angles: deg
joints:
  - {type: R, theta: theta1, d: 0, a: a1, alpha: 0}
  - {type: R, theta: theta2, d: 0, a: a2, alpha: 0}
values: {a1: 1.0, a2: 0.8}
"""


def _err(text: str, file: str = "arm.yaml") -> str:
    with pytest.raises(dhsym.DHError) as info:
        read_table_text(text, file=file)
    return str(info.value)


def test_reads_the_documented_format():
    t = read_table_text(GOOD)
    assert t.name == "Planar 2R" and t.n == 2
    assert t.value_map == {
        sp.Symbol("a1", real=True): 1,
        sp.Symbol("a2", real=True): sp.Rational(4, 5),
    }


def test_degrees_become_exact_radians():
    t = read_table_text("angles: deg\njoints: [{type: R, theta: q3 + 90, d: 0, a: 0, alpha: -90}]")
    q3 = sp.Symbol("q3", real=True)
    assert t.rows[0].theta == q3 + sp.pi / 2
    assert t.rows[0].alpha == -sp.pi / 2
    assert t.rows[0].offset == sp.pi / 2


def test_offset_column_and_symbolic_twist():
    t = read_table_text(
        "angles: deg\njoints: [{type: R, theta: q1, d: 0, a: 0, alpha: alpha1, offset: 180}]"
    )
    assert t.rows[0].theta == sp.Symbol("q1", real=True) + sp.pi
    assert t.rows[0].alpha == sp.Symbol("alpha1", real=True)


@pytest.mark.parametrize("name", dhsym.builtin_names())
def test_builtin_round_trip(name):
    t = dhsym.builtin_table(name)
    back = read_table_text(dump_table(t))
    assert back.rows == t.rows and back.values == t.values and back.convention == t.convention


def test_every_builtin_cites_its_source():
    for name in dhsym.builtin_names():
        assert len(dhsym.builtin_table(name).source) > 20, name


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        (
            "joints: [{type: R, theta: q1, d: 0, a: 0, alfa: 0}]",
            "arm.yaml: row 1, field alfa: unknown column 'alfa'",
        ),
        (
            "joints: [{type: R, theta: q1, d: 0, a: 0}]",
            "arm.yaml: row 1, field alpha: missing column 'alpha'",
        ),
        (
            "convention: craigish\njoints: [{type: R, theta: q1, d: 0, a: 0, alpha: 0}]",
            "arm.yaml: field convention: unknown convention 'craigish'",
        ),
        (
            "angles: grad\njoints: [{type: R, theta: q1, d: 0, a: 0, alpha: 0}]",
            "arm.yaml: field angles: unknown angle unit 'grad'",
        ),
        (
            "joints: [{type: R, theta: 0, d: 0, a: 1, alpha: 0}]",
            "arm.yaml: row 1, field theta: revolute joint has no variable in theta",
        ),
        (
            "joints: [{type: R, theta: q1 + q2, d: 0, a: 1, alpha: 0}]",
            "arm.yaml: row 1, field theta: theta = q1 + q2 has 2 candidate joint variables",
        ),
        (
            "joints: [{type: R, theta: 0, d: d1, a: 1, alpha: 0}]",
            "d = d1 has a symbol: is this joint prismatic (type: P)?",
        ),
        (
            "joints: [{type: P, theta: q1, d: 0, a: 1, alpha: 0}]",
            "arm.yaml: row 1, field d: prismatic joint has no variable in d (got 0); theta = q1",
        ),
        (
            "joints: [{type: R, theta: q1, d: q1, a: 1, alpha: 0}]",
            "arm.yaml: row 1, field d: joint variable q1 of this revolute joint appears in d",
        ),
        (
            "joints: [{type: R, theta: q1, d: 0, a: 0, alpha: 90}]",
            "arm.yaml: row 1, field alpha: angle 90 is larger than 2*pi radians: is this table in "
            "degrees? (set angles: deg)",
        ),
        (
            "joints: [{type: R, theta: q1, d: .nan, a: 0, alpha: 0}]",
            "arm.yaml: row 1, field d: non-finite number",
        ),
        (
            "joints: [{type: R, theta: q1, d: .inf, a: 0, alpha: 0}]",
            "arm.yaml: row 1, field d: non-finite number",
        ),
        ("joints: []", "arm.yaml: field joints: the table has no joints"),
        ("name: x", "arm.yaml: field joints: missing 'joints'"),
        (
            "joints: [{type: Q, theta: q1, d: 0, a: 0, alpha: 0}]",
            "arm.yaml: row 1, field type: unknown joint type 'Q'",
        ),
        (
            "joints: [{type: R, theta: q1, d: 0, a: 0, alpha: 0}, "
            "{type: R, theta: q1, d: 0, a: 0, alpha: 0}]",
            "arm.yaml: row 2, field theta: joint variable q1 is already the variable of row 1",
        ),
        (
            "joints: [{type: R, theta: q1, d: 0, a: 0, alpha: 0}]\nvalues: {a9: 1}",
            "arm.yaml: field values: symbol a9 does not appear in the table",
        ),
        (
            "joints: [{type: R, theta: q1, d: 0, a: a1, alpha: 0}]\nvalues: {q1: 1}",
            "arm.yaml: field values: q1 is a joint variable",
        ),
        (
            "joints: [{type: R, theta: q1, d: 0, a: a1, alpha: 0}]\nvalues: {a1: x}",
            "arm.yaml: field values.a1: value of a1 must be a number",
        ),
        (
            "joints: [{type: R, theta: q1, d: '__import__(\"os\")', a: 0, alpha: 0}]",
            "arm.yaml: row 1, field d: name '__import__' at column 1",
        ),
        (
            "joints: [{type: R, theta: q1, d: 'open(\"x\")', a: 0, alpha: 0}]",
            "arm.yaml: row 1, field d: reserved name 'open'",
        ),
        (
            "joints: [{type: R, theta: q1, d: 0, a: true, alpha: 0}]",
            "arm.yaml: row 1, field a: expected a number or expression, got True",
        ),
        (
            "joints: [{type: R, theta: q1, d: 0, a: [1], alpha: 0}]",
            "arm.yaml: row 1, field a: expected a number or expression, got list",
        ),
        ("joints: {type: R}", "arm.yaml: field joints: 'joints' must be a list of rows"),
        ("joints: [{type: R, theta: q1, d: 0, a: 0, alpha: 0}", "arm.yaml: not valid YAML (line"),
        ("- 1\n- 2", "arm.yaml: expected a mapping with a 'joints' list"),
        (
            "joints: [{type: R, theta: q1, d: 0, a: 0, alpha: 0, limits: [10, -10]}]",
            "arm.yaml: row 1, field limits: limits [10, -10]: low is above high",
        ),
        (
            "joints: [{type: R, theta: q1, d: 0, a: 0, alpha: 0}]\nbase: [{Qz: 1}]",
            "arm.yaml: field base: step 1: unknown transform 'Qz'",
        ),
        (
            "angles: deg\njoints: [{type: R, theta: q1 + pi, d: 0, a: 0, alpha: 0}]",
            "arm.yaml: row 1: angles are in degrees but pi contains pi",
        ),
        (
            "joints: [{type: R, theta: q1, d: 0, a: 0, alpha: 0}]\ncolour: red",
            "arm.yaml: field colour: unknown key 'colour'",
        ),
    ],
)
def test_bad_input_names_file_row_and_field(text, expected):
    assert expected in _err(text)


def test_yaml_never_constructs_python_objects(tmp_path):
    msg = _err("joints: !!python/object/apply:os.system ['echo hacked']")
    assert "not valid YAML" in msg


def test_missing_and_binary_and_huge_files(tmp_path):
    with pytest.raises(TableError, match="cannot read table file"):
        read_table(tmp_path / "nope.yaml")
    junk = tmp_path / "junk.yaml"
    junk.write_bytes(b"\xff\xfe\x00\x01" * 10)
    with pytest.raises(TableError, match="junk.yaml: not a UTF-8 text file"):
        read_table(junk)
    big = tmp_path / "big.yaml"
    big.write_text("# " + "x" * 2_000_000)
    with pytest.raises(TableError, match="big.yaml: table file is 2000002 bytes"):
        read_table(big)


def test_file_path_appears_in_errors(tmp_path):
    p = tmp_path / "bad.yaml"
    p.write_text("joints: [{type: R, theta: q1, d: 0, a: 0, alpha: 0, twist: 1}]")
    with pytest.raises(TableError, match=r"bad\.yaml: row 1, field twist"):
        read_table(p)


def _alias_bomb(levels: int = 8) -> str:
    """About 400 bytes of YAML whose value ``name`` expands to 10**levels strings."""
    lines = ["l0: &l0 [x, x, x, x, x, x, x, x, x, x]"]
    for k in range(1, levels):
        lines.append(f"l{k}: &l{k} [" + ", ".join([f"*l{k - 1}"] * 10) + "]")
    return "\n".join(lines) + f"\nname: *l{levels - 1}\njoints: []\n"


def test_alias_bomb_table_is_refused_before_it_expands(tmp_path):
    bomb = _alias_bomb()
    assert len(bomb) < 600
    p = tmp_path / "bomb.yaml"
    p.write_text(bomb)
    with pytest.raises(TableError, match=r"bomb\.yaml: line \d+: the YAML is too large"):
        read_table(p)


def test_deep_nesting_and_huge_integers_are_clear_errors(tmp_path):
    assert "nested more than 64 levels" in _err("joints: " + "[" * 5000 + "]" * 5000)
    msg = _err("joints: [{type: R, theta: q1, d: " + "9" * 5000 + ", a: 0, alpha: 0}]")
    assert "arm.yaml: line 1: a number with 5000 digits" in msg


def test_special_files_are_refused_without_reading(tmp_path):
    with pytest.raises(TableError, match="/dev/zero: table file is not a regular file"):
        read_table("/dev/zero")
    fifo = tmp_path / "pipe.yaml"
    os.mkfifo(fifo)
    with pytest.raises(TableError, match="pipe.yaml: table file is not a regular file"):
        read_table(fifo)


def test_qlim_is_read_as_limits() -> None:
    row = "{type: R, theta: q1, d: 0, a: 1, alpha: 0, qlim: [-1, 2]}"
    text = f"convention: standard\njoints:\n  - {row}\n"
    t = dhsym.read_table_text(text)
    assert tuple(float(v) for v in t.rows[0].limits) == (-1.0, 2.0)
    with pytest.raises(dhsym.TableError, match="not both"):
        dhsym.read_table_text(text.replace("qlim", "limits: [0, 1], qlim"))
