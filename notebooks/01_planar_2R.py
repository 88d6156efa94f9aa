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
# # 1 · The planar 2R arm: from the DH table to ${}^0T_2$
#
# This notebook follows *Example 2* of IRob2305 Introduction to Robotics, Lecture 5,
# "Manipulator kinematics … Denavit–Hartenberg parameters … forward kinematics" (below:
# *the lecture*): a planar arm with two revolute joints. You will
#
# 1. read its Denavit–Hartenberg (DH) table,
# 2. build the two link matrices ${}^0H_1$ and ${}^1H_2$,
# 3. multiply them into the arm matrix ${}^0T_2$ and read it in the $C_{12}$ notation,
# 4. draw the arm with its frames, plot its workspace, and check the numbers.
#
# Run the cells from top to bottom (**Shift + Enter**).

# %%
# %matplotlib inline
import numpy as np
import sympy as sp
from IPython.display import Markdown, display

import dhsym

# %% [markdown]
# ## 1. The DH table
#
# The lecture uses the **standard** convention: the pose of frame $i$ seen from frame $i-1$ is
#
# $$A_i = R_z(\theta_i)\,T_z(d_i)\,T_x(a_i)\,R_x(\alpha_i).$$
#
# For the planar 2R arm every twist $\alpha_i$ and offset $d_i$ is zero: all joint axes point
# out of the page. The link lengths are $a_1$ and $a_2$; the joint angles $\theta_1$, $\theta_2$
# are the variables.

# %%
robot = dhsym.load("planar2r")
robot

# %% [markdown]
# The lecture keeps $a_1$ and $a_2$ as symbols. For pictures and numbers the table also
# carries illustrative values (in metres):

# %%
robot.table.value_map

# %% [markdown]
# ## 2. The link matrices ${}^0H_1$ and ${}^1H_2$
#
# Each row of the table gives one link matrix: the product of four elementary transforms,
# in this order:

# %%
robot.link_word(1)

# %% [markdown]
# Multiplied out, row 1 gives ${}^0H_1$ (the lecture writes $H$, dhsym writes $T$; they
# are the same matrix). $C_1$ is short for $\cos\theta_1$ and $S_1$ for $\sin\theta_1$.

# %%
H1 = robot.link_matrix(1)
H1

# %%
H2 = robot.link_matrix(2)
H2

# %% [markdown]
# Both are exactly the matrices printed in the lecture. We can let the computer check it:
# type the lecture's matrices in and compare entry by entry.

# %%
t1, t2, a1, a2 = sp.symbols("theta1 theta2 a1 a2", real=True)
C, S = sp.cos, sp.sin
H1_lecture = sp.Matrix([[C(t1), -S(t1), 0, a1 * C(t1)],
                        [S(t1),  C(t1), 0, a1 * S(t1)],
                        [0, 0, 1, 0],
                        [0, 0, 0, 1]])
H2_lecture = H1_lecture.subs({t1: t2, a1: a2}, simultaneous=True)
assert H1.matrix == H1_lecture and H2.matrix == H2_lecture
print("0H1 and 1H2 agree with the lecture")

# %% [markdown]
# ## 3. The arm matrix ${}^0T_2 = {}^0H_1\,{}^1H_2$
#
# Multiplying the two link matrices gives the pose of frame 2 (the end of the arm) in the base
# frame 0:

# %%
T = robot.arm_matrix()
T

# %% [markdown]
# ### The $C_{12}$ notation
#
# $C_{12}$ stands for $\cos(\theta_1 + \theta_2)$ and $S_{12}$ for $\sin(\theta_1 + \theta_2)$.
# They appear because the product contains $C_1 C_2 - S_1 S_2$, which the angle-sum identity
# turns into $\cos(\theta_1 + \theta_2)$. Geometrically: both joint axes are parallel, so the
# second link points at the *sum* of the two joint angles. The abbreviations used above:

# %%
legend = robot.notation.legend(T.matrix)
display(Markdown("\n".join(f"- ${e.latex} = {e.meaning_latex}$" for e in legend)))

# %% [markdown]
# The short form is not a different answer: dhsym proves that it is exactly equal to the
# plain product ${}^0H_1\,{}^1H_2$, and we compare it with the lecture's ${}^0T_2$ as well.

# %%
T_lecture = sp.Matrix([[C(t1 + t2), -S(t1 + t2), 0, a1 * C(t1) + a2 * C(t1 + t2)],
                       [S(t1 + t2),  C(t1 + t2), 0, a1 * S(t1) + a2 * S(t1 + t2)],
                       [0, 0, 1, 0],
                       [0, 0, 0, 1]])
assert robot.verify() and T.matrix == T_lecture
print("0T2 = 0H1 * 1H2, and it is the lecture's matrix")

# %% [markdown]
# The columns of ${}^0T_2$ have names: $\mathbf n$, $\mathbf s$, $\mathbf a$
# are the $x$, $y$, $z$ axes of frame 2 and $\mathbf p$ is its origin, the tip of the arm:

# %%
T.position

# %% [markdown]
# ## 4. The picture
#
# `robot.plot(q)` draws the arm at the joint values `q` with every DH frame:
# $x$ red, $y$ green, $z$ blue. For a planar arm a top view (`view="2d"`) shows everything;
# the $z$ axes point out of the page (drawn as ⊙). The orange bars are the link lengths $a_i$,
# measured along $x_i$.

# %%
robot.plot([30, 45], deg=True, view="2d")

# %% [markdown]
# The same configuration in 3D; the dashed lines are the joint axes $z_0$ and $z_1$:

# %%
robot.plot([30, 45], deg=True)

# %% [markdown]
# ## 5. The workspace
#
# Which points can the tip reach? We draw thousands of random joint values within the joint
# limits of the table and plot where the tip lands. Without limits the workspace of a 2R arm
# is the ring $|a_1 - a_2| \le r \le a_1 + a_2$. Here joint 2 stops at $\pm 150^\circ$, so the arm
# cannot fold back completely and the hole in the middle is a little larger.

# %%
from dhsym.plot.figures import plot_workspace, workspace_points

plot_workspace(robot)

# %%
r = np.linalg.norm(workspace_points(robot)[:, :2], axis=1)
l1, l2 = 1.0, 0.8
r_fold = np.sqrt(l1**2 + l2**2 + 2 * l1 * l2 * np.cos(np.radians(150)))
print(f"reached radii: {r.min():.3f} ... {r.max():.3f}")
print(f"ring without limits: {abs(l1 - l2):.3f} ... {l1 + l2:.3f}")
print(f"innermost point with |theta2| <= 150 deg: {r_fold:.3f}")
assert r_fold - 1e-9 <= r.min() and r.max() <= l1 + l2 + 1e-9

# %% [markdown]
# ## 6. A numeric check
#
# `robot.fk(q)` evaluates ${}^0T_2$ for numbers (it is compiled from the same symbolic matrix).
# Check the tip position against the formula $p_x = a_1 C_1 + a_2 C_{12}$,
# $p_y = a_1 S_1 + a_2 S_{12}$ by hand:

# %%
q = np.radians([30, 45])
T_num = robot.fk(q)
px = l1 * np.cos(q[0]) + l2 * np.cos(q[0] + q[1])
py = l1 * np.sin(q[0]) + l2 * np.sin(q[0] + q[1])
print(np.round(T_num, 4))
assert np.allclose(T_num[:2, 3], [px, py])

# %% [markdown]
# ## 7. Move the joints yourself
#
# `robot.view()` shows the arm in 3D with one slider per joint, its DH frames and the arm
# matrix read out as you move: drag a slider and watch ${}^0T_2$ change; turn on *closed
# form* to see the entries above, and *link matrices* to see which ${}^{i-1}T_i$ a slider
# changes. `view.q` is the configuration you set (in radians). It needs `anywidget`
# (`pip install 'dhsym[widgets]'`); in a static copy of this notebook you see a picture of
# the arm instead. `dhsym view planar2r -o arm.html` writes the same view as a page that
# opens anywhere, offline.

# %%
try:
    view = robot.view([30, 45], deg=True)
except dhsym.DHError as missing:  # anywidget is not installed
    print(missing)
    view = robot.plot([30, 45], deg=True, view="2d")
view

# %% [markdown]
# ## 8. Animate a path
#
# The lecture ends with *"We can animate a path"*. `joint_path` interpolates the joint values from
# one configuration to another; `animate_path` draws the arm at each step and saves a GIF (or a
# folder of PNG frames when no GIF writer is available).

# %%
import base64
import tempfile
from pathlib import Path
from IPython.display import HTML
from dhsym.plot import animate_path, joint_path

path = joint_path([0, 0], [90, -60], 10)
out = animate_path(robot, path, Path(tempfile.mkdtemp()) / "2r.gif", deg=True, view="2d",
                   fps=4, dpi=50, labels=False)
if out.suffix == ".gif":   # shown inline, so that it also survives an HTML export
    gif = base64.b64encode(out.read_bytes()).decode()
    display(HTML(f'<img src="data:image/gif;base64,{gif}" alt="the 2R arm moving along the path">'))
else:
    print("no GIF writer here; the frames are PNG files in", out)

# %% [markdown]
# ## 9. Take the closed form away: MATLAB and C
#
# The arm matrix above is worth most where it runs. `dhsym.export` writes it as source code
# with no dependency on dhsym: a MATLAB/Octave function file and a C99 file here (C++, Rust
# and NumPy work the same way). Each file starts with the DH table it came from.

# %%
import shutil
import subprocess

folder = Path(tempfile.mkdtemp())
for lang in ("matlab", "c"):
    for name, text in dhsym.export(robot, lang, what="fk", prefix="arm").items():
        (folder / name).write_text(text)
print(sorted(p.name for p in folder.iterdir()))
print((folder / "arm_fk.m").read_text().split("\n  q1")[0][-300:])

# %% [markdown]
# Compile the C with `gcc` and run it along the path of section 8; run the MATLAB function in
# GNU Octave. Both print the tip position $(x, y)$ at each step; the plot shows the two tracks
# (they coincide) next to dhsym's own `fk`.

# %%
path_rad = np.radians(joint_path([0, 0], [90, -60], 40))
lines = "\n".join(f"{a:.17g} {b:.17g}" for a, b in path_rad)
tracks = {"dhsym fk": robot.fk(path_rad)[:, :2, 3]}
main_c = r"""
#include <stdio.h>
#include "arm.h"
int main(void)
{
    double q[ARM_NJOINTS], T[16];
    while (scanf("%lf %lf", &q[0], &q[1]) == 2) {
        arm_fk(q, T);
        printf("%.17g %.17g\n", T[3], T[7]);
    }
    return 0;
}
"""
if shutil.which("gcc"):
    (folder / "main.c").write_text(main_c)
    subprocess.run(["gcc", "-std=c99", "-O2", "main.c", "arm.c", "-o", "arm", "-lm"],
                   cwd=folder, check=True)
    out = subprocess.run([str(folder / "arm")], input=lines, capture_output=True, text=True,
                         check=True).stdout
    tracks["C (gcc)"] = np.array([[float(v) for v in row.split()] for row in out.splitlines()])
else:
    print("gcc is not installed: no C track")
if shutil.which("octave"):
    np.savetxt(folder / "path.txt", path_rad, fmt="%.17g")
    script = "Q = dlmread('path.txt'); for i = 1:rows(Q); T = arm_fk(Q(i, :)); " \
             "printf('%.17g %.17g\\n', T(1, 4), T(2, 4)); end"
    out = subprocess.run(["octave", "--no-gui", "--quiet", "--no-window-system", "--eval", script],
                         cwd=folder, capture_output=True, text=True, check=True).stdout
    tracks["MATLAB (Octave)"] = np.array([[float(v) for v in row.split()]
                                          for row in out.splitlines()])
else:
    print("GNU Octave is not installed: no MATLAB track")

import matplotlib.pyplot as plt

fig, ax = plt.subplots(figsize=(4, 4))
styles = {"dhsym fk": "-", "C (gcc)": "o", "MATLAB (Octave)": "x"}
for label, xy in tracks.items():
    ax.plot(xy[:, 0], xy[:, 1], styles[label], label=label, markersize=4)
ax.set_aspect("equal")
ax.set_xlabel("x")
ax.set_ylabel("y")
ax.legend()
plt.close(fig)
display(fig)
for label, xy in tracks.items():
    print(f"{label:16s} largest difference from dhsym: {np.abs(xy - tracks['dhsym fk']).max():.1e}")

# %% [markdown]
# ## What to remember
#
# - One row of the DH table gives one link matrix
#   $A_i = R_z(\theta_i) T_z(d_i) T_x(a_i) R_x(\alpha_i)$.
# - The arm matrix is the product of the link matrices; its last column is the tip position.
# - Parallel joint axes make the angles add up: $C_{12} = \cos(\theta_1 + \theta_2)$.
