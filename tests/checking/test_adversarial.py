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
from dhsym.errors import DHError

HOMEWORK = Path(__file__).resolve().parents[2] / "examples" / "homework"


def verdict(robot: str, question: str, answer: object) -> str:
    return check_answer(Key.load(robot, question), answer).verdict.value


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
    key = Key.load("planar2r", "T0_2")
    matrix = dhsym.Robot(key.table).transform(0, 2).matrix  # the key's own, a sympy matrix
    assert check_answer(key, matrix).verdict.value == "correct"
    assert check_answer(key, matrix.tolist()).verdict.value == "correct"


def test_a_key_of_the_wrong_type_is_refused_clearly():
    with pytest.raises(DHError, match="got int"):
        dhsym.check("C1", key=5, question="px")


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
    from dhsym.checking.gradebooks import Roster, write_lms_gradebook

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

    from dhsym.checking.grading import CACHE_NAME

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
    from dhsym.checking.grading import CACHE_NAME

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
    from dhsym.checking.gradebooks import Roster

    roster = Roster.from_text("submission,canvas_id\n-alice,17\n=bob,18\n")
    assert [e.submission for e in roster.entries] == ["-alice", "=bob"]
    with pytest.raises(DHError, match="formula"):
        Roster.from_text("submission,canvas_id\nalice,=17\n")
