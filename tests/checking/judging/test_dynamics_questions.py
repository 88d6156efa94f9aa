"""The dynamics questions (M, M[i,j], g, C, c_ijk, tau, tau_static) and their mistakes,
on Spong's planar 2R (``m_i``, ``l_i``, ``lc_i``, ``I_i``, gravity ``-g`` along y0)."""

from __future__ import annotations

import pytest
import sympy as sp

from dhsym.checking.reading.questions import Question
from dhsym.dynamics.lagrange_euler import link_jacobians
from dhsym.dynamics.model import dynamic_model
from dhsym.errors import DHError
from dhsym.model.tablefile import read_table_text
from dhsym.robot import Robot

from .._keys import check_answer, load_key  # each key prepared once, as a grading worker does

SPONG = """
name: Two-link planar elbow arm (Spong)
convention: standard
gravity: [0, -g, 0]
joints:
  - {type: R, theta: q1, d: 0, a: l1, alpha: 0, m: m1, r: [lc1 - l1, 0, 0], I: [Ix1, Iy1, I1]}
  - {type: R, theta: q2, d: 0, a: l2, alpha: 0, m: m2, r: [lc2 - l2, 0, 0], I: [Ix2, Iy2, I2]}
"""
TABLE = read_table_text(SPONG)

# Spong's D(q), g(q) and C(q, q̇) for this arm, written out by hand (Robot Modeling and
# Control, the two-link planar elbow manipulator); h = -m2 l1 lc2 sin q2.
D11 = "m1*lc1**2 + m2*(l1**2 + lc2**2 + 2*l1*lc2*C2) + I1 + I2"
D12 = "m2*(lc2**2 + l1*lc2*C2) + I2"
D22 = "m2*lc2**2 + I2"
M_RIGHT = f"[[{D11}, {D12}], [{D12}, {D22}]]"
G1 = "(m1*lc1 + m2*l1)*g*C1 + m2*lc2*g*C12"
G2 = "m2*lc2*g*C12"
H = "(-m2*l1*lc2*S2)"
C_RIGHT = f"[[{H}*qdot2, {H}*qdot2 + {H}*qdot1], [-{H}*qdot1, 0]]"


def check(question: str, answer: str, table: object = TABLE):
    return check_answer(load_key(table, question), answer)


def assert_diagnosed(result, kind: str) -> None:
    assert result.verdict.value == "incorrect", result.message
    assert result.kinds[0] == kind, (result.kinds, result.message)
    assert result.diagnoses[0].title in result.message


def test_questions_parse_with_canonical_labels():
    q = Question.parse("c_{211}", 2)
    assert (q.kind, q.part, q.index, q.label) == ("dynamics", "c", (2, 1, 1), "c_211")
    assert Question.parse("M[1,0]", 2).entry == (1, 0)
    assert Question.parse("tau_static", 2).part == "tau_static"
    assert Question.parse("g", 2).label_latex == "g(q)"
    with pytest.raises(DHError, match="c_ijk are 1"):
        Question.parse("c_113", 2)
    with pytest.raises(DHError, match="0-based"):
        Question.parse("g[0,1]", 2)


@pytest.mark.parametrize(
    ("question", "answer"),
    [
        ("M", M_RIGHT),
        # rearranged: expanded and terms reordered
        (
            "M",
            "[[I2 + I1 + m2*l1**2 + m2*lc2**2 + m1*lc1**2 + 2*m2*l1*lc2*cos(q2),"
            " I2 + m2*lc2**2 + m2*l1*lc2*cos(q2)], [m2*lc2*(lc2 + l1*c2) + I2, I2 + lc2**2*m2]]",
        ),
        ("M[0,1]", D12),
        ("M[1,1]", "I2 + lc2*lc2*m2"),
        ("g", f"[{G1}, {G2}]"),
        ("g", f"[[g*(m1*lc1*cos(q1) + m2*l1*cos(q1) + m2*lc2*cos(q1 + q2))], [{G2}]]"),
        ("C", C_RIGHT),
        ("C", "[[-m2*l1*lc2*S2*thetadot2, -m2*l1*lc2*S2*(qd1 + qd2)], [m2*l1*lc2*S2*qd1, 0]]"),
        ("c_121", H),
        ("c_211", "-m2 l1 lc2 \\sin q_2"),
        ("c_112", "m2*l1*lc2*S2"),
        ("c_111", "0"),
        (
            "tau",
            f"[({D11})*qddot1 + ({D12})*qddot2 + {H}*qdot2**2 + 2*{H}*qdot1*qdot2 + {G1},"
            f" ({D12})*qddot1 + ({D22})*qddot2 - {H}*qdot1**2 + {G2}]",
        ),
        (
            "tau_static",
            "[nz + fy*(l1*C1 + l2*C12) - fx*(l1*S1 + l2*S12), nz + l2*(fy*C12 - fx*S12)]",
        ),
    ],
)
def test_right_and_rearranged_answers_are_correct(question: str, answer: str):
    r = check(question, answer)
    assert r.verdict.value == "correct", r.message


def test_latex_and_markdown_answers():
    latex = (
        r"$$\begin{bmatrix} (m_1 l_{c1}^2 + m_2 (l_1^2 + l_{c2}^2 + 2 l_1 l_{c2} \cos q_2) "
        r"+ I_1 + I_2) \ddot q_1 + \dots \end{bmatrix}$$"
    )
    assert check("tau", latex).verdict.value == "unreadable"  # \dots is no answer
    h = r"(-m_2 l_1 lc_2 \sin\theta_2)"
    answer = rf"\begin{{bmatrix}} {h} \dot q_2 & {h}(\dot{{q}}_1 + \dot{{q}}_2) \\"
    answer += rf" -{h} \dot{{q}}_1 & 0 \end{{bmatrix}}"
    r = check("C", answer)
    assert r.verdict.value == "correct", r.message
    md = f"| {G1} |\n| {G2} |"
    assert check("g", md).verdict.value == "correct"


@pytest.mark.parametrize(
    "answer",
    [
        f"d11 = {D11}\nd12 = {D12}\nd21 = d12\nd22 = {D22}",
        f"d11 = {D11}; d12 = {D12}; d22 = {D22}",  # d21 by symmetry
        f"M_{{11}} = {D11}, M_{{12}} = M_{{21}} = {D12}, M_{{22}} = {D22}",
        r"d_{11} = m_1 \ell_{c1}^2 + m_2(\ell_1^2 + \ell_{c2}^2 + 2\ell_1\ell_{c2}\cos q_2)"
        r" + I_1 + I_2 \\ d_{12} = d_{21} = m_2(\ell_{c2}^2 + \ell_1\ell_{c2}\cos q_2) + I_2"
        r" \\ d_{22} = m_2\ell_{c2}^2 + I_2",
        f"d11 = {D11.replace('l', 'ℓ')}; d12 = {D12}; d22 = {D22}",
    ],
)
def test_the_inertia_matrix_entry_by_entry_as_spong_writes_it(answer):
    r = check("M", answer)
    assert r.verdict.value == "correct", r.message


def test_entries_by_name_leave_nothing_out_and_say_which():
    r = check("M", f"d11 = {D11}; d12 = {D12}")
    assert r.verdict.value == "unreadable" and "(2,2) is missing" in r.message
    assert check("C", f"c11 = {H}*qdot2; c12 = 0; c22 = 0").verdict.value == "unreadable"
    r = check("M", f"d11 = {D11}; d12 = {D12}; d22 = m2*lc2**2")
    assert r.verdict.value == "incorrect"


@pytest.mark.parametrize(
    "question, answer",
    [
        ("g", f"g1 = {G1}\ng2 = {G2}"),  # a vector entry by entry
        ("g", f"phi1 = {G1}; phi2 = {G2}"),  # Spong's φ_k
        ("g", rf"\phi_1 = {G1} \\ \phi_2 = {G2}"),
        ("g", f"φ₂ = {G2}\nφ₁ = {G1}"),
        # Spong's C with its helper h = -m2 l1 lc2 sin q2 defined first
        ("C", f"h = {H}\nC = [[h*qdot2, h*qdot2 + h*qdot1], [-h*qdot1, 0]]"),
        ("C", f"h = {H}\n[h q̇₂, h q̇₂ + h q̇₁; -h q̇₁, 0]"),  # q̇: a combining dot
        ("C", f"h = {H}; k = -h\n[h dq2, h (dq1 + dq2); k dq1, 0]"),  # code's dq
        (
            "C",
            r"h = -m_2 l_1 l_{c2} \sin q_2 \\"
            "\n"
            r"C = \begin{bmatrix} h\dot q_2 & h(\dot q_1 + \dot q_2) \\ -h\dot q_1 & 0"
            r" \end{bmatrix}",
        ),
    ],
)
def test_vectors_by_entry_helpers_and_rates_as_typed(question, answer):
    r = check(question, answer)
    assert r.verdict.value == "correct", r.message


def test_a_helper_is_never_a_robot_symbol_and_cannot_blow_up():
    # l1 = 1 is no helper (l1 is the robot's): nothing is put in for l1, the extra line
    # makes the answer unreadable, as before
    r = check("g", f"l1 = 1\n[{G1}; {G2}]")
    assert r.verdict.value == "unreadable" and "3 rows" in r.message
    wrong = check("C", f"h = {H}\nC = [[h*qdot2, h*qdot2 + h*qdot1], [h*qdot1, 0]]")
    assert wrong.verdict.value == "incorrect" and "(2,1)" in wrong.message
    lines = ["h0 = qdot1"] + [f"h{k} = h{k - 1} + h{k - 1} + h{k - 1}" for k in range(1, 40)]
    r = check("C", "\n".join(lines) + "\n[[h39, 0], [0, 0]]")
    assert r.verdict.value == "unreadable" and "too long" in r.message


def test_wrong_shape_is_unreadable():
    assert check("M", "[[1, 2, 3]]").verdict.value == "unreadable"


def test_parallel_axis_forgotten():
    # each mass on its joint: link 1 has no m1*lc1**2, link 2 moves with the elbow only
    assert_diagnosed(check("M", "[[I1 + I2 + m2*l1**2, I2], [I2, I2]]"), "parallel_axis")


def test_rotational_energy_left_out():
    bad = M_RIGHT.replace(" + I1 + I2", "").replace(" + I2", "")
    assert "I" not in bad
    assert_diagnosed(check("M", bad), "rotational_energy")
    assert_diagnosed(
        check("M[0,0]", "m1*lc1**2 + m2*(l1**2 + lc2**2 + 2*l1*lc2*C2)"), "rotational_energy"
    )


def test_gravity_sign_and_direction():
    assert_diagnosed(check("g", f"[-({G1}), -({G2})]"), "gravity_direction")
    # gravity along -x0 (the arm in a vertical x-z plane read wrongly)
    sideways = "[-(m1*lc1 + m2*l1)*g*S1 - m2*lc2*g*S12, -m2*lc2*g*S12]"
    assert_diagnosed(check("g", sideways), "gravity_direction")


def test_l_used_for_lc():
    bad_M = M_RIGHT.replace("lc", "l")
    assert_diagnosed(check("M", bad_M), "l_for_lc")
    assert_diagnosed(check("g", "[(m1*l1 + m2*l1)*g*C1 + m2*l2*g*C12, m2*l2*g*C12]"), "l_for_lc")


def test_christoffel_indices_swapped():
    # c_kji for c_ijk: c_211 is asked, c_112 given
    assert_diagnosed(check("c_211", "m2*l1*lc2*S2"), "christoffel_indices")
    # C_kj = sum_i c_kji qdot_i
    swapped = f"[[-{H}*qdot2, {H}*qdot1], [{H}*qdot1, {H}*qdot1]]"
    assert_diagnosed(check("C", swapped), "christoffel_indices")


SPATIAL = """
name: pan-tilt arm
convention: standard
gravity: [0, 0, -g]
joints:
  - {type: R, theta: q1, d: 0, a: 0, alpha: pi/2, m: m1, r: [0, 0, 0], I: [Ix1, Iy1, I1]}
  - {type: R, theta: q2, d: 0, a: l2, alpha: 0, m: m2, r: [lc2 - l2, 0, 0], I: [Ix2, Iy2, I2]}
"""


def test_inertia_in_the_wrong_frame():
    # On a planar arm every link turns about z, and (R I R^T)_zz = I_zz: the mistake shows
    # only on a spatial arm. The student's M: omega in the base frame with the body-frame I.
    table = read_table_text(SPATIAL)
    robot = Robot(table)
    key = robot.dynamics().M
    dm = dynamic_model(robot)
    wrong = sp.Matrix(key)
    for i, L in enumerate(dm.links, start=1):
        _, Jw = link_jacobians(dm, i)  # omega in frame i
        Jw0 = robot.transform(0, i).matrix[:3, :3] * Jw  # omega in the base frame
        wrong += Jw0.T * L.I * Jw0 - Jw.T * L.I * Jw
    wrong = wrong.applyfunc(sp.expand)
    assert sp.expand(wrong - key) != sp.zeros(2, 2)
    answer = (
        "[[" + "], [".join(", ".join(str(wrong[r, c]) for c in range(2)) for r in range(2)) + "]]"
    )
    assert_diagnosed(check("M", answer, table), "inertia_frame")
    right = "[[" + "], [".join(", ".join(str(key[r, c]) for c in range(2)) for r in range(2)) + "]]"
    assert check("M", right, table).verdict.value == "correct"


def test_unknown_symbol_named():
    r = check("g", "[m1*g*lc1*C1 + k, 0]")
    assert r.verdict.value == "incorrect"
    assert "unknown_symbol" in r.kinds


def test_builtin_robot_with_textbook_symbols():
    r = check_answer(
        load_key("planar2r", "M[1,1]"), "Izz2 + m2*(a2**2 + 2*a2*rx2 + rx2**2 + ry2**2)"
    )
    assert r.verdict.value == "correct", r.message


def test_kinetic_mistakes_carry_into_c_and_tau():
    # C, c_ijk and tau are derived again from the mistaken M (not the key's symbols)
    assert_diagnosed(check("C", C_RIGHT.replace("lc2", "l2")), "l_for_lc")
    assert_diagnosed(check("c_121", "-m2*l1*l2*S2"), "l_for_lc")
    tau = (
        f"[({D11})*qddot1 + ({D12})*qddot2 + {H}*qdot2**2 + 2*{H}*qdot1*qdot2 + {G1},"
        f" ({D12})*qddot1 + ({D22})*qddot2 - {H}*qdot1**2 + {G2}]"
    )
    assert check("tau", tau).verdict.value == "correct"
    assert_diagnosed(
        check("tau", tau.replace(" + I1", "").replace(" + I2", "")), "rotational_energy"
    )
    flipped = (
        f"[({D11})*qddot1 + ({D12})*qddot2 + {H}*qdot2**2 + 2*{H}*qdot1*qdot2 - ({G1}),"
        f" ({D12})*qddot1 + ({D22})*qddot2 - {H}*qdot1**2 - ({G2})]"
    )
    assert_diagnosed(check("tau", flipped), "gravity_direction")
