r"""An autograder for Gradescope-style platforms: a zip that grades one submission.

Specification followed: Gradescope's *Autograder Specifications*
(https://gradescope-autograders.readthedocs.io/en/latest/specs/, source
``gradescope/autograder_samples: docs/specs.md``).  The zip holds ``setup.sh`` (a Bash
script run once, as root, when the grading image is built) and ``run_autograder``
(an executable run for each submission, working directory ``/autograder``) at its
root; the platform unpacks the zip to ``/autograder/source``, puts the student's
files in ``/autograder/submission`` and reads ``/autograder/results/results.json``::

    {"score": 7.0, "output": "…", "visibility": "visible", "stdout_visibility": "hidden",
     "execution_time": 3, "extra_data": {…},
     "tests": [{"name": "q1: the DH table", "number": "1", "score": 4.0, "max_score": 4.0,
                "output": "CORRECT (4 / 4 points). …", "tags": [], "visibility": "visible"},
               …]}

The zip built by :func:`build_autograder` (``dhsym autograder ASSIGNMENT -o ZIP``)::

    setup.sh                 python3 venv in /autograder/dhsym-venv, pip install the wheel
    run_autograder           exec $PYTHON -m dhsym autograder --run
    dhsym-autograder.json    the assignment file, visibility, whether the key is shown
    assignment/assignment.yaml, assignment/keys/*.yaml   the assignment and its key files
    dist/dhsym-<version>-py3-none-any.whl

A submission is what :mod:`dhsym.checking.grading.batch` reads for one student: files
``q1.md``, ``q2.txt`` … (one per question id), or one YAML/JSON file with
``answers: {q1: …}``; a single top-level folder is looked into.  Scores are those of
``dhsym grade`` (the same :func:`~dhsym.checking.grading.batch.check_submission`); each
question is one test whose ``output`` is its plain-text feedback.

Every path can be moved with an environment variable, so ``run_autograder`` runs
anywhere (the tests run it on the example class with temporary folders):
``DHSYM_AUTOGRADER_ROOT`` (``/autograder``), ``DHSYM_AUTOGRADER_SOURCE``,
``DHSYM_AUTOGRADER_SUBMISSION``, ``DHSYM_AUTOGRADER_RESULTS`` (``ROOT/source``,
``ROOT/submission``, ``ROOT/results``), ``DHSYM_AUTOGRADER_PYTHON`` (the interpreter
``run_autograder`` uses; default the venv ``setup.sh`` made).

Examples
--------
>>> p = AutograderPaths.from_env({"DHSYM_AUTOGRADER_ROOT": "/tmp/ag",
...                               "DHSYM_AUTOGRADER_RESULTS": "/tmp/out"})
>>> str(p.submission), str(p.results)
('/tmp/ag/submission', '/tmp/out')
"""

from __future__ import annotations

import io
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import zipfile
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from dhsym.errors import DHError

from ..grading.assignment import Assignment
from ..grading.batch import check_submission
from ..grading.feedback import QuestionFeedback, render_question_text
from ..grading.report_files import write_atomic
from ..grading.submissions import Submission, read_submission_file, read_submission_folder
from ..judging.key import PreparedKeys
from ..reading.limits import AnswerLimits

__all__ = [
    "CONFIG_NAME",
    "RESULTS_SCHEMA",
    "VISIBILITIES",
    "AutograderPaths",
    "build_autograder",
    "build_wheel",
    "read_submission",
    "results_json",
    "run_autograder",
]

CONFIG_NAME = "dhsym-autograder.json"
#: The visibility settings of the specification ("Controlling Test Case Visibility").
VISIBILITIES = ("hidden", "after_due_date", "after_published", "visible")
_EXEC = 0o100755 << 16  # zip external attributes of an executable regular file
_FILE = 0o100644 << 16
_ZIP_TIME = (1980, 1, 1, 0, 0, 0)  # fixed timestamps: the same inputs give the same zip

_number = {"type": "number"}
_visibility = {"enum": list(VISIBILITIES)}
#: JSON Schema of ``results.json``, written from the specification's "Output format":
#: every field it lists, with its type; nothing else is allowed, so a result that
#: validates uses only documented fields.  A top-level ``score`` or a ``score`` on
#: every test is required ("optional, but required if not on each test case").
RESULTS_SCHEMA: dict[str, Any] = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "title": "Gradescope autograder results.json",
    "type": "object",
    "additionalProperties": False,
    "properties": {
        "score": _number,
        "execution_time": {"type": "number", "minimum": 0},
        "output": {"type": "string"},
        "visibility": _visibility,
        "stdout_visibility": _visibility,
        "extra_data": {"type": "object"},
        "tests": {
            "type": "array",
            "items": {
                "type": "object",
                "additionalProperties": False,
                "properties": {
                    "score": _number,
                    "max_score": {"type": "number", "minimum": 0},
                    "name": {"type": "string"},
                    "number": {"type": "string"},
                    "output": {"type": "string"},
                    "tags": {"type": "array", "items": {"type": "string"}},
                    "visibility": _visibility,
                    "extra_data": {"type": "object"},
                },
            },
        },
        "leaderboard": {
            "type": "array",
            "items": {
                "type": "object",
                "required": ["name", "value"],
                "properties": {
                    "name": {"type": "string"},
                    "value": {"type": ["number", "string"]},
                    "order": {"enum": ["asc", "desc"]},
                },
            },
        },
    },
    "anyOf": [
        {"required": ["score"]},
        {
            "required": ["tests"],
            "properties": {"tests": {"items": {"required": ["score"]}}},
        },
    ],
}


@dataclass(frozen=True)
class AutograderPaths:
    """Where the autograder reads and writes (the platform's layout, or overrides)."""

    source: Path
    submission: Path
    results: Path
    metadata: Path

    @classmethod
    def from_env(cls, env: Mapping[str, str] | None = None) -> AutograderPaths:
        """The layout of the specification, each folder movable by its variable."""
        env = os.environ if env is None else env
        root = Path(env.get("DHSYM_AUTOGRADER_ROOT", "/autograder"))

        def get(name: str, default: Path) -> Path:
            return Path(env.get(f"DHSYM_AUTOGRADER_{name}", str(default)))

        return cls(
            get("SOURCE", root / "source"),
            get("SUBMISSION", root / "submission"),
            get("RESULTS", root / "results"),
            get("METADATA", root / "submission_metadata.json"),
        )


# --- building the zip -------------------------------------------------------------


def _bundle_assignment(path: Path) -> tuple[str, dict[str, bytes]]:
    """The assignment as YAML whose key files are ``keys/<name>``, and those files.

    Key references are resolved as :meth:`Assignment.load` does (relative to the file);
    built-in robot names stay names.
    """
    text = path.read_text(encoding="utf-8")
    data = yaml.safe_load(text)
    if not isinstance(data, dict) or not isinstance(data.get("questions"), list):
        raise DHError("expected 'questions: [...]' (and 'key:') in the assignment", file=str(path))
    files: dict[str, bytes] = {}
    arcs: dict[Path, str] = {}

    def bundle(ref: object) -> object:
        if ref is None:
            return None
        local = path.parent / str(ref)
        if not (local.suffix.lower() in (".yaml", ".yml") or local.exists()):
            return ref  # a built-in robot
        local = local.resolve()
        if local not in arcs:
            if not local.is_file():
                raise DHError(f"key file not found: {local}", file=str(path))
            name, k = f"keys/{local.name}", 1
            while name in files:
                k += 1
                name = f"keys/{local.stem}-{k}{local.suffix}"
            files[name] = local.read_bytes()
            arcs[local] = name
        return arcs[local]

    data["key"] = bundle(data.get("key"))
    if data["key"] is None:
        del data["key"]
    for q in data["questions"]:
        if isinstance(q, dict) and "key" in q:
            q["key"] = bundle(q["key"])
    return yaml.safe_dump(data, sort_keys=False, allow_unicode=True), files


def _source_root() -> Path:
    """The source tree this dhsym runs from (the folder with ``pyproject.toml``)."""
    import dhsym

    root = Path(dhsym.__file__).resolve().parent.parent
    if not (root / "pyproject.toml").is_file():
        raise DHError(
            f"dhsym is not running from a source tree ({root} has no pyproject.toml): "
            "give a wheel (dhsym autograder --wheel dhsym-….whl)"
        )
    return root


def build_wheel(out_dir: str | Path) -> Path:
    """Build dhsym's wheel (templates included as ``dhsym/templates``) into ``out_dir``.

    Runs ``pip wheel`` on a clean copy of the source tree (pyproject maps the top-level
    ``templates/`` onto the package data ``dhsym/templates``); needs the build backend
    from the package index.
    """
    root, out = _source_root(), Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    skip = shutil.ignore_patterns("__pycache__", "*.pyc", "*.egg-info")
    with tempfile.TemporaryDirectory(prefix="dhsym-wheel-") as tmp:
        tree = Path(tmp) / "src"
        tree.mkdir()
        for name in ("pyproject.toml", "README.md", "LICENSE"):
            if (root / name).is_file():
                shutil.copy2(root / name, tree / name)
        shutil.copytree(root / "dhsym", tree / "dhsym", ignore=skip)
        shutil.copytree(root / "templates", tree / "templates", ignore=skip)
        # the example homework, package data dhsym.examples (dhsym new-assignment)
        shutil.copytree(root / "examples" / "homework", tree / "examples" / "homework", ignore=skip)
        proc = subprocess.run(
            [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", tmp, str(tree)],
            capture_output=True,
            text=True,
            timeout=900,
        )
        wheels = sorted(Path(tmp).glob("dhsym-*.whl"))
        if proc.returncode != 0 or not wheels:
            raise DHError(f"building dhsym's wheel failed: {proc.stderr.strip()[-2000:]}")
        target = out / wheels[0].name
        shutil.copy2(wheels[0], target)
    return target


def _check_wheel(wheel: Path) -> None:
    try:
        with zipfile.ZipFile(wheel) as z:
            names = set(z.namelist())
    except (OSError, zipfile.BadZipFile) as err:
        raise DHError(f"not a wheel: {err}", file=str(wheel)) from None
    need = ("dhsym/checking/platforms/autograder.py", "dhsym/templates/feedback_question.txt.j2")
    missing = [n for n in need if n not in names]
    if missing:
        raise DHError(f"the wheel lacks {', '.join(missing)}", file=str(wheel))


_SETUP_SH = """#!/usr/bin/env bash
# dhsym autograder: run once, as root, when the grading image is built (setup.sh of the
# Gradescope autograder specification). Installs dhsym from the wheel in this zip.
set -euo pipefail
SOURCE="${DHSYM_AUTOGRADER_SOURCE:-${DHSYM_AUTOGRADER_ROOT:-/autograder}/source}"
VENV="${DHSYM_AUTOGRADER_VENV:-${DHSYM_AUTOGRADER_ROOT:-/autograder}/dhsym-venv}"
if ! python3 -m venv --help >/dev/null 2>&1 && command -v apt-get >/dev/null 2>&1; then
  apt-get update -q && apt-get install -y -q --no-install-recommends python3 python3-venv
fi
python3 -m venv "$VENV"
"$VENV/bin/python" -m pip install --quiet --upgrade pip
"$VENV/bin/python" -m pip install --quiet "$SOURCE"/dist/dhsym-*.whl
"$VENV/bin/python" -c "import dhsym.checking.platforms.autograder"
"""

_RUN_AUTOGRADER = """#!/usr/bin/env bash
# dhsym autograder: grades /autograder/submission into /autograder/results/results.json.
# Every folder can be moved with DHSYM_AUTOGRADER_ROOT, _SOURCE, _SUBMISSION, _RESULTS.
set -uo pipefail
ROOT="${DHSYM_AUTOGRADER_ROOT:-/autograder}"
PYTHON="${DHSYM_AUTOGRADER_PYTHON:-$ROOT/dhsym-venv/bin/python}"
# sys.path without the current folder (as python -P): a submission's sympy.py never shadows
exec "$PYTHON" -c 'import sys; sys.path[:] = [p for p in sys.path if p]; import runpy
runpy.run_module("dhsym", run_name="__main__", alter_sys=True)' autograder --run
"""


def _zip_add(z: zipfile.ZipFile, name: str, data: bytes, mode: int = _FILE) -> None:
    info = zipfile.ZipInfo(name, _ZIP_TIME)
    info.external_attr = mode
    info.compress_type = zipfile.ZIP_DEFLATED
    z.writestr(info, data)


def build_autograder(
    assignment: str | Path,
    output: str | Path,
    *,
    wheel: str | Path | None = None,
    visibility: str = "visible",
    show_key: bool = False,
) -> Path:
    """Write the autograder zip for ``assignment`` (see the module docstring).

    ``wheel`` is a dhsym wheel to include (default: built from this source tree);
    ``visibility`` is every test's visibility; ``show_key`` puts the key's entries
    in the feedback (off by default: students can resubmit after reading it).
    """
    if visibility not in VISIBILITIES:
        raise DHError(f"visibility {visibility!r}: expected one of {', '.join(VISIBILITIES)}")
    src = Path(assignment)
    original = Assignment.load(src)
    if original.variants is not None:
        raise DHError(
            "the assignment draws values per student (variants:): an autograder zip would "
            "carry its secret to the grading platform and has no class list; grade it with "
            "dhsym grade --variants CLASS.csv",
            file=str(src),
            field="variants",
        )
    text, keys = _bundle_assignment(src)
    with tempfile.TemporaryDirectory(prefix="dhsym-autograder-") as tmp:
        check = Path(tmp) / "assignment"
        (check / "keys").mkdir(parents=True)
        (check / "assignment.yaml").write_text(text, encoding="utf-8")
        for name, data in keys.items():
            (check / name).write_bytes(data)
        bundled = Assignment.load(check / "assignment.yaml")
        if [q.key for q in bundled.questions] != [q.key for q in original.questions]:
            raise DHError(
                "the bundled assignment reads other keys than the original", file=str(src)
            )
        whl = Path(wheel) if wheel is not None else build_wheel(tmp)
        _check_wheel(whl)
        config = {
            "assignment": "assignment/assignment.yaml",
            "visibility": visibility,
            "show_key": bool(show_key),
            "title": original.title,
            "max_score": original.max_score,
        }
        buf = io.BytesIO()
        with zipfile.ZipFile(buf, "w") as z:
            _zip_add(z, "setup.sh", _SETUP_SH.encode(), _EXEC)
            _zip_add(z, "run_autograder", _RUN_AUTOGRADER.encode(), _EXEC)
            _zip_add(z, CONFIG_NAME, (json.dumps(config, indent=2) + "\n").encode())
            _zip_add(z, "assignment/assignment.yaml", text.encode("utf-8"))
            for name, data in sorted(keys.items()):
                _zip_add(z, f"assignment/{name}", data)
            _zip_add(z, f"dist/{whl.name}", whl.read_bytes())
    out = Path(output)
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp_out = out.with_name(f".{out.name}.{os.getpid()}.tmp")
    tmp_out.write_bytes(buf.getvalue())
    os.replace(tmp_out, out)
    return out


# --- running it -------------------------------------------------------------------


def _student(metadata: Path) -> tuple[str, str]:
    """Student id and name from the platform's ``submission_metadata.json`` (if any)."""
    try:
        if metadata.is_file() and not metadata.is_symlink() and metadata.stat().st_size < 1e6:
            users = json.loads(metadata.read_text("utf-8")).get("users") or []
            if users and isinstance(users[0], dict):
                names = [str(u.get("name") or u.get("email") or "") for u in users]
                ids = [str(u.get("email") or u.get("id") or "") for u in users]
                return ", ".join(filter(None, ids)) or "submission", ", ".join(filter(None, names))
    except (OSError, ValueError, AttributeError):
        pass
    return "submission", ""


_NO_RERUN = (
    "The autograder does not run again by itself: resubmit (a busy grader may be faster "
    "next time) or ask the course staff to check this answer."
)


def read_submission(
    folder: str | Path, assignment: Assignment, limits: AnswerLimits, metadata: Path | None = None
) -> Submission:
    """One student's answers from a submission folder (question files or one answers file)."""
    root = Path(folder)
    student, name = _student(metadata) if metadata is not None else ("submission", "")
    qids = [q.id for q in assignment.questions]
    if not root.is_dir():
        return Submission(student, name or student, (), tuple((q, "no submission") for q in qids))
    entries = [p for p in root.iterdir() if not p.name.startswith(".") and not p.is_symlink()]
    if len(entries) == 1 and entries[0].is_dir():
        root = entries[0]  # a zip of one folder
    sub = read_submission_folder(root, qids, limits)
    files = sorted(
        p
        for p in root.iterdir()
        if p.suffix.lower() in (".yaml", ".yml", ".json")
        and not p.is_symlink()
        and not any(p.name == q or p.name.startswith(q + ".") for q in qids)
    )
    flags = list(sub.flags)  # several files for one question: which one was graded
    graded = "the question files"
    if not sub.answers and not sub.problems and files:
        sub, graded = read_submission_file(files[0], qids), files[0].name
        files = files[1:]
    if files:  # never ignored without a word
        flags.append(
            f"not graded: {', '.join(p.name for p in files)} ({graded} graded instead: "
            "one form of answers per submission)"
        )
    return Submission(student, name or student, sub.answers, sub.problems, flags=tuple(flags))


def results_json(
    assignment: Assignment,
    feedback: tuple[QuestionFeedback, ...],
    *,
    visibility: str = "visible",
    show_key: bool = False,
    seconds: float = 0.0,
    flags: tuple[str, ...] = (),
) -> dict[str, Any]:
    """The ``results.json`` object for one graded submission (the specification's format);
    ``flags`` (answer files that were not graded) are notes of its ``output``.

    >>> a = Assignment("HW", ())
    >>> results_json(a, ())["score"], results_json(a, ())["tests"]
    (0.0, [])
    """
    tests = []
    for k, qf in enumerate(feedback, 1):
        result = qf.result
        tests.append(
            {
                "name": f"{qf.id}: {qf.ask}",
                "number": str(k),
                "score": float(qf.score),
                "max_score": float(qf.points),
                "output": render_question_text(qf, show_key=show_key),
                "tags": list(result.kinds) if result is not None else ["missing"],
                "visibility": visibility,
            }
        )
    score = float(sum(qf.score for qf in feedback))
    notes = "".join(f"\nNote: {flag}" for flag in flags)
    verdicts = {qf.id: qf.result.verdict.value if qf.result else "missing" for qf in feedback}
    right = sum(v == "correct" for v in verdicts.values())
    return {
        "score": score,
        "output": (
            f"{assignment.title}: {score:g} / {assignment.max_score:g} points; "
            f"{right} of {len(feedback)} questions right. Each question below says why."
            f"{notes}"
        ),
        "visibility": visibility,
        "stdout_visibility": "hidden",
        "execution_time": round(seconds, 3),
        "extra_data": {"verdicts": verdicts},
        "tests": tests,
    }


def run_autograder(paths: AutograderPaths | None = None) -> dict[str, Any]:
    """Grade the submission in ``paths.submission`` and write ``results.json``.

    If grading itself fails (a broken autograder, not a bad answer: bad answers are
    graded ``unreadable``), a ``results.json`` with score 0 and the reason is written
    before the error is raised, so the platform always shows something.
    """
    p = paths or AutograderPaths.from_env()
    t0 = time.perf_counter()
    out = p.results / "results.json"
    try:
        config = json.loads((p.source / CONFIG_NAME).read_text(encoding="utf-8"))
        keys = PreparedKeys()  # each key prepared once, here, before any answer's clock
        assignment = Assignment.load(p.source / str(config["assignment"]), keys)
        limits = AnswerLimits(seconds=assignment.seconds)
        sub = read_submission(p.submission, assignment, limits, p.metadata)
        feedback = check_submission(assignment, sub, limits, on_timeout=_NO_RERUN, keys=keys)
        data = results_json(
            assignment,
            feedback,
            visibility=str(config.get("visibility", "visible")),
            show_key=bool(config.get("show_key", False)),
            seconds=time.perf_counter() - t0,
            flags=sub.flags,
        )
    except Exception as err:
        failed = {
            "score": 0.0,
            "output": f"The autograder could not grade this submission: {err}",
            "stdout_visibility": "hidden",
            "tests": [],
        }
        p.results.mkdir(parents=True, exist_ok=True)
        write_atomic(out, json.dumps(failed, indent=2, ensure_ascii=False))
        raise
    p.results.mkdir(parents=True, exist_ok=True)
    write_atomic(out, json.dumps(data, indent=2, ensure_ascii=False))
    return data
