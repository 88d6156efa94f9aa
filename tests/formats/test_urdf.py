"""URDF in and out: real robot descriptions against an independent chain product."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.errors import FormatError
from dhsym.formats.urdf import chain_from_urdf, import_urdf, write_urdf

DATA = Path(__file__).resolve().parents[1] / "data" / "urdf"

# (file, tip, number of moving joints): a UR, a 7-joint arm, a 6-joint arm, an education arm
ROBOTS = [
    ("ur5_robot.urdf", "tool0", 6),
    ("panda.urdf", "panda_hand", 7),
    ("kinova.urdf", "j2s6s200_end_effector", 6),
    ("so100.urdf", "gripper", 5),
]


# --- the independent reference: numpy, straight from the XML -------------------------------


def _rot(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues' formula."""
    u = axis / np.linalg.norm(axis)
    K = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


def _origin(joint: ET.Element) -> np.ndarray:
    el = joint.find("origin")
    xyz = [0.0] * 3 if el is None else [float(v) for v in el.get("xyz", "0 0 0").split()]
    r, p, y = [0.0] * 3 if el is None else [float(v) for v in el.get("rpy", "0 0 0").split()]
    ex, ey, ez = np.eye(3)
    T = np.eye(4)
    T[:3, :3] = _rot(ez, y) @ _rot(ey, p) @ _rot(ex, r)
    T[:3, 3] = xyz
    return T


def urdf_pose(path: Path, tip: str, q: np.ndarray) -> np.ndarray:
    """Root link -> tip link at joint values q (moving joints in chain order)."""
    root = ET.parse(path).getroot()
    joints = {j.find("child").get("link"): j for j in root.findall("joint")}
    chain = []
    link = tip
    while link in joints:
        chain.append(joints[link])
        link = joints[link].find("parent").get("link")
    T = np.eye(4)
    k = 0
    for j in reversed(chain):
        T = T @ _origin(j)
        if j.get("type") in ("revolute", "continuous", "prismatic"):
            axis_el = j.find("axis")
            text = axis_el.get("xyz") if axis_el is not None else "1 0 0"
            axis = np.array([float(v) for v in text.split()])
            M = np.eye(4)
            if j.get("type") == "prismatic":
                M[:3, 3] = q[k] * axis / np.linalg.norm(axis)
            else:
                M[:3, :3] = _rot(axis, q[k])
            T = T @ M
            k += 1
    return T


# --- real robots ------------------------------------------------------------------------------


@pytest.mark.parametrize("convention", ["standard", "modified"])
@pytest.mark.parametrize(("file", "tip", "n"), ROBOTS)
def test_fk_equals_the_urdf_chain(file: str, tip: str, n: int, convention: str) -> None:
    robot = chain_from_urdf(DATA / file, tip=tip, convention=convention)
    assert robot.table.n == n
    rng = np.random.default_rng(7)
    for q in [np.zeros(n), *rng.uniform(-math.pi, math.pi, (6, n))]:
        assert np.abs(robot.fk(q) - urdf_pose(DATA / file, tip, q)).max() < 1e-9


@pytest.mark.parametrize(("file", "tip", "n"), ROBOTS)
def test_round_trip_keeps_fk(file: str, tip: str, n: int) -> None:
    robot = chain_from_urdf(DATA / file, tip=tip)
    for convention in ("standard", "modified"):
        again = chain_from_urdf(write_urdf(dhsym.convert(robot.table, convention)), tip="tool")
        q = np.random.default_rng(3).uniform(-math.pi, math.pi, (5, n))
        assert np.abs(again.fk(q) - robot.fk(q)).max() < 1e-9


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
    assert [abs(r.a) for r in rows] == [0, sp.Rational("0.425"), sp.Rational("0.39225"), 0, 0, 0]
    assert rows[0].alpha == -sp.pi / 2 and rows[0].label == "shoulder_pan_joint"
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


def test_written_urdf_is_valid_for_yourdfpy() -> None:
    import yourdfpy  # in the test extra: a missing validator is a failure, not a skip

    robot = chain_from_urdf(DATA / "panda.urdf", tip="panda_hand")
    for convention in ("standard", "modified"):
        text = write_urdf(dhsym.convert(robot.table, convention))
        import io

        model = yourdfpy.URDF.load(io.StringIO(text), load_meshes=False, build_scene_graph=True)
        assert model.validate()
        q = np.random.default_rng(1).uniform(-1, 1, 7)
        names = [f"joint{k}" for k in range(1, 8)]
        model.update_cfg(dict(zip(names, q, strict=True)))
        T = model.get_transform("tool", model.base_link)
        assert np.abs(T - robot.fk(q)).max() < 1e-9
        links = {link.name for link in model.robot.links}
        assert {f"link{k}" for k in range(8)} <= links


def test_robot_to_urdf_method_and_visuals() -> None:
    r = dhsym.load("puma560")
    out = dhsym.Robot(r.table.with_values({s: 0.3 for s in r.table.constants})).to_urdf()
    assert out.count("<cylinder") == 6 and "<box" in out
    with pytest.raises(dhsym.DHError, match="symbolic lengths a1, a2, a3"):
        dhsym.Robot(dhsym.planar_chain(3)).to_urdf()


def test_fixed_rows_and_flipped_joints_are_written() -> None:
    from dhsym.model.table import DHRow, DHTable

    rows = [
        DHRow.revolute("pi/2 - q1", d=0.3, a=0.2, alpha="pi/2"),
        DHRow.fixed(theta="pi/6", d=0.1),
        DHRow.prismatic("0.1 - d3", a=0.1, alpha="-pi/2"),
    ]
    for convention in ("standard", "modified"):
        robot = dhsym.Robot(DHTable.from_rows(rows, convention=convention, name="odd"))
        text = robot.to_urdf()
        assert '<axis xyz="0 0 -1"/>' in text and 'name="joint2" type="fixed"' in text
        again = chain_from_urdf(text, tip="tool")
        for q in ([0.3, 0.2], [-1.0, 0.6]):
            assert np.abs(again.fk(q) - robot.fk(q)).max() < 1e-12


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


@pytest.mark.slow
def test_written_inertials_come_back() -> None:
    """Puma 560 with its published inertial parameters: the URDF holds m, r and I (not the
    motor inertia, gearing or friction, which URDF has no place for)."""
    from dataclasses import replace

    from dhsym.robot import Robot

    table = dhsym.load("puma560").table.substituted()
    rigid = replace(
        table,
        rows=tuple(
            replace(row, inertia=replace(row.inertia, Jm=0, G=1, B=0, Tc=(0, 0)))
            for row in table.rows
        ),
    )
    text = write_urdf(rigid)
    assert text.count("<inertial>") == 6 and '<mass value="17.4"/>' in text
    again = dhsym.from_urdf(text, tip="tool")
    assert again.table.rows[1].inertia.m == sp.Rational(87, 5)
    robot = Robot(rigid)
    rng = np.random.default_rng(3)
    for _ in range(3):
        q, qd, qdd = (rng.uniform(-1.5, 1.5, 6) for _ in range(3))
        np.testing.assert_allclose(again.rne(q, qd, qdd), robot.rne(q, qd, qdd), atol=1e-9, rtol=0)
