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
# # 12 · From a robot's URDF to its DH table, closed form and frames
#
# Robot makers describe their arms in URDF: links joined by joints, each joint with an origin
# (a translation and roll–pitch–yaw angles) and an axis — not as a DH table. This notebook takes
# the URDF of a Universal Robots UR5 and lets dhsym find its DH table the way the lectures do:
# place the joint axes at the zero pose, then assign frames rule by rule (T. Asokan, IIT Madras,
# Introduction to Robotics, Lecture 2.6 "DH algorithm"; A. Ghosal, IISc, Lecture 5, for the
# modified convention).
#
# 1. **the URDF** — the kinematic part of the UR5 description (ros-industrial `universal_robot`,
#    BSD licence), as shipped;
# 2. **the DH table** with a sentence for every choice of frame;
# 3. **the closed form** of the first three links;
# 4. **the frames picture**, and a check that the table moves the tool exactly like the URDF;
# 5. **back to URDF**, for a robot viewer.

# %%
# %matplotlib inline
import numpy as np
from IPython.display import Markdown, display

import dhsym
from dhsym.formats.urdf import import_urdf, write_urdf

# %% [markdown]
# ## 1. The URDF
#
# The joints of `ur5_robot.urdf` (visuals, collisions and inertials left out here; dhsym never
# opens meshes anyway). Note the decimals: `0.089159` is the shoulder height, and `1.57079632679`
# is $\pi/2$ written to 12 digits.

# %%
UR5 = """<robot name="ur5">
  <link name="base_link"/> <link name="shoulder_link"/> <link name="upper_arm_link"/>
  <link name="forearm_link"/> <link name="wrist_1_link"/> <link name="wrist_2_link"/>
  <link name="wrist_3_link"/> <link name="tool0"/>
  <joint name="shoulder_pan_joint" type="revolute">
    <parent link="base_link"/> <child link="shoulder_link"/>
    <origin rpy="0.0 0.0 0.0" xyz="0.0 0.0 0.089159"/> <axis xyz="0 0 1"/>
    <limit effort="150.0" lower="-6.28318530718" upper="6.28318530718" velocity="3.15"/>
  </joint>
  <joint name="shoulder_lift_joint" type="revolute">
    <parent link="shoulder_link"/> <child link="upper_arm_link"/>
    <origin rpy="0.0 1.57079632679 0.0" xyz="0.0 0.13585 0.0"/> <axis xyz="0 1 0"/>
    <limit effort="150.0" lower="-6.28318530718" upper="6.28318530718" velocity="3.15"/>
  </joint>
  <joint name="elbow_joint" type="revolute">
    <parent link="upper_arm_link"/> <child link="forearm_link"/>
    <origin rpy="0.0 0.0 0.0" xyz="0.0 -0.1197 0.425"/> <axis xyz="0 1 0"/>
    <limit effort="150.0" lower="-3.14159265359" upper="3.14159265359" velocity="3.15"/>
  </joint>
  <joint name="wrist_1_joint" type="revolute">
    <parent link="forearm_link"/> <child link="wrist_1_link"/>
    <origin rpy="0.0 1.57079632679 0.0" xyz="0.0 0.0 0.39225"/> <axis xyz="0 1 0"/>
    <limit effort="28.0" lower="-6.28318530718" upper="6.28318530718" velocity="3.2"/>
  </joint>
  <joint name="wrist_2_joint" type="revolute">
    <parent link="wrist_1_link"/> <child link="wrist_2_link"/>
    <origin rpy="0.0 0.0 0.0" xyz="0.0 0.093 0.0"/> <axis xyz="0 0 1"/>
    <limit effort="28.0" lower="-6.28318530718" upper="6.28318530718" velocity="3.2"/>
  </joint>
  <joint name="wrist_3_joint" type="revolute">
    <parent link="wrist_2_link"/> <child link="wrist_3_link"/>
    <origin rpy="0.0 0.0 0.0" xyz="0.0 0.0 0.09465"/> <axis xyz="0 1 0"/>
    <limit effort="28.0" lower="-6.28318530718" upper="6.28318530718" velocity="3.2"/>
  </joint>
  <joint name="wrist_3_link-tool0_fixed_joint" type="fixed">
    <origin rpy="-1.57079632679 0 0" xyz="0 0.0823 0"/>
    <parent link="wrist_3_link"/> <child link="tool0"/>
  </joint>
</robot>"""

# %% [markdown]
# ## 2. The DH table, and why
#
# `import_urdf` follows the chain from the root link to the tip (`tool0`), multiplies the
# origins to place every joint axis at the zero pose, folds the fixed joint into the tool, and
# hands the axes to `assign_frames`. The DH $z$ axes point along the URDF axes and the variables
# are zero at the URDF's zero, so $q$ means the same in both.

# %%
ur5 = import_urdf(UR5, tip="tool0")
display(Markdown(dhsym.notation.table_markdown(ur5.table)))
print(ur5.table.warnings[0])

# %% [markdown]
# The lengths are the file's decimals, exactly: $d_1 = 0.089159$, $a_2 = 0.425$,
# $a_3 = 0.39225$, $d_4 = 0.10915$ (the sideways offsets of shoulder, elbow and wrist added up:
# $0.13585 - 0.1197 + 0.093$), $d_5 = 0.09465$, $d_6 = 0.0823$ — the table Universal Robots
# publish, up to the signs of $a_2, a_3$, which follow the URDF's axis directions. Every choice
# has its sentence:

# %%
for k, step in enumerate(ur5.steps, start=1):
    print(f"{k}. {step}")

# %% [markdown]
# ## 3. The closed form
#
# From here the robot is like any other DH table: the lecture-style closed form of the first
# three links (the shoulder and the two parallel axes that make the planar part of the arm).

# %%
robot = dhsym.Robot(ur5.table)
robot.transform(0, 3)

# %% [markdown]
# ## 4. Frames, and the check against the URDF
#
# The same pose computed two ways: the DH table's `fk`, and the URDF itself — each joint's origin
# times a rotation about its axis (Rodrigues' formula), multiplied along the chain.

# %%
def rodrigues(axis, angle):
    u = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def urdf_pose(q):
    T = np.eye(4)
    for joint, qk in zip(ur5.joints, [*q, 0.0], strict=True):
        (x, y, z), (r, p, w) = [[float(v) for v in t] for t in (joint.origin.xyz, joint.origin.rpy)]
        M = np.eye(4)
        M[:3, :3] = rodrigues((0, 0, 1), w) @ rodrigues((0, 1, 0), p) @ rodrigues((1, 0, 0), r)
        M[:3, 3] = (x, y, z)
        if joint.moving:
            J = np.eye(4)
            J[:3, :3] = rodrigues([float(v) for v in joint.axis], qk)
            M = M @ J
        T = T @ M
    return T


qs = np.random.default_rng(0).uniform(-np.pi, np.pi, (50, 6))
print("largest difference over 50 configurations:",
      max(np.abs(robot.fk(q) - urdf_pose(q)).max() for q in qs))
fig = robot.plot([0, -np.pi / 2, np.pi / 2, 0, np.pi / 2, 0], scale=0.08,
                 title="UR5 from its URDF: DH frames")
fig

# %% [markdown]
# ## 5. Back to URDF
#
# Any DH table can go the other way: one URDF link per DH frame, cylinders on the joint axes,
# boxes along the links. Reading it back gives the same forward kinematics.

# %%
text = write_urdf(robot)
print("\n".join(text.splitlines()[:12]))
again = dhsym.from_urdf(text, tip="tool")
print("round trip, largest difference:", max(np.abs(again.fk(q) - robot.fk(q)).max() for q in qs))

# %% [markdown]
# ## Summary
#
# * `dhsym.from_urdf(path, tip=…)` (or `dhsym.load("robot.urdf", tip=…)`) reads a URDF chain into
#   a DH table in either convention, with exact decimals and the frame-assignment sentences.
# * `robot.to_urdf()` writes a DH table as a URDF for a robot viewer.
# * On the command line: `dhsym convert robot.urdf --tip tool0 --to standard -o table.yaml`,
#   and `dhsym show/derive/fk/plot robot.urdf --tip tool0`.
