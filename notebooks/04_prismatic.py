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
# # 4 · Prismatic joints: when $d$ is the variable
#
# A **revolute** joint turns: $\theta_i$ is its variable and $d_i$ is a constant. A **prismatic**
# joint slides along its axis $z_{i-1}$: now $d_i$ is the variable and $\theta_i$ is a constant.
# In the tables below the variable of each row is **boxed**.

# %%
# %matplotlib inline
import numpy as np
import sympy as sp
from IPython.display import Markdown, display

import dhsym

# %% [markdown]
# ## 1. Example I (RRP with a $180^\circ$ twist)
#
# *Example I* of IRob2305 Introduction to Robotics, Lecture 5, "Manipulator kinematics …
# Denavit–Hartenberg parameters … forward kinematics". The lecture's table has columns
# $\Theta, \alpha, a, d$:
#
# | Link | $\Theta$ | $\alpha$ | $a$ | $d$ |
# |---|---|---|---|---|
# | 1 | $\Theta_1$ | 0 | $a_2$ | $a_1$ |
# | 2 | $\Theta_2$ | 180 | $a_4$ | $a_3$ |
# | 3 | 0 | 0 | 0 | $a_5 + d_3$ |
#
# The third joint is prismatic: $\theta_3 = 0$ is fixed and $d = a_5 + d_3$ changes with the
# joint variable $d_3$ ($a_5$ is a constant part, an *offset*). dhsym shows the same table in
# its own column order $\theta, d, a, \alpha$ (the symbols $a_1 \dots a_5$ are the lecture's):

# %%
ex1 = dhsym.load("example1_rrp")
ex1.table

# %%
row3 = ex1.table.rows[2]
print("joint type:", row3.joint.name, "| variable:", row3.variable,
      "| in column:", row3.variable_field, "| constant offset:", row3.offset)

# %%
for i in range(1, 4):
    display(ex1.link_matrix(i))

# %% [markdown]
# The arm matrix. The $180^\circ$ twist of row 2 turns $z$ upside down: the third column
# (the approach vector $\mathbf a$) is $(0, 0, -1)$, so the tool points **down**, and the
# prismatic joint moves the tool down as $d_3$ grows ($p_z$ contains $-d_3$). Since joints 1
# and 2 have parallel axes, $C_{12}$ appears again.

# %%
T = ex1.arm_matrix()
T

# %%
assert list(T.a) == [0, 0, -1]
print("p_z =", T.position[2])

# %%
ex1.plot([30, 45, 0.15], deg=True)

# %% [markdown]
# ## 2. SCARA (RRPR)
#
# The SCARA is Example I with a fourth, revolute joint that turns the tool. Because of the
# $180^\circ$ twist its axis points down, so $\theta_4$ enters the tool's direction with a minus
# sign: look for $C_{12-4}$ (short for $\cos(\theta_1 + \theta_2 - \theta_4)$).

# %%
scara = dhsym.load("scara")
display(scara.table)
scara.arm_matrix()

# %%
scara.plot([30, 45, 0.1, 0], deg=True)

# %% [markdown]
# ## 3. Cylindrical (RPP)
#
# One revolute joint (the column turns) and two prismatic joints (the carriage goes up with
# $d_2$ and the arm reaches out with $d_3$). The tip moves on cylinders around $z_0$.

# %%
cyl = dhsym.load("cylindrical")
display(cyl.table)
cyl.arm_matrix()

# %%
cyl.plot([30, 0.3, 0.4], deg=True)

# %% [markdown]
# ## 4. Cartesian (PPP)
#
# Three prismatic joints. Every $\theta_i$ is a constant, so **the rotation part of the arm
# matrix is constant**: a Cartesian robot moves its tool without turning it, and the position is
# linear in $d_1, d_2, d_3$.

# %%
cart = dhsym.load("cartesian")
display(cart.table)
T = cart.arm_matrix()
T

# %%
assert not T.rotation.free_symbols
print("rotation part has no variables; position =", list(T.position))

# %%
cart.plot([0.3, 0.2, 0.25])

# %% [markdown]
# ## 5. The Stanford arm (RRP + wrist)
#
# Two revolute joints point a boom, and the prismatic joint 3 slides it in and out ($d_3$, the
# reach); joints 4 to 6 form a spherical wrist. The wrist position is the boom direction times
# $d_3$, plus the shoulder offset $d_2$.

# %%
stanford = dhsym.load("stanford")
display(stanford.table)
stanford.arm_matrix().position

# %%
stanford.plot([30, 60, 0.5, 0, 45, 0], deg=True)

# %% [markdown]
# ## Summary: which column holds the variable?

# %%
lines = ["| robot | joint | type | variable | column |", "|---|---|---|---|---|"]
for r in (ex1, scara, cyl, cart, stanford):
    for i, row in enumerate(r.table.rows, start=1):
        column = sp.latex(sp.Symbol("theta")) if row.variable_field == "theta" else "d"
        lines.append(f"| {r.name} | {i} | {row.joint.name.lower()} "
                     f"| ${sp.latex(row.variable)}$ | ${column}$ |")
display(Markdown("\n".join(lines)))
