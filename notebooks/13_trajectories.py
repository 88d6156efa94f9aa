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

# %% [markdown]
# # 13 · Trajectories: cubic, quintic, blends, via points and a straight line
#
# A trajectory says *when* the arm is where. For one joint moving from $q_0$ to $q_f$ in the
# time $t_f$ the lecture picks a polynomial and finds its coefficients from the **boundary
# conditions**: positions and velocities (a cubic, J. J. Craig, *Introduction to Robotics*,
# chapter 7), and accelerations too (a quintic, M. W. Spong, S. Hutchinson and M.
# Vidyasagar, *Robot Modeling and Control*, chapter 5). Then linear segments with parabolic
# blends, via points, and a straight line in Cartesian space for the PUMA 560 solved by its
# inverse kinematics (K. M. Lynch and F. C. Park, *Modern Robotics*, chapter 9).
#
# Run the cells from top to bottom (**Shift + Enter**).

# %%
# %matplotlib inline
import matplotlib.pyplot as plt
import numpy as np
import sympy as sp

import dhsym
from dhsym.trajectory import cubic, lspb, minimum_time, mstraj, quintic, spline

# %% [markdown]
# ## 1. The cubic from its four conditions
#
# $q(t) = a_0 + a_1 t + a_2 t^2 + a_3 t^3$ with $q(0) = q_0$, $\dot q(0) = 0$, $q(t_f) = q_f$,
# $\dot q(t_f) = 0$: four linear equations in the four coefficients, solved exactly.

# %%
q0, qf, tf = sp.symbols("q_0 q_f t_f", positive=True)
c = cubic(q0, qf, tf)
c.derivation()

# %% [markdown]
# ## 2. The quintic: accelerations at rest too
#
# Six conditions, six coefficients; the lecture's $a_3 = 10(q_f - q_0)/t_f^3$,
# $a_4 = -15(q_f - q_0)/t_f^4$, $a_5 = 6(q_f - q_0)/t_f^5$.

# %%
p = quintic(q0, qf, tf)
p.coefficients

# %% [markdown]
# ## 3. Linear segment with parabolic blends
#
# A blend of constant acceleration $a$ for $t_b$, a line at velocity $V$, a blend back to
# rest. The blend time follows from $V$: $t_b = (q_0 - q_f + V t_f)/V$, and it fits only when
# $|q_f - q_0|/t_f \le |V| \le 2|q_f - q_0|/t_f$: the profile keeps these conditions.

# %%
V = sp.Symbol("V", positive=True)
b = lspb(q0, qf, tf, v=V)
b.derivation().pairs, b.conditions

# %%
t = np.linspace(0, 2, 401)
fig, axes = plt.subplots(1, 3, figsize=(12, 3))
for profile, name in [(cubic(0, 1, 2), "cubic"), (quintic(0, 1, 2), "quintic"), (lspb(0, 1, 2, v=0.75), "LSPB")]:
    for ax, values in zip(axes, profile.sample(t)):
        ax.plot(t, values, label=name)
for ax, title in zip(axes, ["position", "velocity", "acceleration"]):
    ax.set_title(title)
    ax.set_xlabel("t (s)")
axes[0].legend()
plt.show()

# %% [markdown]
# A velocity that does not fit is refused with the condition it breaks:

# %%
try:
    lspb(0, 1, 2, v=2)
except dhsym.DHError as err:
    print(err)

# %% [markdown]
# ## 4. As fast as the limits allow
#
# With $|\dot q| \le v$ and $|\ddot q| \le a$ the fastest motion accelerates fully, cruises at
# $v$ and brakes: $t_f = D/v + v/a$ for a distance $D \ge v^2/a$, else a triangle,
# $t_f = 2\sqrt{D/a}$. A joint vector is timed to its slowest joint.

# %%
m = minimum_time([0, 0, 0], [1, 2, 0.5], [1, 1, 2], [2, 2, 4])
m.duration

# %% [markdown]
# ## 5. Via points
#
# A cubic spline passes through every via point with continuous velocity and acceleration;
# the velocities at the inner points come from a linear system. Straight segments joined
# by short blends pass *near* the via points instead.

# %%
via = [[0, 0], [1, 2], [2, 1], [1, 0]]
s = spline(via, [0, 1, 2, 3])
ms = mstraj(via, dt=0.05, tacc=0.4, qdmax=[1.5, 1.5])
tt = np.linspace(0, 3, 301)
tm = np.linspace(0, float(ms.duration), 301)
plt.figure(figsize=(5, 4))
plt.plot(*s.sample(tt)[0].T, label="cubic spline")
plt.plot(*ms.sample(tm)[0].T, label="lines with blends")
plt.plot(*np.array(via).T, "ko", label="via points")
plt.xlabel("$q_1$")
plt.ylabel("$q_2$")
plt.legend()
plt.show()

# %% [markdown]
# ## 6. A straight line for the PUMA 560
#
# The tool moves along the straight line between two poses, turning about one fixed axis
# (the shortest rotation); every sample is solved by the closed-form inverse kinematics and
# the branch nearest the previous sample is kept.

# %%
puma = dhsym.load("puma560")
qa = np.array([0.2, -0.6, 0.4, 0.3, 0.7, -0.2])
qb = np.array([0.5, -0.3, 0.1, 0.1, 0.9, 0.3])
path = puma.ctraj(puma.fk(qa), puma.fk(qb), np.linspace(0, 2, 101), near=qa)
T = puma.fk(path.q)
a, e = puma.fk(qa)[:3, 3], puma.fk(qb)[:3, 3]
u = (e - a) / np.linalg.norm(e - a)
off = (T[:, :3, 3] - a) - ((T[:, :3, 3] - a) @ u)[:, None] * u
print(f"complete: {path.complete}; largest distance from the line: {np.abs(off).max():.1e} m")

# %%
plt.figure(figsize=(6, 3))
plt.plot(path.t, path.q)
plt.xlabel("t (s)")
plt.ylabel("joint angles (rad)")
plt.title("PUMA 560 joints along a straight line")
plt.show()

# %% [markdown]
# A line that leaves the workspace stops at the first sample it cannot reach, and says why:

# %%
far = puma.fk(qa).copy()
far[:3, 3] = 3 * far[:3, 3]
print(puma.ctraj(puma.fk(qa), far, 51, near=qa).reason)
