"""PoE files: Lynch and Park's UR5 and 3R arm against the book and ``modern_robotics``
(values recorded below), validation errors naming file/row/field, ``dhsym.load`` and
PoE -> DH through the frame assignment with the fk equal."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.errors import TableError
from dhsym.kinematics.simplification import prove_equal
from dhsym.screws.poe_to_dh import to_dh
from dhsym.screws.poefile import read_poe, read_poe_text

ROBOTS = resources.files("dhsym.screws") / "robots"
W1, W2, L1, L2, H1, H2 = sp.symbols("W1 W2 L1 L2 H1 H2", real=True)
THETA = [0.3, -0.5, 0.4, 0.2, 0.7, -1.1]

# modern_robotics 1.1.1 (FKinSpace, FKinBody, JacobianSpace, JacobianBody) for the UR5 of
# Lynch and Park, Example 4.5 (W1=0.109, W2=0.082, L1=0.425, L2=0.392, H1=0.089, H2=0.095),
# at THETA, with the book's M and S_i and B_i = Ad_{M^-1} S_i
MR_FK = [
    [-0.5011323646730016, -0.7743415990879545, 0.38634368248899226, 0.7193432290001012],
    [0.15085774065201896, 0.3614411873612025, 0.9201098902654467, 0.40226404353466133],
    [-0.8521198830931093, 0.5193797801232096, -0.06431445278125648, 0.2320913724028674],
    [0.0, 0.0, 0.0, 1.0],
]
MR_JS = [
    [0.0, -0.29552020666133955, -0.29552020666133955, -0.29552020666133955,
     -0.0953745057567947, 0.38634368248899226],
    [0.0, 0.955336489125606, 0.955336489125606, 0.955336489125606, -0.029502791919178307,
     0.9201098902654467],
    [1.0, 0.0, 0.0, 0.0, -0.9950041652780258, -0.06431445278125644],
    [0.0, -0.08502494753217893, -0.279680349642278, -0.3170671558989415,
     -0.31817938379420563, -0.2394209590266665],
    [0.0, -0.026301298392859218, -0.0865152704478504, -0.09808036488016829,
     0.6615890115252064, 0.13593120162309144],
    [0.0, 0.0, 0.3729725888034084, 0.7630142215923945, 0.01088184241450427,
     0.5064626475863818],
]  # fmt: skip
MR_JB = [
    [-0.8521198830931093, 0.29221464428477223, 0.29221464428477223, 0.29221464428477223,
     0.8912073600614354, 0.0],
    [0.5193797801232096, 0.5741315443479861, 0.5741315443479861, 0.5741315443479861,
     -0.45359612142557726, 0.0],
    [-0.06431445278125648, 0.7648421872844885, 0.7648421872844885, 0.7648421872844885, 0.0,
     1.0],
    [0.3101060256397312, 0.6247612408690466, 0.39540826027686005, 0.08003708435375026,
     -0.03719488195689734, 0.0],
    [0.5714900535362542, -0.5092366494102835, -0.1865562624598323, 0.04079353289502386,
     -0.07307900352503771, 0.0],
    [0.5064626475863818, 0.14356483210073784, -0.011030051938117832, -0.06120068028758065,
     0.0, 0.0],
]  # fmt: skip
# the 3R spatial chain of Lynch and Park, Example 4.1, with L1 = 1, L2 = 0.5, at (0.4, -0.7, 1.2)
MR_3R_FK = [
    [-0.5779630839508428, 0.4119294822192116, 0.7044663052755917, 0.6243791023221914],
    [0.7675600904854725, 0.5675744103749357, 0.2978435767000479, 0.2639832503836434],
    [-0.27714649751343473, 0.7128628131458088, -0.644217687237691, -0.3824210936422443],
    [0.0, 0.0, 0.0, 1.0],
]
MR_3R_JS = [
    [0.0, 0.3894183423086505, 0.7044663052755917],
    [0.0, -0.9210609940028851, 0.2978435767000479],
    [1.0, 0.0, -0.644217687237691],
    [0.0, 0.0, -0.056161012695689044],
    [0.0, 0.0, 0.13283328635994485],
    [0.0, -1.0, 4.409742858583908e-18],
]


def _ur5() -> dhsym.ProductOfExponentials:
    with resources.as_file(ROBOTS / "lynch_park_ur5.poe.yaml") as p:
        return read_poe(p)


def _three_r() -> dhsym.ProductOfExponentials:
    with resources.as_file(ROBOTS / "lynch_park_3r.poe.yaml") as p:
        return read_poe(p)


def test_ur5_reproduces_the_books_m_and_screw_axes() -> None:
    poe = _ur5()
    assert poe.home == sp.Matrix(
        [[-1, 0, 0, L1 + L2], [0, 0, 1, W1 + W2], [0, 1, 0, H1 - H2], [0, 0, 0, 1]]
    )
    assert poe.screw_matrix("space").T == sp.Matrix(
        [
            [0, 0, 1, 0, 0, 0],
            [0, 1, 0, -H1, 0, 0],
            [0, 1, 0, -H1, 0, L1],
            [0, 1, 0, -H1, 0, L1 + L2],
            [0, 0, -1, -W1, L1 + L2, 0],
            [0, 1, 0, H2 - H1, 0, L1 + L2],
        ]
    )
    # the book's body axes (Example 4.5)
    assert sp.simplify(
        poe.screw_matrix("body").T
        - sp.Matrix(
            [
                [0, 1, 0, W1 + W2, 0, L1 + L2],
                [0, 0, 1, H2, -L1 - L2, 0],
                [0, 0, 1, H2, -L2, 0],
                [0, 0, 1, H2, 0, 0],
                [0, -1, 0, -W2, 0, 0],
                [0, 0, 1, 0, 0, 0],
            ]
        )
    ) == sp.zeros(6, 6)
    assert dict(poe.values)[L1] == sp.Rational(425, 1000)  # exact decimals


def test_ur5_numbers_equal_modern_robotics() -> None:
    poe = _ur5()
    np.testing.assert_allclose(poe.function("fk_space")(THETA), MR_FK, atol=1e-12)
    np.testing.assert_allclose(poe.function("fk_body")(THETA), MR_FK, atol=1e-12)
    np.testing.assert_allclose(poe.function("jacobian_space")(THETA), MR_JS, atol=1e-12)
    np.testing.assert_allclose(poe.function("jacobian_body")(THETA), MR_JB, atol=1e-12)


def test_three_r_reproduces_the_book_and_modern_robotics() -> None:
    poe = _three_r()
    a, b = sp.symbols("L1 L2", real=True)
    assert poe.home == sp.Matrix([[0, 0, 1, a], [0, 1, 0, 0], [-1, 0, 0, -b], [0, 0, 0, 1]])
    assert poe.screw_matrix().T == sp.Matrix(
        [[0, 0, 1, 0, 0, 0], [0, -1, 0, 0, 0, -a], [1, 0, 0, 0, -b, 0]]
    )
    q = [0.4, -0.7, 1.2]
    vals = {"L1": 1, "L2": 0.5}
    np.testing.assert_allclose(poe.function("fk_space", vals)(q), MR_3R_FK, atol=1e-12)
    np.testing.assert_allclose(poe.function("fk_body", vals)(q), MR_3R_FK, atol=1e-12)
    np.testing.assert_allclose(poe.function("jacobian_space", vals)(q), MR_3R_JS, atol=1e-12)


@pytest.mark.parametrize("convention", ["standard", "modified"])
@pytest.mark.parametrize("which", ["lynch_park_ur5", "lynch_park_3r"])
def test_poe_to_dh_has_the_same_fk(which: str, convention: str) -> None:
    with resources.as_file(ROBOTS / f"{which}.poe.yaml") as p:
        poe = read_poe(p)
        robot = dhsym.load(str(p), convention=convention)
    fa = to_dh(poe, convention)
    assert fa.steps and robot.table.rows == fa.table.rows
    assert robot.convention.value == convention
    # the same variables, zero at home: the plain DH product equals the PoE product exactly
    plain = robot.plain_transform(-1 if robot.table.base else 0, robot.n + 1)
    renamed = poe.product("space").xreplace(dict(zip(poe.variables, robot.variables)))
    assert prove_equal(renamed, plain)
    # and back: the loaded robot's screw axes are the file's
    S, M = robot.screw_axes()
    assert sp.simplify(S - poe.screw_matrix()) == sp.zeros(6, robot.n)
    assert sp.simplify(M - poe.home) == sp.zeros(4, 4)


def test_body_frame_files_are_carried_to_the_space_frame() -> None:
    poe = read_poe_text(
        """
frame: body
M: [[1, 0, 0, 2], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
joints:
  - {w: [0, 0, 1], v: [0, 2, 0]}
  - {w: [0, 0, 1], v: [0, 1, 0]}
"""
    )
    assert poe.screw_matrix("space").T == sp.Matrix([[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, -1, 0]])


def test_m_as_steps_in_degrees() -> None:
    poe = read_poe_text(
        "angles: deg\nM: [{Tx: 0.5}, {Rz: 90}]\njoints: [{type: P, v: [1, 0, 0], q: s}]"
    )
    assert poe.home[:2, :2] == sp.Matrix([[0, -1], [1, 0]])
    assert poe.home[0, 3] == sp.Rational(1, 2)
    assert poe.variables == (sp.Symbol("s", real=True),)


@pytest.mark.parametrize(
    ("text", "where", "message"),
    [
        ("joints: [{w: [0, 0, 1], v: [0, 0, 0]}]", "field M", "missing 'M'"),
        ("M: [[1, 0], [0, 1]]\njoints: []", "field M", "4×4 matrix"),
        (
            "M: [[2,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]\njoints: [{w: [0, 0, 1], v: [0, 0, 0]}]",
            "field M",
            "rigid",
        ),
        ("M: [{Tx: 1}]\njoints: [{w: [0, 0, 1], v: [0, 0, 1]}]", "row 1, field v", "omega·v"),
        ("M: [{Tx: 1}]\njoints: [{w: [0, 1, 1], v: [0, 0, 0]}]", "row 1, field w", "unit"),
        ("M: [{Tx: 1}]\njoints: [{type: P, v: [0, 0, 2]}]", "row 1, field v", "unit v"),
        (
            "M: [{Tx: 1}]\njoints: [{w: [0, 0, 1], v: [0, 0, 0]}, {w: [0, 0, 1], vv: [1]}]",
            "row 2, field vv",
            "unknown key",
        ),
        ("M: [{Tx: 1}]\njoints: [{w: [0, 0, 1], point: [__import__, 0, 0]}]", "row 1", ""),
        ("M: [{Tx: 1}]\nframe: world\njoints: []", "field frame", "space or body"),
        (
            "M: [{Tx: 1}]\njoints: [{w: [0, 0, 1], v: [0, 0, 0]}]\nvalues: {a: b}",
            "field values.a",
            "",
        ),
    ],
)
def test_errors_name_file_row_and_field(text: str, where: str, message: str) -> None:
    with pytest.raises(TableError) as info:
        read_poe_text(text, file="arm.poe.yaml")
    assert str(info.value).startswith(f"arm.poe.yaml: {where}")
    assert message in str(info.value)


def test_a_file_that_is_not_there_or_not_yaml(tmp_path: Path) -> None:
    bad = tmp_path / "x.poe.yaml"
    bad.write_text("M: [\n")
    with pytest.raises(TableError, match=f"{bad}: not valid YAML"):
        dhsym.load(str(bad))
    with pytest.raises(TableError, match="missing.poe.yaml"):
        dhsym.load(str(tmp_path / "missing.poe.yaml"))
