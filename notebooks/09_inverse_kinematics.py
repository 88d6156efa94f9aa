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
# # 9 · Inverse kinematics in closed form: the 2R and the PUMA 560
#
# Forward kinematics gives the pose from the joints. The **inverse** problem asks the
# opposite: which joint values put the tool at a given pose
# $T = \begin{bmatrix} n & s & a & p \\ 0 & 0 & 0 & 1 \end{bmatrix}$? The PUMA lecture
# announces it ("set up these reference frames, define these linkage parameters, and then
# do the forward and inverse kinematics"; IRob2305 Introduction to Robotics, Lecture 5),
# and so does T. Asokan's lecture on the DH algorithm (IIT Madras, Introduction to Robotics,
# Lecture 2.6: "first we talk about forward kinematics and then we go to the inverse
# kinematics problem"). We solve it as the textbooks do (M. W. Spong, S. Hutchinson and
# M. Vidyasagar, *Robot Modeling and Control*, §5.3; J. J. Craig, *Introduction to Robotics*,
# §4.7):
#
# 1. the planar 2R: the **law of cosines** for the elbow and one `atan2` for the shoulder,
#    with the two elbow branches;
# 2. why `atan2` and not `atan`;
# 3. the PUMA 560 by **kinematic decoupling**: the wrist centre, the arm (left/right,
#    elbow up/down), the wrist (flipped or not): all **8 solutions**, drawn side by side;
# 4. what happens at a wrist singularity.
#
# Run the cells from top to bottom (**Shift + Enter**).

# %%
# %matplotlib inline
import numpy as np
from IPython.display import Markdown, display

import dhsym
from dhsym.explain import derive_inverse

# %% [markdown]
# ## 1. The planar 2R
#
# The tool point is $p_x = a_1 C_1 + a_2 C_{12}$, $p_y = a_1 S_1 + a_2 S_{12}$. The sum of
# their squares does not contain $\theta_1$: it is the law of cosines of the triangle
# base–elbow–tool, $p_x^2 + p_y^2 = a_1^2 + a_2^2 + 2 a_1 a_2 C_2$. So $C_2$ is known, and
# $S_2 = \pm\sqrt{1 - C_2^2}$ gives **two** elbows. Then $\theta_1$ is the angle of the
# point minus the angle the second link adds. dhsym derives exactly these steps; every sign is
# a named branch $\sigma = \pm 1$:

# %%
robot = dhsym.load("planar2r")
display(Markdown(derive_inverse(robot).to_markdown()))

# %% [markdown]
# In numbers: pick a configuration, compute its tool point, and ask for every configuration
# that reaches it. (A 2R arm only places a point: we give `ik` the position $p$.)

# %%
q = np.array([0.3, 0.9])
p = robot.fk(q)[:3, 3]
sol = robot.ik(p)
for name, qs in zip(sol.branches, sol.q):
    print(f"{name:10s}  q = {qs.round(6)}   reaches p: {np.allclose(robot.fk(qs)[:3, 3], p)}")

# %%
dhsym.plot_solutions(robot, sol)

# %% [markdown]
# ## 2. Why `atan2`
#
# $\tan\theta = y/x$ does not decide the quadrant: $(x, y)$ and $(-x, -y)$ give the same
# ratio. `atan(y/x)` always answers in $(-90°, 90°)$, so it is wrong by $180°$ for every
# point with $x < 0$; `atan2(y, x)` uses both signs. A point behind the arm:

# %%
q_back = np.array([2.5, 0.6])
px, py = robot.fk(q_back)[:2, 3]
gamma = np.arctan2(0.8 * np.sin(0.6), 1.0 + 0.8 * np.cos(0.6))  # atan2(a2 S2, a1 + a2 C2)
for name, theta1 in [("atan2(py, px)", np.arctan2(py, px) - gamma),
                     ("atan(py/px)  ", np.arctan(py / px) - gamma)]:
    err = np.linalg.norm(robot.fk([theta1, 0.6])[:2, 3] - [px, py])
    print(f"theta1 from {name} = {np.degrees(theta1):8.3f}°   tool misses the point by {err:.3f}")

# %% [markdown]
# The homework checker recognises this mistake (see section 5).
#
# ## 3. The PUMA 560: eight solutions
#
# The last three axes of the PUMA meet in one point, the **wrist centre**. The wrist joints
# turn the tool about that point but cannot move it, so the problem splits in two
# (*kinematic decoupling*):
#
# - **position**: joints 1–3 place the wrist centre $c$ (here $c = p$, since $d_6 = 0$);
#   joint 1 has two solutions (left and right arm: $\pm\sqrt{\;}$ for the reach past the
#   shoulder offset $d_3$), joint 3 two (the law of cosines: elbow up and down), joint 2 one
#   `atan2`;
# - **orientation**: with the arm known, the wrist's own rotation
#   $R_w = ({}^0R_3)^T R$ is $R_z(\theta_4) R_x(\tfrac{\pi}{2}) R_z(\theta_5) R_x(-\tfrac{\pi}{2})
#   R_z(\theta_6)$: $\theta_5$ from one entry with two signs (wrist flipped or not),
#   $\theta_4$ and $\theta_6$ from its third column and third row.
#
# $2 \times 2 \times 2 = 8$ solutions. The derivation, with the solutions of one pose at the end:

# %%
puma = dhsym.load("puma560")
q0 = np.array([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
display(Markdown(derive_inverse(puma, check=q0).to_markdown()))

# %% [markdown]
# `puma.ik(T)` evaluates the same steps, compiled once for numbers, over every branch at once.
# Every solution reproduces the pose to about $10^{-15}$, and the configuration we started
# from is among them:

# %%
T = puma.fk(q0)
sol = puma.ik(T)
print(f"{len(sol)} solutions; largest |fk(q) - T| = {sol.residual.max():.1e}")
print("q0 is solution", int(np.argmin(np.abs(sol.q - q0).max(axis=1))) + 1)

# %% [markdown]
# All eight, side by side: the same tool pose, reached with the arm to the right or the left
# of the base, the elbow above or below the line from the shoulder to the wrist, and the wrist
# flipped or not (the triads are the DH frames; the wrist flip turns frames 4 and 5 half a turn).

# %%
dhsym.plot_solutions(puma, sol, frames=True)

# %% [markdown]
# A batch of poses is solved at once; every pose gets all of its solutions:

# %%
rng = np.random.default_rng(7)
Q = rng.uniform(-np.pi, np.pi, size=(1000, 6))
batch = puma.ik(puma.fk(Q))
found = [np.any(np.abs(np.angle(np.exp(1j * (batch.q[k][batch.valid[k]] - Q[k])))).max(axis=1) < 1e-9)
         for k in range(len(Q))]
print(f"{len(Q)} random poses: {int(batch.count.sum())} solutions, "
      f"the configuration that made the pose found every time: {all(found)}")

# %% [markdown]
# ## 3b. The UR5: three parallel axes instead of a wrist
#
# The UR5's last three axes do not meet, but its axes 2, 3 and 4 are parallel. dhsym reads
# that from the table and solves it the way Hawkins's note on the UR arms does: $\theta_1$
# from the height of the wrist point along the parallel axes (two shoulders), $\theta_5$
# from the axis of joint 6 (two wrists), $\theta_6$ by one `atan2`, then a planar 3R.

# %%
from dhsym.ik import classify

ur5 = dhsym.load("ur5")
print(classify(ur5))
q_ur = np.array([0.3, -1.1, 1.4, -0.6, 1.2, 0.4])
sol = ur5.ik(ur5.fk(q_ur))
for name, qs in zip(sol.branches, sol.q):
    print(f"{name:42s}", np.round(qs, 3))

# %%
dhsym.plot_solutions(ur5, sol)

# %% [markdown]
# In the 3D view, type a target under *inverse kinematics* (a position, and turns about the
# world axes), press *solve*, and choose among the branches by name: the arm jumps to each
# solution of the same pose. A target out of reach says which step has no real solution.

# %%
ur5.view(q_ur)

# %% [markdown]
# ## 4. At a wrist singularity
#
# With $\theta_5 = 0$ axes 4 and 6 line up: only $\theta_4 + \theta_6$ is determined. The
# derivation sets $\theta_4 = 0$ there and takes $\theta_6$ from the whole wrist rotation; the
# solver flags such solutions instead of returning something silently wrong.

# %%
q_sing = np.array([0.3, -0.5, 0.4, 0.2, 0.0, -1.1])
sol = puma.ik(puma.fk(q_sing))
for name, qs, flags in zip(sol.branches, sol.q, sol.singular):
    print(f"{name:42s} theta4 + theta6 = {qs[3] + qs[5]:+.4f}   near: {', '.join(flags) or '-'}")

# %% [markdown]
# Two of the eight branches coincide here (the flip of a wrist at $\theta_5 = 0$ is the same
# wrist), so there are 7 distinct solutions; the first keeps $\theta_4 + \theta_6 = -0.9$ as
# given.
#
# ## 5. Checking a student's inverse kinematics
#
# A student's joint angles, as formulas in $p_x$, $p_y$ (any branch is right), go through the
# same checker as the matrices of notebook 6. Writing `atan` instead of `atan2` is recognised:

# %%
from dhsym.checking import Key, check_answer

key = Key.load("planar2r", "ik")
good = "theta2 = atan2(-sqrt(1 - D^2), D), theta1 = atan2(p_y, p_x) - atan2(a2*S2, a1 + a2*C2)"
good = good.replace("D", "((p_x^2 + p_y^2 - a1^2 - a2^2)/(2*a1*a2))")
print(check_answer(key, good).message)
bad = good.replace("atan2(p_y, p_x)", "atan(p_y/p_x)")
print(check_answer(key, bad).message)

# %% [markdown]
# ## Summary
#
# - A 2R arm: the law of cosines gives $C_2$, two signs of $S_2$ give two elbows, one `atan2`
#   gives $\theta_1$.
# - An arm with a spherical wrist: the wrist centre decouples position from orientation; the
#   PUMA 560 has up to $2 \times 2 \times 2 = 8$ solutions, named by their branches.
# - An arm with three parallel axes (the UR5): the wrist point's height gives $\theta_1$,
#   the tool's rotation $\theta_5$ and $\theta_6$, a planar 3R the rest: again 8 solutions.
# - `atan2(y, x)`, never `atan(y/x)`; every $\pm\sqrt{\;}$ is a branch.
#
# From the command line: `dhsym derive puma560 --what ik` (also `--format latex|markdown|json`)
# and `dhsym handout puma560 -o puma.tex --sections fk,ik --check --pdf`.
