"""dhsym as installed: what a new user gets from ``pip install dhsym-*.whl``, used from an
empty folder.

The module builds the sdist and, from it, the wheel (``python -m build``: a file missing
from the sdist breaks the wheel), installs the wheel with its ``notebooks`` extra into a
fresh virtual environment (no system site packages, no editable install, no source tree
on ``sys.path``), and from an empty temporary folder runs what a teacher runs: ``derive``
in every format, ``handout --pdf``, ``check`` on a right and a wrong answer, ``grade`` on
the homework example, every Python example of the README, and notebook 06. The homework
example and the notebook come from the sdist, as a teacher would download them. A data
file missing from the wheel (a template, a robot) makes these commands fail.

Slow (about a minute and a half here, most of it pip). It runs in CI (``CI=true``) and
never skips there; elsewhere it skips only when the distributions cannot be built (no
``build`` package, or no index to fetch setuptools from).
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import tarfile
import zipfile
from pathlib import Path

import pytest

from tests.conftest import _need

pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parent.parent
RIGHT = "[[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 + a2*S12], [0, 0, 1, 0]]"
WRONG = RIGHT.replace("+ a2*S12", "- a2*S12")
NOTEBOOK = "06_homework_checking.ipynb"

# Runs the README's ```python blocks (text on stdin) with doctest, in the installed package.
README_DOCTESTS = """
import doctest, re, sys
text = sys.stdin.read()
blocks = re.findall(r"```python\\n(.*?)```", text, re.S)
test = doctest.DocTestParser().get_doctest("\\n".join(blocks), {}, "README", "README.md", 0)
flags = doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS
runner = doctest.DocTestRunner(optionflags=flags)
runner.run(test)
print(f"README examples: {runner.tries} tried, {runner.failures} failed")
sys.exit(1 if runner.failures or runner.tries < 10 else 0)
"""


def _in_ci() -> bool:
    return os.environ.get("CI", "").lower() in ("1", "true", "yes")


@pytest.fixture(scope="module")
def dists(tmp_path_factory):
    """The sdist and the wheel built from it."""
    try:
        import build  # noqa: F401
    except ImportError:
        _need("the build package", False, "pip install build (it is in the test extra)")
    out = tmp_path_factory.mktemp("dist")
    proc = subprocess.run(
        [sys.executable, "-m", "build", "--outdir", str(out), str(ROOT)],
        capture_output=True,
        text=True,
        timeout=900,
    )
    if proc.returncode != 0:
        detail = (proc.stdout + proc.stderr)[-3000:]
        if _in_ci():
            pytest.fail(f"python -m build failed:\n{detail}")
        if "Could not find a version" in detail or "No matching distribution" in detail:
            pytest.skip("cannot build here: no package index to fetch the build backend from")
        pytest.fail(f"python -m build failed:\n{detail}")
    (wheel,) = out.glob("dhsym-*.whl")
    (sdist,) = out.glob("dhsym-*.tar.gz")
    return wheel, sdist


class Installed:
    """A fresh venv with the wheel installed, an empty work folder, and how to run in it."""

    def __init__(self, root: Path, wheel: Path, sdist: Path) -> None:
        self.venv = root / "venv"
        self.work = root / "work"
        self.src = root / "src"
        for d in (self.work, self.src):
            d.mkdir()
        home = root / "home"
        home.mkdir()
        self.env = {
            k: v
            for k, v in os.environ.items()
            if not k.startswith(("PYTHON", "VIRTUAL_ENV", "JUPYTER", "IPYTHON", "MPL"))
        }
        cache = os.environ.get("PIP_CACHE_DIR") or os.path.join(
            os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "pip"
        )
        self.env.update(
            PIP_CACHE_DIR=cache,  # pip's cache makes the install fast
            PATH=f"{self.venv / 'bin'}{os.pathsep}{os.environ.get('PATH', '')}",
            VIRTUAL_ENV=str(self.venv),
            HOME=str(home),  # no user site packages, Jupyter or IPython settings
            JUPYTER_DATA_DIR=str(home / "jupyter"),
            PYTHONNOUSERSITE="1",
        )
        subprocess.run(
            [sys.executable, "-m", "venv", str(self.venv)], check=True, env=self.env, timeout=300
        )
        pip = subprocess.run(
            [self.python, "-m", "pip", "install", "--quiet", "--no-compile",
             f"{wheel}[notebooks]"],
            capture_output=True, text=True, env=self.env, timeout=900,
        )  # fmt: skip
        assert pip.returncode == 0, pip.stdout + pip.stderr
        with tarfile.open(sdist) as tar:
            safe = {"filter": "data"} if hasattr(tarfile, "data_filter") else {}
            tar.extractall(self.src, **safe)  # noqa: S202 - our own sdist
        (self.sdist_root,) = self.src.iterdir()

    @property
    def python(self) -> str:
        return str(self.venv / "bin" / "python")

    def run(
        self, *args: str, stdin: str = "", cwd: Path | None = None, timeout: float = 300
    ) -> subprocess.CompletedProcess:
        """Run a program of the venv (``dhsym``, ``python``) in the work folder."""
        exe = self.venv / "bin" / args[0]
        return subprocess.run(
            [str(exe), *args[1:]],
            input=stdin,
            capture_output=True,
            text=True,
            cwd=cwd or self.work,
            env=self.env,
            timeout=timeout,
        )

    def start(self, *args: str, cwd: Path) -> subprocess.Popen:
        """Start a program of the venv in the background (output to files in ``cwd``)."""
        return subprocess.Popen(
            [str(self.venv / "bin" / args[0]), *args[1:]],
            cwd=cwd,
            env=self.env,
            stdin=subprocess.DEVNULL,
            stdout=open(cwd / "stdout.txt", "w"),  # noqa: SIM115 - closed with the process
            stderr=open(cwd / "stderr.txt", "w"),  # noqa: SIM115
        )


@pytest.fixture(scope="module")
def installed(dists, tmp_path_factory):
    """The installed wheel; notebook 06 starts running in the background at once."""
    wheel, sdist = dists
    inst = Installed(tmp_path_factory.mktemp("installed"), wheel, sdist)
    nb_dir = inst.work.parent / "course"
    shutil.copytree(inst.sdist_root / "examples", nb_dir / "examples")
    (nb_dir / "notebooks").mkdir()
    shutil.copy(inst.sdist_root / "notebooks" / NOTEBOOK, nb_dir / "notebooks" / NOTEBOOK)
    inst.notebook = inst.start(
        "dhsym", "notebooks", "run", f"notebooks/{NOTEBOOK}", "--timeout", "300", cwd=nb_dir
    )
    inst.notebook_dir = nb_dir
    yield inst
    if inst.notebook.poll() is None:
        inst.notebook.kill()
        inst.notebook.wait()


def test_the_wheel_ships_code_robots_templates_and_py_typed(dists):
    wheel, _ = dists
    names = set(zipfile.ZipFile(wheel).namelist())
    templates = {f"dhsym/templates/{p.name}" for p in (ROOT / "templates").glob("*.j2")}
    robots = {f"dhsym/model/robots/{p.name}" for p in (ROOT / "dhsym/model/robots").glob("*.yaml")}
    modules = {str(p.relative_to(ROOT)) for p in (ROOT / "dhsym").rglob("*.py")}
    assert len(templates) >= 10 and len(robots) >= 10
    view = {"dhsym/view/static/viewer.js"}  # three.js and the view, bundled from js/
    missing = (templates | robots | modules | view | {"dhsym/py.typed"}) - names
    assert missing == set(), f"not in the wheel: {sorted(missing)}"
    assert any(n.endswith(".dist-info/licenses/LICENSE") for n in names)
    assert not any(n.startswith(("tests/", "notebooks/", "examples/")) for n in names)


def test_the_sdist_has_readme_license_tests_notebooks_examples_templates(dists):
    _, sdist = dists
    with tarfile.open(sdist) as tar:
        names = {n.split("/", 1)[1] for n in tar.getnames() if "/" in n}
    for path in ("README.md", "LICENSE", "pyproject.toml", "tests/conftest.py",
                 f"notebooks/{NOTEBOOK}", "examples/homework/assignment.yaml",
                 "templates/handout.tex.j2", "dhsym/model/robots/puma560.yaml",
                 "docs/handout-puma560-page1.png"):  # fmt: skip
        assert path in names, path
    for folder in ("tests", "notebooks", "examples/homework/submissions", "templates"):
        tracked = {
            str(p.relative_to(ROOT))
            for p in (ROOT / folder).rglob("*")
            if p.is_file() and "__pycache__" not in p.parts and p.suffix != ".pyc"
        }
        assert tracked - names == set(), folder


def test_the_package_imported_is_the_installed_one(installed):
    out = installed.run("python", "-c", "import dhsym, sys; print(dhsym.__file__, sys.prefix)")
    assert out.returncode == 0, out.stderr
    where, prefix = out.stdout.split()
    assert where.startswith(str(installed.venv)) and prefix == str(installed.venv)
    assert list(installed.work.iterdir()) == []  # the folder is empty: no source tree


@pytest.mark.parametrize("fmt", ["text", "markdown", "latex", "json"])
def test_derive_in_every_format(installed, fmt):
    out = installed.run("dhsym", "derive", "puma560", "--format", fmt)
    assert out.returncode == 0 and out.stderr == "", out.stderr
    marker = {"text": "PUMA 560: forward kinematics", "markdown": "C_{23}",
              "latex": r"\begin{bmatrix}", "json": '"label": "T0_6"'}[fmt]  # fmt: skip
    assert marker in out.stdout
    if fmt == "json":
        data = json.loads(out.stdout)
        assert data["schema"] == 1 and len(data["compact"]) == len(data["matrix"]) == 4


def test_handout_pdf(installed, need_tex):
    out = installed.run("dhsym", "handout", "puma560", "-o", "x.tex", "--pdf", timeout=600)
    assert out.returncode == 0, out.stderr
    assert out.stderr == "wrote x.tex\nwrote x.pdf\n"
    assert (installed.work / "x.pdf").read_bytes().startswith(b"%PDF")
    assert not (installed.work / "x.aux").exists()
    for p in installed.work.iterdir():
        p.unlink()


def test_check_a_right_and_a_wrong_answer(installed):
    args = ("dhsym", "check", "--key", "planar2r", "--question", "T0_2", "--answer", "-")
    right = installed.run(*args, stdin=RIGHT)
    assert right.returncode == 0 and right.stdout.startswith("CORRECT"), right.stderr
    wrong = installed.run(*args, stdin=WRONG)
    assert wrong.returncode == 1 and "wrong sign" in wrong.stdout, wrong.stderr
    md = installed.run(*args, "--format", "markdown", stdin=WRONG)
    assert md.returncode == 1 and md.stdout.startswith("# Feedback"), md.stderr


def test_view_writes_a_page_that_needs_nothing(installed):
    """The README's ``dhsym view``: one page, three.js inlined, no address to fetch."""
    out = installed.run("dhsym", "view", "puma560", "-o", "arm.html")
    assert out.returncode == 0, out.stderr
    html = (installed.work / "arm.html").read_text(encoding="utf-8")
    (installed.work / "arm.html").unlink()
    assert "DhsymViewer.mountPage" in html and "three.js" in html.lower()
    assert "https://" not in html.split("<script>")[0] and len(html.encode()) < 1_000_000


def test_grade_the_homework_example(installed):
    """The README's command, in the folder that holds the example (from the sdist)."""
    course = installed.notebook_dir
    hw = course / "examples" / "homework"
    out = installed.run(
        "dhsym", "grade", "examples/homework/assignment.yaml", "examples/homework/submissions",
        "-o", "build/grades", "--quiet", cwd=course, timeout=600,
    )  # fmt: skip
    assert out.returncode == 0, out.stderr
    assert "gradebook: build/grades/gradebook.csv" in out.stdout
    report = course / "build" / "grades"
    students = {p.name for p in (hw / "submissions").iterdir()}
    assert {p.stem for p in (report / "feedback").glob("*.md")} == students
    assert (report / "summary.html").is_file()
    assert len((report / "gradebook.csv").read_text().splitlines()) == len(students) + 1
    shutil.rmtree(report)


def test_every_python_example_of_the_readme(installed):
    readme = (installed.sdist_root / "README.md").read_text(encoding="utf-8")
    assert len(re.findall(r"```python\n", readme)) >= 4
    out = installed.run("python", "-c", README_DOCTESTS, stdin=readme)
    assert out.returncode == 0, out.stdout[-4000:] + out.stderr[-2000:]
    assert ", 0 failed" in out.stdout


def test_notebook_06_runs_against_the_installed_package(installed):
    kernel = installed.run(
        "python", "-c",
        "from jupyter_client.kernelspec import KernelSpecManager as K;"
        "import shutil; s = K().get_kernel_spec('python3');"
        "print(shutil.which(s.argv[0]) if s.argv[0] == 'python' else s.argv[0])",
    )  # fmt: skip
    assert kernel.returncode == 0, kernel.stderr
    assert kernel.stdout.strip().startswith(str(installed.venv)), kernel.stdout
    try:
        status = installed.notebook.wait(timeout=900)
    except subprocess.TimeoutExpired:
        installed.notebook.kill()
        raise
    err = (installed.notebook_dir / "stderr.txt").read_text()
    assert status == 0, err
    assert f"ran notebooks/{NOTEBOOK}" in err
