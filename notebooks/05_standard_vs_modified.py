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
# # 5 · Standard versus modified DH: same robot, different frames
#
# Two DH conventions are in use. S. Mohan (IIT Palakkad), Mechanics and Control of Robotic
# Manipulators, Lecture 9 "DH parameters", builds both from the same four elementary
# transforms:
#
# | | standard (distal) | modified (proximal, Craig) |
# |---|---|---|
# | link matrix | $R_z(\theta_i)\,T_z(d_i)\,T_x(a_i)\,R_x(\alpha_i)$ | $R_x(\alpha_{i-1})\,T_x(a_{i-1})\,R_z(\theta_i)\,T_z(d_i)$ |
# | frame $i$ sits | at the far end of link $i$, $z_i$ on the axis of joint $i+1$ | at the near end of link $i$, $z_i$ on the axis of joint $i$ |
# | row $i$ holds | $\theta_i, d_i, a_i, \alpha_i$ | $\alpha_{i-1}, a_{i-1}, d_i, \theta_i$ |
#
# This notebook writes the PUMA 560 both ways, shows that the frames land in different places,
# and that the tool pose agrees.

# %%
# %matplotlib inline
import numpy as np
import sympy as sp
from IPython.display import Markdown, display

import dhsym
from dhsym.plot import frame_origins

# %% [markdown]
# ## 1. From the standard table to a modified one
#
# Write the standard product for two links and regroup it:
#
# $$R_z(\theta_1)T_z(d_1)\,\underbrace{T_x(a_1)R_x(\alpha_1)\,R_z(\theta_2)T_z(d_2)}_{\text{modified link 2}}\,T_x(a_2)R_x(\alpha_2)\cdots$$
#
# So the modified row $i$ takes $\theta_i$, $d_i$ from standard row $i$ and $\alpha_{i-1}$,
# $a_{i-1}$ from standard row $i-1$ (zero for row 1). What is left over at the end,
# $T_x(a_n)R_x(\alpha_n)$, becomes a **tool transform**. Done in code:

# %%
std = dhsym.load("puma560")
rows = std.table.rows
shifted = [
    dhsym.DHRow(row.joint, row.theta, row.d,
                rows[i - 1].a if i else 0, rows[i - 1].alpha if i else 0)
    for i, row in enumerate(rows)
]
a_n, alpha_n = rows[-1].a, rows[-1].alpha
tool = (dhsym.Elementary("T", "x", a_n), dhsym.Elementary("R", "x", alpha_n))
if a_n == alpha_n == 0:
    tool = ()   # nothing left over
mod = dhsym.Robot(dhsym.DHTable(tuple(shifted), convention="modified", values=std.table.values,
                                tool=tool, name="PUMA 560 (modified, from the standard table)"))
print("tool transform:", tool or "none needed (a6 = 0 and alpha6 = 0)")
display(std.table)
display(mod.table)

# %% [markdown]
# ## 2. The frames are in different places
#
# Standard frame $i$ sits at the end of link $i$, modified frame $i$ at its start. Compare the
# origins at $q = 0$ (in metres):

# %%
o_std, o_mod = frame_origins(std), frame_origins(mod)
lines = ["| frame | standard origin | modified origin |", "|---|---|---|"]
for k, (p, r) in enumerate(zip(o_std, o_mod)):
    lines.append(f"| {{{k}}} | {np.round(p + 0.0, 4)} | {np.round(r + 0.0, 4)} |")
display(Markdown("\n".join(lines)))

# %% [markdown]
# For example, standard frame $\{2\}$ is at the elbow (end of the upper arm $a_2$), while
# modified frame $\{2\}$ is at the shoulder, on the axis of joint 2. The link matrices differ
# too: compare ${}^{1}T_{2}$ in both conventions.

# %%
display(std.link_matrix(2))
display(mod.link_matrix(2))

# %%
q = np.radians([30, 30, -60, 0, 45, 0])
std.plot(q, title="standard DH: frames at the far end of each link")

# %%
mod.plot(q, title="modified DH: frames at the near end of each link")

# %% [markdown]
# ## 3. … but the tool pose is the same
#
# Both are the same product of elementary transforms, only grouped differently, so
# ${}^0T_6$ must agree for **every** $q$. Symbolically:

# %%
difference = (std.arm_matrix().matrix - mod.tool_pose().matrix).applyfunc(sp.simplify)
assert difference == sp.zeros(4)
print("standard 0T6 == modified 0T6 (times the tool transform), exactly")

# %% [markdown]
# and numerically, at 1000 random configurations:

# %%
Q = np.random.default_rng(0).uniform(-np.pi, np.pi, size=(1000, 6))
err = np.abs(std.fk(Q) - mod.fk(Q)).max()
print(f"largest difference: {err:.1e}")
assert err < 1e-12

# %% [markdown]
# ## 4. Craig's published table: base and tool transforms
#
# Craig's own modified table for the PUMA 560 (`puma560_modified`) differs from the one we just
# built in one entry: $\alpha_1 = -90^\circ$ instead of $+90^\circ$. He points $z_2$ the other
# way, so his zero configuration is a different pose (forearm down). To compare two descriptions
# of one robot we look for a **base** transform $B$ (between the two base frames) and a
# **tool** transform $E$ (between the two last frames) with
#
# $$ {}^0T_6^{\text{std}}(q) = B\;{}^0T_6^{\text{Craig}}(q')\;E .$$
#
# Both last frames sit at the wrist centre with $z$ along joint 6, so try $E = I$ and compute
# $B$ from the two results at $q = 0$:

# %%
craig = dhsym.load("puma560_modified")
display(craig.table)
B = std.fk(np.zeros(6)) @ np.linalg.inv(craig.fk(np.zeros(6)))
print(np.round(B, 6) + 0.0)

# %% [markdown]
# $B$ is a rotation by $180^\circ$ about $x$: Craig's base frame is the standard one
# turned upside down. Turning the base over also reverses the sense in which joint 1 turns (its axis
# is $z_0$), so the same physical motion is $q' = (-\theta_1, \theta_2, \dots, \theta_6)$:

# %%
Qc = Q.copy()
Qc[:, 0] *= -1
same = np.abs(std.fk(Q) - B @ craig.fk(Qc)).max()
naive = np.abs(std.fk(Q) - B @ craig.fk(Q)).max()
print(f"with q' = (-theta1, theta2, ...): {same:.1e};   with q' = q: {naive:.2f}")
assert same < 1e-12 and naive > 0.1

# %%
craig.plot(np.zeros(6), title="Craig's frames at q = 0 (forearm down)")

# %% [markdown]
# ## What to remember
#
# - Standard: frame $i$ at the **end** of link $i$. Modified: frame $i$ at the **start** of link $i$.
# - The same robot gives the same tool pose in both conventions; only the intermediate
#   frames (and link matrices) differ. Converting a table shifts $a$ and $\alpha$ by one row.
# - Two *different* frame choices (like Craig's table and Corke's) are related by base and tool
#   transforms, and sometimes by a change of joint sign or zero; compute them, don't guess.
