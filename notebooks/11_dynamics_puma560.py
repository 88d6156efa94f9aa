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
# # 11 · Dynamics of the PUMA 560: its inertia over the workspace, regressor and base parameters
#
# The 2R arm of notebook 10 fits on a page. A six-joint industrial arm does not: its symbolic
# $M(q)$ runs to thousands of terms, so here we work with **numbers**, compiled once and
# evaluated for thousands of configurations in one call. The arm is the PUMA 560 of the
# earlier notebooks, with its **published inertial parameters** (masses, centres of mass,
# inertias, motor inertias and gear ratios of Armstrong, Khatib and Burdick, 1986, as in
# Corke's Robotics Toolbox). The equations are those of M. W. Spong, S. Hutchinson and
# M. Vidyasagar, *Robot Modeling and Control*, chapter 7, and J. J. Craig, *Introduction to
# Robotics*, chapter 6. You will
#
# 1. read the inertial parameters of each link,
# 2. compute $M(q)$, $g(q)$ and the joint torques numerically,
# 3. picture $M_{11}$ and $M_{22}$ over the shoulder and elbow angles $(q_2, q_3)$,
# 4. write the torques as linear in the parameters, $\tau = Y(q, \dot q, \ddot q)\,\pi$, and
#    find the **base parameters**: the combinations of $\pi$ that a measurement can identify.
#
# Run the cells from top to bottom (**Shift + Enter**).

# %%
# %matplotlib inline
import dataclasses

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp

import dhsym
from dhsym.dynamics import base_parameters
from dhsym.dynamics.inertial_parameters import standard_values

puma = dhsym.load("puma560")
puma.plot()

# %% [markdown]
# ## 1. The published inertial parameters
#
# Each row of the table carries the mass $m$, the centre of mass $r$ and the inertia $I$ about
# it, both in the link's own frame, and the motor inertia $J_m$ with the gear ratio $G$ (the
# motor adds $J_m G^2$ to the diagonal of $M$):

# %%
print(f"{'link':>4} {'m [kg]':>7}  {'r [m]':<24} {'Ixx, Iyy, Izz [kg m^2]':<26} {'Jm':>8} {'G':>7}")
for i, row in enumerate(puma.table.rows, start=1):
    L = row.inertia
    r = ", ".join(f"{float(x):.3f}" for x in L.r)
    inertia = ", ".join(f"{float(L.I[k, k]):.3f}" for k in range(3))
    print(f"{i:>4} {float(L.m):>7.2f}  {r:<24} {inertia:<26} {float(L.Jm):>8.1e} {float(L.G):>7.2f}")
print("gravity:", [float(g) for g in puma.table.gravity], "m/s^2 in the base frame")

# %% [markdown]
# ## 2. Numbers: M(q), g(q) and τ
#
# `inertia`, `gravload`, `coriolis` and `rne` take one configuration or a whole batch; the
# first call compiles the recursion for these parameters. At the zero configuration the arm
# stretches forward horizontally, and the shoulder carries most of the gravity load:

# %%
q0 = np.zeros(6)
np.set_printoptions(precision=3, suppress=True)
print("M(0) =\n", puma.inertia(q0))
print("g(0) =", puma.gravload(q0), "N m")

# %% [markdown]
# The torques of a motion are $\tau = M\ddot q + C\dot q + g$, plus the friction of the
# drives (viscous $B G^2 \dot q$ and Coulomb $|G| T_c$, published too); `rne` computes them by
# the Newton–Euler recursion, and they agree with the parts assembled by hand:

# %%
rng = np.random.default_rng(1)
q, qd, qdd = rng.uniform(-1, 1, (3, 6))
tau = puma.rne(q, qd, qdd)
friction = puma.dynamics_functions().friction(qd)
assembled = puma.inertia(q) @ qdd + puma.coriolis(q, qd) @ qd + puma.gravload(q) + friction
print("tau =", tau)
print("largest difference:", np.max(np.abs(tau - assembled)))

# %% [markdown]
# ## 3. M(q) over the workspace
#
# $M$ depends on the shape of the arm, not on where it points: $q_1$ (the turn about the
# vertical) and $q_6$ never enter. The waist inertia $M_{11}$ grows as the arm stretches out
# and shrinks as it folds; the shoulder inertia $M_{22}$ depends only on the elbow $q_3$.
# One batched call gives $M$ on a $60 \times 60$ grid of $(q_2, q_3)$:

# %%
angles = np.linspace(-np.pi, np.pi, 60)
Q = np.zeros((60, 60, 6))
Q[..., 1] = angles[:, None]  # q2 down the rows
Q[..., 2] = angles[None, :]  # q3 along the columns
M = puma.inertia(Q)  # shape (60, 60, 6, 6)

fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
extent = [-180, 180, -180, 180]
for ax, (i, j) in zip(axes, [(0, 0), (1, 1)]):
    im = ax.imshow(M[..., i, j], origin="lower", extent=extent, aspect="equal", cmap="viridis")
    ax.set(xlabel="$q_3$ [deg]", ylabel="$q_2$ [deg]", title=f"$M_{{{i + 1}{j + 1}}}$ [kg m$^2$]")
    fig.colorbar(im, ax=ax)
fig.tight_layout()
print(f"M11 from {M[..., 0, 0].min():.2f} to {M[..., 0, 0].max():.2f} kg m^2")
print(f"M22 from {M[..., 1, 1].min():.2f} to {M[..., 1, 1].max():.2f} kg m^2")

# %% [markdown]
# Every $M$ on the grid is symmetric positive definite, as an inertia matrix must be:

# %%
eigs = np.linalg.eigvalsh(M)
print("symmetric:", np.allclose(M, np.swapaxes(M, -1, -2)), "| smallest eigenvalue:", eigs.min())

# %% [markdown]
# ## 4. The regressor and the base parameters
#
# The torques are **linear** in the ten standard parameters of each link,
# $\pi_i = (XX_i, XY_i, XZ_i, YY_i, YZ_i, ZZ_i, MX_i, MY_i, MZ_i, M_i)$ (the inertia about the
# frame origin, the first moments $m_i r_i$ and the mass): $\tau = Y(q, \dot q, \ddot q)\,\pi$.
# Identifying a real arm means measuring $\tau$ along a trajectory and solving for $\pi$. But
# some parameters never affect $\tau$ and others only in fixed combinations: only the
# **base parameters** can be identified (Gautier and Khalil's grouping, found here by a QR
# decomposition of $Y$ at random states).
#
# The symbolic regressor of all six joints takes minutes, so we take the PUMA's first three
# joints, the arm that positions the wrist (30 standard parameters):

# %%
rows = puma.table.rows[:3]
values = tuple((s, v) for s, v in puma.table.values if str(s) in {"a2", "a3", "d3"})
arm = dhsym.Robot(dataclasses.replace(puma.table, rows=rows, values=values, name="PUMA 560 arm"))
base = base_parameters(arm)
print(f"Y is {base.regressor.Y.shape[0]} x {base.regressor.Y.shape[1]};"
      f" {len(base.combinations)} base parameters;"
      f" {len(base.unidentifiable)} parameters never affect tau")
print("\n".join(base.lines()))

# %% [markdown]
# `ZZ2R`, for instance, is $ZZ_2$ minus $a_2^2(M_2 + M_3)$: the parallel-axis share of the
# masses carried at distance $a_2$ is lumped with the inertias of the joint before. Check
# $\tau = Y_b\,\pi_b$ at a random state, with the published values in the combinations:

# %%
dm = base.regressor.model
state = dict(zip((*dm.variables, *dm.rates, *dm.accelerations), rng.uniform(-1, 1, 9)))
Yb = base.Y.subs(arm.table.value_map).subs(state)
pi_b = sp.Matrix(base.combinations).subs(standard_values(dm))
tau_Y = np.array((Yb * pi_b).evalf(), dtype=float).ravel()
x = np.array(list(state.values()), dtype=float)
tau_rne = arm.dynamics_functions().rne(x[:3], x[3:6], x[6:], friction=False)
print("Y_b pi_b =", tau_Y)
print("rne      =", tau_rne)

# %% [markdown]
# The two agree except for the motor inertias $J_m G^2 \ddot q$, which `rne` includes and the
# rigid-body regressor leaves out (friction is left out of both here):

# %%
motors = np.array([float(r.inertia.Jm * r.inertia.G**2) for r in rows]) * x[6:]
print("largest difference after the motors:", np.max(np.abs(tau_rne - motors - tau_Y)))
