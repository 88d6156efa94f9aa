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
# # 8 · Velocities: the Jacobian and the singular configurations
#
# The lectures so far end with forward kinematics: the pose of the tool, ${}^0T_n(q)$. The
# next question is how fast the tool moves when the joints move. The answer is a matrix, the
# **manipulator Jacobian** $J(q)$: $\;[v;\ \omega] = J(q)\,\dot q$. Where $J$ loses rank the
# arm is *singular*: some direction of motion is lost, whatever the joints do.
#
# We build $J$ the way the textbook does (M. W. Spong, S. Hutchinson and M. Vidyasagar,
# *Robot Modeling and Control*, §4.6 the geometric Jacobian, §4.10 singularities, §4.12
# manipulability), on the two arms of the earlier notebooks: the planar 2R of IRob2305
# Introduction to Robotics, Lecture 5 (Example 2) and the PUMA 560 of the same lecture's
# toolbox printout. You will
#
# 1. build the 2R Jacobian column by column and check it against the derivative of ${}^0T_2$,
# 2. factor its determinant and find where it vanishes,
# 3. draw the **manipulability ellipse** and watch it flatten near the singularity,
# 4. do the same for the PUMA 560: its $6 \times 6$ Jacobian, and $\det J$ factored into the
#    elbow, shoulder and wrist singularities.
#
# Run the cells from top to bottom (**Shift + Enter**).

# %%
# %matplotlib inline
import numpy as np
import sympy as sp
from IPython.display import Markdown, display

import dhsym
from dhsym.explain import derive_jacobian, derive_singularities

# %% [markdown]
# ## 1. The 2R Jacobian, column by column
#
# Joint $i$ turns about the axis $z_{i-1}$ of frame $i-1$ (standard convention), through the
# origin $o_{i-1}$. A rotation $\dot\theta_i$ about that axis moves the tool point $o_n$ with
# velocity $\dot\theta_i\, z_{i-1} \times (o_n - o_{i-1})$ and turns the tool with angular
# velocity $\dot\theta_i\, z_{i-1}$. So column $i$ of $J$ is
#
# $$J_i = \begin{bmatrix} z_{i-1} \times (o_n - o_{i-1}) \\ z_{i-1} \end{bmatrix}
# \quad\text{(revolute)}, \qquad
# J_i = \begin{bmatrix} z_{i-1} \\ 0 \end{bmatrix} \quad\text{(prismatic)}.$$
#
# Both vectors come from the forward kinematics: $z_{i-1}$ is the third column of
# ${}^0T_{i-1}$ and $o_n - o_{i-1}$ the difference of two position columns.

# %%
robot = dhsym.load("planar2r")
display(Markdown(derive_jacobian(robot).to_markdown()))

# %% [markdown]
# The same matrix as an exact sympy object, in the lecture's $C_{12}$ notation:

# %%
J = robot.jacobian()
J

# %% [markdown]
# **Check.** The top three rows are the derivative of the position $p(q)$ of ${}^0T_2$; the
# bottom three are the angular velocity read from $\dot R R^T$. `verify()` proves both exactly
# (no numbers involved):

# %%
J.verify()

# %% [markdown]
# And with numbers: at one configuration the Jacobian times a small joint step is the step
# of the tool point, to first order.

# %%
q = np.array([0.4, 1.1])
dq = np.array([1e-6, -2e-6])
step = robot.fk(q + dq)[:3, 3] - robot.fk(q)[:3, 3]
print("J_v dq      =", robot.jacob0(q)[:3] @ dq)
print("p(q+dq)-p(q)=", step)

# %% [markdown]
# ## 2. Where the 2R arm is singular
#
# Only the $x$ and $y$ rows move the tool point of a planar arm, so its position Jacobian
# $J_v$ is $2 \times 2$, and it loses rank where $\det J_v = 0$:

# %%
sing = derive_singularities(robot)
display(Markdown(sing.to_markdown()))

# %% [markdown]
# $\det J_v = a_1 a_2 S_2$ vanishes at $\theta_2 = 0$ (stretched out) and $\theta_2 = \pi$
# (folded back): the two edges of the workspace. There the tool can only move along one
# direction, the tangent of the circle it lies on. In numbers:

# %%
for t2 in (1.2, 0.1, 0.0):
    Jv = robot.jacob0([0.5, t2])[:2]
    det = round(float(np.linalg.det(Jv)), 4) + 0.0  # + 0.0: no "-0.0000"
    print(f"theta2 = {t2:3.1f}:  det J_v = {det:+.4f},  rank = {np.linalg.matrix_rank(Jv)}")

# %% [markdown]
# ## 3. The manipulability ellipse
#
# All joint rates with $\|\dot q\| = 1$ move the tool point with velocities
# $v = J_v \dot q$ that fill an ellipse: its semi-axes point along the *left singular
# vectors* of $J_v$ and are as long as its *singular values* $\sigma_1 \ge \sigma_2$. Their
# product is the **manipulability** $w = \sigma_1 \sigma_2 = \sqrt{\det(J_v J_v^T)}$
# (Yoshikawa's measure), here $w = a_1 a_2 |S_2|$.
#
# Three configurations with the same $\theta_1 = 30°$, the elbow opening from $90°$ to $10°$:
# the ellipse flattens as the arm stretches out, and $w$ drops.

# %%
dhsym.plot_manipulability(robot, [[30, 90], [30, 45], [30, 10]], deg=True)

# %%
from dhsym.plot.ellipses import velocity_ellipse

for t2 in (90, 45, 10, 0):
    e = velocity_ellipse(robot, [30, t2], deg=True)
    print(f"theta2 = {t2:2d}°:  sigma = {e.axes.round(4)},  w = {e.w:.4f},  "
          f"a1 a2 |S2| = {1.0 * 0.8 * abs(np.sin(np.radians(t2))):.4f}")

# %% [markdown]
# At $\theta_2 = 0$ one singular value is $0$: the ellipse is a segment.
#
# ## 4. The PUMA 560
#
# The same construction for the six joints of the PUMA 560. The joint axes now point in every
# direction, but each column is still $z_{i-1} \times (o_6 - o_{i-1})$ over $z_{i-1}$. The
# three wrist axes meet at the wrist centre $o_4 = o_5 = o_6$, so the wrist joints do not move
# it: the top half of columns 4–6 is zero.

# %%
puma = dhsym.load("puma560")
display(Markdown(derive_jacobian(puma).to_markdown()))

# %%
puma.jacobian().verify()

# %% [markdown]
# ### Its singular configurations
#
# Take the Jacobian at the wrist centre. The wrist does not move that point, so
# $J = \begin{bmatrix} J_{11} & 0 \\ J_{21} & J_{22} \end{bmatrix}$ is block triangular and
# $\det J = \det J_{11} \det J_{22}$ (Spong, Hutchinson and Vidyasagar, §4.10: *decoupling of
# singularities*). Moving the reference point from the wrist centre to the tool does not
# change $\det J$. dhsym factors each block as it expands it and names every factor from the
# arm's structure:

# %%
puma_sing = derive_singularities(puma)
display(Markdown(puma_sing.to_markdown()))

# %% [markdown]
# - the **elbow** singularity $a_3 S_3 + d_4 C_3 = 0$: the forearm is stretched out or folded
#   back along the upper arm (the edge of the workspace);
# - the **shoulder** singularity $a_2 C_2 + a_3 C_{23} - d_4 S_{23} = 0$: the wrist centre is
#   on the vertical line through the shoulder offset, where joint 1 cannot move it sideways;
# - the **wrist** singularity $S_5 = 0$: axes 4 and 6 line up and turn the tool about the same
#   axis.
#
# The exact factored form equals the determinant of the $6 \times 6$ matrix:

# %%
from dhsym.kinematics.singularities import singularities

singularities(puma).verify()

# %% [markdown]
# **In numbers.** Start from a general configuration and move onto each singular set: the
# determinant of the numeric Jacobian drops to zero, and the smallest singular value with it.

# %%
a2, a3, d4 = 0.4318, 0.0203, 0.4318
q0 = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
elbow = q0.copy()
elbow[2] = np.arctan2(-d4, a3)  # a3 S3 + d4 C3 = 0
shoulder = q0.copy()
# a2 C2 + a3 C23 - d4 S23 = 0 is A cos(theta2) + B sin(theta2) = 0 for theta3 fixed
A = a2 + a3 * np.cos(q0[2]) - d4 * np.sin(q0[2])
B = -a3 * np.sin(q0[2]) - d4 * np.cos(q0[2])
shoulder[1] = np.arctan2(-A, B)
wrist = q0.copy()
wrist[4] = 0.0
for name, q in [("general", q0), ("elbow", elbow), ("shoulder", shoulder), ("wrist", wrist)]:
    Jq = puma.jacob0(q)
    print(f"{name:9s} det J = {np.linalg.det(Jq):+.2e}   smallest singular value = "
          f"{np.linalg.svd(Jq, compute_uv=False)[-1]:.2e}")

# %% [markdown]
# At the shoulder singularity the wrist centre sits above the shoulder offset: its distance
# from the axis of joint 1 is exactly $|d_3|$.

# %%
c = puma.fk(shoulder)[:3, 3]
print(f"distance of the wrist centre from z0 = {np.hypot(c[0], c[1]):.6f},  d3 = 0.15005")

# %% [markdown]
# The velocity ellipsoid of the PUMA's tool point (the three position rows of $J$) at the
# general configuration:

# %%
dhsym.plot_manipulability(puma, q0)

# %% [markdown]
# ## Summary
#
# - Column $i$ of the geometric Jacobian is $z_{i-1} \times (o_n - o_{i-1})$ over $z_{i-1}$
#   for a revolute joint and $z_{i-1}$ over $0$ for a prismatic one; dhsym prints it in the
#   lecture's notation and proves it equal to the derivative of the forward kinematics.
# - The arm is singular where $\det J = 0$. For the 2R that is $S_2 = 0$; for the PUMA 560
#   $\det J = a_2 S_5 (a_2 C_2 + a_3 C_{23} - d_4 S_{23})(a_3 S_3 + d_4 C_3)$: wrist, shoulder
#   and elbow.
# - The manipulability ellipse shows the directions the tool moves easily; it collapses at a
#   singularity.
#
# From the command line: `dhsym derive puma560 --what jacobian` and
# `dhsym derive puma560 --what singularities` (also `--format latex|markdown|json`), and
# `dhsym handout puma560 -o puma.tex --sections fk,jacobian,singularities --pdf`.
