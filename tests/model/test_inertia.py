"""Inertial parameters in rows and table files: reading, checking, writing back."""

from __future__ import annotations

import pytest
import sympy as sp

from dhsym.errors import DHError, TableError
from dhsym.model.inertia import LinkInertia
from dhsym.model.tablefile import dump_table, read_table_text

ROW = "{type: R, theta: q1, d: 0, a: l1, alpha: 0, %s}"


def table(extra: str, top: str = ""):
    return read_table_text(f"{top}\njoints: [{ROW % extra}]", file="arm.yaml")


def test_values_are_exact_and_expressions_go_through_the_parser():
    t = table(
        "m: m1, r: [lc1 - l1, 0, 0], I: [0.1, 0.2, 0.25, 0, 0, 0.01], Tc: 0.4",
        "gravity: [0, -g, 0]",
    )
    L = t.rows[0].inertia
    assert L.r[0] == sp.Symbol("lc1", real=True) - sp.Symbol("l1", real=True)
    assert L.I[0, 2] == L.I[2, 0] == sp.Rational(1, 100)
    assert L.Tc == (sp.Rational(2, 5), -sp.Rational(2, 5))
    assert t.gravity == (0, -sp.Symbol("g", real=True), 0)


def test_three_by_three_inertia_and_default_gravity():
    t = table("m: 1, I: [[1, 0, 0], [0, 1, 0], [0, 0, 1.5]]")
    assert t.rows[0].inertia.I == sp.diag(1, 1, sp.Rational(3, 2))
    assert t.gravity == (0, 0, sp.Rational(-981, 100))


@pytest.mark.parametrize(
    ("extra", "field", "words"),
    [
        ("m: -2", "m", "negative"),
        ("m: 1, I: [1, 1, -1]", "I", "semi-definite"),
        ("m: 1, I: [1, 1, 3]", "I", "triangle"),
        ("m: 1, I: [[1, 0.2, 0], [0, 1, 0], [0, 0, 1]]", "I", "not symmetric"),
        ("m: 1, r: [1, 2]", "r", "3 values"),
        ("m: 1, I: [1, 2, 3, 4]", "I", "6 values"),
        ("m: 1, Tc: [1, 2, 3]", "Tc", "2 values"),
        ("m: __import__('os')", "m", ""),
    ],
)
def test_bad_values_name_file_row_and_field(extra, field, words):
    with pytest.raises(DHError) as err:  # a TableError, or the parser's ParseError
        table(extra)
    assert err.value.file == "arm.yaml" and err.value.row == 1 and err.value.field == field
    assert words in str(err.value)


def test_unknown_key_is_refused():
    with pytest.raises(TableError, match="unknown column 'mass'"):
        table("mass: 2")


def test_published_data_that_breaks_the_triangle_inequality():
    t = table("m: 1, I: [1, 1, 3]", "physical: false")
    assert not t.physical and t.rows[0].inertia.I[2, 2] == 3
    with pytest.raises(TableError, match="semi-definite"):
        table("m: 1, I: [1, 1, -3]", "physical: false")


def test_writing_a_table_back_keeps_the_inertial_parameters():
    t = table(
        "m: 17.4, r: [-0.3638, 0.006, lc2], I: [0.13, 0.524, 0.539, 0, 0, 0], Jm: 200e-6, "
        "G: -62.6111, B: 1.48e-3, Tc: [0.395, -0.435]",
        "gravity: [0, -g, 0]",
    )
    text = dump_table(t)
    assert "m: 17.4" in text and "Jm: 0.0002" in text and "gravity: [0, -g, 0]" in text
    assert read_table_text(text) == t


def test_puma560_carries_the_published_parameters():
    from dhsym.model.library import builtin_table

    t = builtin_table("puma560")
    assert [r.inertia.m for r in t.rows] == [
        0,
        sp.Rational(87, 5),
        sp.Rational(24, 5),
        sp.Rational(41, 50),
        sp.Rational(17, 50),
        sp.Rational(9, 100),
    ]
    assert read_table_text(dump_table(t)) == t


def test_textbook_set_and_substitution():
    L = LinkInertia.textbook(3)
    assert L.m == sp.Symbol("m3", real=True) and L.I.is_symmetric()
    num = L.subs({s: 1 for s in L.free_symbols})
    assert num.m == 1 and num.I[0, 1] == 1


# --- one body of several: the parallel-axis theorem ------------------------------------------


def test_two_point_masses_combine_as_computed_by_hand():
    """1 kg at (1, 0, 0) and 3 kg at (0, 2, 0): mass 4, centre (1/4, 3/2, 0); by hand, the
    inertia about the origin, Σ m (|p|² E − p pᵀ) = diag(12, 1, 13), less the whole mass's
    about the origin, 4 (|c|² E − c cᵀ), is [[3, 3/2, 0], [3/2, 3/4, 0], [0, 0, 15/4]]."""
    zero = sp.zeros(3)
    both = LinkInertia.combine([LinkInertia(1, (1, 0, 0), zero), LinkInertia(3, (0, 2, 0), zero)])
    half = sp.Rational(1, 2)
    assert both.m == 4
    assert both.r == (sp.Rational(1, 4), 3 * half, 0)
    assert both.I == sp.Matrix(
        [[3, 3 * half, 0], [3 * half, sp.Rational(3, 4), 0], [0, 0, 15 * half / 2]]
    )
    assert both.I.is_symmetric() and not both.has_drive
    both.check()  # a rigid body: positive semi-definite, the triangle inequality holds


def test_own_inertias_add_and_symbols_stay_exact():
    m, l = sp.symbols("m l", positive=True)  # noqa: E741 (a length)
    rod = LinkInertia(m, (l, 0, 0), sp.diag(0, m * l**2 / 12, m * l**2 / 12))
    hub = LinkInertia(m, (-l, 0, 0), sp.diag(1, 2, 3))
    whole = LinkInertia.combine([rod, hub])
    assert whole.m == 2 * m and whole.r == (0, 0, 0)
    assert sp.expand(
        whole.I - sp.diag(1, 2 + m * l**2 / 12 + 2 * m * l**2, 3 + m * l**2 / 12 + 2 * m * l**2)
    ) == sp.zeros(3)


def test_one_part_is_itself_and_massless_parts_sit_at_the_origin():
    L = LinkInertia(2, (1, 2, 3), sp.diag(1, 2, 3))
    assert LinkInertia.combine([L]) == L
    empty = LinkInertia.combine([])
    assert empty.m == 0 and empty.r == (0, 0, 0) and empty.I == sp.zeros(3)


def test_inertia_about_the_origin_is_the_parallel_axis_theorem():
    L = LinkInertia(2, (0, 0, 3), sp.diag(1, 1, 1))
    assert L.inertia_about((0, 0, 0)) == sp.diag(19, 19, 1)  # 1 + 2·3² about x and y
    assert L.inertia_about(L.r) == L.I


def test_a_part_with_a_drive_is_refused():
    motor = LinkInertia(1, (0, 0, 0), sp.zeros(3), Jm=sp.Rational(1, 1000))
    with pytest.raises(TableError, match="part 2 has a drive"):
        LinkInertia.combine([LinkInertia(1, (0, 0, 0), sp.zeros(3)), motor])


# A hostile campaign (issue 33, item 6): every input is refused by the reader with the
# file, the row, the field and the offending symbol or value in the message.
CAMPAIGN = [
    # complex values, in every inertial field
    ("d: 0, a: l2, I: [0, sqrt(-4), 0.1]", 2, "I", "2*I"),
    ("d: 0, a: l2, m: sqrt(-1)", 2, "m", "I is complex"),
    ("d: 0, a: l2, m: 1 + sqrt(-1)*l1", 2, "m", "I*l1"),
    ("d: 0, a: l2, m: acos(2)", 2, "m", "acos(2)"),
    ("d: 0, a: l2, m: asin(3)", 2, "m", "asin(3)"),
    ("d: 0, a: l2, m: (-1)**(1/3)", 2, "m", "(-1)**(1/3)"),
    ("d: 0, a: l2, r: [0, sqrt(-1), 0]", 2, "r", "I is complex"),
    ("d: 0, a: l2, I: [[1, sqrt(-1), 0], [sqrt(-1), 1, 0], [0, 0, 1]]", 2, "I", "I is complex"),
    ("d: 0, a: l2, G: sqrt(-1)", 2, "G", "I is complex"),
    ("d: 0, a: l2, B: sqrt(-2)", 2, "B", "sqrt(2)*I"),
    ("d: 0, a: l2, Tc: sqrt(-1)", 2, "Tc", "I is complex"),
    ("d: 0, a: l2, Tc: [0.1, sqrt(-1)]", 2, "Tc", "I is complex"),
    ("d: 0, a: l2, Jm: sqrt(-3)", 2, "Jm", "sqrt(3)*I"),
    # joint variables in inertial parameters
    ("d: 0, a: l2, m: 2 + sin(theta2)", 2, "m", "theta2"),
    ("d: 0, a: l2, m: 2 + sin(theta1)", 2, "m", "theta1"),
    ("d: 0, a: l2, r: [theta1 - 1, 0, 0]", 2, "r", "theta1"),
    ("d: 0, a: l2, I: [theta2, 1, 1]", 2, "I", "theta2"),
    ("d: 0, a: l2, G: theta2", 2, "G", "theta2"),
    ("d: 0, a: l2, B: cos(theta1)", 2, "B", "theta1"),
    ("d: 0, a: l2, Tc: theta1", 2, "Tc", "theta1"),
    ("d: 0, a: l2, Jm: theta2**2", 2, "Jm", "theta2"),
    # names of rates and accelerations
    ("d: 0, a: l2, m: thetadot1", 2, "m", "thetadot1"),
    ("d: 0, a: l2, m: thetaddot2", 2, "m", "thetaddot2"),
    ("d: 0, a: l2, r: [thetadot2, 0, 0]", 2, "r", "thetadot2"),
    ("d: 0, a: l2, I: [1, 1, thetaddot1]", 2, "I", "thetaddot1"),
    ("d: 0, a: thetaddot2", 2, "a", "thetaddot2"),
    ("d: thetadot1, a: l2", 2, "d", "thetadot1"),
    ("theta: theta2 + thetadot1, d: 0, a: l2", 2, "theta", "thetadot1"),
    # beyond the range of a double (written back as .inf, which the reader refuses)
    ("d: 0, a: l2, m: 1e308*10", 2, "m", "1.0E+309"),
    ("d: 0, a: l2, r: [-1e308*10, 0, 0]", 2, "r", "-1.0E+309"),
    ("d: 0, a: l2, G: 1e308*10", 2, "G", "1.0E+309"),
    ("d: 1e308*10, a: l2", 2, "d", "1.0E+309"),
    # complex DH entries
    ("d: 0, a: sqrt(-1)", 2, "a", "I is complex"),
    ("d: acos(2), a: l2", 2, "d", "acos(2)"),
]


def _campaign_text(row2: str, top: str = "") -> str:
    row1 = "{type: R, theta: theta1, d: 0, a: l1, alpha: 0, m: m1}"
    head = "type: R, alpha: 0" if "theta:" in row2 else "type: R, theta: theta2, alpha: 0"
    row2 = f"{{{head}, {row2}}}"
    return f"{top}\njoints:\n  - {row1}\n  - {row2}\n"


@pytest.mark.parametrize(("row2", "row", "field", "shown"), CAMPAIGN)
def test_campaign_inputs_are_refused_with_file_row_field_and_symbol(row2, row, field, shown):
    with pytest.raises(TableError) as err:
        read_table_text(_campaign_text(row2), file="bad.yaml")
    e = err.value
    assert (e.file, e.row, e.field) == ("bad.yaml", row, field)
    assert shown in str(e) and str(e).startswith(f"bad.yaml: row {row}, field {field}: ")


@pytest.mark.parametrize(
    ("top", "shown"),
    [("gravity: [0, -thetaddot1, 0]", "thetaddot1"), ("gravity: [0, sqrt(-96), 0]", "I")],
)
def test_gravity_is_real_and_free_of_rates(top, shown):
    with pytest.raises(TableError) as err:
        read_table_text(_campaign_text("d: 0, a: l2", top), file="bad.yaml")
    assert err.value.field == "gravity" and shown in str(err.value)


@pytest.mark.parametrize("row2", [c[0] for c in CAMPAIGN[::6]])
def test_the_command_line_exits_2_not_70(row2, tmp_path, capsys):
    from dhsym.cli.main import main

    path = tmp_path / "bad.yaml"
    path.write_text(_campaign_text(row2), encoding="utf-8")
    assert main(["show", str(path)]) == 2
    err = capsys.readouterr().err
    assert "bad.yaml: row 2, field" in err and "internal error" not in err


def test_python_inertials_are_checked_as_the_file_reader_checks_them():
    with pytest.raises(TableError, match="field m: I is complex"):
        LinkInertia(sp.sqrt(-1), (0, 0, 0), sp.zeros(3))
    with pytest.raises(TableError, match="field I: 2\\*I is complex"):
        LinkInertia(1, (0, 0, 0), sp.diag(1, 2 * sp.I, 1))
    with pytest.raises(TableError, match="field Tc: .*beyond the range"):
        LinkInertia(1, (0, 0, 0), sp.zeros(3), Tc=(sp.Integer(10) ** 309, 0))
    from dhsym.model.table import DHRow, DHTable

    q1, q1dot = sp.symbols("q1 qdot1", real=True)
    bad = LinkInertia(2 + sp.sin(q1), (0, 0, 0), sp.zeros(3))
    with pytest.raises(TableError, match="row 1, field m: uses q1, the joint variable q1"):
        DHTable.from_rows([DHRow.revolute(q1, a=1, inertia=bad)])
    rate = LinkInertia(q1dot, (0, 0, 0), sp.zeros(3))
    with pytest.raises(TableError, match="field m: uses qdot1, the rate of the joint variable"):
        DHTable.from_rows([DHRow.revolute(q1, a=1, inertia=rate)])


def test_a_substituted_value_that_makes_a_parameter_complex_is_refused():
    t = table("m: sqrt(k - 1)", "values: {k: 0.5}")
    with pytest.raises(TableError, match="complex"):
        t.substituted()


@pytest.mark.parametrize("k", [0.5, 2])
def test_exporters_refuse_a_value_that_makes_an_entry_complex(k):
    import dhsym
    from dhsym.export.program import fk_program, rne_program

    t = read_table_text(
        "joints:\n"
        "  - {type: R, theta: q1, d: 0, a: sqrt(k - 1), alpha: 0, m: 1, I: [0, 0.1, 0.1]}\n"
        "  - {type: R, theta: q2, d: 0, a: acos(k), alpha: 0, m: 1, I: [0, 0.1, 0.1]}\n"
        "values: {k: 1}\n"
    )
    assert fk_program(dhsym.Robot(t)).outputs  # k = 1: real
    with pytest.raises(TableError, match="complex"):
        fk_program(dhsym.Robot(t.with_values({"k": k})))
    with pytest.raises(TableError, match="complex"):
        rne_program(dhsym.Robot(t), values={"k": k})
