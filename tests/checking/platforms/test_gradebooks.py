"""LMS import files: the documented headers, rosters, unmatched students, hostile names."""

from __future__ import annotations

import csv
import re
from pathlib import Path

import pytest

from dhsym.checking import Assignment, grade
from dhsym.checking.platforms.gradebooks import CANVAS_HEADER, Roster, write_lms_gradebook
from dhsym.cli.main import main
from dhsym.errors import DHError

ROOT = Path(__file__).resolve().parents[3]
HW = ROOT / "examples" / "homework"
FORMULA = ("=", "+", "-", "@", "\t", "\r")

# The example CSV class: s001 (all right), "../../etc/passwd" (a hostile id and the name
# =HYPERLINK(...)), s003 (the name </td><script>…).
ROSTER = (
    "submission,name,canvas_id,sis_user_id,sis_login_id,section,email,username,idnumber\n"
    's001,"Lovelace, Ada",101,SIS-1,ada,Sec A,ada@uni.edu,ada,N001\n'
    '../../etc/passwd,"=HYPERLINK(""http://evil.example"",""click"")",102,SIS-2,mal,@Sec B,'
    "mal@uni.edu,mal,N002\n"
    "s003,</td><script>alert(1)</script>,103,SIS-3,s3,Sec A,s3@uni.edu,s3,N003\n"
    "s999,Absent Student,104,SIS-4,abs,Sec A,abs@uni.edu,abs,N004\n"
)


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    a = Assignment.load(HW / "assignment.yaml")
    out = tmp_path_factory.mktemp("report")
    return a, grade(a, HW / "class.csv", out, workers=0, progress=False)


def _rows(path: Path) -> list[list[str]]:
    with path.open(newline="", encoding="utf-8") as fh:
        return list(csv.reader(fh))


def _safe(cell: str) -> bool:
    return not cell.startswith(FORMULA)


def test_canvas_import_has_canvas_headers_and_points_possible(graded):
    a, report = graded
    out = write_lms_gradebook(
        "canvas", report, a, Roster.from_text(ROSTER, "roster.csv"), column="HW 3 (4242)"
    )
    rows = _rows(out.path)
    # Canvas's GradebookImporter: Student, ID, then SIS User ID, SIS Login ID, and Section
    # as the last student column; the assignment columns follow as "Name (id)".
    assert rows[0] == [*CANVAS_HEADER, "HW 3 (4242)"]
    assert re.search(r"Student", rows[0][0]) and re.search(r"ID", rows[0][1])
    assert re.match(r"\A(.*)\s\((\d+)\)\Z", rows[0][5])
    assert rows[1][0] == "Points Possible" and float(rows[1][5]) == a.max_score
    body = {r[1]: r for r in rows[2:]}
    assert set(body) == {"101", "102", "103"}  # the absent roster student is left out
    assert float(body["101"][5]) == a.max_score  # s001 answers everything right
    assert all(_safe(c) for r in rows for c in r)
    assert body["102"][0].startswith("'=HYPERLINK") and body["102"][4] == "'@Sec B"
    assert any("s999" in n for n in out.notes)


def test_moodle_import_has_identifier_columns_and_numeric_grades(graded):
    a, report = graded
    out = write_lms_gradebook("moodle", report, a, Roster.from_text(ROSTER, "roster.csv"))
    rows = _rows(out.path)
    assert rows[0] == ["ID number", "Email address", "Username", "Full name", a.title]
    for r in rows[1:]:
        float(r[4])  # Moodle refuses a grade that is not a number
        assert all(_safe(c) for c in r)
    assert {r[1] for r in rows[1:]} == {"ada@uni.edu", "mal@uni.edu", "s3@uni.edu"}
    assert any("Map" in n for n in out.notes)


def test_moodle_writes_only_identifiers_every_student_has(graded):
    a, report = graded
    partial = ROSTER.replace("s3@uni.edu", "").replace(",N003", ",")
    rows = _rows(write_lms_gradebook("moodle", report, a, Roster.from_text(partial)).path)
    assert rows[0][:2] == ["Username", "Full name"]
    only_email = "submission,email\ns001,a@u\n../../etc/passwd,b@u\ns003,\n"
    with pytest.raises(DHError, match="s003"):
        write_lms_gradebook("moodle", report, a, Roster.from_text(only_email, "r.csv"))


def test_generic_import_without_roster(graded):
    a, report = graded
    rows = _rows(write_lms_gradebook("generic", report, a).path)
    assert rows[0] == ["student", "name", "email", "lms_id", "q1", "q2", "q3", "q4", "q5"] + [
        "total",
        "max",
        "status",
    ]
    assert all(_safe(c) for r in rows for c in r)
    assert any(r[1].startswith("'=HYPERLINK") for r in rows)


def test_unmatched_students_are_named(graded):
    a, report = graded
    roster = Roster.from_text("submission,canvas_id\ns001,1\n", "roster.csv")
    with pytest.raises(DHError, match=r"roster.csv: 2 graded submission.*etc/passwd.*s003"):
        write_lms_gradebook("canvas", report, a, roster)
    no_ids = Roster.from_text("submission,name\ns001,A\n../../etc/passwd,B\ns003,C\n", "r.csv")
    with pytest.raises(DHError, match="Canvas needs canvas_id or sis_user_id or sis_login_id"):
        write_lms_gradebook("canvas", report, a, no_ids)
    with pytest.raises(DHError, match="needs a roster"):
        write_lms_gradebook("canvas", report, a)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("name,email\nA,a@u\n", "needs a 'submission' column"),
        ("submission,canvas_id\na,=1+1\n", r"r.csv: row 2, field canvas_id: .*formula"),
        ("submission,email\na,x@u\nb,x@u\n", r"row 3, field email: 'x@u' is already"),
        ("submission,email\na,x@u\na,y@u\n", r"row 3, field submission"),
        ("submission,name\n ,Bob\n", "row 2, field submission: empty"),
        ("", "empty"),
    ],
)
def test_roster_errors_name_file_row_and_field(text, message):
    with pytest.raises(DHError, match=message):
        Roster.from_text(text, "r.csv")


def test_roster_reads_canvas_export_headers_and_bom(tmp_path):
    p = tmp_path / "roster.csv"
    p.write_bytes(
        "\ufeffStudent,ID,SIS User ID,SIS Login ID,Section,Submission\n"
        '"Chen, Carol",7,S7,carol,A,carol\n'.encode()
    )
    e = Roster.load(p).entries[0]
    assert (e.submission, e.name, e.canvas_id, e.sis_login_id) == (
        "carol",
        "Chen, Carol",
        "7",
        "carol",
    )


def test_cli_grade_writes_the_canvas_import(tmp_path, capsys):
    roster = tmp_path / "roster.csv"
    roster.write_text(ROSTER, encoding="utf-8")
    args = [str(HW / "assignment.yaml"), str(HW / "class.csv"), "-o", str(tmp_path / "r")]
    assert (
        main(
            [
                "grade",
                *args,
                "--workers",
                "0",
                "--quiet",
                "--gradebook",
                "canvas",
                "--roster",
                str(roster),
            ]
        )
        == 0
    )
    assert (tmp_path / "r" / "canvas-import.csv").is_file()
    assert "canvas import:" in capsys.readouterr().out
    assert main(["grade", *args, "--gradebook", "moodle"]) == 2
    assert "--roster" in capsys.readouterr().err
