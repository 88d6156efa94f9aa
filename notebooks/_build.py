# ruff: noqa: E501  (the notebooks' Markdown tables are long lines)
"""Regenerate the course notebooks (with outputs) and the README picture.

Run from the repository root::

    python notebooks/_build.py            # all notebooks + docs/puma560-frames.png
    python notebooks/_build.py 03         # only notebooks whose name starts with 03

Each notebook is written from the cell lists below by ``_nbtools.build_notebook``
(cell ids are fixed, so a rebuild changes only what really changed), which executes
it in place with :func:`dhsym.explain.notebooks.execute_notebook`, failing on any error or
warning output.
"""

from __future__ import annotations

import sys
from pathlib import Path

from _nbtools import ROOT, build_notebook

IMPORTS = """\
%matplotlib inline
import numpy as np
import sympy as sp
from IPython.display import Markdown, display

import dhsym"""

SLIDER_NOTE = (
    "> **Note:** `ipywidgets` is not installed, so there are no sliders here. "
    "Install it (`pip install ipywidgets`) and run this cell again; "
    "the picture below shows one fixed configuration instead."
)

NB01 = [
    (
        "md",
        r"""# 1 · The planar 2R arm: from the DH table to ${}^0T_2$

This notebook follows **seed 001** (IRob2305, Lecture 5), *Example 2*: a planar arm with two
revolute joints. You will

1. read its Denavit–Hartenberg (DH) table,
2. build the two link matrices ${}^0H_1$ and ${}^1H_2$,
3. multiply them into the arm matrix ${}^0T_2$ and read it in the $C_{12}$ notation,
4. draw the arm with its frames, plot its workspace, and check the numbers.

Run the cells from top to bottom (**Shift + Enter**).""",
    ),
    ("code", IMPORTS),
    (
        "md",
        r"""## 1. The DH table

The lecture uses the **standard** convention: the pose of frame $i$ seen from frame $i-1$ is

$$A_i = R_z(\theta_i)\,T_z(d_i)\,T_x(a_i)\,R_x(\alpha_i).$$

For the planar 2R arm every twist $\alpha_i$ and offset $d_i$ is zero: all joint axes point
out of the page. The link lengths are $a_1$ and $a_2$; the joint angles $\theta_1$, $\theta_2$
are the variables.""",
    ),
    ("code", 'robot = dhsym.load("planar2r")\nrobot'),
    (
        "md",
        r"""The lecture keeps $a_1$ and $a_2$ as symbols. For pictures and numbers the table also
carries illustrative values (in metres):""",
    ),
    ("code", "robot.table.value_map"),
    (
        "md",
        r"""## 2. The link matrices ${}^0H_1$ and ${}^1H_2$

Each row of the table gives one link matrix: the product of four elementary transforms,
in this order:""",
    ),
    ("code", "robot.link_word(1)"),
    (
        "md",
        r"""Multiplied out, row 1 gives ${}^0H_1$ (the lecture writes $H$, dhsym writes $T$; they
are the same matrix). $C_1$ is short for $\cos\theta_1$ and $S_1$ for $\sin\theta_1$.""",
    ),
    ("code", "H1 = robot.link_matrix(1)\nH1"),
    ("code", "H2 = robot.link_matrix(2)\nH2"),
    (
        "md",
        r"""Both are exactly the matrices printed in the lecture. We can let the computer check it:
type the lecture's matrices in and compare entry by entry.""",
    ),
    (
        "code",
        """\
t1, t2, a1, a2 = sp.symbols("theta1 theta2 a1 a2", real=True)
C, S = sp.cos, sp.sin
H1_lecture = sp.Matrix([[C(t1), -S(t1), 0, a1 * C(t1)],
                        [S(t1),  C(t1), 0, a1 * S(t1)],
                        [0, 0, 1, 0],
                        [0, 0, 0, 1]])
H2_lecture = H1_lecture.subs({t1: t2, a1: a2}, simultaneous=True)
assert H1.matrix == H1_lecture and H2.matrix == H2_lecture
print("0H1 and 1H2 agree with seed 001")""",
    ),
    (
        "md",
        r"""## 3. The arm matrix ${}^0T_2 = {}^0H_1\,{}^1H_2$

Multiplying the two link matrices gives the pose of frame 2 (the end of the arm) in the base
frame 0:""",
    ),
    ("code", "T = robot.arm_matrix()\nT"),
    (
        "md",
        r"""### The $C_{12}$ notation

$C_{12}$ stands for $\cos(\theta_1 + \theta_2)$ and $S_{12}$ for $\sin(\theta_1 + \theta_2)$.
They appear because the product contains $C_1 C_2 - S_1 S_2$, which the angle-sum identity
turns into $\cos(\theta_1 + \theta_2)$. Geometrically: both joint axes are parallel, so the
second link points at the *sum* of the two joint angles. The abbreviations used above:""",
    ),
    (
        "code",
        """\
legend = robot.notation.legend(T.matrix)
display(Markdown("\\n".join(f"- ${e.latex} = {e.meaning_latex}$" for e in legend)))""",
    ),
    (
        "md",
        r"""The short form is not a different answer: dhsym proves that it is exactly equal to the
plain product ${}^0H_1\,{}^1H_2$, and we compare it with the lecture's ${}^0T_2$ as well.""",
    ),
    (
        "code",
        """\
T_lecture = sp.Matrix([[C(t1 + t2), -S(t1 + t2), 0, a1 * C(t1) + a2 * C(t1 + t2)],
                       [S(t1 + t2),  C(t1 + t2), 0, a1 * S(t1) + a2 * S(t1 + t2)],
                       [0, 0, 1, 0],
                       [0, 0, 0, 1]])
assert robot.verify() and T.matrix == T_lecture
print("0T2 = 0H1 * 1H2, and it is the lecture's matrix")""",
    ),
    (
        "md",
        r"""The columns of ${}^0T_2$ have names (seed 001): $\mathbf n$, $\mathbf s$, $\mathbf a$
are the $x$, $y$, $z$ axes of frame 2 and $\mathbf p$ is its origin, the tip of the arm:""",
    ),
    ("code", "T.position"),
    (
        "md",
        r"""## 4. The picture

`robot.plot(q)` draws the arm at the joint values `q` with every DH frame:
$x$ red, $y$ green, $z$ blue. For a planar arm a top view (`view="2d"`) shows everything;
the $z$ axes point out of the page (drawn as ⊙). The orange bars are the link lengths $a_i$,
measured along $x_i$.""",
    ),
    ("code", 'robot.plot([30, 45], deg=True, view="2d")'),
    ("md", "The same configuration in 3D; the dashed lines are the joint axes $z_0$ and $z_1$:"),
    ("code", "robot.plot([30, 45], deg=True)"),
    (
        "md",
        r"""## 5. The workspace

Which points can the tip reach? We draw thousands of random joint values within the joint
limits of the table and plot where the tip lands. Without limits the workspace of a 2R arm
is the ring $|a_1 - a_2| \le r \le a_1 + a_2$. Here joint 2 stops at $\pm 150^\circ$, so the arm
cannot fold back completely and the hole in the middle is a little larger.""",
    ),
    (
        "code",
        "from dhsym.plot.figures import plot_workspace, workspace_points\n\nplot_workspace(robot)",
    ),
    (
        "code",
        """\
r = np.linalg.norm(workspace_points(robot)[:, :2], axis=1)
l1, l2 = 1.0, 0.8
r_fold = np.sqrt(l1**2 + l2**2 + 2 * l1 * l2 * np.cos(np.radians(150)))
print(f"reached radii: {r.min():.3f} ... {r.max():.3f}")
print(f"ring without limits: {abs(l1 - l2):.3f} ... {l1 + l2:.3f}")
print(f"innermost point with |theta2| <= 150 deg: {r_fold:.3f}")
assert r_fold - 1e-9 <= r.min() and r.max() <= l1 + l2 + 1e-9""",
    ),
    (
        "md",
        r"""## 6. A numeric check

`robot.fk(q)` evaluates ${}^0T_2$ for numbers (it is compiled from the same symbolic matrix).
Check the tip position against the formula $p_x = a_1 C_1 + a_2 C_{12}$,
$p_y = a_1 S_1 + a_2 S_{12}$ by hand:""",
    ),
    (
        "code",
        """\
q = np.radians([30, 45])
T_num = robot.fk(q)
px = l1 * np.cos(q[0]) + l2 * np.cos(q[0] + q[1])
py = l1 * np.sin(q[0]) + l2 * np.sin(q[0] + q[1])
print(np.round(T_num, 4))
assert np.allclose(T_num[:2, 3], [px, py])""",
    ),
    (
        "md",
        r"""## 7. Move the joints yourself

With `ipywidgets` installed, the next cell shows two sliders; move them and watch the frames
follow. (In a static copy of this notebook, on GitHub or in HTML, you only see a text
stand-in for the sliders.)""",
    ),
    (
        "code",
        """\
try:
    import ipywidgets
except ImportError:
    ipywidgets = None

def show(theta1=30, theta2=45):
    return robot.plot([theta1, theta2], deg=True, view="2d")

if ipywidgets is None:
    display(Markdown(SLIDER_NOTE))
    display(show())
else:
    ipywidgets.interact(show, theta1=(-180, 180, 5), theta2=(-150, 150, 5))""".replace(
            "SLIDER_NOTE", repr(SLIDER_NOTE)
        ),
    ),
    (
        "md",
        r"""## 8. Animate a path

Seed 001 ends with *"We can animate a path"*. `joint_path` interpolates the joint values from
one configuration to another; `animate_path` draws the arm at each step and saves a GIF (or a
folder of PNG frames when no GIF writer is available).""",
    ),
    (
        "code",
        """\
import base64
import tempfile
from pathlib import Path
from IPython.display import HTML
from dhsym.plot.animation import animate_path, joint_path

path = joint_path([0, 0], [90, -60], 10)
out = animate_path(robot, path, Path(tempfile.mkdtemp()) / "2r.gif", deg=True, view="2d",
                   fps=4, dpi=50, labels=False)
if out.suffix == ".gif":   # shown inline, so that it also survives an HTML export
    gif = base64.b64encode(out.read_bytes()).decode()
    display(HTML(f'<img src="data:image/gif;base64,{gif}" alt="the 2R arm moving along the path">'))
else:
    print("no GIF writer here; the frames are PNG files in", out)""",
    ),
    (
        "md",
        r"""## What to remember

- One row of the DH table gives one link matrix
  $A_i = R_z(\theta_i) T_z(d_i) T_x(a_i) R_x(\alpha_i)$.
- The arm matrix is the product of the link matrices; its last column is the tip position.
- Parallel joint axes make the angles add up: $C_{12} = \cos(\theta_1 + \theta_2)$.""",
    ),
]

NB02 = [
    (
        "md",
        r"""# 2 · The planar 4R arm: a redundant robot

Seed 001, *Example 3*: four revolute joints, all axes parallel. In the plane the tip has only
three things to choose: its position $x$, $y$ and its direction $\varphi$. Four joints for three
numbers means the arm is **redundant**: many joint sets give the same tip pose.""",
    ),
    ("code", IMPORTS),
    ("code", 'robot = dhsym.load("planar4r")\nrobot'),
    (
        "md",
        r"""## 1. Every link matrix has the same shape

All four rows look alike ($d_i = 0$, $\alpha_i = 0$), so every link matrix is the one of the
lecture, with its own index $i$:

$${}^{i-1}H_i = \begin{bmatrix} C_i & -S_i & 0 & a_i C_i \\ S_i & C_i & 0 & a_i S_i \\
0 & 0 & 1 & 0 \\ 0 & 0 & 0 & 1 \end{bmatrix}$$""",
    ),
    ("code", "for i in range(1, 5):\n    display(robot.link_matrix(i))"),
    (
        "md",
        r"""## 2. The arm matrix and $C_{1234}$

The four angles add up, just as $\theta_1 + \theta_2$ did for the 2R arm:
$C_{1234} = \cos(\theta_1 + \theta_2 + \theta_3 + \theta_4)$, and the tip position is a sum of
four link vectors, each pointing at the sum of the angles before it.""",
    ),
    ("code", "T = robot.arm_matrix()\nT"),
    (
        "code",
        """\
legend = robot.notation.legend(T.matrix)
display(Markdown("\\n".join(f"- ${e.latex} = {e.meaning_latex}$" for e in legend)))""",
    ),
    (
        "md",
        r"""The direction of the tip is $\varphi = \theta_1 + \theta_2 + \theta_3 + \theta_4$
(read it from $C_{1234}$, $S_{1234}$ in the first column).""",
    ),
    (
        "md",
        r"""## 3. Same tip pose, different joints

Start from one configuration $q_A$ and compute its tip pose $(x, y, \varphi)$. Then *choose*
a different $\theta_1$ and find the other three joints:

1. link 4 must end at the tip pointing along $\varphi$, so it starts at the *wrist point*
   $w = (x - a_4\cos\varphi,\; y - a_4\sin\varphi)$;
2. link 1 ends at $(a_1 C_1, a_1 S_1)$, so links 2 and 3 must bridge the gap to $w$:
   that is a 2R problem, solved by the law of cosines;
3. $\theta_4$ makes the angles add up to $\varphi$.""",
    ),
    (
        "code",
        """\
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
assert np.allclose(tip(qB), pose) and np.allclose(tip(qC), pose)""",
    ),
    (
        "md",
        r"""Three joint sets, one tip pose. Drawn on top of each other (only the frames of $q_A$
are drawn, $q_B$ and $q_C$ are the pale arms):""",
    ),
    (
        "code",
        """\
from dhsym.plot.figures import view_limits

limits = view_limits(robot, [qA, qB, qC], dim=2)
fig = robot.plot(qB, view="2d", frames=False, labels=False, limits=limits, alpha=0.35)
ax = fig.axes[0]
robot.plot(qC, ax=ax, frames=False, labels=False, limits=limits, alpha=0.35)
robot.plot(qA, ax=ax, limits=limits, title="Three joint sets, the same tip pose")
fig""",
    ),
    (
        "md",
        r"""The redundancy is useful: a robot can keep its tool still while it moves its elbow away
from an obstacle. The price is that "the" inverse kinematics has infinitely many answers, and
the controller must choose one.""",
    ),
    (
        "md",
        r"""## What to remember

- A planar $n$R arm has the arm matrix with $C_{12\dots n}$ in the rotation part.
- With more joints than task coordinates the arm is redundant: one tip pose, many joint sets.""",
    ),
]

NB03 = [
    (
        "md",
        r"""# 3 · The PUMA 560, link by link, in both conventions

The PUMA 560 is the classic six-joint industrial arm. Seed 001 ends with a printout from
Corke's Robotics Toolbox (`mdl_puma560`):

```
j  theta    d        a       alpha    offset
1  q1       0        0       1.5708   0
2  q2       0        0.4318  0        0
3  q3       0.15005  0.0203  -1.5708  0
4  q4       0.4318   0       1.5708   0
5  q5       0        0       -1.5708  0
6  q6       0        0       0        0

>> p560.fkine([0 0 0 0 0 0])
1 0 0 0.4521
0 1 0 -0.15
0 0 1 0.4318
```

This notebook rebuilds that table (standard DH), its link matrices and the arm matrix, checks
the zero configuration against the printout, draws the frames, and then does the same with
Craig's modified-DH table of the same robot.""",
    ),
    ("code", IMPORTS),
    ("md", "## 1. The standard table (Corke, seed 001)"),
    ("code", 'puma = dhsym.load("puma560")\npuma'),
    ("code", "puma.table.value_map   # metres"),
    (
        "md",
        r"""The toolbox prints $\alpha = 1.5708$; the table keeps $\pi/2$ exactly, so that
$\cos\alpha_1$ is exactly 0 in the matrices below. Compare with the printout:""",
    ),
    (
        "code",
        """\
printout = np.array([[0, 0, 1.5708], [0, 0.4318, 0], [0.15005, 0.0203, -1.5708],
                     [0.4318, 0, 1.5708], [0, 0, -1.5708], [0, 0, 0]])   # d, a, alpha
values = puma.table.value_map
ours = np.array([[float(row.d.subs(values)), float(row.a.subs(values)), float(row.alpha)]
                 for row in puma.table.rows])
assert np.allclose(ours, printout, atol=5e-5)
print("d, a and alpha agree with the toolbox printout")""",
    ),
    (
        "md",
        r"""## 2. Link by link

Each link matrix is $A_i = R_z(\theta_i) T_z(d_i) T_x(a_i) R_x(\alpha_i)$. Watch how a twist of
$\pm 90^\circ$ moves the entries: the middle columns swap and a $\pm 1$ appears in the third
row.""",
    ),
    (
        "code",
        """\
for i in range(1, 7):
    display(Markdown(f"**Link {i}**: `{puma.link_word(i)}`"))
    display(puma.link_matrix(i))""",
    ),
    (
        "md",
        r"""## 3. The arm matrix in $C_{23}$/$S_{23}$ form

Joints 2 and 3 have parallel axes (both horizontal), so their angles add up, as in the planar
arms: $C_{23} = \cos(\theta_2 + \theta_3)$, $S_{23} = \sin(\theta_2 + \theta_3)$.

The whole $4 \times 4$ matrix is too wide for the page, so we show it column by column:
$\mathbf n$, $\mathbf s$, $\mathbf a$ (the $x$, $y$, $z$ axes of frame 6) and $\mathbf p$ (its
origin, the wrist centre). `T` itself holds the full matrix.""",
    ),
    (
        "code",
        """\
def show_columns(robot, T):
    for name, column in (("n", T.n), ("s", T.s), ("a", T.a), ("p", T.position)):
        display(Markdown(f"$$\\mathbf{{{name}}} = {robot.notation.latex(column)}$$"))

T = puma.arm_matrix()
show_columns(puma, T)""",
    ),
    (
        "code",
        """\
legend = puma.notation.legend(T.matrix)
pairs = [f"${e.latex} = {e.meaning_latex}$" for e in legend if "23" in e.text]
display(Markdown(", ".join(pairs)))""",
    ),
    (
        "md",
        r"""The position $\mathbf p$ does not depend on $\theta_4$, $\theta_5$, $\theta_6$: the
last three axes meet in one point (a *spherical wrist*), so turning the wrist does not move it.""",
    ),
    ("code", "T.position.free_symbols"),
    (
        "md",
        r"""## 4. The zero configuration: the toolbox printout

At $q = 0$ the arm matrix must be the matrix that `p560.fkine([0 0 0 0 0 0])` printed
(the toolbox rounds $-0.15005$ to $-0.15$):""",
    ),
    (
        "code",
        """\
T0 = puma.fk(np.zeros(6))
fkine_printout = np.array([[1, 0, 0, 0.4521], [0, 1, 0, -0.15], [0, 0, 1, 0.4318], [0, 0, 0, 1]])
print(np.round(T0, 5))
assert np.allclose(T0, fkine_printout, atol=1e-4)""",
    ),
    (
        "md",
        r"""## 5. The frames, at home and at another pose

At $q = 0$ the upper arm ($a_2$) points along $x_0$ and the forearm ($d_4$) points up. The
shoulder offset $d_3$ shifts the forearm sideways by $0.15\,$m. Frames $\{0\}$ and $\{1\}$
share their origin, and so do the wrist frames $\{4\}$, $\{5\}$, $\{6\}$ (shorter triads
belong to the later frames).""",
    ),
    ("code", "puma.plot()"),
    ("code", "puma.plot([30, 30, -60, 0, 45, 0], deg=True)"),
    (
        "md",
        r"""## 6. The same robot in Craig's modified convention

Craig (and seeds 000 and 002) attach frame $i$ at the *near* (proximal) end of link $i$ and
write the link matrix in the other order:

$${}^{i-1}T_i = R_x(\alpha_{i-1})\,T_x(a_{i-1})\,R_z(\theta_i)\,T_z(d_i).$$

Row $i$ of a modified table holds $\alpha_{i-1}$ and $a_{i-1}$: the twist and length of the
link *before* joint $i$.""",
    ),
    ("code", 'craig = dhsym.load("puma560_modified")\ncraig'),
    (
        "code",
        """\
for i in range(1, 7):
    display(Markdown(f"**Link {i}**: `{craig.link_word(i)}`"))
    display(craig.link_matrix(i))""",
    ),
    ("code", "show_columns(craig, craig.arm_matrix())"),
    (
        "md",
        r"""The $C_{23}$, $S_{23}$ structure is the same, but signs differ: Craig chose the frames
differently (his $z_2$ points the other way, $\alpha_1 = -90^\circ$), so his zero configuration
has the forearm pointing **down**:""",
    ),
    ("code", "print(np.round(craig.fk(np.zeros(6)), 5))"),
    ("code", "craig.plot()"),
    (
        "md",
        r"""Notebook 5 compares the two conventions on one table and shows how the tool poses are
related.

## What to remember

- A $\pm 90^\circ$ twist swaps the middle columns of a link matrix.
- Parallel axes (joints 2 and 3) give $C_{23}$, $S_{23}$; a spherical wrist makes the wrist
  position independent of $\theta_4 \dots \theta_6$.
- The table reproduces the toolbox: ${}^0T_6(0)$ has $\mathbf p = (0.4521, -0.15005, 0.4318)$.""",
    ),
]

NB04 = [
    (
        "md",
        r"""# 4 · Prismatic joints: when $d$ is the variable

A **revolute** joint turns: $\theta_i$ is its variable and $d_i$ is a constant. A **prismatic**
joint slides along its axis $z_{i-1}$: now $d_i$ is the variable and $\theta_i$ is a constant.
In the tables below the variable of each row is **boxed**.""",
    ),
    ("code", IMPORTS),
    (
        "md",
        r"""## 1. Seed 001, Example I (RRP with a $180^\circ$ twist)

The lecture's table has columns $\Theta, \alpha, a, d$:

| Link | $\Theta$ | $\alpha$ | $a$ | $d$ |
|---|---|---|---|---|
| 1 | $\Theta_1$ | 0 | $a_2$ | $a_1$ |
| 2 | $\Theta_2$ | 180 | $a_4$ | $a_3$ |
| 3 | 0 | 0 | 0 | $a_5 + d_3$ |

The third joint is prismatic: $\theta_3 = 0$ is fixed and $d = a_5 + d_3$ changes with the
joint variable $d_3$ ($a_5$ is a constant part, an *offset*). dhsym shows the same table in
its own column order $\theta, d, a, \alpha$ (the symbols $a_1 \dots a_5$ are the lecture's):""",
    ),
    ("code", 'ex1 = dhsym.load("example1_rrp")\nex1.table'),
    (
        "code",
        """\
row3 = ex1.table.rows[2]
print("joint type:", row3.joint.name, "| variable:", row3.variable,
      "| in column:", row3.variable_field, "| constant offset:", row3.offset)""",
    ),
    ("code", "for i in range(1, 4):\n    display(ex1.link_matrix(i))"),
    (
        "md",
        r"""The arm matrix. The $180^\circ$ twist of row 2 turns $z$ upside down: the third column
(the approach vector $\mathbf a$) is $(0, 0, -1)$, so the tool points **down**, and the
prismatic joint moves the tool down as $d_3$ grows ($p_z$ contains $-d_3$). Since joints 1
and 2 have parallel axes, $C_{12}$ appears again.""",
    ),
    ("code", "T = ex1.arm_matrix()\nT"),
    (
        "code",
        """\
assert list(T.a) == [0, 0, -1]
print("p_z =", T.position[2])""",
    ),
    ("code", "ex1.plot([30, 45, 0.15], deg=True)"),
    (
        "md",
        r"""## 2. SCARA (RRPR)

The SCARA is Example I with a fourth, revolute joint that turns the tool. Because of the
$180^\circ$ twist its axis points down, so $\theta_4$ enters the tool's direction with a minus
sign: look for $C_{12-4}$ (short for $\cos(\theta_1 + \theta_2 - \theta_4)$).""",
    ),
    ("code", 'scara = dhsym.load("scara")\ndisplay(scara.table)\nscara.arm_matrix()'),
    ("code", "scara.plot([30, 45, 0.1, 0], deg=True)"),
    (
        "md",
        r"""## 3. Cylindrical (RPP)

One revolute joint (the column turns) and two prismatic joints (the carriage goes up with
$d_2$ and the arm reaches out with $d_3$). The tip moves on cylinders around $z_0$.""",
    ),
    ("code", 'cyl = dhsym.load("cylindrical")\ndisplay(cyl.table)\ncyl.arm_matrix()'),
    ("code", "cyl.plot([30, 0.3, 0.4], deg=True)"),
    (
        "md",
        r"""## 4. Cartesian (PPP)

Three prismatic joints. Every $\theta_i$ is a constant, so **the rotation part of the arm
matrix is constant**: a Cartesian robot moves its tool without turning it, and the position is
linear in $d_1, d_2, d_3$.""",
    ),
    ("code", 'cart = dhsym.load("cartesian")\ndisplay(cart.table)\nT = cart.arm_matrix()\nT'),
    (
        "code",
        """\
assert not T.rotation.free_symbols
print("rotation part has no variables; position =", list(T.position))""",
    ),
    ("code", "cart.plot([0.3, 0.2, 0.25])"),
    (
        "md",
        r"""## 5. The Stanford arm (RRP + wrist)

Two revolute joints point a boom, and the prismatic joint 3 slides it in and out ($d_3$, the
reach); joints 4 to 6 form a spherical wrist. The wrist position is the boom direction times
$d_3$, plus the shoulder offset $d_2$.""",
    ),
    (
        "code",
        'stanford = dhsym.load("stanford")\ndisplay(stanford.table)\n'
        "stanford.arm_matrix().position",
    ),
    ("code", "stanford.plot([30, 60, 0.5, 0, 45, 0], deg=True)"),
    ("md", r"""## Summary: which column holds the variable?"""),
    (
        "code",
        """\
lines = ["| robot | joint | type | variable | column |", "|---|---|---|---|---|"]
for r in (ex1, scara, cyl, cart, stanford):
    for i, row in enumerate(r.table.rows, start=1):
        column = sp.latex(sp.Symbol("theta")) if row.variable_field == "theta" else "d"
        lines.append(f"| {r.name} | {i} | {row.joint.name.lower()} "
                     f"| ${sp.latex(row.variable)}$ | ${column}$ |")
display(Markdown("\\n".join(lines)))""",
    ),
]

NB05 = [
    (
        "md",
        r"""# 5 · Standard versus modified DH: same robot, different frames

Two DH conventions are in use (seeds 001 and 002):

| | standard (distal) | modified (proximal, Craig) |
|---|---|---|
| link matrix | $R_z(\theta_i)\,T_z(d_i)\,T_x(a_i)\,R_x(\alpha_i)$ | $R_x(\alpha_{i-1})\,T_x(a_{i-1})\,R_z(\theta_i)\,T_z(d_i)$ |
| frame $i$ sits | at the far end of link $i$, $z_i$ on the axis of joint $i+1$ | at the near end of link $i$, $z_i$ on the axis of joint $i$ |
| row $i$ holds | $\theta_i, d_i, a_i, \alpha_i$ | $\alpha_{i-1}, a_{i-1}, d_i, \theta_i$ |

This notebook writes the PUMA 560 both ways, shows that the frames land in different places,
and that the tool pose agrees.""",
    ),
    ("code", IMPORTS + "\nfrom dhsym.plot.figures import frame_origins"),
    (
        "md",
        r"""## 1. From the standard table to a modified one

Write the standard product for two links and regroup it:

$$R_z(\theta_1)T_z(d_1)\,\underbrace{T_x(a_1)R_x(\alpha_1)\,R_z(\theta_2)T_z(d_2)}_{\text{modified link 2}}\,T_x(a_2)R_x(\alpha_2)\cdots$$

So the modified row $i$ takes $\theta_i$, $d_i$ from standard row $i$ and $\alpha_{i-1}$,
$a_{i-1}$ from standard row $i-1$ (zero for row 1). What is left over at the end,
$T_x(a_n)R_x(\alpha_n)$, becomes a **tool transform**. Done in code:""",
    ),
    (
        "code",
        """\
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
display(mod.table)""",
    ),
    (
        "md",
        r"""## 2. The frames are in different places

Standard frame $i$ sits at the end of link $i$, modified frame $i$ at its start. Compare the
origins at $q = 0$ (in metres):""",
    ),
    (
        "code",
        """\
o_std, o_mod = frame_origins(std), frame_origins(mod)
lines = ["| frame | standard origin | modified origin |", "|---|---|---|"]
for k, (p, r) in enumerate(zip(o_std, o_mod)):
    lines.append(f"| {{{k}}} | {np.round(p + 0.0, 4)} | {np.round(r + 0.0, 4)} |")
display(Markdown("\\n".join(lines)))""",
    ),
    (
        "md",
        r"""For example, standard frame $\{2\}$ is at the elbow (end of the upper arm $a_2$), while
modified frame $\{2\}$ is at the shoulder, on the axis of joint 2. The link matrices differ
too: compare ${}^{1}T_{2}$ in both conventions.""",
    ),
    ("code", "display(std.link_matrix(2))\ndisplay(mod.link_matrix(2))"),
    (
        "code",
        "q = np.radians([30, 30, -60, 0, 45, 0])\n"
        'std.plot(q, title="standard DH: frames at the far end of each link")',
    ),
    ("code", 'mod.plot(q, title="modified DH: frames at the near end of each link")'),
    (
        "md",
        r"""## 3. … but the tool pose is the same

Both are the same product of elementary transforms, only grouped differently, so
${}^0T_6$ must agree for **every** $q$. Symbolically:""",
    ),
    (
        "code",
        """\
difference = (std.arm_matrix().matrix - mod.tool_pose().matrix).applyfunc(sp.simplify)
assert difference == sp.zeros(4)
print("standard 0T6 == modified 0T6 (times the tool transform), exactly")""",
    ),
    ("md", "and numerically, at 1000 random configurations:"),
    (
        "code",
        """\
Q = np.random.default_rng(0).uniform(-np.pi, np.pi, size=(1000, 6))
err = np.abs(std.fk(Q) - mod.fk(Q)).max()
print(f"largest difference: {err:.1e}")
assert err < 1e-12""",
    ),
    (
        "md",
        r"""## 4. Craig's published table: base and tool transforms

Craig's own modified table for the PUMA 560 (`puma560_modified`) differs from the one we just
built in one entry: $\alpha_1 = -90^\circ$ instead of $+90^\circ$. He points $z_2$ the other
way, so his zero configuration is a different pose (forearm down). To compare two descriptions
of one robot we look for a **base** transform $B$ (between the two base frames) and a
**tool** transform $E$ (between the two last frames) with

$$ {}^0T_6^{\text{std}}(q) = B\;{}^0T_6^{\text{Craig}}(q')\;E .$$

Both last frames sit at the wrist centre with $z$ along joint 6, so try $E = I$ and compute
$B$ from the two results at $q = 0$:""",
    ),
    (
        "code",
        """\
craig = dhsym.load("puma560_modified")
display(craig.table)
B = std.fk(np.zeros(6)) @ np.linalg.inv(craig.fk(np.zeros(6)))
print(np.round(B, 6) + 0.0)""",
    ),
    (
        "md",
        r"""$B$ is a rotation by $180^\circ$ about $x$: Craig's base frame is the standard one
turned upside down. Turning the base over also reverses the sense in which joint 1 turns (its axis
is $z_0$), so the same physical motion is $q' = (-\theta_1, \theta_2, \dots, \theta_6)$:""",
    ),
    (
        "code",
        """\
Qc = Q.copy()
Qc[:, 0] *= -1
same = np.abs(std.fk(Q) - B @ craig.fk(Qc)).max()
naive = np.abs(std.fk(Q) - B @ craig.fk(Q)).max()
print(f"with q' = (-theta1, theta2, ...): {same:.1e};   with q' = q: {naive:.2f}")
assert same < 1e-12 and naive > 0.1""",
    ),
    ("code", 'craig.plot(np.zeros(6), title="Craig\'s frames at q = 0 (forearm down)")'),
    (
        "md",
        r"""## What to remember

- Standard: frame $i$ at the **end** of link $i$. Modified: frame $i$ at the **start** of link $i$.
- The same robot gives the same tool pose in both conventions; only the intermediate
  frames (and link matrices) differ. Converting a table shifts $a$ and $\alpha$ by one row.
- Two *different* frame choices (like Craig's table and Corke's) are related by base and tool
  transforms, and sometimes by a change of joint sign or zero; compute them, don't guess.""",
    ),
]

NOTEBOOKS = {
    "01_planar_2R.ipynb": NB01,
    "02_planar_4R.ipynb": NB02,
    "03_puma560.ipynb": NB03,
    "04_prismatic.ipynb": NB04,
    "05_standard_vs_modified.ipynb": NB05,
}


def puma_picture(path: Path = ROOT / "docs" / "puma560-frames.png") -> Path:
    """The README picture: the PUMA 560 with its DH frames at q = 0 (the printout's pose)."""
    import dhsym

    robot = dhsym.load("puma560")
    fig = robot.plot(
        scale=0.1,
        title="PUMA 560, standard DH frames at q = 0\n"
        "(the pose of the toolbox printout in seed 001)",
    )
    fig.set_size_inches(8.0, 7.2)
    fig.axes[0].view_init(elev=20, azim=-125)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    return path


def main(argv: list[str]) -> int:
    for name, cells in NOTEBOOKS.items():
        if argv and not any(name.startswith(a) for a in argv):
            continue
        build_notebook(name, cells, timeout=120)
    if not argv or "docs" in argv:
        print(f"wrote {puma_picture().relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
