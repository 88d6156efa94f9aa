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
# # 15 · The product of exponentials: screw axes beside DH, both ways
#
# Lynch and Park (*Modern Robotics*, chapter 4) describe an arm without DH frames: with every
# joint at zero the tool sits at its **home configuration** $M$, and joint $i$ moves about
# (along) its **screw axis** $\mathcal{S}_i = (\omega_i, v_i)$ written in the space frame, with
# $v_i = -\omega_i \times q_i$ for a point $q_i$ on the axis. Then
#
# $$T(\theta) = e^{[\mathcal{S}_1]\theta_1} \cdots e^{[\mathcal{S}_n]\theta_n} M
#             = M e^{[\mathcal{B}_1]\theta_1} \cdots e^{[\mathcal{B}_n]\theta_n}.$$
#
# This notebook
#
# 1. reproduces the book's **3R spatial open chain** (Example 4.1) and **UR5** (Example 4.5):
#    $M$ and every $\mathcal{S}_i$, exactly, with their numbers;
# 2. reads the screw axes of a DH robot (the PUMA 560) off its frames, step by step, and
#    proves the product of exponentials equal to the DH product;
# 3. relates the space and body Jacobians to dhsym's DH Jacobian (rows $[v; \omega]$);
# 4. goes back from the UR5's screw axes to a DH table through the frame-assignment algorithm.

# %%
# %matplotlib inline
from importlib import resources

import numpy as np
from IPython.display import Markdown, display

import dhsym
from dhsym.explain.documents import render_derivation
from dhsym.screws import prove_same_fk, read_poe, to_dh

robots = resources.files("dhsym.screws") / "robots"

# %% [markdown]
# ## 1. The 3R spatial open chain (Lynch and Park, Example 4.1)
#
# The file gives each axis by its direction and a point on it; dhsym forms $v = -\omega \times q$.

# %%
print((robots / "lynch_park_3r.poe.yaml").read_text())
with resources.as_file(robots / "lynch_park_3r.poe.yaml") as path:
    three_r = read_poe(path)
three_r.home, three_r.screw_matrix("space")

# %% [markdown]
# Each factor is a closed form (Rodrigues' formula), printed in the lecture's notation:

# %%
for e in three_r.exponentials("space"):
    display(e)

# %%
print(three_r.fk_space().text())

# %% [markdown]
# ## 2. The UR5 (Lynch and Park, Example 4.5)
#
# $W_1 = 0.109$, $W_2 = 0.082$, $L_1 = 0.425$, $L_2 = 0.392$, $H_1 = 0.089$, $H_2 = 0.095$ m.

# %%
with resources.as_file(robots / "lynch_park_ur5.poe.yaml") as path:
    ur5 = read_poe(path)
display(ur5.home)
display(ur5.screw_matrix("space").T)
display(ur5.screw_matrix("body").T)

# %% [markdown]
# The book's example configuration, $\theta = (0, -\pi/2, 0, 0, \pi/2, 0)$, as numbers from the
# exact product (the space and the body forms agree):

# %%
theta = [0, -np.pi / 2, 0, 0, np.pi / 2, 0]
T_space = ur5.function("fk_space")(theta)
T_body = ur5.function("fk_body")(theta)
print(np.round(T_space, 4))
print("space and body forms agree:", np.allclose(T_space, T_body, atol=1e-12))

# %% [markdown]
# ## 3. From a DH table to screw axes, with a proof
#
# Joint $i$ turns about $z$ of DH frame $i-1$ (standard convention). At home, that frame's $z$
# column is $\omega_i$ and its origin is a point $q_i$ on the axis.

# %%
puma = dhsym.load("puma560")
display(Markdown(render_derivation(puma, "markdown", what="screws")))

# %%
print("PoE fk = DH fk, exactly:", prove_same_fk(puma.poe(), puma))

# %% [markdown]
# ## 4. The space and body Jacobians
#
# dhsym's DH Jacobian has rows $[v; \omega]$, $v$ the velocity of the tool origin. The space
# Jacobian has rows $[\omega; v_s]$ with $v_s = v - \omega \times p$ (the velocity of the body
# point at the space origin), the body Jacobian is the tool-frame Jacobian with its halves
# swapped, and $J_s = [\mathrm{Ad}_T] J_b$.

# %%
q = np.array([0.2, -0.4, 0.5, 0.3, 0.9, -0.6])
J0, Je, T = puma.jacob0(q), puma.jacobe(q), puma.fk(q)
p = T[:3, 3]
skew_p = np.array([[0, -p[2], p[1]], [p[2], 0, -p[0]], [-p[1], p[0], 0]])
Js, Jb = puma.jacobian_space(q), puma.jacobian_body(q)
print("J_s from jacob0:", np.allclose(Js, np.vstack([J0[3:], J0[:3] + skew_p @ J0[3:]])))
print("J_b from jacobe:", np.allclose(Jb, np.vstack([Je[3:], Je[:3]])))
print("det J_s = det J_b:", np.isclose(np.linalg.det(Js), np.linalg.det(Jb)))

# %% [markdown]
# ## 5. Back to DH: the UR5's screw axes as lines, given DH frames
#
# Each revolute axis passes through $q = \omega \times v$ along $\omega$; the frame-assignment
# algorithm places the DH frames on these lines, with a sentence for each choice.

# %%
fa = to_dh(ur5)
for k, text in enumerate(fa.step_texts[:6], start=1):
    print(f"{k}. {text}")
display(fa.table)

# %%
robot = dhsym.Robot(fa.table)
rng = np.random.default_rng(0)
qs = rng.uniform(-np.pi, np.pi, size=(100, 6))
error = np.abs(robot.fk(qs) - ur5.function("fk_space")(qs)).max()
print(f"largest difference of the two fk over 100 configurations: {error:.1e}")

# %% [markdown]
# The DH frames the algorithm placed on the UR5's axes, at home:

# %%
fig = robot.plot(np.zeros(6), scale=0.08, title="UR5 from its screw axes (Lynch and Park)")
fig
