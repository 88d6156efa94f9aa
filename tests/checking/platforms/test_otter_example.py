"""examples/otter: the example class graded through otter-grader with dhsym's checks.

The otter autograder is generated from ``examples/otter/tests`` (each test file one
``assert_answer`` call); each student's answers from ``examples/homework/submissions``
are put into the assignment notebook, and otter runs the notebook and its tests (a
Jupyter kernel, no container).  The points per question must be those of ``dhsym grade``.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from dhsym.checking import Assignment, grade, read_submissions

pytestmark = [pytest.mark.jupyter, pytest.mark.slow]

ROOT = Path(__file__).resolve().parents[3]
HW = ROOT / "examples" / "homework"
OTTER = ROOT / "examples" / "otter"


@pytest.fixture(scope="module")
def autograder(tmp_path_factory) -> Path:
    import importlib.util
    import os

    if importlib.util.find_spec("otter") is None:
        pytest.skip("otter-grader not installed")  # the test below fails first in CI
    from otter.generate import main as generate

    out = tmp_path_factory.mktemp("otter") / "autograder.zip"
    cwd = os.getcwd()
    os.chdir(OTTER)  # otter takes support files from the working directory
    try:
        generate(
            tests_dir="tests",
            output_path=str(out),
            no_config=True,
            no_requirements=True,
            no_environment=True,
            files=["generic_modified_link.yaml"],
        )
    finally:
        os.chdir(cwd)
    return out


def _student_notebook(answers: dict[str, str], path: Path) -> None:
    import nbformat

    nb = nbformat.read(OTTER / "hw3.ipynb", as_version=4)
    for cell in nb.cells:
        for qid, text in answers.items():
            if cell.cell_type == "code" and cell.source.startswith(f"{qid} = ..."):
                cell.source = f"{qid} = {text!r}"
    nbformat.write(nb, path)


def test_otter_grades_the_example_class_as_dhsym_does(
    autograder, tmp_path, need_otter, need_jupyter
):
    from otter.api import grade_submission

    assignment = Assignment.load(HW / "assignment.yaml")
    report = grade(assignment, HW / "submissions", tmp_path / "dhsym", workers=0, progress=False)
    expected = {r.student: r for r in report.records}
    subs = read_submissions(HW / "submissions", assignment)
    assert len(subs) == 10
    for sub in subs:
        answers = {
            q: t.decode("utf-8", "replace") if isinstance(t, bytes) else t for q, t in sub.answers
        }
        nb = tmp_path / f"{sub.student}.ipynb"
        _student_notebook(answers, nb)
        results = grade_submission(str(nb), str(autograder), quiet=True)
        want = expected[sub.student]
        got = {name: float(r.score) for name, r in results.results.items()}
        assert got == pytest.approx(want.scores), sub.student
        assert results.total == pytest.approx(want.score) and results.possible == 10
        for q in assignment.questions:
            messages = " ".join(tc.message for tc in results.results[q.id].test_case_results)
            if want.verdicts[q.id] == "missing":
                assert "No answer yet" in messages
            elif want.verdicts[q.id] != "correct":
                assert want.verdicts[q.id].upper() in messages  # dhsym's feedback
