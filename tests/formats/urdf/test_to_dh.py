"""A URDF chain as a DH table: real robot descriptions against an independent chain product,
inertials against pinocchio, and chains that a DH table cannot hold."""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.errors import FormatError, GeometryError
from dhsym.formats.urdf.to_dh import chain_from_urdf, import_urdf
from dhsym.kinematics.chain import KinematicChain
from dhsym.model.table import Elementary

from .support import DATA, ROBOTS, joint, long_chain, urdf, urdf_pose

# --- real robots ------------------------------------------------------------------------------


@pytest.mark.parametrize("convention", ["standard", "modified"])
@pytest.mark.parametrize(("file", "tip", "n"), ROBOTS)
def test_fk_equals_the_urdf_chain(file: str, tip: str, n: int, convention: str) -> None:
    robot = chain_from_urdf(DATA / file, tip=tip, convention=convention)
    assert robot.table.n == n
    rng = np.random.default_rng(7)
    for q in [np.zeros(n), *rng.uniform(-math.pi, math.pi, (6, n))]:
        assert np.abs(robot.fk(q) - urdf_pose(DATA / file, tip, q)).max() < 1e-9


def test_ur5_is_the_ur_dh_table_with_exact_decimals() -> None:
    imp = import_urdf(DATA / "ur5_robot.urdf", tip="tool0")
    rows = imp.table.rows
    assert [r.d for r in rows] == [
        sp.Rational("0.089159"),
        0,
        0,
        sp.Rational("0.10915"),
        sp.Rational("0.09465"),
        sp.Rational("0.0823"),
    ]
    # issue 32, item 5: Universal Robots' published table (a2, a3 < 0, α1 = α4 = 90°,
    # α5 = −90°, no offsets of θ), frame 0 turned by 180° in the base
    assert [r.a for r in rows] == [0, -sp.Rational("0.425"), -sp.Rational("0.39225"), 0, 0, 0]
    half = sp.pi / 2
    assert [r.alpha for r in rows] == [half, 0, 0, half, -half, 0]
    assert [r.theta for r in rows] == list(imp.table.variables)
    assert imp.table.base == (Elementary("R", "z", sp.pi),) and imp.table.tool == ()
    assert rows[0].label == "shoulder_pan_joint"
    assert rows[0].limits == (sp.Rational("-6.28318530718"), sp.Rational("6.28318530718"))
    assert "1.57079632679 as ±π/2" in imp.table.warnings[0]
    assert any("parallel" in s for s in imp.steps)


def test_continuous_joints_have_no_limits_and_inertials_are_recorded() -> None:
    imp = import_urdf(DATA / "kinova.urdf", tip="j2s6s200_end_effector")
    assert imp.table.rows[0].limits is None  # continuous
    assert imp.table.rows[1].limits is not None
    assert sum(bool(i.mass > 0) for _, i in imp.inertials) == 7  # the base link and the 6 arm links
    assert all(bool(i.mass >= 0) for _, i in imp.inertials)


def test_branching_tree_lists_the_tips() -> None:
    with pytest.raises(FormatError, match="panda_leftfinger .*panda_rightfinger"):
        import_urdf(DATA / "panda.urdf")


def test_mimic_joint_on_the_chain_is_refused() -> None:
    with pytest.raises(FormatError, match="finger_joint2.*mimics joint 'panda_finger_joint1'"):
        import_urdf(DATA / "panda.urdf", tip="panda_rightfinger")


def test_base_link_and_text_input() -> None:
    text = (DATA / "ur5_robot.urdf").read_text()
    r = chain_from_urdf(text, tip="wrist_3_link", base="shoulder_link")
    assert r.table.n == 5
    with pytest.raises(FormatError, match="not above"):
        import_urdf(text, tip="base", base="wrist_3_link")


def test_load_reads_urdf_paths() -> None:
    r = dhsym.load(DATA / "ur5_robot.urdf", tip="tool0")
    assert r.table.n == 6 and r.table.source.startswith("URDF ur5_robot.urdf")


def test_snap_angles_false_keeps_the_decimals() -> None:
    imp = import_urdf(DATA / "ur5_robot.urdf", tip="tool0", snap_angles=False)
    assert not any("angles" in w for w in imp.table.warnings)
    snapped = import_urdf(DATA / "ur5_robot.urdf", tip="tool0")
    assert any("angles" in w for w in snapped.table.warnings)


# --- inertials: the DH table's dynamics against pinocchio on the URDF itself -------------------


def _chain_only(text: str, tip: str) -> str:
    """The URDF without the links that hang behind moving joints off the chain to ``tip``
    (the Panda's fingers), so that pinocchio sees the same bodies as the DH table."""
    root = ET.fromstring(text)
    parent = {j.find("child").get("link"): j for j in root.findall("joint")}
    chain, link = set(), tip
    while link in parent:
        chain.add(parent[link].get("name"))
        link = parent[link].find("parent").get("link")
    cut = {
        j.find("child").get("link")
        for j in root.findall("joint")
        if j.get("type") != "fixed" and j.get("name") not in chain
    }
    for j in root.findall("joint"):  # cut links and everything below them
        if j.find("parent").get("link") in cut:
            cut.add(j.find("child").get("link"))
    for el in list(root):
        if (el.tag == "link" and el.get("name") in cut) or (
            el.tag == "joint" and el.find("child").get("link") in cut
        ):
            root.remove(el)
    return ET.tostring(root, encoding="unicode")


@pytest.mark.slow
@pytest.mark.parametrize("convention", ["standard", "modified"])
@pytest.mark.parametrize(
    ("file", "tip"), [("panda.urdf", "panda_hand"), ("ur5_robot.urdf", "tool0")]
)
def test_inertials_give_pinocchios_dynamics(file: str, tip: str, convention: str) -> None:
    pin = pytest.importorskip("pinocchio")
    text = (DATA / file).read_text()
    robot = dhsym.from_urdf(text, tip=tip, convention=convention)
    assert all(row.inertia is not None for row in robot.table.rows)
    model = pin.buildModelFromXML(_chain_only(text, tip))
    data = model.createData()
    assert model.nq == robot.n
    rng = np.random.default_rng(7)
    for _ in range(3):
        q, qd, qdd = (rng.uniform(-1.5, 1.5, robot.n) for _ in range(3))
        tau = pin.rnea(model, data, q, qd, qdd)
        np.testing.assert_allclose(robot.rne(q, qd, qdd), tau, atol=1e-9, rtol=0)
        M = pin.crba(model, data, q)
        M = np.triu(M) + np.triu(M, 1).T
        np.testing.assert_allclose(robot.inertia(q), M, atol=1e-9, rtol=0)


def test_inertials_stay_exact_and_drops_are_named() -> None:
    imp = import_urdf(DATA / "ur5_robot.urdf", tip="tool0")
    link2 = imp.table.rows[1].inertia
    assert link2 is not None and link2.m == sp.Rational(8393, 1000)  # mass="8.393"
    assert any("base_link (the base" in w for w in imp.table.warnings)
    panda = import_urdf(DATA / "panda.urdf", tip="panda_hand")
    assert any("panda_leftfinger" in w for w in panda.table.warnings)


@pytest.mark.parametrize(("file", "tip", "n"), ROBOTS)
def test_measured_numbers_print_as_decimals_and_read_back_equal(file: str, tip: str, n: int):
    # issue 32, item 7: the SO-100 once gave d1 = 15726572319968823/132156387503562500, a2 =
    # sqrt(134560049)/100000, θ2 + atan2(4840101082143211/331871697081907052, 1) and
    # inertias as 26-digit fractions; what the frame geometry makes of a URDF's decimals is
    # written as a decimal of 12 significant digits, the decimals of the URDF as written
    from dhsym.formats.urdf import table_yaml
    from dhsym.model.tablefile import read_table_text

    for convention in ("standard", "modified"):
        imp = import_urdf(DATA / file, tip=tip, convention=convention)
        text = table_yaml(imp)
        body = "\n".join(line for line in text.splitlines() if not line.startswith("#"))
        assert not re.search(r"\d{14}/|/\d{14}|sqrt\(\d{4}|atan2\(\d{4}", text), file
        # the decimals are the table's own (the limits are read back in degrees: -360.0
        # of the UR5 as -2*pi, not as the URDF's -6.28318530718)
        back = read_table_text(body)
        assert (back.base, back.tool) == (imp.table.base, imp.table.tool)
        for mine, read in zip(imp.table.rows, back.rows, strict=True):
            assert read.params() == mine.params() and read.inertia == mine.inertia
        for row in imp.table.rows:
            inertia = [] if row.inertia is None else [row.inertia.m, *row.inertia.r, *row.inertia.I]
            for v in [row.theta, row.d, row.a, row.alpha, *inertia]:
                # each number a decimal of at most 12 significant digits, or a small fraction
                for r in v.atoms(sp.Rational):
                    assert r.q <= 1000 or r == sp.Rational(f"{float(r):.12g}"), (file, v)
        # fk of the decimals: the URDF chain's to well below the check's 1e-9
        assert imp.verify(5) < 1e-9
    so100 = table_yaml(import_urdf(DATA / "so100.urdf", tip="gripper"))
    assert "d: 0.118999714029, a: -0.0306, alpha: pi/2" in so100
    assert "theta: 'theta2 + atan2(0.0145842538689, 1)'" in so100
    assert "I: [0.000161511709312, 7.58044906884e-05, 0.000213312," in so100


# --- chains a DH table cannot hold, or holds differently ------------------------------------


def test_fixed_joint_axis_is_ignored() -> None:
    text = urdf(joint("j", "a", "b") + joint("f", "b", "c", "fixed", '<axis xyz="0 0 0"/>'))
    assert chain_from_urdf(text).table.n == 1


@pytest.mark.parametrize("kind", ["floating", "planar"])
def test_floating_and_planar_joints_are_refused(kind: str) -> None:
    text = urdf(joint("free", "a", "b", kind) + joint("j", "b", "c"))
    with pytest.raises(FormatError, match=f"<joint name='free'>: a {kind} joint"):
        import_urdf(text)
    assert import_urdf(text, base="b").table.n == 1  # below it, the chain is fine


def test_coincident_revolute_axes_are_refused_with_the_file() -> None:
    text = urdf(joint("j1", "a", "b") + joint("j2", "b", "c", body='<origin xyz="0 1 0"/>'))
    same = urdf(joint("j1", "a", "b") + joint("j2", "b", "c"))
    with pytest.raises(GeometryError, match="row 2: the axes of joints j1 and j2 coincide"):
        import_urdf(same)
    assert import_urdf(text).table.n == 2


def test_no_moving_joint_is_refused() -> None:
    with pytest.raises(FormatError, match="no revolute, continuous or prismatic joint"):
        import_urdf(urdf(joint("j", "a", "b", "fixed"), "ab"))


def test_long_chains_are_refused() -> None:
    with pytest.raises(FormatError, match="has 1999 joints: at most 100"):
        import_urdf(long_chain(2000))


# --- the hostile-input campaign: inputs that hung or loaded what they should not --------------


def _two_joints(second_axis: str) -> str:
    """Joint 1 about z, joint 2 above it about ``second_axis`` (as written in the file)."""
    return urdf(
        joint("j1", "a", "b", body='<origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>')
        + joint("j2", "b", "c", body=f'<origin xyz="0.2 0 0.1"/><axis xyz="{second_axis}"/>')
    )


@pytest.mark.parametrize(
    "axis",
    ["3 1e-40 7", "1e300 1e-300 1", "0.3 1e-17 0.95", "0.6 0 0.8", "0.30000000000000004 0 1"],
)
def test_measured_axes_convert_without_factorising_huge_numbers(axis: str, tmp_path: Path) -> None:
    # these axes once ran for over 20 s in sympy's factorint; a hang shows as a stuck test
    text = _two_joints(axis)
    robot = chain_from_urdf(text, tip="c")
    rng = np.random.default_rng(3)
    exact = [Fraction(v) for v in axis.split()]  # the reference normalises without overflow
    big = max(abs(v) for v in exact)
    path = tmp_path / "hostile.urdf"
    path.write_text(_two_joints(" ".join(repr(float(v / big)) for v in exact)))
    for q in [np.zeros(2), *rng.uniform(-math.pi, math.pi, (5, 2))]:
        assert np.abs(robot.fk(q) - urdf_pose(path, "c", q)).max() < 1e-9
    # what keeps it fast: the axis is an exact unit vector of bounded rationals (a small
    # integer direction exactly, a measured one through 12-digit stereographic coordinates),
    # never a root of a huge integer
    (axis2,) = [a for a in import_urdf(text, tip="c").assignment.axes if a.name == "j2"]
    assert sp.expand(axis2.direction.dot(axis2.direction)) == 1
    assert all(c.is_Rational and abs(c.p) < 10**25 and c.q < 10**25 for c in axis2.direction)


_RPY = ("0 0 0", "0 0 0", "1.5707963267948966 0 0")


def plain_chain(n: int) -> str:
    """A chain of ``n`` revolute joints, axes alternating y and z, each 0.1 up and 0.05 aside."""
    links = "".join(f'<link name="l{i}"/>' for i in range(n + 1))
    joints = "".join(
        joint(
            f"j{i}",
            f"l{i}",
            f"l{i + 1}",
            body=f'<origin xyz="0 0.05 0.1" rpy="{_RPY[i % 3]}"/>'
            f'<axis xyz="{"0 1 0" if i % 2 else "0 0 1"}"/>'
            '<limit lower="-1" upper="1" effort="1" velocity="1"/>',
        )
        for i in range(n)
    )
    return f'<robot name="chain{n}">{links}{joints}</robot>'


@pytest.mark.parametrize("n", [30, 100])
def test_long_plain_chains_convert(n: int, tmp_path: Path) -> None:
    # 30 joints once took over 20 s (the home check multiplied every prefix anew); 100 joints
    # are allowed (MAX_CHAIN). Speed is measured in benchmarks/bench_urdf.py; here a hang
    # would show as a stuck test, and the result must still be right.
    text = plain_chain(n)
    robot = chain_from_urdf(text, tip=f"l{n}")
    assert robot.table.n == n
    q = np.random.default_rng(n).uniform(-1, 1, n)
    path = tmp_path / "chain.urdf"
    path.write_text(text)
    assert np.abs(robot.fk(q) - urdf_pose(path, f"l{n}", q)).max() < 1e-9


def test_a_rational_chain_is_assigned_frames_without_matrix_dot_or_simplify(monkeypatch) -> None:
    # what keeps a 100-joint chain fast (benchmarks/bench_urdf.py): 3-vectors of rationals
    # are multiplied entry by entry (sympy's Matrix.dot and cross convert each to a domain
    # matrix first), and no entry is simplified per joint: only the base and tool words are
    # (a fixed number of calls, the same for 10 joints as for 30)
    calls: list[str] = []
    for cls in (sp.ImmutableDenseMatrix, sp.MutableDenseMatrix):
        for name in ("dot", "cross"):
            original = getattr(cls, name)

            def counted(*args: object, _f=original, _n=name, **kw: object) -> object:
                calls.append(_n)
                return _f(*args, **kw)

            monkeypatch.setattr(cls, name, counted)
    simplify = sp.simplify

    def counted_simplify(*args: object, **kw: object) -> object:
        calls.append("simplify")
        return simplify(*args, **kw)

    monkeypatch.setattr(sp, "simplify", counted_simplify)
    counts = []
    for n in (10, 30):
        calls.clear()
        imp = import_urdf(plain_chain(n), tip=f"l{n}")
        assert imp.table.n == n and imp.verify(2) < 1e-9
        counts.append((calls.count("dot") + calls.count("cross"), calls.count("simplify")))
    # one Matrix.dot: the tool's approach · sliding, whatever the length
    assert counts[0] == counts[1] and counts[0][0] <= 1, counts


_MASSLESS = (
    '<inertial><mass value="0"/>'
    '<inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>'
)
_HEAVY = (
    '<inertial><origin xyz="0.1 0 0"/><mass value="2"/>'
    '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/></inertial>'
)


def test_explicit_zero_inertial_is_a_massless_link_not_symbols() -> None:
    text = (
        '<robot name="r"><link name="a"/>'
        f'<link name="b">{_MASSLESS}</link><link name="c">{_HEAVY}</link>'
        + joint("j1", "a", "b", body='<axis xyz="0 0 1"/>')
        + joint("j2", "b", "c", body='<origin xyz="0.3 0 0"/><axis xyz="0 0 1"/>')
        + "</robot>"
    )
    imp = import_urdf(text, tip="c")
    first = imp.table.rows[0].inertia
    assert first is not None and first.m == 0 and first.I == sp.zeros(3)
    robot = dhsym.Robot(imp.table)
    tau = robot.rne(np.zeros(2), np.zeros(2), np.zeros(2))  # no m1 asked for
    assert np.all(np.isfinite(tau))
    # gravity along -z and joints about z: no static torque
    assert np.abs(tau).max() < 1e-12


def test_physical_false_accepts_a_broken_triangle_and_says_so() -> None:
    broken = (
        '<inertial><mass value="1"/>'
        '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.05"/></inertial>'
    )
    text = (
        f'<robot name="r"><link name="a"/><link name="b">{broken}</link>'
        + joint("j1", "a", "b", body='<axis xyz="0 0 1"/>')
        + "</robot>"
    )
    with pytest.raises(FormatError, match="triangle inequality.*physical=False"):
        import_urdf(text)
    imp = import_urdf(text, physical=False)
    assert imp.table.physical is False
    assert "physical: false" in dhsym.formats.urdf.table_yaml(imp)


def test_names_cannot_write_keys_into_the_table_file() -> None:
    # YAML ends a comment at U+2028 too: a link name must not turn into a key
    from dhsym.formats.urdf import table_yaml
    from dhsym.model.tablefile import read_table_text

    evil = "b\u2028physical: false\u2028#"
    text = urdf(joint("j", "a", evil, "continuous", '<axis xyz="0 0 1"/>'), ["a", evil])
    written = table_yaml(import_urdf(text))
    assert read_table_text(written).physical is True


def test_the_ur5_urdf_gives_universal_robots_table_and_the_same_fk() -> None:
    from dhsym.model.library import builtin_table

    imp = import_urdf(DATA / "ur5_robot.urdf", tip="tool0")
    ur5 = builtin_table("ur5")
    values = ur5.value_map
    for mine, theirs in zip(imp.table.rows, ur5.rows, strict=True):
        for name, value in mine.params().items():
            assert sp.simplify(value - theirs.params()[name].xreplace(values)) == 0, name
    assert imp.verify(10) < 1e-9
    robot = KinematicChain(imp.table)
    q = np.random.default_rng(5).uniform(-math.pi, math.pi, (6, 6))
    for row in q:
        assert np.abs(robot.fk(row) - urdf_pose(DATA / "ur5_robot.urdf", "tool0", row)).max() < 1e-9
    assert any("turned by 180°" in s for s in imp.steps)
    # as the frame assignment chose them: the old table, a2 = +0.425, θ6 + 180°
    plain = import_urdf(DATA / "ur5_robot.urdf", tip="tool0", frames="assigned")
    assert plain.table.rows[1].a == sp.Rational("0.425") and plain.choice is None
    assert plain.table.rows[5].offset == sp.pi


def test_a_reference_table_is_matched_or_the_rows_that_cannot_are_named() -> None:
    from dhsym.model.library import builtin_table

    imp = import_urdf(DATA / "ur5_robot.urdf", tip="tool0", frames=builtin_table("ur5"))
    assert imp.choice is not None and imp.choice.mismatches == ()
    other = import_urdf(DATA / "ur5_robot.urdf", tip="tool0", frames=builtin_table("puma560"))
    assert other.choice is not None
    why = other.choice.mismatches
    assert "row 2: a = -0.425 here, 0.4318 in the reference: a length no frame choice" in why[1]
    assert any(w.startswith("row 3: α = 0° here, -90° in the reference") for w in why)
    assert other.verify(4) < 1e-9  # whatever is chosen, the same arm


@pytest.mark.slow
@pytest.mark.parametrize(("file", "tip", "n"), ROBOTS)
def test_every_example_keeps_its_fk_and_dynamics_under_the_textbook_choice(file, tip, n) -> None:
    from dhsym.robot import Robot

    imp = import_urdf(DATA / file, tip=tip)
    plain = import_urdf(DATA / file, tip=tip, frames="assigned")
    assert imp.verify(6) < 1e-9 and len(imp.table.variables) == n
    # the inertias turn with their frames: the same torques
    if all(r.inertia is not None for r in imp.table.rows):
        q = np.random.default_rng(1).uniform(-1, 1, n)
        qd = np.full_like(q, 0.3)
        a, b = Robot(imp.table), Robot(plain.table)
        assert np.abs(a.rne(q, qd, qd) - b.rne(q, qd, qd)).max() < 1e-9


@pytest.mark.parametrize("n", [20, 30])
def test_checking_a_long_chain_derives_no_closed_form(n: int, monkeypatch) -> None:
    # the check of the chosen table against the joint axes is one numeric product of the
    # elementary words: a 100-joint closed form (or the Panda's) is never derived for it
    imp = import_urdf(plain_chain(n), tip=f"l{n}")

    def refuse(*args: object, **kw: object) -> None:
        raise AssertionError("a closed form was derived to check the table")

    monkeypatch.setattr(KinematicChain, "fk", refuse)
    monkeypatch.setattr(KinematicChain, "transform", refuse)
    assert imp.choice is not None and imp.verify(5) < 1e-9
    panda = import_urdf(DATA / "panda.urdf", tip="panda_hand")
    assert panda.verify(5) < 1e-9


def test_a_turned_table_that_does_not_fit_the_axes_is_caught() -> None:
    # the check can fail: a frame turned in the table but not in the frames it is checked on
    from dataclasses import replace

    from dhsym.geometry.frame_choices import flip_x

    imp = import_urdf(DATA / "ur5_robot.urdf", tip="tool0")
    wrong = replace(imp, table=flip_x(imp.table, 3))
    with pytest.raises(GeometryError, match="does not reproduce the joint axes"):
        wrong.verify(3)


@pytest.mark.parametrize(("file", "tip", "n"), ROBOTS)
def test_parallel_axes_get_the_common_normal_with_no_offset(file: str, tip: str, n: int) -> None:
    # where the origin may slide along a pair of parallel axes, it slides to d = 0
    imp = import_urdf(DATA / file, tip=tip)
    axes = imp.assignment.axes
    parallel = [
        k
        for k in range(1, n)
        if all(c == 0 for c in axes[k - 1].direction.cross(axes[k].direction))
    ]
    assert file != "ur5_robot.urdf" or parallel == [2, 3]
    for k in parallel:  # row k: from z_(k-1) (joint k) to z_k (joint k + 1)
        row = imp.table.rows[k - 1]
        assert (row.offset if row.variable_field == "d" else row.d) == 0


def test_a_half_turn_between_joint_axes_is_explained_in_the_table_file() -> None:
    from dhsym.formats.urdf import table_yaml

    imp = import_urdf(DATA / "kinova.urdf", tip="j2s6s200_end_effector")
    assert imp.table.rows[1].alpha == sp.pi  # Kinova's own table has it too
    assert any(
        s.startswith("α2 = 180° stays: z1 and z2 are the axes of joints 2 and 3") for s in imp.steps
    )
    lines = table_yaml(imp).splitlines()
    assert any(line.startswith("# ") and "α2 = 180° stays" in line for line in lines)


def test_a_tool_turned_upside_down_reverses_the_last_z_and_keeps_fk(tmp_path: Path) -> None:
    text = urdf(
        joint("j1", "a", "b", body='<origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>')
        + joint("j2", "b", "c", body='<origin xyz="0.2 0 0"/><axis xyz="0 0 1"/>')
        + joint("t", "c", "d", "fixed", '<origin xyz="0.1 0 0" rpy="3.141592653589793 0 0"/>'),
        links="abcd",
    )
    assigned = import_urdf(text, tip="d", frames="assigned")
    assert abs(assigned.table.rows[1].alpha) == sp.pi
    imp = import_urdf(text, tip="d")
    assert imp.choice is not None and imp.choice.last_z_reversed
    assert imp.table.rows[1].alpha == 0 and imp.verify(5) < 1e-9
    path = tmp_path / "upside_down.urdf"
    path.write_text(text)
    robot = KinematicChain(imp.table)
    for q in np.random.default_rng(4).uniform(-math.pi, math.pi, (5, 2)):
        assert np.abs(robot.fk(q) - urdf_pose(path, "d", q)).max() < 1e-9


def test_the_triangle_inequality_is_the_rigid_bodys_not_each_inertials() -> None:
    """A frame link with a placeholder inertia (the Sawyer's right_hand: mass and every
    inertia entry 1e-8, a rank-one matrix) merges into the link it is fixed to; that body
    is a rigid body. The same placeholder on a moving link of its own is refused, naming it."""
    placeholder = (
        '<inertial><mass value="1e-8"/><inertia ixx="1e-8" ixy="1e-8" ixz="1e-8"'
        ' iyy="1e-8" iyz="1e-8" izz="1e-8"/></inertial>'
    )
    arm = (
        '<inertial><mass value="2"/>'
        '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/></inertial>'
    )
    text = (
        f'<robot name="r"><link name="a"/><link name="b">{arm}</link>'
        f'<link name="hand">{placeholder}</link>'
        + joint("j1", "a", "b", body='<axis xyz="0 0 1"/>')
        + joint("j2", "b", "hand", kind="fixed")
        + "</robot>"
    )
    imp = import_urdf(text)
    assert imp.table.physical and imp.table.rows[0].inertia is not None
    moving = text.replace(
        joint("j2", "b", "hand", kind="fixed"),
        joint("j2", "b", "hand", body='<axis xyz="1 0 0"/>'),
    )
    with pytest.raises(FormatError, match="triangle inequality") as err:
        import_urdf(moving, tip="hand")
    assert err.value.field == "<link name='hand'> <inertial>"


def test_a_urdf_without_inertials_says_its_dynamics_are_symbols() -> None:
    text = (
        '<robot name="r"><link name="a"/><link name="b"/>'
        + joint("j1", "a", "b", body='<axis xyz="0 0 1"/>')
        + "</robot>"
    )
    imp = import_urdf(text)
    assert any("no <inertial> on the links of row 1:" in w for w in imp.table.warnings)
    assert imp.table.rows[0].inertia is None
