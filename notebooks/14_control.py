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
# # 14 · Control: PD, gravity compensation and computed torque
#
# The arm follows a trajectory only if its joint torques make it. Three laws from the
# lecture (M. W. Spong, S. Hutchinson and M. Vidyasagar, *Robot Modeling and Control*,
# chapters 8 and 9; J. J. Craig, *Introduction to Robotics*, chapter 10), with
# $e = q_d - q$:
#
# * PD: $\tau = K_p e + K_d \dot e$;
# * PD with gravity compensation: $\tau = K_p e + K_d \dot e + g(q)$;
# * computed torque: $\tau = M(q)(\ddot q_d + K_d \dot e + K_p e) + C(q, \dot q)\dot q + g(q)$.
#
# We simulate them on Spong's two-link arm and on the PUMA 560 with the arms' own dynamics,
# then give the controller a model 10 % too heavy.
#
# Run the cells from top to bottom (**Shift + Enter**).

# %%
# %matplotlib inline
import matplotlib.pyplot as plt
import numpy as np

import dhsym
from dhsym.control import (
    PD,
    ComputedTorque,
    PDGravity,
    error_equation,
    gains,
    plot_torques,
    plot_tracking_error,
    scaled_model,
    simulate,
)
from dhsym.trajectory import quintic

# %% [markdown]
# ## 1. The error equation and the gains
#
# Under computed torque with an exact model the arm's equation $M\ddot q + C\dot q + g = \tau$
# becomes $M(\ddot e + K_d \dot e + K_p e) = 0$, and since $M$ is invertible
# $\ddot e + K_d \dot e + K_p e = 0$: each joint's error is a second-order system. Matching
# $s^2 + K_d s + K_p$ with $s^2 + 2\zeta\omega s + \omega^2$ gives the gains.

# %%
ee = error_equation()
ee.equation, ee.gains.pairs

# %%
kp, kd = (float(g) for g in gains(8))  # critically damped, omega = 8 rad/s
kp, kd

# %% [markdown]
# ## 2. Spong's two-link arm: three laws, one motion

# %%
arm = dhsym.load("spong2r")
values = {"m1": 1, "m2": 1, "l1": 1, "l2": 1, "lc1": 0.5, "lc2": 0.5, "I1": 0.1, "I2": 0.1, "g": 9.81}
model = arm.dynamics_functions(values)
ref = quintic([0.0, 0.0], [1.0, -0.8], 1.5)
runs = {
    "PD": simulate(arm, PD(kp, kd, ref), 2.0, values=values, dt=2e-3),
    "PD + gravity": simulate(arm, PDGravity(kp, kd, ref, model=model), 2.0, values=values, dt=2e-3),
    "computed torque": simulate(arm, ComputedTorque(kp, kd, ref, model=model), 2.0, values=values, dt=2e-3),
}
fig, axes = plt.subplots(1, 2, figsize=(11, 3.5))
plot_tracking_error(runs, largest=True, log=True, ax=axes[0])
plot_torques(runs, joints=[1], ax=axes[1])
plt.show()
{name: f"{run.max_error:.1e}" for name, run in runs.items()}

# %% [markdown]
# PD alone leaves a steady error where $K_p e = g(q)$; gravity compensation removes it at
# rest; computed torque follows the whole motion, to rounding.

# %% [markdown]
# ## 3. The PUMA 560, exact model and a model 10 % too heavy
#
# With the exact model the error stays at rounding level. With masses and inertias 10 %
# too large the commanded and actual accelerations differ by some $\eta(t)$:
# $\ddot e + K_d \dot e + K_p e = \eta$. For a critically damped loop starting on the
# reference this bounds the error: $|e| \le \max|\eta| / K_p$.

# %%
puma = dhsym.load("puma560")
qa = np.array([0.0, -0.5, 0.3, 0.1, 0.4, -0.2])
qb = np.array([0.6, -0.2, -0.1, 0.5, 0.9, 0.3])
ref = quintic(qa, qb, 1)
exact = simulate(puma, ComputedTorque(kp, kd, ref, model=puma.dynamics_functions()), 1.0, dt=2e-3)
heavy = simulate(puma, ComputedTorque(kp, kd, ref, model=scaled_model(puma, 1.1)), 1.0, dt=2e-3)
f = puma.dynamics_functions()
eta = (heavy.qdd_ref - f.accel(heavy.q, heavy.qd, heavy.tau)) + kd * (heavy.qd_ref - heavy.qd) + kp * heavy.error
print(f"exact model: largest error {exact.max_error:.1e} rad")
print(f"10 % heavier model: largest error {heavy.max_error:.1e} rad, bound {np.abs(eta).max() / kp:.1e} rad")

# %%
fig = plot_tracking_error(heavy)
fig.axes[0].set_title("PUMA 560, computed torque with a 10 % heavier model")
fig
