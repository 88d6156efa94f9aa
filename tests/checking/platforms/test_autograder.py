"""The autograder zip: its layout, and run_autograder on the example class.

``run_autograder`` runs as the platform runs it (bash, a fresh interpreter) with the
source, submission and results folders moved to temporary folders; every
``results.json`` must validate against the schema written from the platform's
specification, and its scores must be those of ``dhsym grade``.
"""

from __future__ import annotations

import json
import os
import stat
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from dhsym.checking.grading.batch import grade
from dhsym.checking.grading.records import GradeRecord
from dhsym.checking.platforms.autograder import (
    RESULTS_SCHEMA,
    AutograderPaths,
    build_autograder,
    run_autograder,
)
from dhsym.errors import DHError

ROOT = Path(__file__).resolve().parents[3]
HW = ROOT / "examples" / "homework"
STUDENTS = sorted(p.name for p in (HW / "submissions").iterdir() if p.is_dir())


@pytest.fixture(scope="module")
def jsonschema():
    """jsonschema, imported by the worker that runs these tests, not by every worker at
    collection (its import builds the grammars of rfc3987-syntax: seconds)."""
    import jsonschema

    return jsonschema


@pytest.fixture(scope="module")
def autograder_zip(tmp_path_factory) -> Path:
    return build_autograder(HW / "assignment.yaml", tmp_path_factory.mktemp("ag") / "ag.zip")


@pytest.fixture(scope="module")
def source(autograder_zip, tmp_path_factory) -> Path:
    src = tmp_path_factory.mktemp("source")
    with zipfile.ZipFile(autograder_zip) as z:
        z.extractall(src)
    return src


@pytest.fixture(scope="module")
def class_scores(tmp_path_factory) -> dict[str, GradeRecord]:
    report = grade(
        HW / "assignment.yaml",
        HW / "submissions",
        tmp_path_factory.mktemp("grades"),
        workers=0,
        progress=False,
    )
    return {r.student: r for r in report.records}


def _run(source: Path, submission: Path, results: Path, **env: str) -> subprocess.CompletedProcess:
    environ = {
        **os.environ,
        "DHSYM_AUTOGRADER_SOURCE": str(source),
        "DHSYM_AUTOGRADER_SUBMISSION": str(submission),
        "DHSYM_AUTOGRADER_RESULTS": str(results),
        "DHSYM_AUTOGRADER_METADATA": str(results / "no-metadata.json"),
        "DHSYM_AUTOGRADER_PYTHON": sys.executable,
        **env,
    }
    return subprocess.run(
        ["bash", str(source / "run_autograder")],
        env=environ,
        capture_output=True,
        text=True,
        timeout=120,
        cwd=results,
    )


def test_zip_layout_follows_the_specification(autograder_zip):
    with zipfile.ZipFile(autograder_zip) as z:
        infos = {i.filename: i for i in z.infolist()}
        for script in ("setup.sh", "run_autograder"):
            assert script in infos  # at the root of the archive, not in a folder
            assert stat.S_IMODE(infos[script].external_attr >> 16) & 0o111
            assert z.read(script).startswith(b"#!/usr/bin/env bash\n")
        config = json.loads(z.read("dhsym-autograder.json"))
        assert config["visibility"] == "visible" and config["show_key"] is False
        wheels = [n for n in infos if n.startswith("dist/") and n.endswith(".whl")]
        assert len(wheels) == 1
        assert "assignment/keys/generic_modified_link.yaml" in infos
        with zipfile.ZipFile(z.open(wheels[0])) as whl:
            names = set(whl.namelist())
    assert "dhsym/templates/feedback_question.txt.j2" in names
    assert "dhsym/checking/platforms/autograder.py" in names


@pytest.mark.slow
@pytest.mark.parametrize("student", STUDENTS)
def test_run_autograder_matches_dhsym_grade(student, source, class_scores, tmp_path, jsonschema):
    proc = _run(source, HW / "submissions" / student, tmp_path)
    assert proc.returncode == 0, proc.stderr
    data = json.loads((tmp_path / "results.json").read_text(encoding="utf-8"))
    jsonschema.validate(data, RESULTS_SCHEMA)
    expected = class_scores[student]
    assert data["score"] == pytest.approx(expected.score)
    assert [t["name"].split(":")[0] for t in data["tests"]] == list(expected.scores)
    for t in data["tests"]:
        qid = t["name"].split(":")[0]
        assert t["score"] == pytest.approx(expected.scores[qid])
        assert 0 <= t["score"] <= t["max_score"]
        verdict = expected.verdicts[qid]
        assert t["output"].startswith(verdict.upper()), (qid, t["output"][:80])


def test_the_key_is_shown_only_when_asked(tmp_path, source):
    data = run_autograder(
        AutograderPaths(source, HW / "submissions" / "frank", tmp_path, tmp_path / "none")
    )
    q5 = next(t for t in data["tests"] if t["name"].startswith("q5"))
    assert "yours" in q5["output"] and "correct " not in q5["output"]
    config = json.loads((source / "dhsym-autograder.json").read_text())
    shown = tmp_path / "shown"
    (shown / "dhsym-autograder.json").parent.mkdir()
    for p in source.iterdir():
        if p.name != "dhsym-autograder.json":
            (shown / p.name).symlink_to(p)
    (shown / "dhsym-autograder.json").write_text(json.dumps({**config, "show_key": True}))
    data = run_autograder(
        AutograderPaths(shown, HW / "submissions" / "frank", tmp_path, tmp_path / "none")
    )
    q5 = next(t for t in data["tests"] if t["name"].startswith("q5"))
    assert "correct " in q5["output"]


def test_answers_file_metadata_and_hostile_text(tmp_path, source, jsonschema):
    sub = tmp_path / "submission" / "hw3"  # a zip of one folder
    sub.mkdir(parents=True)
    (sub / "answers.yaml").write_text(
        "answers:\n  q5: \"__import__('os').system('touch /tmp/x')\"\n"
        "  q3: 'C3 -S3 0 a3 \\\\ oops'\n",
        encoding="utf-8",
    )
    meta = tmp_path / "submission_metadata.json"
    meta.write_text(json.dumps({"users": [{"name": "<b>Eve</b>", "email": "eve@uni.edu"}]}))
    out = tmp_path / "results"
    data = run_autograder(AutograderPaths(source, tmp_path / "submission", out, meta))
    jsonschema.validate(json.loads((out / "results.json").read_text()), RESULTS_SCHEMA)
    by_q = {t["name"].split(":")[0]: t for t in data["tests"]}
    assert by_q["q5"]["output"].startswith("UNREADABLE") and by_q["q5"]["score"] == 0
    assert by_q["q1"]["output"].startswith("MISSING") and by_q["q1"]["tags"] == ["missing"]
    assert data["score"] == 0


def test_no_submission_folder_is_graded_zero(tmp_path, source, jsonschema):
    data = run_autograder(
        AutograderPaths(source, tmp_path / "absent", tmp_path, tmp_path / "none.json")
    )
    jsonschema.validate(data, RESULTS_SCHEMA)
    assert data["score"] == 0 and all(t["output"].startswith("UNREADABLE") for t in data["tests"])


def test_a_broken_autograder_still_writes_results(tmp_path, jsonschema):
    (tmp_path / "source").mkdir()
    (tmp_path / "source" / "dhsym-autograder.json").write_text('{"assignment": "gone.yaml"}')
    with pytest.raises(DHError):
        run_autograder(
            AutograderPaths(tmp_path / "source", tmp_path, tmp_path / "out", tmp_path / "m")
        )
    data = json.loads((tmp_path / "out" / "results.json").read_text())
    jsonschema.validate(data, RESULTS_SCHEMA)
    assert data["score"] == 0 and "could not grade" in data["output"]


def test_schema_rejects_what_the_specification_does_not_allow(jsonschema):
    ok = {"tests": [{"score": 1.0, "max_score": 2.0, "name": "q1", "visibility": "visible"}]}
    jsonschema.validate(ok, RESULTS_SCHEMA)
    for bad in (
        {"tests": [{"max_score": 2.0}]},  # no score anywhere
        {"score": 1, "visibility": "sometimes"},
        {"score": "1"},
        {"score": 1, "tests": [{"score": 1, "points": 1}]},  # not a documented field
    ):
        with pytest.raises(jsonschema.ValidationError):
            jsonschema.validate(bad, RESULTS_SCHEMA)


def test_wheel_in_the_zip_grades_without_the_source_tree(tmp_path, source, jsonschema):
    """Install only the zip's wheel (its dependencies are this environment's) and run."""
    site = tmp_path / "site"
    wheel = next((source / "dist").glob("dhsym-*.whl"))
    subprocess.run(
        [sys.executable, "-m", "pip", "install", "-q", "--no-deps", "--target", str(site), wheel],
        check=True,
        capture_output=True,
        timeout=300,
    )
    env = {"PYTHONPATH": str(site)}
    where = subprocess.run(
        [sys.executable, "-c", "import dhsym; print(dhsym.__file__)"],
        env={**os.environ, **env},
        capture_output=True,
        text=True,
        check=True,
        cwd=tmp_path,  # not the source tree
    ).stdout.strip()
    assert Path(where).is_relative_to(site)
    proc = _run(source, HW / "submissions" / "alice", tmp_path, **env)
    assert proc.returncode == 0, proc.stderr
    data = json.loads((tmp_path / "results.json").read_text())
    jsonschema.validate(data, RESULTS_SCHEMA)
    assert data["score"] == 10


def test_cli_builds_and_refuses(tmp_path, capsys):
    from dhsym.cli.main import main

    assert main(["autograder"]) == 2
    assert "ASSIGNMENT -o" in capsys.readouterr().err
    assert (
        main(
            [
                "autograder",
                str(HW / "assignment.yaml"),
                "-o",
                str(tmp_path / "a.zip"),
                "--visibility",
                "after_due_date",
                "--wheel",
                str(tmp_path / "none.whl"),
            ]
        )
        == 2
    )


def test_the_zip_refuses_an_assignment_with_variants(tmp_path):
    (tmp_path / "hw.secret").write_text("a-secret-of-the-autograder-test-0123\n")
    (tmp_path / "hw.yaml").write_text(
        "key: planar2r\nsecret: hw.secret\nvariants: {a1: [0.4, 0.5]}\n"
        "questions: [{id: q1, ask: T0_2}]\n"
    )
    with pytest.raises(DHError, match="dhsym grade --variants") as err:
        build_autograder(tmp_path / "hw.yaml", tmp_path / "ag.zip", wheel=tmp_path / "none.whl")
    assert err.value.field == "variants"
