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
# # 6 · Homework checking: an instructor's whole flow
#
# A DH homework has many right answers and a few classic wrong ones. `dhsym.checking`
# says right or wrong, says where and most likely why, accepts valid alternative frame
# choices, and grades a whole class without ever running what a student typed.
#
# This notebook: check single answers (a lecture slide's misprint, a valid alternative table),
# then grade the small example class in `examples/homework/` and read the reports.

# %%
from pathlib import Path
import tempfile
from IPython.display import SVG, Markdown, display

from dhsym.checking import Key, check_answer, grade, render_check

ROOT = Path.cwd().parent if Path.cwd().name == "notebooks" else Path.cwd()
HW = ROOT / "examples" / "homework"


# %% [markdown]
# ## One answer: a slide with a misprint
#
# One slide of S. Mohan (IIT Palakkad), Mechanics and Control of Robotic Manipulators,
# Lecture 9 "DH parameters", prints the modified link matrix with `+d_i sin α_{i−1}` in entry
# (2,4); the correct entry is `−d_i sin α_{i−1}`. The key is the generic one-row modified
# table `generic_modified_link.yaml`; the answer is the slide's LaTeX exactly as printed.

# %%
slide = (r"\begin{bmatrix} \cos \theta_i & -\sin \theta_i & 0 & a_{i-1} \\ "
         r"\sin \theta_i \cos \alpha_{i-1} & \cos \theta_i \cos \alpha_{i-1} & -\sin \alpha_{i-1}"
         r" & d_i \sin \alpha_{i-1} \\ \sin \theta_i \sin \alpha_{i-1} & \cos \theta_i "
         r"\sin \alpha_{i-1} & \cos \alpha_{i-1} & d_i \cos \alpha_{i-1} \\ 0 & 0 & 0 & 1 "
         r"\end{bmatrix}")
key = Key.load(HW / "generic_modified_link.yaml", "A1")
result = check_answer(key, slide)
print(result.verdict.value, result.kinds, result.diagnoses[0].entries)
display(Markdown(render_check(result)))

# %% [markdown]
# ## A valid alternative DH table
#
# x0 turned by 90°, z1 reversed, and the origin of frame 2 moved along the parallel
# axes z1, z2: a different table of the same PUMA 560, so it is right.

# %%
alternative = '''Link	$\theta_i$	$d_i$	$a_i$	$\alpha_i$
1	$\theta_1 - 90^\circ$	0	0	$-90^\circ$
2	$\theta_2$	0.1	$a_2$	$180^\circ$
3	$\theta_3$	$d_3 + 0.1$	$a_3$	$-90^\circ$
4	$\theta_4$	$d_4$	0	$90^\circ$
5	$\theta_5$	0	0	$-90^\circ$
6	$\theta_6$	0	0	0'''
r = check_answer(Key.load("puma560", "table"), alternative)
print(r.verdict.value)
print(r.alternative)

# %% [markdown]
# ## Untrusted input
#
# Code, huge powers, deep nesting and LaTeX commands are answered "unreadable" with the
# reason; nothing is executed.

# %%
for text in ["__import__('os').system('ls')", "x**9999999", "(" * 500 + "x" + ")" * 500,
             r"\input{/etc/passwd}"]:
    r = check_answer(Key.load("puma560", "T0_6[0,3]"), text)
    print(f"{r.verdict.value:10s} {r.reason[:90]}")

# %% [markdown]
# ## Grading the class
#
# `examples/homework/assignment.yaml` asks five questions (a table, `T0_2`, a link matrix
# with an offset, the modified link matrix of that slide, `p_x`). The class has right answers, every
# kind of classic mistake, a missing answer and a hostile student.
# The same as `dhsym grade examples/homework/assignment.yaml examples/homework/submissions -o REPORT`.

# %%
report_dir = Path(tempfile.mkdtemp()) / "report"
report = grade(HW / "assignment.yaml", HW / "submissions", report_dir, workers=2, progress=False)
print(report.students, "students, mean", round(report.mean, 2), "of", 10)
print((report_dir / "gradebook.csv").read_text())

# %%
display(SVG(filename=str(report_dir / "summary.svg")))

# %% [markdown]
# Each student gets a feedback page (Markdown and HTML): the verdict, the diagnosis,
# their entry and the correct one in the lecture notation.

# %%
display(Markdown((report_dir / "feedback" / "erin.md").read_text()))

# %% [markdown]
# A rerun skips everything already graded (the cache in the report folder):

# %%
again = grade(HW / "assignment.yaml", HW / "submissions", report_dir, workers=2,
              progress=False)
print("graded", again.graded, "skipped", again.skipped)
