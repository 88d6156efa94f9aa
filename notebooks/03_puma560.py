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
# # 3 · The PUMA 560, link by link, in both conventions
#
# The PUMA 560 is the classic six-joint industrial arm. The lecture IRob2305 Introduction to
# Robotics, Lecture 5, "Manipulator kinematics … Denavit–Hartenberg parameters … forward
# kinematics", ends with a printout from Corke's Robotics Toolbox (`mdl_puma560`):
#
# ```
# j  theta    d        a       alpha    offset
# 1  q1       0        0       1.5708   0
# 2  q2       0        0.4318  0        0
# 3  q3       0.15005  0.0203  -1.5708  0
# 4  q4       0.4318   0       1.5708   0
# 5  q5       0        0       -1.5708  0
# 6  q6       0        0       0        0
#
# >> p560.fkine([0 0 0 0 0 0])
# 1 0 0 0.4521
# 0 1 0 -0.15
# 0 0 1 0.4318
# ```
#
# This notebook rebuilds that table (standard DH), its link matrices and the arm matrix, checks
# the zero configuration against the printout, draws the frames, and then does the same with
# Craig's modified-DH table of the same robot.

# %%
# %matplotlib inline
import numpy as np
import sympy as sp
from IPython.display import Markdown, display

import dhsym

# %% [markdown]
# ## 1. The standard table (Corke)

# %%
puma = dhsym.load("puma560")
puma

# %%
puma.table.value_map   # metres

# %% [markdown]
# The toolbox prints $\alpha = 1.5708$; the table keeps $\pi/2$ exactly, so that
# $\cos\alpha_1$ is exactly 0 in the matrices below. Compare with the printout:

# %%
printout = np.array([[0, 0, 1.5708], [0, 0.4318, 0], [0.15005, 0.0203, -1.5708],
                     [0.4318, 0, 1.5708], [0, 0, -1.5708], [0, 0, 0]])   # d, a, alpha
values = puma.table.value_map
ours = np.array([[float(row.d.subs(values)), float(row.a.subs(values)), float(row.alpha)]
                 for row in puma.table.rows])
assert np.allclose(ours, printout, atol=5e-5)
print("d, a and alpha agree with the toolbox printout")

# %% [markdown]
# ## 2. Link by link
#
# Each link matrix is $A_i = R_z(\theta_i) T_z(d_i) T_x(a_i) R_x(\alpha_i)$. Watch how a twist of
# $\pm 90^\circ$ moves the entries: the middle columns swap and a $\pm 1$ appears in the third
# row.

# %%
for i in range(1, 7):
    display(Markdown(f"**Link {i}**: `{puma.link_word(i)}`"))
    display(puma.link_matrix(i))


# %% [markdown]
# ## 3. The arm matrix in $C_{23}$/$S_{23}$ form
#
# Joints 2 and 3 have parallel axes (both horizontal), so their angles add up, as in the planar
# arms: $C_{23} = \cos(\theta_2 + \theta_3)$, $S_{23} = \sin(\theta_2 + \theta_3)$.
#
# The whole $4 \times 4$ matrix is too wide for the page, so we show it column by column:
# $\mathbf n$, $\mathbf s$, $\mathbf a$ (the $x$, $y$, $z$ axes of frame 6) and $\mathbf p$ (its
# origin, the wrist centre). `T` itself holds the full matrix.

# %%
def show_columns(robot, T):
    for name, column in (("n", T.n), ("s", T.s), ("a", T.a), ("p", T.position)):
        display(Markdown(rf"$$\mathbf{{{name}}} = {robot.notation.latex(column)}$$"))

T = puma.arm_matrix()
show_columns(puma, T)

# %%
legend = puma.notation.legend(T.matrix)
pairs = [f"${e.latex} = {e.meaning_latex}$" for e in legend if "23" in e.text]
display(Markdown(", ".join(pairs)))

# %% [markdown]
# The position $\mathbf p$ does not depend on $\theta_4$, $\theta_5$, $\theta_6$: the
# last three axes meet in one point (a *spherical wrist*), so turning the wrist does not move it.

# %%
T.position.free_symbols

# %% [markdown]
# ## 4. The zero configuration: the toolbox printout
#
# At $q = 0$ the arm matrix must be the matrix that `p560.fkine([0 0 0 0 0 0])` printed
# (the toolbox rounds $-0.15005$ to $-0.15$):

# %%
T0 = puma.fk(np.zeros(6))
fkine_printout = np.array([[1, 0, 0, 0.4521], [0, 1, 0, -0.15], [0, 0, 1, 0.4318], [0, 0, 0, 1]])
print(np.round(T0, 5))
assert np.allclose(T0, fkine_printout, atol=1e-4)

# %% [markdown]
# ## 5. The frames, at home and at another pose
#
# At $q = 0$ the upper arm ($a_2$) points along $x_0$ and the forearm ($d_4$) points up. The
# shoulder offset $d_3$ shifts the forearm sideways by $0.15\,$m. Frames $\{0\}$ and $\{1\}$
# share their origin, and so do the wrist frames $\{4\}$, $\{5\}$, $\{6\}$ (shorter triads
# belong to the later frames).

# %%
puma.plot()

# %%
puma.plot([30, 30, -60, 0, 45, 0], deg=True)

# %% [markdown]
# ## 6. The same robot in Craig's modified convention
#
# Craig attaches frame $i$ at the *near* (proximal) end of link $i$ and writes the link matrix
# in the other order, as do A. Ghosal (IISc), Lecture 5 "Elements of robot – Joints, Links", and
# S. Mohan (IIT Palakkad), Mechanics and Control of Robotic Manipulators, Lecture 9 "DH
# parameters":
#
# $${}^{i-1}T_i = R_x(\alpha_{i-1})\,T_x(a_{i-1})\,R_z(\theta_i)\,T_z(d_i).$$
#
# Row $i$ of a modified table holds $\alpha_{i-1}$ and $a_{i-1}$: the twist and length of the
# link *before* joint $i$.

# %%
craig = dhsym.load("puma560_modified")
craig

# %%
for i in range(1, 7):
    display(Markdown(f"**Link {i}**: `{craig.link_word(i)}`"))
    display(craig.link_matrix(i))

# %%
show_columns(craig, craig.arm_matrix())

# %% [markdown]
# The $C_{23}$, $S_{23}$ structure is the same, but signs differ: Craig chose the frames
# differently (his $z_2$ points the other way, $\alpha_1 = -90^\circ$), so his zero configuration
# has the forearm pointing **down**:

# %%
print(np.round(craig.fk(np.zeros(6)), 5))

# %%
craig.plot()

# %% [markdown]
# ## Move the PUMA yourself
#
# One slider per joint, in the table's unit (radians) and within the PUMA's joint limits;
# the frames carry their numbers (the wrist's frames 4, 5 and 6 share one origin, so one
# label). Turn on *link matrices* and move $\theta_3$: only ${}^2T_3$ changes. (Needs
# `anywidget`; a static copy shows a picture.)

# %%
puma.view([0, -0.6, 0.4, 0, 0.8, 0])

# %% [markdown]
# Notebook 5 compares the two conventions on one table and shows how the tool poses are
# related.
#
# ## What to remember
#
# - A $\pm 90^\circ$ twist swaps the middle columns of a link matrix.
# - Parallel axes (joints 2 and 3) give $C_{23}$, $S_{23}$; a spherical wrist makes the wrist
#   position independent of $\theta_4 \dots \theta_6$.
# - The table reproduces the toolbox: ${}^0T_6(0)$ has $\mathbf p = (0.4521, -0.15005, 0.4318)$.
