# ---
# jupyter:
#   jupytext:
#     formats: ipynb,py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#       format_version: '1.3'
#       jupytext_version: 1.19.6
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 7 · From geometry to DH: frames, conventions, joints and task chains
#
# The hardest part of the DH method is not multiplying matrices: it is *getting the table*.
# This notebook lets dhsym do it the way the lectures do, one rule at a time. The lectures:
#
# - T. Asokan (IIT Madras), Introduction to Robotics, Lecture 2.6 "DH algorithm";
# - K. Kurien Issac (IIT Bombay), Robotics, Lecture 19;
# - A. Ghosal (IISc), Lecture 5 "Elements of robot – Joints, Links";
# - S. Mohan (IIT Palakkad), Mechanics and Control of Robotic Manipulators, Lecture 9 "DH
#   parameters";
# - IRob2305 Introduction to Robotics, Lecture 5 "Manipulator kinematics … Denavit–Hartenberg
#   parameters … forward kinematics" (the toolbox numbers of the PUMA 560).
#
# 1. **Frames from joint axes** — Asokan's DH algorithm on the PUMA 560 set up in its
#    stretched-out home pose (as Issac draws it), with every rule written out;
# 2. **parallel axes** — Ghosal's special cases on a SCARA;
# 3. **the two conventions side by side** (as Mohan builds them) and the conversion between them;
# 4. **joint types** — Ghosal's table of pairs, a spherical wrist as three revolute joints,
#    and the mobility of textbook mechanisms;
# 5. **the pick-and-place chain** of Issac's lecture: ${}^1T_3 = {}^1T_2\,{}^2T_3$ and
#    ${}^1T_6 = {}^1T_4\,{}^4T_5\,{}^5T_6$ with ${}^5T_6 = {}^2T_3$, with a picture of the frames.

# %%
# %matplotlib inline
import numpy as np
import sympy as sp
from IPython.display import Markdown, display
from matplotlib.figure import Figure

import dhsym
from dhsym.errors import GeometryError
from dhsym.geometry import (
    PAIRS,
    FrameChain,
    Joint,
    JointAxis,
    assign_frames,
    check_conversion,
    to_modified,
    to_standard,
)
from dhsym.geometry.joints import decompose, four_bar, planar_five_bar, serial_6r, stewart_platform
from dhsym.notation import table_markdown

# %% [markdown]
# ## 1. The PUMA 560, stretched out
#
# Issac draws the PUMA "stretched out" so that every joint axis and every offset lies along a
# global $x$, $y$ or $z$ direction. Joint 1 is vertical; the shoulder (2), elbow (3) and wrist pitch
# (5) axes are horizontal; the forearm roll (4) and the hand roll (6) run along the arm. The
# lengths stay symbols: $a_2$ (upper arm), $a_3$ (elbow offset), $d_3$ (shoulder offset) and $d_4$
# (forearm), with the toolbox numbers of the IRob2305 lecture for pictures and checks.
#
# Each axis is a line: a point on it and a direction (exact numbers, or symbols for lengths).

# %%
a2, a3, d3, d4 = sp.symbols("a2 a3 d3 d4", real=True)
values = {a2: 0.4318, a3: 0.0203, d3: 0.15005, d4: 0.4318}
wrist = (a2 + d4, -d3, -a3)
axes = [
    JointAxis((0, 0, 0), (0, 0, 1), "R", "1"),         # waist: vertical
    JointAxis((0, 0, 0), (0, -1, 0), "R", "2"),        # shoulder: horizontal
    JointAxis((a2, 0, 0), (0, -1, 0), "R", "3"),       # elbow: parallel to the shoulder
    JointAxis((a2, -d3, -a3), (1, 0, 0), "R", "4"),    # forearm roll: along the arm
    JointAxis(wrist, (0, -1, 0), "R", "5"),            # wrist pitch
    JointAxis(wrist, (1, 0, 0), "R", "6"),             # hand roll
]
tool = (wrist, (1, 0, 0), (0, 1, 0))  # tool point, approach a (z6), sliding s (y6)
display(Markdown("| joint | point | direction |\n|---|---|---|\n" + "\n".join(
    f"| {ax.name} | ${sp.latex(tuple(ax.point))}$ | ${sp.latex(tuple(ax.direction))}$ |" for ax in axes)))

# %% [markdown]
# `assign_frames` follows Asokan's algorithm step by step: $z_k$ along the axis of joint $k+1$, the origin
# at the intersection of consecutive axes or at the foot of their common normal, $x_k$ along the
# common normal (or $\pm z_{k-1}\times z_k$ when the axes meet), the last frame at the tool point
# with $z_n$ along the approach vector and $y_n$ along the sliding vector. Every step is recorded
# as a sentence; the last one is a check that the table moves each frame exactly like the joints
# move the links (at the home pose and at random configurations).

# %%
puma = assign_frames(axes, tool=tool, values=values, name='PUMA 560 (from its axes)')
puma

# %% [markdown]
# The algorithm found Corke's table (the toolbox printout) — with one difference: in the stretched-out pose
# the elbow sits at $-90^\circ$ of Corke's zero pose, so row 3 carries the constant offset
# $\theta_3 - 90^\circ$ (the joint variable is zero *at the home pose we drew*). The points $b_k$
# of Asokan's algorithm (where $x_k$ meets $z_{k-1}$) are part of the result:

# %%
corke = dhsym.load_table("puma560")
for mine, theirs in zip(puma.table.rows, corke.rows):
    assert (mine.d, mine.a, mine.alpha) == (theirs.d, theirs.a, theirs.alpha)
print("theta column:", [r.theta for r in puma.table.rows])
print("b_k:", [tuple(b) for b in puma.points_b])
print("variable map (variable = sign*q + offset):", [(str(m.variable), m.sign, m.offset) for m in puma.variable_map])

# %% [markdown]
# Same robot, same numbers: the tool pose of our table at $q$ equals Corke's at $q$ with the elbow
# shifted by $-90^\circ$. The picture is the stretched-out home pose with the frames the algorithm
# assigned.

# %%
q = np.random.default_rng(0).uniform(-np.pi, np.pi, (100, 6))
ours, theirs = dhsym.Robot(puma.table).fk(q), dhsym.Robot(corke).fk(q - [0, 0, np.pi / 2, 0, 0, 0])
print("largest difference over 100 random configurations:", np.abs(ours - theirs).max())
fig = dhsym.Robot(puma.table).plot([0] * 6, scale=0.12, title="PUMA 560 stretched out: frames from the DH algorithm")
fig.axes[0].view_init(elev=25, azim=-60)
fig

# %% [markdown]
# ## 2. Parallel axes: a SCARA
#
# Ghosal's first special case: when consecutive axes are **parallel** there are infinitely many
# common normals, so one is *chosen* — the one through the previous origin, which makes the offset
# $d$ zero. A SCARA has four vertical axes: the shoulder, the elbow, the quill (prismatic, pointing
# down) and the hand roll on the same line as the quill (a revolute and a prismatic joint on one
# line: a cylindrical pair).

# %%
scara_axes = [
    ((0, 0, 0), (0, 0, 1), "R"),
    ((0.4, 0, 0), (0, 0, 1), "R"),
    ((0.7, 0, 0), (0, 0, -1), "P"),
    ((0.7, 0, 0), (0, 0, -1), "R"),
]
scara_tool = ((0.7, 0, -0.05), (0, 0, -1), (0, -1, 0))
scara = assign_frames(scara_axes, tool=scara_tool, name="SCARA (from its axes)")
for s in scara.steps[:6]:
    display(Markdown("- " + s.markdown))
display(scara.table)

# %% [markdown]
# This is exactly the built-in SCARA of Spong (Table 3.6), and the tool poses agree for every
# configuration. Two consecutive **prismatic** joints on parallel axes are refused: their
# displacements are not independent (Ghosal).

# %%
builtin = dhsym.load_table("scara")
q = np.random.default_rng(1).uniform(-1, 1, (50, 4))
print("same rows as the built-in SCARA:", [r.params() for r in scara.table.rows] == [r.params() for r in builtin.substituted().rows])
print("largest difference to the built-in SCARA:", np.abs(dhsym.Robot(scara.table).fk(q) - dhsym.Robot(builtin).fk(q)).max())
try:
    assign_frames([((0, 0, 0), (0, 0, 1), "R"), ((1, 0, 0), (1, 0, 0), "P"), ((1, 1, 0), (1, 0, 0), "P")])
except GeometryError as err:
    print("GeometryError:", err)

# %% [markdown]
# ## 3. Standard and modified, side by side
#
# Mohan builds both link matrices from the same four elementary transforms, in a different
# order: standard $R_z(\theta_i)T_z(d_i)T_x(a_i)R_x(\alpha_i)$, modified (Craig)
# $R_x(\alpha_{i-1})T_x(a_{i-1})R_z(\theta_i)T_z(d_i)$. From the same axes the algorithm gives
# both tables; in the modified one frame $i$ sits *on* joint axis $i$ (Ghosal's first- and
# last-link rules fix frames 0 and $n$).

# %%
craig = assign_frames(axes, tool=tool, values=values, convention="modified", name="PUMA 560 (modified)")
display(Markdown("**standard (Asokan's rules)**\n\n" + table_markdown(puma.table)
                 + "\n\n**modified (Ghosal's rules)**\n\n" + table_markdown(craig.table)))
for s in craig.steps[1:3]:
    display(Markdown("- " + s.markdown))

# %% [markdown]
# Because $T_x$ and $R_x$ commute, a product of standard link matrices regroups into modified ones
# with the *same numbers*: row $i$ of the modified table takes $\alpha_{i-1}, a_{i-1}$ from
# standard row $i-1$, and $T_x(a_n)R_x(\alpha_n)$ moves into the tool transform. `to_modified` and
# `to_standard` do exactly that, and `check_conversion` compares the tool poses at random $q$
# (the command line: `dhsym convert puma560 --to modified -o puma560_mod.yaml`).

# %%
mod = to_modified(corke)
display(mod)
print("tool transform:", mod.tool, "| base transform:", mod.base)
print("largest tool-pose difference:", check_conversion(corke, mod))
print("round trip gives the table back:", to_standard(mod) == corke)

# %% [markdown]
# ## 4. Joint types and mobility
#
# Ghosal's table of pairs: a joint that imposes $m$ constraints leaves $6-m$ freedoms.

# %%
display(Markdown("| pair | symbol | DOF | constraints $m$ | as 1-DOF joints |\n|---|---|---|---|---|\n" + "\n".join(
    f"| {p.name} | {p.symbol} | {p.dof} | {p.constraints} | {p.equivalent or '—'} |" for p in PAIRS.values())))

# %% [markdown]
# A spherical joint "can be represented as 3 intersecting rotary joints" (Ghosal), so a robot
# can be *described* with its wrist as one S joint and still get a DH table. Here the PUMA again,
# wrist written as `Joint("S", …, euler=True)` (roll–pitch–roll, like the real wrist):

# %%
joints = [Joint("R", (0, 0, 0), (0, 0, 1)), Joint("R", (0, 0, 0), (0, -1, 0)),
          Joint("R", (a2, 0, 0), (0, -1, 0)),
          Joint("S", wrist, (1, 0, 0), second=(0, -1, 0), euler=True, name="wrist")]
print([(ax.name, ax.joint, tuple(ax.direction)) for ax in decompose(joints)])
same = assign_frames(decompose(joints), tool=tool, values=values)
print("same table as from the six axes:", [r.params() for r in same.table.rows] == [r.params() for r in puma.table.rows])

# %% [markdown]
# The Grübler–Kutzbach count $M = \lambda(N-1-J) + \sum f_i$ ($\lambda = 6$ in space, 3 in the
# plane; $N$ links with the ground, $J$ joints). For the Stewart platform it gives 12, of which 6
# are *idle*: each S–P–S leg can spin about its own axis without moving anything.

# %%
for m in (four_bar(), planar_five_bar(), serial_6r(), stewart_platform()):
    print(f"{m.name:26s} {m.equation}")

# %% [markdown]
# ## 5. The pick-and-place chain (Issac's lecture)
#
# Frame {1} is the global frame, {2} the part on the table, {3} the gripper holding it, {4} the
# inclined plane, {5} the part's final place on it and {6} the gripper there. The numbers below
# are an illustrative scene (metres): the part turned $90^\circ$ on the table, the gripper $0.15$
# above it pointing down, the plane tilted by the angle with $\cos = 4/5$, $\sin = 3/5$.
# Because the grip does not change, ${}^5T_6 = {}^2T_3$.

# %%
R = sp.Rational
def trans(x, y, z):
    return sp.Matrix([[1, 0, 0, x], [0, 1, 0, y], [0, 0, 1, z], [0, 0, 0, 1]])
def rot(axis, c, s):
    M = sp.eye(4)
    j, k = {"x": (1, 2), "z": (0, 1)}[axis]
    M[j, j], M[j, k], M[k, j], M[k, k] = c, -s, s, c
    return M

chain = (FrameChain()
         .known(1, 2, trans(R(3, 5), R(-1, 5), R(1, 10)) * rot("z", 0, 1), "part on the table")
         .known(2, 3, trans(R(1, 20), R(1, 50), R(3, 20)) * rot("x", -1, 0), "grip")
         .known(1, 4, trans(R(-1, 5), R(3, 5), R(3, 10)) * rot("x", R(4, 5), R(3, 5)), "inclined plane")
         .known(4, 5, trans(R(1, 10), R(1, 20), 0), "final place of the part")
         .same_as(5, 6, 2, 3, "the grip does not change"))
pick = chain.derive(1, 3)
pick

# %%
place = chain.derive(1, 6)
place

# %% [markdown]
# The gripper must not dig into the table: it lifts off along its own $z$ axis first and comes down
# onto the plane along $z_6$ (Issac: "a translation along the $z_3$ axis with nothing else
# changing"). With $z$ pointing into the part, the frame $h$ before it is $T\,T_z(-h)$.
# A transform given twice must agree — a loop that does not close is an error.

# %%
chain = chain.approach(3, R(1, 10), "lift").approach(6, R(1, 10), "above")
print("lift :", chain[1, "lift"].matrix[:3, 3].T)
print("above:", chain[1, "above"].matrix[:3, 3].T)
print(chain.derive("lift", "above").text)
try:
    chain.known(1, 3, trans(0, 0, 1) * chain[1, 3].matrix)
except dhsym.ChainError as err:
    print("ChainError:", err)


# %%
def triad(ax, T, label, length=0.08):
    T = np.array(T.evalf(), dtype=float)
    o = T[:3, 3]
    for k, color in enumerate(("tab:red", "tab:green", "tab:blue")):
        ax.quiver(*o, *(length * T[:3, k]), color=color, linewidth=1.5)
    ax.text(*(o + 0.015), label, fontsize=9)

fig = Figure(figsize=(7, 6), layout="constrained")
ax = fig.add_subplot(projection="3d")
for name in ["1", "2", "3", "4", "5", "6", "lift", "above"]:
    triad(ax, chain[1, name].matrix, "{%s}" % name)
corner, tilt = np.array([-0.2, 0.6, 0.3]), np.array(chain[1, 4].matrix[:3, :3].evalf(), dtype=float)
plane = np.array([corner + tilt @ [u, v, 0] for u, v in [(0, 0), (0.35, 0), (0.35, 0.25), (0, 0.25), (0, 0)]])
ax.plot(*plane.T, color="0.5")
table = np.array([[0.4, -0.4, 0.1], [0.8, -0.4, 0.1], [0.8, 0.1, 0.1], [0.4, 0.1, 0.1], [0.4, -0.4, 0.1]])
ax.plot(*table.T, color="0.5")
path = np.array([np.array(chain[1, f].matrix[:3, 3].evalf(), dtype=float).ravel() for f in ["3", "lift", "above", "6"]])
ax.plot(*path.T, "k--", linewidth=1)
ax.set(xlabel="x", ylabel="y", zlabel="z", title="pick and place: frames {1} … {6}, lift-off and approach")
ax.set_box_aspect((1, 1, 0.6))
ax.view_init(elev=22, azim=-50)
fig

# %% [markdown]
# ## Summary
#
# * `assign_frames(axes, tool=…, convention=…)` turns joint axes into frames and a DH table, with a
#   lecture-style sentence per rule and a check against the geometry; exact inputs give exact tables.
# * `to_modified` / `to_standard` (and `dhsym convert`) switch conventions, moving $T_x R_x$ into the
#   base or tool transform so the tool pose is unchanged.
# * `Joint` writes C, U, S and E joints as 1-DOF joints; `Mechanism.mobility` counts freedoms.
# * `FrameChain` composes, inverts and closes loops of named frames, exactly.
