"""Write the example class of examples/homework (run: python examples/homework/make_class.py).

Ten students in ``submissions/`` (one folder each, one file per question) and a
CSV class ``class.csv``: right answers in several notations, a valid alternative
table, every kind of classic mistake, unreadable and hostile answers.
"""

from __future__ import annotations

import csv
import shutil
from pathlib import Path

import sympy as sp

import dhsym
from dhsym.kinematics.transforms import link_word, plain_product
from dhsym.notation.printers import Notation

HERE = Path(__file__).resolve().parent
SLIDES = [  # Mohan, Lecture 9: two slides of ^{i-1}T_i: the first prints +d_i sin(alpha_{i-1})
    r"$${}^{i-1}T_i = \begin{bmatrix} \cos \theta_i & -\sin \theta_i & 0 & a_{i-1} \\ "
    r"\sin \theta_i \cos \alpha_{i-1} & \cos \theta_i \cos \alpha_{i-1} & -\sin \alpha_{i-1} & "
    r"d_i \sin \alpha_{i-1} \\ \sin \theta_i \sin \alpha_{i-1} & \cos \theta_i \sin \alpha_{i-1} "
    r"& \cos \alpha_{i-1} & d_i \cos \alpha_{i-1} \\ 0 & 0 & 0 & 1 \end{bmatrix}$$",
]
SLIDES.append(SLIDES[0].replace(r"& d_i \sin \alpha_{i-1}", r"& -d_i \sin \alpha_{i-1}"))

BOB_Q4 = (  # the right link matrix in the c_{theta_i} notation of IRob2305 Lecture 5
    r"\begin{bmatrix} c_{\theta_i} & -s_{\theta_i} & 0 & a_{i-1} \\ "
    r"s_{\theta_i} c_{\alpha_{i-1}} & c_{\theta_i} c_{\alpha_{i-1}} & -s_{\alpha_{i-1}} & "
    r"-s_{\alpha_{i-1}} d_i \\ s_{\theta_i} s_{\alpha_{i-1}} & c_{\theta_i} s_{\alpha_{i-1}} & "
    r"c_{\alpha_{i-1}} & c_{\alpha_{i-1}} d_i \\ 0 & 0 & 0 & 1 \end{bmatrix}"
)
# Mohan's standard link matrix: alpha_i, a_i where alpha_{i-1}, a_{i-1} belong
STANDARD_GENERIC = (
    r"\begin{bmatrix} \cos \theta_i & -\sin \theta_i \cos \alpha_i & \sin \theta_i \sin \alpha_i "
    r"& a_i \cos \theta_i \\ \sin \theta_i & \cos \theta_i \cos \alpha_i & -\cos \theta_i "
    r"\sin \alpha_i & a_i \sin \theta_i \\ 0 & \sin \alpha_i & \cos \alpha_i & d_i \\ "
    r"0 & 0 & 0 & 1 \end{bmatrix}"
)
TABLE = """| j | θ | d | a | α |
|---|---|---|---|---|
| 1 | θ1 | 0 | 0 | 90° |
| 2 | θ2 | 0 | a2 | 0 |
| 3 | θ3 | d3 | a3 | -90° |
| 4 | θ4 | d4 | 0 | 90° |
| 5 | θ5 | 0 | 0 | -90° |
| 6 | θ6 | 0 | 0 | 0 |
"""
ALTERNATIVE = """Link\t$\\theta_i$\t$d_i$\t$a_i$\t$\\alpha_i$
1\t$\\theta_1 - 90^\\circ$\t0\t0\t$-90^\\circ$
2\t$\\theta_2$\t0.1\t$a_2$\t$180^\\circ$
3\t$\\theta_3$\t$d_3 + 0.1$\t$a_3$\t$-90^\\circ$
4\t$\\theta_4$\t$d_4$\t0\t$90^\\circ$
5\t$\\theta_5$\t0\t0\t$-90^\\circ$
6\t$\\theta_6$\t0\t0\t0
"""
MODIFIED = """| i | alpha_{i-1} | a_{i-1} | d_i | theta_i |
|---|---|---|---|---|
| 1 | 0 | 0 | 0 | q1 |
| 2 | -90 | 0 | 0 | q2 |
| 3 | 0 | a2 | d3 | q3 |
| 4 | -90 | a3 | d4 | q4 |
| 5 | 90 | 0 | 0 | q5 |
| 6 | -90 | 0 | 0 | q6 |
"""


def plain(M: sp.MatrixBase, nota: Notation) -> str:
    return (
        "["
        + ",\n ".join(
            "[" + ", ".join(nota.text(M[i, j]) for j in range(4)) + "]" for i in range(M.rows)
        )
        + "]"
    )


def latex(M: sp.MatrixBase, nota: Notation) -> str:
    return f"$${nota.latex(sp.Matrix(M))}$$"


def product(table, rows, convention=None, reverse=False) -> sp.Matrix:
    links = [list(link_word(r, convention or table.convention)) for r in rows]
    return plain_product([e for link in (links[::-1] if reverse else links) for e in link])


def answers() -> dict[str, tuple[str, dict[str, str]]]:
    puma, ex4 = dhsym.load("puma560"), dhsym.load("example4_6dof")
    nota = puma.notation
    full = Notation(nota.labels, compact=False)
    T02, A3 = puma.transform(0, 2).matrix, ex4.transform(2, 3).matrix
    px = nota.text(puma.arm_matrix().matrix[0, 3])
    t1 = sp.Symbol("theta1", real=True)
    rows = puma.table.rows
    right = {
        "q1": TABLE,
        "q2": plain(T02, nota),
        "q3": plain(A3, ex4.notation),
        "q4": SLIDES[1],
        "q5": px,
    }
    deg_rows = [r.__class__(r.joint, r.theta, r.d, r.a, r.alpha * 180 / sp.pi) for r in rows[:2]]
    no_offset = [r.__class__(r.joint, r.variable, r.d, r.a, r.alpha) for r in ex4.table.rows[2:3]]
    swapped = px.replace("C1", "X").replace("S1", "C1").replace("X", "S1")
    bad_row = TABLE.replace("| 2 | θ2 | 0 | a2 | 0 |", "| 2 | θ2 | 0 | a3 | 0 |")
    shifted = (
        TABLE.replace("| 1 | θ1 | 0 | 0 | 90° |", "| 1 | θ1 | 0 | 0 | 0 |")
        .replace("| 2 | θ2 | 0 | a2 | 0 |", "| 2 | θ2 | 0 | 0 | 90° |")
        .replace("| 3 | θ3 | d3 | a3 | -90° |", "| 3 | θ3 | d3 | a2 | 0 |")
        .replace("| 4 | θ4 | d4 | 0 | 90° |", "| 4 | θ4 | d4 | a3 | -90° |")
        .replace("| 5 | θ5 | 0 | 0 | -90° |", "| 5 | θ5 | 0 | 0 | 90° |")
        .replace("| 6 | θ6 | 0 | 0 | 0 |", "| 6 | θ6 | 0 | 0 | -90° |")
    )
    deep = "(" * 200 + "x" + ")" * 200
    return {
        "alice": ("Alice Andersen", {**right, "q2": latex(T02, nota)}),
        "bob": (
            "Bob Brown",
            {
                "q1": ALTERNATIVE,
                "q2": plain(sp.expand(T02), full),
                "q3": latex(A3, ex4.notation),
                "q4": BOB_Q4,
                "q5": px.replace("C", "c").replace("S", "s"),
            },
        ),
        "carol": ("Carol Chen", {**right, "q2": plain(T02.T, nota), "q4": SLIDES[0]}),
        "dave": (
            "Dave Diaz",
            {
                **right,
                "q1": shifted,
                "q4": STANDARD_GENERIC,
                "q2": plain(product(puma.table, rows[:2], dhsym.Convention.MODIFIED), nota),
            },
        ),
        "erin": (
            "Erin Evans",
            {
                **right,
                "q2": plain(product(puma.table, deg_rows), full),
                "q3": plain(product(ex4.table, no_offset), ex4.notation),
            },
        ),
        "frank": (
            "Frank Fischer",
            {
                **right,
                "q2": plain(product(puma.table, rows[:2], reverse=True), nota),
                "q5": swapped,
            },
        ),
        "grace": (
            "Grace Green",
            {
                **right,
                "q1": bad_row,
                "q2": "C12 -S12 ??? \\\\ oops",
                "q5": px.replace("d3*S1 +", "d3*S1 -"),
            },
        ),
        "heidi": ("Heidi Hall", {**right, "q1": MODIFIED}),
        "ivan": ("Ivan Ivanov", {"q1": TABLE, "q2": plain(T02, nota)}),  # q3-q5 missing
        "mallory": (
            "<script>alert('x')</script> & \\input{/etc/passwd}",
            {
                "q1": "joints: &a [*a, *a]\nname: &b [*a, *a]\n",
                "q2": "__import__('os').system('touch /tmp/dhsym-pwned')",
                "q3": deep,
                "q4": r"\input{/etc/passwd} \write18{rm -rf /}",
                "q5": "x**9999999",
            },
        ),
    }, t1


def main() -> None:
    data, _ = answers()
    out = HERE / "submissions"
    if out.exists():
        shutil.rmtree(out)
    for student, (name, qs) in data.items():
        folder = out / student
        folder.mkdir(parents=True)
        (folder / "name.txt").write_text(name + "\n", encoding="utf-8")
        for qid, text in qs.items():
            ext = ".md" if text.lstrip().startswith(("|", "$")) or "\\" in text else ".txt"
            (folder / (qid + ext)).write_text(
                text if text.endswith("\n") else text + "\n", encoding="utf-8"
            )
    with (HERE / "class.csv").open("w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(["student", "name", "q1", "q2", "q3", "q4", "q5"])
        right = data["alice"][1]
        w.writerow(["s001", "Ada", *(right[q] for q in ("q1", "q2", "q3", "q4", "q5"))])
        w.writerow(
            [
                "../../etc/passwd",
                '=HYPERLINK("http://evil.example","click")',
                right["q1"],
                "",
                "",
                SLIDES[0],
                "1e999999",
            ]
        )
        w.writerow(["s003", "</td><script>alert(1)</script>", "", "", "", "", "cos(theta1"])
    print(f"wrote {out} and {HERE / 'class.csv'}")


if __name__ == "__main__":
    main()
