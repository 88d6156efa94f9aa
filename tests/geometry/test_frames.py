"""The DH algorithm: every built-in robot back from its axes, and each special case of the seeds.

What "identical fk" means here: the tool pose (world → tool, base and tool
transforms included) as a function of the joint variables. The algorithm keeps
the sense of every given axis and makes each variable zero at the given home
pose, so the map between the old variables q and the new ones is reported by
``FrameAssignment.variable_map`` as ``new = sign·q + offset``; with the home
pose at q = 0 it is the identity (sign +1, offset 0) for every built-in robot,
which the round-trip test asserts before comparing the tool poses.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import dhsym
from dhsym.errors import GeometryError
from dhsym.geometry.axes import Frame, JointAxis, Tool
from dhsym.geometry.frames import assign_frames
from dhsym.kinematics.transforms import chain_word, plain_product
from dhsym.model.table import Convention, Elementary
from dhsym.robot import Robot

pi = sp.pi
S = lambda n: sp.Symbol(n, real=True)  # noqa: E731


def home_frame(table, k):
    """World pose of frame k (-1 … n+1) of ``table`` at q = 0, exact."""
    zero = {v: 0 for v in table.variables}
    word = [Elementary(e.kind, e.axis, e.value.subs(zero)) for e in chain_word(table, -1, k)]
    return sp.simplify(plain_product(word))


def axes_from_table(table):
    """Joint axes at home: z of frame i-1 (standard) or i (modified), through its origin."""
    t = table.substituted()
    axes = []
    for i, row in enumerate(t.rows, start=1):
        M = home_frame(t, i - 1 if t.convention is Convention.STANDARD else i)
        # the axis points the way its variable turns or slides the joint: a flipped joint
        # (theta = -q1, the Jaco's first) turns about -z
        entry = getattr(row, row.variable_field) if row.variable_field else None
        sign = entry.diff(row.variable) if row.variable is not None else 1
        axes.append(JointAxis(M[:3, 3], sign * M[:3, 2], row.joint.value, str(i)))
    T = home_frame(t, t.n + 1)
    return axes, Tool(T[:3, 3], T[:3, 2], T[:3, 1])


def said(fa, rule):
    """The text of the (first) step of the given rule."""
    return next(s.text for s in fa.steps if s.rule == rule)


def tool_poses(table, q):
    return Robot(table).fk(q)


@pytest.mark.parametrize("name", dhsym.builtin_names())
@pytest.mark.parametrize("convention", ["standard", "modified"])
def test_every_builtin_robot_comes_back_from_its_axes(name, convention):
    original = dhsym.load_table(name)
    axes, tool = axes_from_table(original)
    fa = assign_frames(axes, tool=tool, convention=convention)
    assert fa.table.convention.value == convention
    # the variable map is the identity: same variables, sign +1, no offset
    assert [(m.sign, m.offset) for m in fa.variable_map] == [(1, 0)] * original.n
    assert fa.table.variables == original.variables
    q = np.random.default_rng(7).uniform(-np.pi, np.pi, (25, original.n))
    assert np.max(np.abs(tool_poses(original, q) - tool_poses(fa.table, q))) < 1e-12
    assert fa.verify(samples=10) < 1e-9


@pytest.mark.parametrize("name", ["puma560", "planar2r", "stanford", "example4_6dof", "puma260"])
def test_standard_tables_are_reproduced_exactly(name):
    original = dhsym.load_table(name).substituted()
    axes, tool = axes_from_table(original)
    fa = assign_frames(axes, tool=tool)
    assert [r.params() for r in fa.table.rows] == [r.params() for r in original.rows]
    assert fa.table.base == () and fa.table.tool == ()


def test_craig_puma_560_is_reproduced_exactly_in_the_modified_convention():
    original = dhsym.load_table("puma560_modified").substituted()
    axes, tool = axes_from_table(original)
    fa = assign_frames(axes, tool=tool, convention="modified")
    got = [(r.alpha, r.a, r.d, r.theta) for r in fa.table.rows]
    assert got == [(r.alpha, r.a, r.d, r.theta) for r in original.rows]
    assert [r.alpha for r in fa.table.rows] == [0, -pi / 2, 0, -pi / 2, pi / 2, -pi / 2]


def puma_stretched():
    """Seed 003's PUMA stretched out: shoulder, elbow and wrist pitch axes along -y."""
    a2, a3, d3, d4 = S("a2"), S("a3"), S("d3"), S("d4")
    wrist = (a2 + d4, -d3, -a3)
    axes = [
        ((0, 0, 0), (0, 0, 1)),
        ((0, 0, 0), (0, -1, 0)),
        ((a2, 0, 0), (0, -1, 0)),
        ((a2, -d3, -a3), (1, 0, 0)),
        (wrist, (0, -1, 0)),
        (wrist, (1, 0, 0)),
    ]
    values = {a2: 0.4318, a3: 0.0203, d3: 0.15005, d4: 0.4318}
    return axes, (wrist, (1, 0, 0), (0, 1, 0)), values


def test_symbolic_puma_560_in_its_stretched_out_pose_gives_corkes_table():
    axes, tool, values = puma_stretched()
    fa = assign_frames(axes, tool=tool, values=values)
    a2, a3, d3, d4 = S("a2"), S("a3"), S("d3"), S("d4")
    t3 = S("theta3")
    assert [(r.theta - r.variable, r.d, r.a, r.alpha) for r in fa.table.rows] == [
        (0, 0, 0, pi / 2),
        (0, 0, a2, 0),
        (-pi / 2, d3, a3, -pi / 2),
        (0, d4, 0, pi / 2),
        (0, 0, 0, -pi / 2),
        (0, 0, 0, 0),
    ]
    assert fa.table.rows[2].theta == t3 - pi / 2  # stretched out: the elbow is at -90° in Corke's
    corke = dhsym.load_table("puma560")
    q = np.random.default_rng(3).uniform(-3, 3, (10, 6))
    shifted = q + np.array([0, 0, -np.pi / 2, 0, 0, 0])
    assert np.allclose(Robot(fa.table).fk(q), Robot(corke).fk(shifted), atol=1e-12)
    assert fa.table.angles.value == "deg"  # every angle is an exact multiple of pi


def test_offsets_false_moves_the_home_angle_into_the_variable_map():
    axes, tool, values = puma_stretched()
    fa = assign_frames(axes, tool=tool, values=values, offsets=False)
    assert fa.table.rows[2].theta == S("theta3")
    assert [m.offset for m in fa.variable_map] == [0, 0, -pi / 2, 0, 0, 0]
    fa.verify()  # uses the map: variable = q + offset


def test_symbols_without_values_are_refused_when_a_sign_is_needed():
    a = S("a")
    with pytest.raises(GeometryError, match="give values for a"):
        assign_frames([((0, 0, 0), (0, 0, 1)), ((a, 0, 0), (0, 0, 1))], verify=False)
    b = sp.Symbol("b", positive=True)
    fa = assign_frames([((0, 0, 0), (0, 0, 1)), ((b, 0, 0), (0, 0, 1))])
    assert fa.table.rows[0].a == b


# --- seed 000 / 004 special cases -------------------------------------------------------


def test_parallel_axes_take_the_common_normal_through_the_previous_origin_so_d_is_zero():
    axes = [((0, 0, 5), (0, 0, 1)), ((2, 0, 0), (0, 0, 1)), ((2, 3, 9), (0, 0, -1))]
    fa = assign_frames(axes)
    assert [r.d for r in fa.table.rows] == [0, 0, 0]
    assert [r.a for r in fa.table.rows][:2] == [2, 3]
    assert fa.table.rows[1].alpha == pi  # antiparallel: alpha = 180°
    assert "the common normal is not unique" in fa.steps[2].text
    assert "so that d1 = 0" in fa.steps[2].text
    mod = assign_frames(axes, convention="modified")
    assert [r.d for r in mod.table.rows] == [0, 0, 0]
    assert [r.a for r in mod.table.rows] == [0, 2, 3]


def test_intersecting_axes_have_a_zero_and_x_along_the_cross_product_closest_to_the_last_x():
    axes = [((0, 0, 0), (0, 0, 1)), ((0, 0, 1), (0, 1, 0)), ((0, 0, 1), (1, 0, 0))]
    fa = assign_frames(axes)
    f1, f2 = fa.frames[1], fa.frames[2]
    assert fa.table.rows[0].a == 0 and fa.table.rows[1].a == 0
    assert tuple(f1.origin) == (0, 0, 1)
    # z0 × z1 = (-1, 0, 0) points against x0 = (1, 0, 0): the sign - gives x1 = (1, 0, 0)
    assert tuple(f1.x) == (1, 0, 0) and "the sign −" in fa.steps[2].text
    # z1 × z2 = (0, 0, -1) is perpendicular to x1: the tie keeps the sign +
    assert tuple(f2.x) == (0, 0, -1) and "the sign +" in fa.steps[3].text
    assert "intersect at (0, 0, 1)" in fa.steps[2].text
    flipped = assign_frames(
        axes, base=Frame(0, sp.Matrix([0, 0, 0]), sp.Matrix([-1, 0, 0]), sp.Matrix([0, 0, 1]))
    )
    assert tuple(flipped.frames[1].x) == (-1, 0, 0)


def test_sign_of_x_follows_the_previous_x():
    axes = [((0, 0, 0), (0, 0, 1)), ((0, 0, 1), (0, -1, 0))]
    fa = assign_frames(axes)  # z0 × z1 = (1, 0, 0) = x0: sign +
    assert tuple(fa.frames[1].x) == (1, 0, 0) and fa.table.rows[0].theta == S("theta1")
    base = Frame(0, sp.Matrix([0, 0, 0]), sp.Matrix([-1, 0, 0]), sp.Matrix([0, 0, 1]))
    fb = assign_frames(axes, base=base)  # now x0 = -x: the sign - keeps theta1 = 0 at home
    assert tuple(fb.frames[1].x) == (-1, 0, 0) and fb.table.rows[0].theta == S("theta1")
    assert "sign −" in fb.steps[2].text


def test_skew_axes_give_the_unique_common_normal():
    axes = [((0, 0, 0), (0, 0, 1)), ((3, 0, 7), (0, 1, 0))]
    fa = assign_frames(axes)
    row = fa.table.rows[0]
    assert (row.d, row.a, row.alpha) == (7, 3, -pi / 2)
    assert tuple(fa.points_b[0]) == (0, 0, 7)  # b1: where x1 meets z0
    assert "skew" in fa.steps[2].text


def test_first_link_revolute_frame_0_coincides_with_frame_1_modified():
    axes = [((1, 2, 0), (0, 0, 1)), ((1, 2, 4), (0, 1, 0))]
    fa = assign_frames(axes, convention="modified")
    r1 = fa.table.rows[0]
    assert (r1.alpha, r1.a, r1.d, r1.theta) == (0, 0, 0, S("theta1"))
    assert fa.frames[0].origin == fa.frames[1].origin and fa.frames[0].x == fa.frames[1].x
    assert fa.table.base == (
        Elementary("T", "x", 1),
        Elementary("T", "y", 2),
        Elementary("T", "z", 4),
    )
    assert "coincident with frame 1" in fa.steps[1].text


def test_first_link_prismatic_frame_0_parallel_to_frame_1_modified():
    axes = [((0, 0, 0), (0, 0, 1), "P"), ((0, 0, 0), (1, 0, 0))]
    fa = assign_frames(axes, convention="modified")
    r1 = fa.table.rows[0]
    assert (r1.alpha, r1.a, r1.theta, r1.d) == (0, 0, 0, S("d1"))
    assert "parallel to frame 1" in fa.steps[1].text


@pytest.mark.parametrize("kind", ["R", "P"])
def test_last_link_modified_has_d_and_theta_zero_at_home(kind):
    axes = [((0, 0, 0), (0, 0, 1)), ((1, 0, 2), (0, 1, 0), kind)]
    fa = assign_frames(axes, convention="modified", tool=((1, 5, 2), (0, 1, 0), (0, 0, 1)))
    last = fa.table.rows[-1]
    assert last.offset == 0 and (last.theta if kind == "P" else last.d) == 0
    assert fa.frames[-1].x == fa.frames[-2].x
    assert fa.table.tool  # the tool point is 3 along the last axis: a tool transform
    assert said(fa, "last link").startswith("Last link (modified convention)")


def test_last_frame_standard_is_the_tool_frame_when_it_obeys_the_dh_rules():
    axes = [((0, 0, 0), (0, 0, 1)), ((1, 0, 0), (0, 0, 1))]
    good = assign_frames(axes, tool=((1.5, 0, 0.25), (0, 0, 1), (0, 1, 0)))
    assert good.table.tool == ()
    assert (good.table.rows[1].a, good.table.rows[1].d) == (sp.Rational(1, 2), sp.Rational(1, 4))
    bad = assign_frames(axes, tool=((1.5, 0, 0), (1, 0, 0), (0, 1, 0)))  # approach along x
    assert bad.table.tool == (Elementary("R", "y", pi / 2),)
    assert "breaks a DH rule" in said(bad, "tool")
    none = assign_frames(axes)
    assert none.frames[-1].origin == none.frames[-2].origin and none.table.rows[-1].a == 0


def test_a_revolute_and_a_prismatic_joint_on_one_line_form_a_cylindrical_pair():
    axes = [((0, 0, 0), (0, 0, 1), "R"), ((0, 0, 3), (0, 0, 1), "P"), ((0, 0, 3), (1, 0, 0), "P")]
    for conv in ("standard", "modified"):
        fa = assign_frames(axes, convention=conv)
        assert "cylindrical pair" in " ".join(fa.step_texts)
        assert all(r.a >= 0 for r in fa.table.rows)


def test_bad_geometry_names_the_joints():
    with pytest.raises(GeometryError, match="joints 1 and 2 coincide"):
        assign_frames([((0, 0, 0), (0, 0, 1)), ((0, 0, 4), (0, 0, -1))])
    with pytest.raises(GeometryError, match="joints 2 and 3 are both prismatic with parallel"):
        assign_frames(
            [((0, 0, 0), (0, 0, 1)), ((1, 0, 0), (1, 0, 0), "P"), ((1, 5, 0), (2, 0, 0), "P")]
        )
    with pytest.raises(GeometryError, match="joint 2: the direction of the axis has zero length"):
        assign_frames([((0, 0, 0), (0, 0, 1)), ((1, 0, 0), (0, 0, 0))])
    with pytest.raises(GeometryError, match="must be orthogonal"):
        assign_frames([((0, 0, 0), (0, 0, 1))], tool=((1, 0, 0), (0, 0, 1), (0, 1, 1)))
    with pytest.raises(GeometryError, match="z0 = .* must point along the axis of joint 1"):
        assign_frames([((0, 0, 0), (0, 0, 1))], base=np.eye(4)[[1, 2, 0, 3]])
    with pytest.raises(GeometryError, match="not on the axis of joint 1"):
        assign_frames([((1, 0, 0), (0, 0, 1))], base=np.eye(4))


def test_exact_inputs_give_exact_tables_and_floats_are_read_exactly():
    h = 0.7071067811865476
    fa = assign_frames([((0, 0, 0), (0, 0, 1)), ((0, 0, 0.5), (0, h, h))])
    assert fa.table.rows[0].alpha == -pi / 4
    assert fa.table.rows[0].d == sp.Rational(1, 2)
    assert "1.57" not in repr(fa.table)


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    st.lists(
        st.tuples(
            st.tuples(*[st.integers(-2, 2)] * 3),
            st.sampled_from(
                [(0, 0, 1), (1, 0, 0), (0, 1, 0), (0, -1, 0), (1, 1, 0), (1, 2, 2), (0, 0, -1)]
            ),
            st.sampled_from("RRP"),
        ),
        min_size=1,
        max_size=4,
    ),
    st.sampled_from(["standard", "modified"]),
)
def test_random_geometry_respects_the_sign_ranges_and_verifies(axes, convention):
    try:
        fa = assign_frames(axes, convention=convention)
    except GeometryError as err:  # only the documented refusals
        assert "coincide" in str(err) or "both prismatic" in str(err)
        return
    for r in fa.table.rows:
        assert r.a.is_nonnegative
        for angle in (r.theta - (r.variable if r.joint.value == "R" else 0), r.alpha):
            assert -sp.pi < angle <= sp.pi
    assert fa.verify(samples=3) < 1e-9


def test_steps_render_as_markdown_with_the_table():
    fa = assign_frames([((0, 0, 0), (0, 0, 1)), ((1, 0, 0), (0, 0, 1))])
    md = fa._repr_markdown_()
    assert md.startswith("**DH frames from joint axes** (standard convention)")
    assert "$z_{0}$ and $z_{1}$ are parallel" in md
    assert "| $i$ | $\\theta_i$ | $d_i$ | $a_i$ | $\\alpha_i$ | joint |" in md
    assert fa.step_texts[-1].startswith("Check: at the home pose and at 5 random configurations")


MEASURED = [  # a measured arm: 12 decimals, generic directions, huge integers in the exact forms
    ((0, 0, 0.431800000003), (0.000000000001, 0.000000000002, 0.999999999999), "R"),
    (
        (0.123456789012, -0.150050000007, 0.650000000001),
        (0.267261241912, -0.534522483825, 0.801783725737),
        "R",
    ),
    (
        (0.554321098765, 0.203000000004, 0.350000000003),
        (0.912870929175, 0.36514837167, -0.182574185835),
        "P",
    ),
]


def test_measured_geometry_works_through_frames_fk_and_convert(capsys, tmp_path):
    from dhsym.cli.main import main
    from dhsym.geometry.conversion import check_conversion, convert
    from dhsym.model.tablefile import dump_table

    approach = (0.267261241912, -0.534522483825, 0.801783725737)
    tool = ((0.9, 0.1, 0.2), approach, (0.534522483825, 0.267261241912, 0))  # a·s = 0 exactly
    fa = assign_frames(MEASURED, tool=tool)  # verified at home and 5 random configurations
    big = [n for r in fa.table.rows for n in r.a.atoms(sp.Integer) if abs(n) > 2**63]
    assert big  # the exact forms hold integers that numpy cannot take the root of
    robot = fa.chain()
    q = np.array([0.3, -1.1, 0.05])
    T = robot.fk(q)
    np.testing.assert_allclose(T, robot.fk([q, q])[1], atol=1e-15)
    # the tool pose equals the geometry: the tool frame moved by the joints' screw motions
    motion = np.eye(4)
    for axis, value in zip(fa.axes, q, strict=True):
        motion = motion @ axis.motion(value)
    home = np.array(fa.tool.frame.matrix.evalf(), dtype=float)
    np.testing.assert_allclose(T, motion @ home, atol=1e-9)
    modified = convert(fa.table, "modified")
    assert check_conversion(fa.table, modified) < 1e-12
    path = tmp_path / "measured.yaml"
    path.write_text(dump_table(fa.table))
    assert main(["convert", str(path), "--to", "modified"]) == 0
    assert "tool pose agrees" in capsys.readouterr().err


@pytest.mark.parametrize("angle", [sp.pi / 2, sp.Rational(1, 3)])
def test_the_home_check_fails_on_a_table_that_does_not_fit_its_frames(angle) -> None:
    # rational factors are checked exactly over QQ, others at 50 digits: both must catch a
    # table whose frame 1 is turned while the assigned frame is not
    from dataclasses import replace

    from dhsym.geometry.frame_choices import flip_x
    from dhsym.geometry.frames import _check_home_exact

    c, s = sp.cos(angle), sp.sin(angle)
    fa = assign_frames(
        [((0, 0, 0), (0, 0, 1), "R"), ((1, 0, 0), (0, -s, c), "R"), ((2, 0, 0), (0, 0, 1), "R")]
    )
    _check_home_exact(fa)  # the table as assigned fits
    with pytest.raises(GeometryError, match="internal check failed: frame 1"):
        _check_home_exact(replace(fa, table=flip_x(fa.table, 1)))
