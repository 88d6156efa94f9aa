"""Grading a class: gradebook, feedback, summary, rerun cache, pool, Dask, safety."""

from __future__ import annotations

import csv
import json
import os
import shutil
from pathlib import Path

import pytest

from dhsym.checking import Assignment, grade, read_submissions
from dhsym.checking.grading.report_files import CACHE_NAME, safe_name

HW = Path(__file__).resolve().parents[3] / "examples" / "homework"
EXPECTED = {
    "alice": 10,
    "bob": 10,
    "carol": 6,
    "dave": 2,
    "erin": 7,
    "frank": 7,
    "grace": 3,
    "heidi": 6,
    "ivan": 6,
    "mallory": 0,
}


def tree(root: Path) -> set[str]:
    return {str(p.relative_to(root)) for p in root.rglob("*")}


def test_example_class_in_process(tmp_path):
    before = tree(tmp_path)
    out = tmp_path / "report"
    report = grade(HW / "assignment.yaml", HW / "submissions", out, workers=0, progress=False)
    assert report.graded == 10 and report.failed == 0
    rows = list(csv.DictReader((out / "gradebook.csv").open(encoding="utf-8")))
    assert {r["student"]: float(r["total"]) for r in rows} == EXPECTED
    assert (out / "feedback" / "carol.md").read_text(encoding="utf-8").count("wrong sign") >= 1
    summary = (out / "summary.html").read_text(encoding="utf-8")
    assert "<script>alert" not in summary and "&lt;script&gt;alert" in summary
    assert (out / "summary.svg").read_text(encoding="utf-8").count("<rect") > 10
    assert not (out / "summary.png").exists()
    assert tree(tmp_path) - before <= {str(Path("report") / p) for p in tree(out)} | {"report"}
    # a rerun skips everything (and writes the same cache); a changed answer is graded again
    cached = (out / CACHE_NAME).read_bytes()
    again = grade(HW / "assignment.yaml", HW / "submissions", out, workers=0, progress=False)
    assert (again.graded, again.skipped) == (0, 10)
    assert (out / CACHE_NAME).read_bytes() == cached
    assert again.records == report.records
    subs = tmp_path / "subs"
    shutil.copytree(HW / "submissions", subs)
    (subs / "ivan" / "q5.txt").write_text("a2*C1*C2\n", encoding="utf-8")
    third = grade(HW / "assignment.yaml", subs, out, workers=0, progress=False)
    assert (third.graded, third.skipped) == (1, 9)
    cache = json.loads((out / CACHE_NAME).read_text(encoding="utf-8"))
    assert set(cache["records"]) == set(EXPECTED)


def test_process_pool_and_hostile_csv(tmp_path):
    out = tmp_path / "r"
    report = grade(HW / "assignment.yaml", HW / "class.csv", out, workers=2, progress=False)
    assert report.students == 3 and report.failed == 0
    names = sorted(p.name for p in (out / "feedback").iterdir())
    assert all(".." not in n and "/" not in n for n in names)
    assert any(n.startswith("etc_passwd-") for n in names)
    book = (out / "gradebook.csv").read_text(encoding="utf-8")
    assert "'=HYPERLINK" in book  # no spreadsheet formula injection
    assert not (tmp_path / "etc").exists()


def test_submission_reading_skips_links_and_limits_size(tmp_path):
    a = Assignment.load(HW / "assignment.yaml")
    s = tmp_path / "subs"
    (s / "eve").mkdir(parents=True)
    (s / "eve" / "q1.md").write_bytes(b"x" * 10_000_000)
    (s / "eve" / "q2.txt").symlink_to("/etc/passwd")
    (s / "eve" / "q5.txt").write_bytes(os.urandom(256))
    (s / "link").symlink_to(HW / "submissions" / "alice")
    (s / "zoe.yaml").write_text("name: Zoe\nanswers: {q5: a2*C1}\n", encoding="utf-8")
    subs = read_submissions(s, a)
    assert [x.student for x in subs] == ["eve", "zoe"]
    problems = dict(subs[0].problems)
    assert "10000000 bytes" in problems["q1"] and "not a regular file" in problems["q2"]
    report = grade(a, s, tmp_path / "out", workers=0, progress=False)
    verdicts = report.records[0].verdicts
    assert verdicts["q1"] == verdicts["q2"] == verdicts["q5"] == "unreadable"


def test_safe_names_are_unique_and_plain():
    used: set[str] = set()
    names = [safe_name(s, used) for s in ("a/b", "a_b", "a_b", "..", "CON", "ok")]
    assert len(set(names)) == 6 and names[-1] == "ok"
    assert all(n and n[0] not in "." and "/" not in n for n in names)


def test_bad_assignment_is_an_error(tmp_path):
    from dhsym.errors import DHError

    bad = tmp_path / "a.yaml"
    bad.write_text("key: puma560\nquestions: [{id: '../x', ask: table}]\n", encoding="utf-8")
    with pytest.raises(DHError, match="question id"):
        Assignment.load(bad)


@pytest.mark.slow
def test_dask_local_cluster(tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        report = grade(
            HW / "assignment.yaml",
            HW / "submissions",
            tmp_path / "d",
            dask=cluster.scheduler_address,
            progress=False,
        )
    rows = list(csv.DictReader((tmp_path / "d" / "gradebook.csv").open(encoding="utf-8")))
    assert report.graded == 10 and {r["student"]: float(r["total"]) for r in rows} == EXPECTED


# --- a batch that survives any class (issue 15) ------------------------------------------


def _class(tmp_path: Path) -> Path:
    subs = tmp_path / "subs"
    shutil.copytree(HW / "submissions", subs)
    return subs


def _book(out: Path) -> list[dict]:
    return list(csv.DictReader((out / "gradebook.csv").open(encoding="utf-8")))


def _totals(out: Path) -> dict[str, float]:
    return {r["student"]: float(r["total"]) for r in _book(out)}


def test_one_bad_file_never_stops_the_batch(tmp_path):
    subs = _class(tmp_path)
    (subs / "deep.yaml").write_text("answers: {q5: " + "[" * 5000 + "]" * 5000 + "}\n")
    (subs / "bigint.yaml").write_text("answers: {q5: " + "9" * 5000 + "}\n")
    odd = os.path.join(os.fsencode(subs), b"caf\xe9")  # unzipped from another OS: not UTF-8
    os.mkdir(odd)
    shutil.copy(HW / "submissions" / "alice" / "q5.txt", os.path.join(odd, b"q5.txt"))
    out = tmp_path / "out"
    report = grade(HW / "assignment.yaml", subs, out, workers=0, progress=False)
    totals = _totals(out)
    assert report.students == 13 and {k: totals[k] for k in EXPECTED} == EXPECTED
    assert totals["caf\\xe9"] == 1.0  # p_x right, graded like anyone else
    assert (out / "feedback" / "caf_xe9-{}.md".format(safe_name("caf\\xe9", set())[-8:])).is_file()
    deep = (out / "feedback" / "deep.md").read_text(encoding="utf-8")
    big = (out / "feedback" / "bigint.md").read_text(encoding="utf-8")
    assert "nested more than" in deep and "5000 digits" in big
    assert {r["student"]: r["status"] for r in _book(out)}["deep"] == "graded"


def test_every_submission_may_fail_and_the_gradebook_is_still_written(tmp_path, monkeypatch):
    from dhsym.checking.grading import batch as grading
    from dhsym.checking.grading import submissions as _submissions

    real = _submissions.read_submission_folder

    def unreadable_carol(folder, qids, limits):
        if folder.name == "carol":
            raise RuntimeError("disk on fire")
        return real(folder, qids, limits)

    monkeypatch.setattr(_submissions, "read_submission_folder", unreadable_carol)
    out = tmp_path / "out"
    grade(HW / "assignment.yaml", HW / "submissions", out, workers=0, progress=False)
    status = {r["student"]: r["status"] for r in _book(out)}
    assert status["carol"] == "error: could not be read (RuntimeError: disk on fire)"
    assert _totals(out)["bob"] == EXPECTED["bob"]

    def boom(job, keys=None):
        raise RuntimeError("checker crashed")

    monkeypatch.setattr(grading, "grade_submission", boom)
    out2 = tmp_path / "out2"
    report = grade(HW / "assignment.yaml", HW / "submissions", out2, workers=0, progress=False)
    assert report.failed == 10 and (out2 / "summary.html").is_file()
    assert {r["status"] for r in _book(out2)} == {
        "error: RuntimeError: checker crashed",
        "error: could not be read (RuntimeError: disk on fire)",
    }
    assert "error: RuntimeError: checker crashed" in (out2 / "feedback" / "bob.md").read_text()


def test_duplicate_ids_are_both_graded_and_flagged(tmp_path):
    subs = _class(tmp_path)
    (subs / "alice.yaml").write_text("name: Alice again\nanswers: {q5: '0'}\n")
    shutil.copytree(subs / "bob", subs / "BOB")  # the same file name on a case-blind disk
    out = tmp_path / "out"
    grade(HW / "assignment.yaml", subs, out, workers=0, progress=False)
    rows = _book(out)
    alices = [r for r in rows if r["student"] == "alice"]
    assert [(r["source"], float(r["total"])) for r in alices] == [("alice.yaml", 0), ("alice/", 10)]
    assert all("duplicate id" in r["flags"] for r in alices)
    assert len({r["feedback"] for r in rows}) == len(rows) == 12
    assert all("duplicate id" in r["flags"] for r in rows if r["student"].lower() == "bob")
    summary = (out / "summary.html").read_text(encoding="utf-8")
    assert summary.count("duplicate id") >= 4
    again = tmp_path / "again"
    grade(HW / "assignment.yaml", subs, again, workers=0, progress=False)
    assert (again / "gradebook.csv").read_text() == (out / "gradebook.csv").read_text()
    csv_class = tmp_path / "class.csv"
    csv_class.write_text("student,q5\nbob,x\nbob,d3*S1 + (a2*C2 + a3*C23 - d4*S23)*C1\n")
    grade(HW / "assignment.yaml", csv_class, tmp_path / "c", workers=0, progress=False)
    rows = _book(tmp_path / "c")
    assert [(r["source"], r["total"]) for r in rows] == [("row 2", "0"), ("row 3", "1")]
    assert all(r["flags"].startswith("duplicate id: 2 submissions") for r in rows)


def test_a_timeout_is_never_kept_and_every_limit_is_in_the_fingerprint(tmp_path):
    out = tmp_path / "out"
    first = grade(
        HW / "assignment.yaml", HW / "submissions", out, workers=0, progress=False, timeout=0.001
    )
    timed_out = [r for r in first.records if r.status == "timeout"]
    assert timed_out and all("timeout" in r.verdicts.values() for r in timed_out)
    cache = json.loads((out / CACHE_NAME).read_text(encoding="utf-8"))
    assert all(r["status"] == "graded" for r in cache["records"].values())
    assert "Checking took longer than the time limit of 0.001 s" in (
        out / "feedback" / f"{timed_out[0].student}.md"
    ).read_text(encoding="utf-8")
    second = grade(HW / "assignment.yaml", HW / "submissions", out, workers=0, progress=False)
    assert second.graded == 10 and _totals(out) == EXPECTED  # another limit: all graded again
    third = grade(HW / "assignment.yaml", HW / "submissions", out, workers=0, progress=False)
    assert (third.graded, third.skipped) == (0, 10)


@pytest.mark.parametrize("bad", [float("inf"), 1e300, -1, float("nan"), 0])
def test_time_limits_are_finite_positive_and_bounded(tmp_path, bad):
    from dhsym.errors import DHError

    with pytest.raises(DHError, match=r"--timeout: expected a time limit in seconds above 0"):
        grade(
            HW / "assignment.yaml",
            HW / "submissions",
            tmp_path / "o",
            timeout=bad,
            workers=0,
            progress=False,
        )
    assert not (tmp_path / "o").exists()


BAD_ASSIGNMENTS = [
    ("key: puma560\nquestions: [{id: q1, ask: table\n", "a.yaml: not valid YAML (line"),
    (
        "key: puma560\ntime_limit: .inf\nquestions: [{id: q1, ask: table}]\n",
        "a.yaml: field time_limit: expected a time limit in seconds above 0 and at most 3600, "
        "got inf",
    ),
    (
        "key: puma560\ntime_limit: abc\nquestions: [{id: q1, ask: table}]\n",
        "a.yaml: field time_limit: expected a time limit in seconds above 0 and at most 3600, "
        "got 'abc'",
    ),
    (
        "key: puma560\nquestions: [{id: q1, ask: table, points: [1]}]\n",
        "a.yaml: row 1, field points: expected a number of points from 0 to 1e+06, got [1]",
    ),
    (
        "key: puma560\nquestions: [{id: q1, ask: table, points: .nan}]\n",
        "a.yaml: row 1, field points: expected a number of points",
    ),
    (
        "key: puma560\nquestions: [{id: q1, ask: table, points: -2}]\n",
        "a.yaml: row 1, field points: expected a number of points",
    ),
    (
        "key: puma560\nquestions: [{id: q1, ask: 'T0_" + "9" * 5000 + "'}]\n",
        "a.yaml: row 1, field ask: unknown question",
    ),
    ("key: [puma560]\nquestions: [{id: q1, ask: table}]\n", "a.yaml: row 1, field key: no key"),
    (
        "x: &a [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]\n"
        + "".join(
            f"x{k}: &a{k} [" + ", ".join(["*a" if k == 0 else f"*a{k - 1}"] * 10) + "]\n"
            for k in range(6)
        )
        + "questions: []\n",
        "a.yaml: line 5: the YAML is too large",
    ),
]


@pytest.mark.parametrize(("text", "message"), BAD_ASSIGNMENTS, ids=range(len(BAD_ASSIGNMENTS)))
def test_assignment_errors_are_one_line_naming_file_and_field(tmp_path, capsys, text, message):
    from dhsym.cli.main import main

    a = tmp_path / "a.yaml"
    a.write_text(text)
    code = main(["grade", str(a), str(HW / "submissions"), "-o", str(tmp_path / "o"), "--quiet"])
    err = capsys.readouterr().err
    assert code == 2 and err.startswith("dhsym: error: ") and err.count("\n") == 1
    assert message in err


@pytest.mark.parametrize(
    "junk",
    ["[]", "{", '{"assignment": "x", "records": []}', "[" * 100_000, "\xff\xfe", "7"],
)
def test_a_corrupted_cache_is_ignored_with_a_warning(tmp_path, junk):
    out = tmp_path / "out"
    out.mkdir()
    (out / CACHE_NAME).write_text(junk, encoding="utf-8", errors="surrogateescape")
    report = grade(HW / "assignment.yaml", HW / "submissions", out, workers=0, progress=False)
    assert report.graded == 10 and _totals(out) == EXPECTED
    assert any("ignoring the grading cache" in w for w in report.warnings)


def test_a_cache_with_malformed_records_regrades_them(tmp_path):
    out = tmp_path / "out"
    grade(HW / "assignment.yaml", HW / "submissions", out, workers=0, progress=False)
    data = json.loads((out / CACHE_NAME).read_text(encoding="utf-8"))
    data["records"]["bob"]["scores"] = "all of them"
    data["records"]["carol"]["score"] = 1e999
    data["records"]["dave"]["wrong"] = {"q1": 5}
    del data["records"]["erin"]["verdicts"]
    (out / CACHE_NAME).write_text(json.dumps(data), encoding="utf-8")
    report = grade(HW / "assignment.yaml", HW / "submissions", out, workers=0, progress=False)
    assert (report.graded, report.skipped) == (4, 6) and _totals(out) == EXPECTED
    assert report.warnings == (
        "ignoring 4 malformed record(s) of the grading cache .dhsym-grading-cache.json",
    )


def test_the_report_folder_inside_the_submissions_is_no_student(tmp_path):
    subs = _class(tmp_path)
    out = subs / "feedback-report"
    grade(HW / "assignment.yaml", subs, out, workers=0, progress=False)
    report = grade(HW / "assignment.yaml", subs, out, workers=0, progress=False)
    assert set(_totals(out)) == set(EXPECTED) and report.skipped == 10
    assert report.warnings == ("not graded: feedback-report/: the report folder of this run",)
    assert report.refused == (("feedback-report/", "the report folder of this run"),)


def test_several_answer_files_for_one_question_follow_the_documented_rule(tmp_path):
    subs = _class(tmp_path)
    (subs / "alice" / "q5.md").write_text("0\n")  # q5.md comes before q5.txt: it is graded
    out = tmp_path / "out"
    grade(HW / "assignment.yaml", subs, out, workers=0, progress=False)
    alice = next(r for r in _book(out) if r["student"] == "alice")
    assert float(alice["total"]) == 9.0
    assert alice["flags"].startswith("q5: graded q5.md; not graded: q5.txt")
    page = (out / "feedback" / "alice.md").read_text(encoding="utf-8")
    assert "q5: graded q5.md; not graded: q5.txt" in page


def test_hard_links_and_special_files_are_refused_like_symbolic_links(tmp_path):
    subs = _class(tmp_path)
    secret = tmp_path / "secret.txt"
    secret.write_text("TOPSECRET-4711 | theta | d | a | alpha |\n")
    (subs / "bob" / "q1.md").unlink()
    os.link(secret, subs / "bob" / "q1.md")
    (subs / "bob" / "q2.txt").unlink()
    os.mkfifo(subs / "bob" / "q2.txt")
    out = tmp_path / "out"
    grade(HW / "assignment.yaml", subs, out, workers=0, progress=False)
    page = (out / "feedback" / "bob.md").read_text(encoding="utf-8")
    assert "TOPSECRET" not in page and "hard links" in page and "not a regular file" in page
    assert _totals(out)["bob"] == EXPECTED["bob"] - 4 - 2


def test_a_dhsym_bug_while_checking_is_an_internal_error_of_that_submission(tmp_path, monkeypatch):
    from dhsym.checking.judging import checker

    real = checker.check_matrix

    def buggy(pk, answer, limits):
        if "d4*s23" in str(answer):  # some answers reach a (simulated) bug of dhsym
            raise TypeError("simulated bug")
        return real(pk, answer, limits)

    monkeypatch.setattr(checker, "check_matrix", buggy)
    out = tmp_path / "out"
    report = grade(HW / "assignment.yaml", HW / "submissions", out, workers=0, progress=False)
    status = {r["student"]: r["status"] for r in _book(out)}
    hit = {s for s, v in status.items() if v.startswith("error: ")}
    assert hit and all("TypeError: simulated bug" in status[s] for s in hit)
    assert report.failed == len(hit) and (out / "summary.html").is_file()
    for student in set(status) - hit:
        assert _totals(out)[student] == EXPECTED.get(student, _totals(out)[student])


@pytest.mark.parametrize(
    "names",
    [
        ("jos\u00e9".encode(), "jose\u0301".encode()),  # NFC and NFD: the same on screen
        (b"eve\xff", b"eve\\xff"),  # a byte that is not UTF-8, and its escape typed out
    ],
)
def test_colliding_ids_are_every_student_exactly_once(tmp_path, names):
    """Issue 34, item 6: both graded, each under its own id and feedback page."""
    subs = tmp_path / "subs"
    subs.mkdir()
    right, wrong = (os.path.join(os.fsencode(subs), n) for n in names)
    shutil.copytree(HW / "submissions" / "alice", os.fsdecode(right))
    os.mkdir(wrong)
    Path(os.fsdecode(wrong), "q5.txt").write_text("0\n")
    out = tmp_path / "out"
    report = grade(HW / "assignment.yaml", subs, out, workers=0, progress=False)
    assert len({r.uid for r in report.records}) == 2
    rows = _book(out)
    assert len(rows) == 2 and len({r["feedback"] for r in rows}) == 2
    assert sorted(float(r["total"]) for r in rows) == [0.0, 10.0]
    for r in rows:
        page = (out / r["feedback"]).read_text(encoding="utf-8")
        assert f"{float(r['total']):g}" in page
        assert "duplicate id" in r["flags"]
    summary = (out / "summary.html").read_text(encoding="utf-8")
    assert summary.count("duplicate id") >= 2
    again = tmp_path / "again"
    grade(HW / "assignment.yaml", subs, again, workers=0, progress=False)
    assert (again / "gradebook.csv").read_text() == (out / "gradebook.csv").read_text()
