"""The findings of a hostile grading campaign (issue 25), one test (or more) each.

Each test failed on the code before its fix: wrong answers graded right, right answers
graded wrong, grades lost in class runs, tracebacks instead of errors.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy as sp

import dhsym
from dhsym.checking import Key, check_answer
from dhsym.checking.reading.answers import answer_text
from dhsym.errors import DHError

from ._keys import KEYS, load_key  # each key prepared once, as a grading worker does

HOMEWORK = Path(__file__).resolve().parents[2] / "examples" / "homework"


def verdict(robot: str, question: str, answer: object) -> str:
    return check_answer(load_key(robot, question), answer, keys=KEYS).verdict.value


# --- 5: the notations of textbooks and numpy ------------------------------------------------


@pytest.mark.parametrize(
    "answer",
    [
        "cos(Atan2(S12, C12))",  # Craig
        "cos(arctan2(S12, C12))",  # numpy
        "cos(atan2(S12, C12))",
        r"\cos(\cos^{-1}(C12))",
        r"\cos\left(\operatorname{Atan2}(S_{12}, C_{12})\right)",
        "cos(cos^-1(C12))",
        "cos(arccos(C12))",
        "cos(acos(C12))",
        "tan(tan^-1(C12))",
        "sin(sin^-1 C12)",
    ],
)
def test_inverse_function_spellings_are_read(answer):
    assert verdict("planar2r", "T0_2[0,0]", answer) == "correct"


# --- 15, 16: errors, not tracebacks ---------------------------------------------------------


@pytest.mark.parametrize("address", ["garbage://x", "", "tcp://[::1", 5])
def test_dask_address_is_checked_before_anything_runs(address, tmp_path):
    from dhsym.checking import grade

    with pytest.raises(DHError, match="--dask"):
        grade(HOMEWORK / "assignment.yaml", tmp_path, tmp_path / "out", dask=address)


x = sp.Symbol("theta1", real=True)


@pytest.mark.parametrize(
    ("answer", "expected"),
    [
        (5, "incorrect"),
        (sp.cos(x), "incorrect"),
        (sp.Symbol("a1", positive=True) * sp.cos(x) + 0, "incorrect"),
        ([1, 2], "unreadable"),
        (np.float64(0.5), "incorrect"),
        ({1: 2}, "unreadable"),
        (True, "unreadable"),
        (object(), "unreadable"),
    ],
)
def test_check_takes_numbers_and_sympy_objects_or_refuses_clearly(answer, expected):
    result = dhsym.check(answer, key="planar2r", question="px").result
    assert result.verdict.value == expected
    if expected == "unreadable":
        assert "expected" in result.reason or "matrix" in result.reason


def test_check_reads_a_sympy_matrix_and_a_list_of_statements():
    a1, a2 = sp.symbols("a1 a2", positive=True)
    t2 = sp.Symbol("theta2", real=True)
    px = a1 * sp.cos(x) + a2 * sp.cos(x + t2)
    assert dhsym.check(px, key="planar2r", question="px").result.verdict.value == "correct"
    key = load_key("planar2r", "T0_2")
    matrix = dhsym.Robot(key.table).transform(0, 2).matrix  # the key's own, a sympy matrix
    assert check_answer(key, matrix, keys=KEYS).verdict.value == "correct"
    assert check_answer(key, matrix.tolist(), keys=KEYS).verdict.value == "correct"


def test_a_key_of_the_wrong_type_is_refused_clearly():
    with pytest.raises(DHError, match="got int"):
        dhsym.check("C1", key=5, question="px")
    with pytest.raises(DHError, match="expected a Key"):
        check_answer("planar2r", "C1")


# --- 9-14: grades never lost or corrupted in a class run -------------------------------------

PX = "a1*C1 + a2*C12"


def _assignment(tmp_path: Path) -> Path:
    path = tmp_path / "hw.yaml"
    path.write_text("title: HW\nkey: planar2r\nquestions:\n  - {id: q1, ask: px, points: 10}\n")
    return path


def _student(folder: Path, answer: str = PX) -> Path:
    folder.mkdir(parents=True)
    (folder / "q1.txt").write_text(answer, encoding="utf-8")
    return folder


def _grade(tmp_path: Path, subs: Path, out: Path | None = None):
    from dhsym.checking import grade

    return grade(_assignment(tmp_path), subs, out or tmp_path / "out", workers=0, progress=False)


def test_duplicate_ids_never_give_two_lms_rows(tmp_path):
    from dhsym.checking.platforms.gradebooks import Roster, write_lms_gradebook

    subs = tmp_path / "subs"
    _student(subs / "alice")
    (subs / "alice.yaml").write_text("answers: {q1: '0'}\n")
    report = _grade(tmp_path, subs)
    assert [r.score for r in report.records] == [0.0, 10.0]
    assert all(any("duplicate id" in f for f in r.flags) for r in report.records)
    roster = Roster.from_text("submission,canvas_id,email\nalice,17,alice@uni.edu\n")
    a = dhsym.checking.Assignment.load(tmp_path / "hw.yaml")
    for kind in ("canvas", "moodle", "generic"):
        with pytest.raises(DHError, match=r"more than one submission.*alice.*alice\.yaml"):
            write_lms_gradebook(kind, report, a, roster)
        assert not (report.out_dir / f"{kind}-import.csv").exists()


def test_nfc_and_nfd_spellings_are_one_student(tmp_path):
    subs = tmp_path / "subs"
    _student(subs / "jos\u00e9")  # NFC
    _student(subs / "jose\u0301", "0")  # NFD: looks the same
    report = _grade(tmp_path, subs)
    assert {r.student for r in report.records} == {"jos\u00e9"}
    assert all(any("duplicate id" in f for f in r.flags) for r in report.records)


@pytest.mark.parametrize(
    "change",
    [
        {"uid": "mallory"},  # a record filed under another key
        {"student": "mallory"},
        {"name": "Mallory"},
        {"scores": {"q1": 999.0}, "score": 999.0},
        {"scores": {"q1": 1e308}, "score": 1e308},
        {"score": 10.0},
    ],
    ids=["uid", "student", "name", "999", "1e308", "total"],
)
def test_a_tampered_cache_record_is_regraded_never_trusted(tmp_path, change):
    import json

    from dhsym.checking.grading.report_files import CACHE_NAME

    subs = tmp_path / "subs"
    _student(subs / "alice", "0")
    out = tmp_path / "out"
    _grade(tmp_path, subs, out)
    data = json.loads((out / CACHE_NAME).read_text(encoding="utf-8"))
    data["records"]["alice"].update(change)
    (out / CACHE_NAME).write_text(json.dumps(data), encoding="utf-8")
    report = _grade(tmp_path, subs, out)
    assert (report.graded, report.skipped) == (1, 0)
    assert [(r.student, r.name, r.score) for r in report.records] == [("alice", "alice", 0.0)]


def test_no_entry_of_the_submissions_folder_is_dropped_silently(tmp_path):
    from dhsym.checking.grading.report_files import CACHE_NAME

    subs = tmp_path / "subs"
    _student(subs / "alice")
    (_student(subs / "bob") / CACHE_NAME).write_text("{}")  # a file named like the cache
    _student(tmp_path / "carol")
    (subs / "carol").symlink_to(tmp_path / "carol")
    (subs / "notes.pdf").write_bytes(b"%PDF")
    report = _grade(tmp_path, subs)
    assert {r.student for r in report.records} == {"alice", "bob"}
    assert dict(report.refused) == {
        "carol": "a symbolic link (never followed: make it a real folder or file)",
        "notes.pdf": "not a submission (expected a student folder or a .yaml/.yml/.json file)",
    }
    assert any("carol" in w for w in report.warnings)
    summary = (report.out_dir / "summary.html").read_text(encoding="utf-8")
    assert "Not graded" in summary and "notes.pdf" in summary


def test_the_report_folder_is_never_the_submissions_folder(tmp_path):
    subs = tmp_path / "subs"
    _student(subs / "alice")
    with pytest.raises(DHError, match="report folder is the submissions folder"):
        _grade(tmp_path, subs, subs)
    assert not (subs / "feedback").exists()


def test_a_csv_saved_by_excel_is_read(tmp_path):
    for i, (text, sep) in enumerate(
        [(f"\ufeffstudent,q1\r\nalice,{PX}\r\n", ","), (f"\ufeffstudent;q1\r\nalice;{PX}\r\n", ";")]
    ):
        path = tmp_path / f"class{i}.csv"
        path.write_bytes(text.encode("utf-8"))
        report = _grade(tmp_path, path, tmp_path / f"out{i}")
        assert [(r.student, r.score) for r in report.records] == [("alice", 10.0)], sep
    bad = tmp_path / "latin1.csv"
    bad.write_bytes("student,q1\njos\u00e9,0\n".encode("latin-1"))
    with pytest.raises(DHError, match="not UTF-8"):
        _grade(tmp_path, bad, tmp_path / "out9")


def test_roster_columns_that_never_reach_the_lms_are_not_refused(tmp_path):
    from dhsym.checking.platforms.gradebooks import Roster

    roster = Roster.from_text("submission,canvas_id\n-alice,17\n=bob,18\n")
    assert [e.submission for e in roster.entries] == ["-alice", "=bob"]
    with pytest.raises(DHError, match="formula"):
        Roster.from_text("submission,canvas_id\nalice,=17\n")


# --- 17: the autograder -------------------------------------------------------------------


def test_autograder_names_every_answer_file_it_does_not_grade(tmp_path):
    from dhsym.checking.grading.assignment import Assignment
    from dhsym.checking.grading.batch import check_submission
    from dhsym.checking.platforms.autograder import read_submission, results_json

    hw = tmp_path / "hw.yaml"
    hw.write_text(
        "title: HW\nkey: planar2r\nquestions:\n  - {id: q1, ask: px, points: 1}\n"
        "  - {id: q2, ask: py, points: 1}\n"
    )
    sub = tmp_path / "sub"
    sub.mkdir()
    (sub / "q2.md").write_text("a1*S1 + a2*S12")
    (sub / "q2.txt").write_text("0")
    (sub / "answers.json").write_text('{"answers": {"q1": "0"}}')
    a = Assignment.load(hw)
    s = read_submission(sub, a, dhsym.checking.AnswerLimits())
    data = results_json(a, check_submission(a, s, dhsym.checking.AnswerLimits()), flags=s.flags)
    assert "not graded: q2.txt" in data["output"]
    assert "not graded: answers.json" in data["output"]


def test_autograder_python_never_imports_from_the_current_folder(tmp_path):
    import json
    import os
    import subprocess
    import sys

    from dhsym.checking.platforms.autograder import _RUN_AUTOGRADER, CONFIG_NAME

    source = tmp_path / "source"
    source.mkdir()
    (source / "hw.yaml").write_text(
        "title: HW\nkey: planar2r\nquestions:\n  - {id: q1, ask: px, points: 1}\n"
    )
    (source / CONFIG_NAME).write_text(json.dumps({"assignment": "hw.yaml"}))
    (source / "run_autograder").write_text(_RUN_AUTOGRADER)
    sub = tmp_path / "submission"
    sub.mkdir()
    (sub / "q1.txt").write_text(PX)
    canary = tmp_path / "shadowed"
    (sub / "sympy.py").write_text(f"open({str(canary)!r}, 'w').close()\nraise SystemExit(3)\n")
    results = tmp_path / "results"
    results.mkdir()
    env = {
        **os.environ,
        "DHSYM_AUTOGRADER_SOURCE": str(source),
        "DHSYM_AUTOGRADER_SUBMISSION": str(sub),
        "DHSYM_AUTOGRADER_RESULTS": str(results),
        "DHSYM_AUTOGRADER_METADATA": str(results / "none.json"),
        "DHSYM_AUTOGRADER_PYTHON": sys.executable,
    }
    proc = subprocess.run(
        ["bash", str(source / "run_autograder")],
        env=env,
        cwd=sub,  # the student's folder as the current folder
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert not canary.exists()
    assert proc.returncode == 0, proc.stderr
    assert json.loads((results / "results.json").read_text())["score"] == 1


# --- 18: YAML 1.2, duplicate keys, key tables validated, nothing of a foreign file echoed ------

ROW1 = "  - {type: R, theta: theta1, d: 0, a: a1, alpha: 0}\n"


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("alpha: 1:30", {"alpha": "1:30"}),  # YAML 1.1: 90
        ("a: yes", {"a": "yes"}),
        ("a: 012", {"a": 12}),
        ("a: 0o12", {"a": 10}),
        ("a: 2024-01-01", {"a": "2024-01-01"}),
        ("a: [1, 2.5, .inf, true, null]", {"a": [1, 2.5, float("inf"), True, None]}),
    ],
)
def test_yaml_is_read_with_yaml_12_semantics(text, expected):
    from dhsym.model.yamlsafe import load_yaml

    assert load_yaml(text) == expected


@pytest.mark.parametrize(
    "text", ["a: 1\na: 2\n", "joints:\n  - {type: R, theta: q1, d: 0, a: 1, alpha: 0, a: 3}\n"]
)
def test_a_key_given_twice_is_refused(text):
    from dhsym.model.yamlsafe import YAMLInputError, load_yaml

    with pytest.raises(YAMLInputError, match="given twice"):
        load_yaml(text)


def test_sexagesimal_and_duplicates_in_answers_are_never_read_silently():
    table = "joints:\n" + ROW1 + "  - {type: R, theta: theta2, d: 0, a: a2, alpha: 1:30}\n"
    assert verdict("planar2r", "table", table) == "unreadable"
    twice = "joints:\n" + ROW1 + "  - {type: R, theta: theta2, d: 0, a: a2, alpha: 0, a: 0}\n"
    assert verdict("planar2r", "table", twice) == "unreadable"


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        (ROW1 + "  - {type: F, theta: 0, d: 0, a: a2, alpha: 0, q: theta2}\n", "remove q"),
        (ROW1 + "  - {type: F, theta: theta1, d: 0, a: a2, alpha: 0}\n", "fixed row"),
        ("  - {type: R, theta: theta1, d: 0, a: a1, alpha: 0, limits: [a, b]}\n", "two numbers"),
        (ROW1 + "tool: [{Tz: theta1}]\n", "constant transform"),
        (ROW1 + "base: [{Rz: theta1}]\n", "constant transform"),
    ],
)
def test_key_table_fields_are_validated(text, fragment, tmp_path):
    path = tmp_path / "key.yaml"
    path.write_text(text if text.startswith(("joints", "tool")) else "joints:\n" + text)
    with pytest.raises(DHError, match=fragment):
        Key.load(path, "T0_1")


def test_a_file_that_is_not_a_table_is_never_echoed(tmp_path):
    path = tmp_path / "secrets.yaml"
    path.write_text("root_password: hunter2\nzz_api_token: s3cr3t\n")
    with pytest.raises(DHError) as err:
        Key.load(path, "T0_1")
    assert "not a DH table" in str(err.value)
    assert not any(w in str(err.value) for w in ("root_password", "hunter2", "zz_api", "s3cr3t"))


# --- 2, 3: tables compared symbolically, joint variables by position ----------------------

PUMA_ROWS = [
    "{type: R, theta: theta1, d: 0, a: 0, alpha: pi/2}",
    "{type: R, theta: theta2, d: 0, a: a2, alpha: 0}",
    "{type: R, theta: theta3, d: d3, a: a3, alpha: -pi/2}",
    "{type: R, theta: theta4, d: d4, a: 0, alpha: pi/2}",
    "{type: R, theta: theta5, d: 0, a: 0, alpha: -pi/2}",
    "{type: R, theta: theta6, d: 0, a: 0, alpha: 0}",
]


def _yaml_table(rows: list[str]) -> str:
    return "joints:\n" + "".join(f"  - {r}\n" for r in rows)


def test_symbols_with_equal_values_are_not_interchangeable():
    assert verdict("puma560", "table", _yaml_table(PUMA_ROWS)) == "correct"
    swapped = list(PUMA_ROWS)
    swapped[1] = swapped[1].replace("a: a2", "a: d4")
    swapped[3] = swapped[3].replace("d: d4", "d: a2")  # a2 = d4 = 0.4318 in the key
    assert verdict("puma560", "table", _yaml_table(swapped)) == "incorrect"


def test_joint_variables_are_matched_by_position():
    relabelled = _yaml_table(
        [
            "{type: R, theta: theta2, d: 0, a: a1, alpha: 0}",
            "{type: R, theta: theta1, d: 0, a: a2, alpha: 0}",
        ]
    )
    assert verdict("planar2r", "table", relabelled) == "incorrect"
    q_names = _yaml_table(
        [
            "{type: R, theta: q1, d: 0, a: a1, alpha: 0}",
            "{type: R, theta: q2, d: 0, a: a2, alpha: 0}",
        ]
    )
    assert verdict("planar2r", "table", q_names) == "correct"


# --- 1, 4: tolerances from the numbers that stand for the value ----------------------------

IK_T2 = (
    "c2 = (px^2 + py^2 - a1^2 - a2^2)/(2*a1*a2)\n"
    "theta2 = atan2(-sqrt(1 - c2^2), c2)\n"
    "theta1 = atan2(py, px) - atan2(a2*S2, a1 + a2*C2)"
)


@pytest.mark.parametrize("padding", ["", " + 0*100.0", " + 0*100.000", " + 0.0*12.345"])
def test_an_unrelated_decimal_never_widens_the_ik_tolerance(padding):
    assert verdict("planar2r", "ik", IK_T2) == "correct"
    assert verdict("planar2r", "ik", IK_T2 + " + 0.09" + padding) == "incorrect"


def test_an_ik_value_is_as_precise_as_it_is_written():
    assert verdict("planar2r", "ik@0.3,0.9", "0.300, 0.900") == "correct"
    assert verdict("planar2r", "ik@0.3,0.9", "0.38, 0.9") == "incorrect"
    assert verdict("planar2r", "ik@0.3,0.9", "380.0e-3, 0.9") == "incorrect"
    assert verdict("planar2r", "ik@0.3,0.9", "300.0e-3, 0.9") == "correct"


@pytest.mark.parametrize(
    "answer", ["a1 C1 + a2 C12 + 100.1 - 100.0", "a1 C1 + a2 C12 + 100.1 C1 - 100.0 C1"]
)
def test_cancelling_decimals_buy_no_rounding_slack(answer):
    assert verdict("planar2r", "T0_2[0,3]", answer) == "incorrect"
    matrix = f"[[C12, -S12, 0, {answer}], [S12, C12, 0, a1 S1 + a2 S12], [0,0,1,0], [0,0,0,1]]"
    assert verdict("planar2r", "T0_2", matrix) == "incorrect"


def test_rounded_decimals_that_stand_for_values_are_still_accepted():
    assert verdict("planar2r", "T0_2[0,0]", "cos(theta1 + theta2 + 6.2832)") == "correct"
    assert verdict("planar2r", "T0_2[0,3]", "a1 C1 + a2 C12 + 0.1 - 0.1") == "correct"


# --- 7, 8: cancellation in doubles, preparation off the clock, bounded proofs ---------------


def test_cancellation_in_doubles_does_not_decide():
    right = "(C1^2 + S1^2 - 1)*10^13 + C12"
    assert verdict("planar2r", "T0_2[0,0]", right) == "correct"
    assert verdict("planar2r", "T0_2[0,0]", right + " + 0.001") == "incorrect"
    assert verdict("planar2r", "T0_2[0,0]", "(C1^2 + S1^2 - 1)*10^13 + C12 + 10^-6") == "incorrect"


@pytest.mark.slow
def test_the_first_ik_check_of_a_process_is_not_charged_for_the_solver():
    import subprocess
    import sys

    code = (
        "import dhsym\n"
        "from dhsym.checking import Key, check_answer, AnswerLimits\n"
        "q = [0.3, -0.5, 0.4, 0.2, 0.7, -1.1]\n"
        "key = Key.load('puma560', 'ik@' + ','.join(map(str, q)))\n"
        "r = check_answer(key, ', '.join(map(str, q)), limits=AnswerLimits(seconds=1))\n"
        "print(r.verdict.value)\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=True
    )
    assert out.stdout.split() == ["correct"]


def test_a_proof_after_agreement_is_bounded_by_size_and_time():
    from dhsym.checking.comparing.equivalence import prove_entry
    from dhsym.checking.reading.limits import AnswerLimits, time_limit

    t1, t2 = sp.symbols("theta1 theta2", real=True)
    key = sp.cos(t1 + t2) ** 6
    answer = (sp.cos(t1) * sp.cos(t2) - sp.sin(t1) * sp.sin(t2)) ** 6
    assert prove_entry(answer, key) is True
    assert prove_entry(answer, key, AnswerLimits(proof_terms=5), agreed=True) is None
    with time_limit(0.5):  # less time left than a proof needs: the numbers decide
        assert prove_entry(answer, key, AnswerLimits(proof_seconds=1.0)) is None


def test_no_signal_timer_in_the_library():
    import re

    root = Path(dhsym.__file__).parent
    found = [
        f"{p.relative_to(root)}:{n}"
        for p in root.rglob("*.py")
        for n, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1)
        if re.search(r"signal\.(alarm|setitimer|SIGALRM)|ITIMER_", line)
    ]
    assert found == []


def test_a_time_limit_leaves_the_host_process_alone():
    import signal

    from dhsym.checking.reading.limits import CheckTimeout, check_time, time_limit

    before = signal.getsignal(signal.SIGALRM), signal.getitimer(signal.ITIMER_REAL)
    with time_limit(0.01):
        assert signal.getsignal(signal.SIGALRM) == before[0]
        assert signal.getitimer(signal.ITIMER_REAL) == before[1]
        import time

        time.sleep(0.02)
        with pytest.raises(CheckTimeout):
            check_time()
    check_time()  # no deadline outside the block


# --- 6: the Jacobian's row order, and diagnoses only when the mistake reproduces the answer --


def _text(matrix: sp.Matrix) -> str:
    return answer_text(matrix.tolist())


@pytest.mark.parametrize("robot", ["planar2r", "scara"])
def test_a_jacobian_in_omega_v_order_is_right_and_named(robot):
    key = load_key(robot, "J")
    J = KEYS.get(key).part.expected
    result = check_answer(key, _text(sp.Matrix.vstack(J[3:, :], J[:3, :])), keys=KEYS)
    assert result.verdict.value == "correct"
    assert "[ω; v]" in result.message and not result.diagnoses
    assert check_answer(key, _text(J), keys=KEYS).verdict.value == "correct"


@pytest.mark.parametrize("question", ["px", "T0_2[0,3]"])
def test_a_constant_answer_is_no_transposed_matrix(question):
    result = check_answer(load_key("planar2r", question), "0", keys=KEYS)
    assert result.verdict.value == "incorrect"
    assert "transposed" not in result.kinds


def test_a_circular_ik_answer_is_named_not_misdiagnosed():
    answer = IK_T2.replace("theta1 = atan2(py, px) - atan2(a2*S2, a1 + a2*C2)", "theta1 = theta1")
    result = check_answer(load_key("planar2r", "ik"), answer, keys=KEYS)
    assert result.verdict.value == "incorrect"
    assert result.kinds == ("circular",)


# --- the property: a random edit that changes the value is never graded right ---------------

from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

_QUESTIONS = [
    ("planar2r", "T0_2"),
    ("scara", "T0_4"),
    ("puma560", "T0_3"),
    ("stanford", "T0_3"),
    ("planar2r", "J"),
]


def _nodes(expr: sp.Expr, kind: type) -> list[sp.Expr]:
    return sorted(expr.atoms(kind), key=sp.default_sort_key)


@st.composite
def _edits(draw: st.DrawFn) -> tuple[Key, tuple[int, int], sp.Expr, sp.Expr]:
    robot, question = draw(st.sampled_from(_QUESTIONS))
    key = load_key(robot, question)
    expected = KEYS.get(key).part.expected
    i = draw(st.integers(0, expected.rows - 1))
    j = draw(st.integers(0, expected.cols - 1))
    entry = expected[i, j]
    how = draw(st.sampled_from(["add", "scale", "swap_function", "rename", "tiny"]))
    symbols = sorted(
        KEYS.get(key).part.symbols & set(expected.free_symbols), key=sp.default_sort_key
    )
    if how == "add":
        edited = entry + draw(st.sampled_from([sp.Rational(1, 3), -2, sp.Rational(1, 1000)]))
    elif how == "scale":
        edited = entry * draw(st.sampled_from([-1, 2, sp.Rational(1001, 1000)]))
    elif how == "tiny":
        edited = entry + sp.Rational(1, 10**7) * draw(st.sampled_from(symbols or [1]))
    elif how == "swap_function":
        funcs = _nodes(entry, sp.cos) + _nodes(entry, sp.sin)
        f = draw(st.sampled_from(funcs)) if funcs else None
        other = sp.sin if isinstance(f, sp.cos) else sp.cos
        edited = entry.xreplace({f: other(*f.args)}) if f is not None else entry + 1
    else:
        if len(symbols) >= 2:
            a, b = draw(st.permutations(symbols))[:2]
            edited = entry.xreplace({a: b})
        else:
            edited = entry - 1
    return key, (i, j), entry, edited


def _differs(a: sp.Expr, b: sp.Expr) -> bool:
    """True when ``a - b`` is not zero at some of a few random points (30 digits)."""
    import random

    rng = random.Random(7)
    syms = sorted((a - b).free_symbols, key=sp.default_sort_key)
    for _ in range(4):
        subs = {s: sp.Float(rng.uniform(0.3, 1.4), 30) for s in syms}
        if abs(complex((a - b).evalf(30, subs=subs))) > 1e-20:
            return True
    return False


@pytest.mark.slow
@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(_edits())
def test_a_random_edit_that_changes_the_value_is_never_graded_right(case):
    key, (i, j), entry, edited = case
    if not _differs(entry, edited):
        return  # the edit kept the value (cos of a zero angle, a symbol renamed to itself)
    matrix = sp.Matrix(KEYS.get(key).part.expected)
    matrix[i, j] = edited
    result = check_answer(key, answer_text(matrix.tolist()), keys=KEYS)
    assert result.verdict.value != "correct", (key.name, key.question.spec, (i, j), edited)


def test_the_sandbox_child_never_imports_from_the_current_folder(tmp_path, monkeypatch):
    from dhsym.checking.grading.sandbox import Sandbox

    canary = tmp_path / "shadowed"
    (tmp_path / "json.py").write_text(f"open({str(canary)!r}, 'w').close()\n")
    monkeypatch.chdir(tmp_path)
    with Sandbox(preload=("json",)) as box:
        assert box.call(abs, -3, deadline=60) == 3
    assert not canary.exists()
