"""Reading URDF files and text into the model; broken and hostile files: one FormatError
naming the element, meshes never opened."""

from __future__ import annotations

from pathlib import Path

import pytest

from dhsym.errors import FormatError
from dhsym.formats.urdf.read import is_urdf_source, read_urdf
from dhsym.formats.urdf.to_dh import chain_from_urdf, import_urdf

from .support import joint, long_chain, urdf


@pytest.mark.parametrize(
    ("value", "message"),
    [
        ("nan 0 0", "'nan' is not a finite decimal number"),
        ("inf 0 0", "'inf' is not a finite decimal number"),
        ("1e99999 0 0", "exponent"),
        ("1e309 0 0", "1.0E+309 is beyond the range of floating-point numbers"),
        ("0.1 two 0", "'two' is not a finite decimal number"),
        ("${d1} 0 0", "xacro expressions must be expanded first"),
        ("0 0", "expected 3 numbers"),
    ],
)
def test_bad_numbers_name_the_element(value: str, message: str) -> None:
    text = urdf(joint("elbow", "a", "b", body=f'<origin xyz="{value}"/>'), "ab")
    with pytest.raises(FormatError) as err:
        read_urdf(text)
    assert "field <joint name='elbow'> <origin> xyz" in str(err.value)
    assert message in str(err.value)


def test_zero_length_axis_is_refused() -> None:
    text = urdf(joint("wrist", "a", "b", body='<axis xyz="0 0 0"/>'), "ab")
    with pytest.raises(FormatError, match="<joint name='wrist'> <axis> xyz: the axis has zero"):
        read_urdf(text)


def test_cycle_without_root_is_refused() -> None:
    text = urdf(joint("j1", "a", "b") + joint("j2", "b", "a"), "ab")
    with pytest.raises(FormatError, match="cycle through link 'a'"):
        read_urdf(text)


def test_second_parent_is_refused() -> None:
    text = urdf(joint("j1", "a", "b") + joint("j2", "c", "b"))
    with pytest.raises(FormatError, match="<joint name='j2'>: link 'b' is already the child"):
        read_urdf(text)


def test_two_roots_are_refused() -> None:
    with pytest.raises(FormatError, match="links a, c are no joint's child"):
        read_urdf(urdf(joint("j1", "a", "b")))


def test_unknown_kind_and_missing_links() -> None:
    with pytest.raises(FormatError, match="unknown joint type 'ball'"):
        read_urdf(urdf(joint("j", "a", "b", "ball"), "ab"))
    with pytest.raises(FormatError, match="child link 'z' is not defined"):
        read_urdf(urdf(joint("j", "a", "z"), "ab"))
    with pytest.raises(FormatError, match="field tip: no link named 'z'"):
        import_urdf(urdf(joint("j", "a", "b"), "ab"), tip="z")


def test_wrong_root_is_refused() -> None:
    with pytest.raises(FormatError, match="expected <robot>"):
        read_urdf("<sdf/>")


def test_meshes_and_package_paths_are_never_opened(tmp_path: Path) -> None:
    visual = (
        '<visual><geometry><mesh filename="package://nowhere/meshes/x.stl"/></geometry></visual>'
        f'<collision><geometry><mesh filename="{tmp_path}/missing.dae"/></geometry></collision>'
    )
    text = (
        '<robot name="r"><link name="a">'
        + visual
        + '</link><link name="b"/>'
        + joint("j", "a", "b")
        + "</robot>"
    )
    path = tmp_path / "r.urdf"
    path.write_text(text)
    assert chain_from_urdf(path).table.n == 1


def test_xacro_files_say_how_to_expand_them(tmp_path: Path) -> None:
    path = tmp_path / "arm.urdf.xacro"
    path.write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r"/>')
    with pytest.raises(FormatError, match="xacro robot.urdf.xacro > robot.urdf"):
        read_urdf(path)


def test_too_many_links_are_refused_before_the_joints_are_read() -> None:
    with pytest.raises(FormatError, match="field <link>: the robot has 2500 links: at most 2000"):
        read_urdf(long_chain(2500))


def test_far_cycles_are_found_in_one_pass() -> None:
    cycle = joint("jc", "l1999", "l0", "fixed")
    with pytest.raises(FormatError, match="<joint name='j.*'>: the links form a cycle"):
        read_urdf(long_chain(2000, cycle))


def test_urdf_sources_by_suffix_or_text(tmp_path: Path) -> None:
    assert is_urdf_source(tmp_path / "arm.URDF") and is_urdf_source("arm.urdf.xacro")
    assert is_urdf_source("  <robot name='r'/>") and not is_urdf_source("puma560")
    assert not is_urdf_source(tmp_path / "arm.yaml") and not is_urdf_source(3)


def test_an_inertial_beyond_a_double_is_refused_with_its_element() -> None:
    body = '<inertial><mass value="1e309"/><inertia ixx="1" iyy="1" izz="1"/></inertial>'
    text = urdf(joint("j1", "a", "b"), "a").replace(
        "</robot>", f'<link name="b">{body}</link></robot>'
    )
    with pytest.raises(FormatError) as err:
        read_urdf(text)
    assert "<link name='b'> <inertial> <mass>" in str(err.value)
    assert "beyond the range" in str(err.value)


def _inertial(mass: str, inertia: str) -> str:
    keys = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
    attrs = " ".join(f'{k}="{v}"' for k, v in zip(keys, inertia.split(), strict=True))
    return (
        f'<robot name="r"><link name="a"><inertial><mass value="{mass}"/>'
        f"<inertia {attrs}/></inertial></link></robot>"
    )


@pytest.mark.parametrize(
    ("mass", "inertia", "message"),
    [
        ("-1", "1 0 0 1 0 1", "a mass cannot be negative"),
        ("1", "-1 0 0 1 0 1", "not positive semi-definite"),
        ("1", "1 2 0 1 0 1", "not positive semi-definite"),  # indefinite
    ],
)
def test_inertials_get_the_table_readers_checks(mass: str, inertia: str, message: str) -> None:
    with pytest.raises(FormatError, match=message) as err:
        read_urdf(_inertial(mass, inertia))
    assert err.value.field == "<link name='a'> <inertial>"


def test_physical_false_keeps_only_the_triangle_inequality_off() -> None:
    # the triangle inequality is the rigid bodies' (import_urdf): read_urdf keeps the rest
    model = read_urdf(_inertial("1", "0.01 0 0 0.01 0 0.05"), physical=False)
    assert model.links[0][1] is not None and not model.physical
    assert read_urdf(_inertial("1", "0.01 0 0 0.01 0 0.05")).physical
    with pytest.raises(FormatError, match="negative"):
        read_urdf(_inertial("-1", "1 0 0 1 0 1"), physical=False)
