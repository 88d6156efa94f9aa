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
# # 10 · Dynamics of the 2R arm: Lagrange, Newton–Euler, a free swing
#
# Kinematics says where the arm is and how fast it moves; **dynamics** says which joint
# torques make it move that way. The lecture writes the equations of motion as
#
# $$\tau = M(q)\,\ddot q + C(q, \dot q)\,\dot q + g(q),$$
#
# with $M$ the inertia matrix (Spong's $D(q)$), $C$ the Coriolis and centrifugal terms and $g$
# the gravity torques. We derive them twice, as the textbooks do: with **Lagrange's
# equations** (M. W. Spong, S. Hutchinson and M. Vidyasagar, *Robot Modeling and Control*,
# chapter 7, the two-link planar elbow arm of §7.3) and with the **recursive Newton–Euler**
# algorithm (J. J. Craig, *Introduction to Robotics*, chapter 6). Then we let the arm swing
# freely and check that its energy is conserved, and hold it still against gravity.
#
# Run the cells from top to bottom (**Shift + Enter**).

# %%
# %matplotlib inline
import matplotlib.pyplot as plt
import numpy as np
import sympy as sp
from IPython.display import Markdown, display

import dhsym
from dhsym.explain import derive_dynamics

# %% [markdown]
# ## 1. The arm and its inertial parameters
#
# Spong's arm hangs in the $x$–$y$ plane, gravity along $-y$. Link $i$ has length $l_i$, mass
# $m_i$, its centre of mass at distance $l_{ci}$ from joint $i$ and moment of inertia $I_i$
# about the axis through its centre of mass parallel to $z$. In the standard convention frame
# $i$ sits at the *far* end of link $i$, so the centre of mass is at $l_{ci} - l_i$ along
# $x_i$. The built-in table `spong2r` carries these as the `m`, `r` and `I` of each row (the
# names of roboticstoolbox's `Link`), with Spong's symbols ($l_{c1}$, $m_1$, $I_1$):

# %%
arm = dhsym.load("spong2r")
arm.table

# %% [markdown]
# ## 2. Lagrange, step by step
#
# **Energies.** Link $i$ has kinetic energy
# $K_i = \tfrac12 m_i v_{ci}^T v_{ci} + \tfrac12 \omega_i^T R_i I_i R_i^T \omega_i$ (translation
# of its centre of mass plus rotation about it) and potential energy $P_i = -m_i g^T r_{ci}$:

# %%
eom = arm.dynamics()
for i, (K, P) in enumerate(zip(eom.kinetic, eom.potential), start=1):
    display(
        Markdown(f"$K_{i} = {arm.notation.latex(K)}$, $\\quad P_{i} = {arm.notation.latex(P)}$")
    )

# %% [markdown]
# **The inertia matrix.** The kinetic energy is a quadratic form in the rates,
# $K = \tfrac12 \dot q^T M(q) \dot q$, so $M$ is read off it:

# %%
eom.M

# %% [markdown]
# It is Spong's $D(q)$ exactly. Written out by hand from §7.3:

# %%
q1, q2, m1, m2, l1, lc1, lc2, I1, I2, g = (
    sp.Symbol(n, real=True)
    for n in ("theta1", "theta2", "m1", "m2", "l1", "lc1", "lc2", "I1", "I2", "g")
)
d11 = m1 * lc1**2 + m2 * (l1**2 + lc2**2 + 2 * l1 * lc2 * sp.cos(q2)) + I1 + I2
d12 = m2 * (lc2**2 + l1 * lc2 * sp.cos(q2)) + I2
d22 = m2 * lc2**2 + I2
D = sp.Matrix([[d11, d12], [d12, d22]])
phi = sp.Matrix(
    [
        (m1 * lc1 + m2 * l1) * g * sp.cos(q1) + m2 * lc2 * g * sp.cos(q1 + q2),
        m2 * lc2 * g * sp.cos(q1 + q2),
    ]
)
print("M == D:", sp.expand(eom.M - D) == sp.zeros(2, 2))
print("g == phi:", sp.expand(eom.g - phi) == sp.zeros(2, 1))

# %% [markdown]
# **Christoffel symbols.** $c_{ijk} = \tfrac12(\partial M_{kj}/\partial q_i +
# \partial M_{ki}/\partial q_j - \partial M_{ij}/\partial q_k)$ and $C_{kj} = \sum_i c_{ijk}
# \dot q_i$. Four differ from zero, each $\pm h$ with Spong's $h = -m_2 l_1 l_{c2} \sin q_2$:

# %%
[
    (f"c{i}{j}{k}", eom.c(i, j, k))
    for i in (1, 2)
    for j in (1, 2)
    for k in (1, 2)
    if eom.c(i, j, k) != 0
]

# %% [markdown]
# The whole derivation as the lecture prints it (`dhsym derive FILE --what dynamics`):

# %%
display(Markdown(derive_dynamics(arm).to_markdown()))

# %% [markdown]
# ## 3. Newton–Euler gives the same torques
#
# The recursive Newton–Euler algorithm never forms $M$: it carries velocities and accelerations
# outward from the base, then forces and torques inward from the tip. Its torques are the
# Lagrange torques, term by term:

# %%
ne = arm.dynamics(method="newton-euler")
print("Newton-Euler tau == Lagrange tau:", sp.expand(ne.tau - eom.tau) == sp.zeros(2, 1))
[(s.sweep, s.name, s.link) for s in ne.steps][:6]

# %% [markdown]
# ## 4. A free swing, and its energy
#
# Give the symbols numbers: two 1 m links of 1 kg, centres of mass at mid-length, thin rods
# ($I = m l^2/12$). With no torque and no friction, the total energy $\tfrac12 \dot q^T M
# \dot q + P$ must stay constant; the compiled dynamics integrates the motion with RK4.

# %%
values = {
    "l1": 1.0,
    "l2": 1.0,
    "lc1": 0.5,
    "lc2": 0.5,
    "m1": 1.0,
    "m2": 1.0,
    "I1": 1 / 12,
    "I2": 1 / 12,
    "g": 9.81,
}
swing = arm.simulate([0.0, 0.0], [0.0, 0.0], 4.0, dt=2e-3, values=values)
energy = arm.dynamics_functions(values).energy(swing.q, swing.qd)

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.5))
ax1.plot(swing.t, np.degrees(swing.q))
ax1.set(xlabel="t [s]", ylabel="joint angle [deg]", title="free swing from rest")
ax1.legend(["$q_1$", "$q_2$"])
ax2.plot(swing.t, energy - energy[0])
ax2.set(xlabel="t [s]", ylabel="E(t) - E(0) [J]", title="energy drift")
fig.tight_layout()
print(f"largest energy drift: {np.max(np.abs(energy - energy[0])):.2e} J")

# %% [markdown]
# The arm falls from the horizontal and swings chaotically, but its energy stays constant to
# the accuracy of the integrator.
#
# ## 5. Gravity compensation
#
# A controller that applies exactly $\tau = g(q)$ cancels gravity: the arm, released at rest
# anywhere, stays where it is. `gravload` gives $g(q)$ numerically:

# %%
q0 = np.radians([30.0, 45.0])
print("g(q0) =", arm.gravload(q0, values=values), "N m")
held = arm.simulate(
    q0, [0.0, 0.0], 2.0, dt=2e-3, values=values, tau=lambda t, q, qd: arm.gravload(q, values=values)
)
print(f"largest motion under gravity compensation: {np.max(np.abs(held.q - q0)):.1e} rad")

# %% [markdown]
# Without compensation the same start falls away at once. The next notebook scales this up to
# the PUMA 560 with its published inertial parameters.
