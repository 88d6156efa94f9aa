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
# # 2 · The planar 4R arm: a redundant robot
#
# *Example 3* of IRob2305 Introduction to Robotics, Lecture 5, "Manipulator kinematics …
# Denavit–Hartenberg parameters … forward kinematics": four revolute joints, all axes
# parallel. In the plane the tip has only three things to choose: its position $x$, $y$ and
# its direction $\varphi$. Four joints for three numbers means the arm is **redundant**: many
# joint sets give the same tip pose.

# %%
# %matplotlib inline
import numpy as np
import sympy as sp
from IPython.display import Markdown, display

import dhsym

# %%
robot = dhsym.load("planar4r")
robot

# %% [markdown]
# ## 1. Every link matrix has the same shape
#
# All four rows look alike ($d_i = 0$, $\alpha_i = 0$), so every link matrix is the one of the
# lecture, with its own index $i$:
#
# $${}^{i-1}H_i = \begin{bmatrix} C_i & -S_i & 0 & a_i C_i \\ S_i & C_i & 0 & a_i S_i \\
# 0 & 0 & 1 & 0 \\ 0 & 0 & 0 & 1 \end{bmatrix}$$

# %%
for i in range(1, 5):
    display(robot.link_matrix(i))

# %% [markdown]
# ## 2. The arm matrix and $C_{1234}$
#
# The four angles add up, just as $\theta_1 + \theta_2$ did for the 2R arm:
# $C_{1234} = \cos(\theta_1 + \theta_2 + \theta_3 + \theta_4)$, and the tip position is a sum of
# four link vectors, each pointing at the sum of the angles before it.

# %%
T = robot.arm_matrix()
T

# %%
legend = robot.notation.legend(T.matrix)
display(Markdown("\n".join(f"- ${e.latex} = {e.meaning_latex}$" for e in legend)))

# %% [markdown]
# The direction of the tip is $\varphi = \theta_1 + \theta_2 + \theta_3 + \theta_4$
# (read it from $C_{1234}$, $S_{1234}$ in the first column).

# %% [markdown]
# ## 3. Same tip pose, different joints
#
# Start from one configuration $q_A$ and compute its tip pose $(x, y, \varphi)$. Then *choose*
# a different $\theta_1$ and find the other three joints:
#
# 1. link 4 must end at the tip pointing along $\varphi$, so it starts at the *wrist point*
#    $w = (x - a_4\cos\varphi,\; y - a_4\sin\varphi)$;
# 2. link 1 ends at $(a_1 C_1, a_1 S_1)$, so links 2 and 3 must bridge the gap to $w$:
#    that is a 2R problem, solved by the law of cosines;
# 3. $\theta_4$ makes the angles add up to $\varphi$.

# %%
a = np.array([1.0, 0.8, 0.6, 0.4])          # a1 ... a4, the values in the table

def tip(q):
    T = robot.fk(q)
    return np.array([T[0, 3], T[1, 3], np.arctan2(T[1, 0], T[0, 0])])

def another_solution(pose, theta1, elbow=+1):
    x, y, phi = pose
    wx = x - a[3] * np.cos(phi) - a[0] * np.cos(theta1)
    wy = y - a[3] * np.sin(phi) - a[0] * np.sin(theta1)
    c3 = (wx**2 + wy**2 - a[1]**2 - a[2]**2) / (2 * a[1] * a[2])
    if abs(c3) > 1:
        raise ValueError("links 2 and 3 cannot reach the wrist point from this theta1")
    theta3 = elbow * np.arccos(c3)
    elbow_angle = np.arctan2(a[2] * np.sin(theta3), a[1] + a[2] * np.cos(theta3))
    theta2 = np.arctan2(wy, wx) - elbow_angle - theta1
    theta4 = phi - theta1 - theta2 - theta3
    return np.array([theta1, theta2, theta3, theta4])

qA = np.radians([20, 40, -30, 50])
pose = tip(qA)
qB = another_solution(pose, np.radians(40), elbow=+1)
qC = another_solution(pose, np.radians(30), elbow=-1)
for name, q in [("qA", qA), ("qB", qB), ("qC", qC)]:
    x, y, phi = tip(q)
    print(f"{name} = {np.round(np.degrees(q), 1)} deg  ->  "
          f"x = {x:.4f}, y = {y:.4f}, phi = {np.degrees(phi):.2f} deg")
assert np.allclose(tip(qB), pose) and np.allclose(tip(qC), pose)

# %% [markdown]
# Three joint sets, one tip pose. Drawn on top of each other (only the frames of $q_A$
# are drawn, $q_B$ and $q_C$ are the pale arms):

# %%
from dhsym.plot.figures import view_limits

limits = view_limits(robot, [qA, qB, qC], dim=2)
fig = robot.plot(qB, view="2d", frames=False, labels=False, limits=limits, alpha=0.35)
ax = fig.axes[0]
robot.plot(qC, ax=ax, frames=False, labels=False, limits=limits, alpha=0.35)
robot.plot(qA, ax=ax, limits=limits, title="Three joint sets, the same tip pose")
fig

# %% [markdown]
# The redundancy is useful: a robot can keep its tool still while it moves its elbow away
# from an obstacle. The price is that "the" inverse kinematics has infinitely many answers, and
# the controller must choose one.

# %% [markdown]
# ## What to remember
#
# - A planar $n$R arm has the arm matrix with $C_{12\dots n}$ in the rotation part.
# - With more joints than task coordinates the arm is redundant: one tip pose, many joint sets.
