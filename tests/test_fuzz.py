"""Fuzz: the command line and every file loader answer any input clearly, never crash or hang.

Hypothesis drives a fixed number of inputs (derandomized: the same inputs on every
run) built from the hostile kinds found so far — NUL bytes, non-finite and huge
numbers, 5000-digit frame numbers, special files, alias bombs, deep nesting, binary
junk, long tables — mixed with ordinary values.  Each input is either answered (a
result, a verdict) or refused with one clear line (``dhsym: error: …``, a
:class:`~dhsym.errors.DHError`); a traceback, an internal error or an input that
runs past its time limit fails the test.
"""

from __future__ import annotations

import contextlib
import io
import os
import sys
import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dhsym.checking import Assignment, Key, check_answer, read_submissions
from dhsym.cli.main import main
from dhsym.errors import DHError
from dhsym.model.tablefile import read_table

from .checking.chaos_class import HW

CLI_EXAMPLES = 150
FILE_EXAMPLES = 150
PER_INPUT_SECONDS = 60.0  # a hang, not a slow input, fails


class Hang(BaseException):
    """An input ran past its time limit."""


@contextlib.contextmanager
def time_limit(seconds: float, error: type[BaseException]):
    """The harness's watchdog: a real timer of this test process (the library has none:
    its deadlines are checked between steps), so that a hang fails instead of hanging."""
    import signal

    def expire(signum: int, frame: object) -> None:
        raise error(f"no answer within {seconds:g} s")

    previous = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


# --- hostile building blocks --------------------------------------------------------------

WORDS = [
    "inf",
    "-inf",
    "nan",
    "-1",
    "0",
    "1e300",
    "1e-300",
    "9" * 5000,
    "T0_" + "9" * 5000,
    "T0_2",
    "T0_2[0,3]",
    "A1",
    "table",
    "arm",
    "px",
    "planar2r",
    "puma560",
    "stanford",
    "planar60r",
    "planar61r",
    "-",
    "/dev/zero",
    "/dev/null",
    "/etc/passwd",
    "../../etc/passwd",
    "a\x00b",
    "\udcff",
    "θ",
    "",
    " ",
    "0,0",
    "1,x",
    "__import__('os')",
    "sqrt(-1),0",
    "0" + ",0" * 59,
    # issue 25: the hostile grading campaign
    "garbage://x",
    "tcp://[::1",
    "Atan2(p_y, p_x)",
    "arctan2(1, 0)",
    "cos^-1(0.5)",
    "\\cos^{-1}(x)",
    "tan^-1 x",
    "1:30",
    "theta1 = theta1",
    "0.09 + 0*100.0",
    "380.0e-3, 0.9",
    "a1 C1 + a2 C12 + 100.1 - 100.0",
    "(C1^2 + S1^2 - 1)*10^13 + C12",
    "jos\u00e9",
    "jose\u0301",
]
OPTIONS = [
    "--format",
    "--from",
    "--to",
    "--q",
    "--deg",
    "--json",
    "--full",
    "--timeout",
    "--question",
    "--answer",
    "--key",
    "--workers",
    "--tool-free",
    "--view",
    "--samples",
    "--mode",
    "--quiet",
    "--numeric",
]


def _table_yaml(rows: int, twisted: bool) -> str:
    joints = [
        f"  - {{type: R, theta: q{k}, d: 0.1, a: 0.2, alpha: {(-1) ** k * 90 if twisted else 0}}}"
        for k in range(1, rows + 1)
    ]
    return "angles: deg\njoints:\n" + "\n".join(joints) + "\n"


def _bomb(levels: int, width: int) -> str:
    lines = [f"l0: &l0 [{', '.join(['x'] * width)}]"]
    for k in range(1, levels):
        lines.append(f"l{k}: &l{k} [" + ", ".join([f"*l{k - 1}"] * width) + "]")
    return "\n".join(lines) + f"\nname: *l{levels - 1}\njoints: *l{levels - 1}\n"


contents = st.one_of(
    st.sampled_from(  # issue 25: YAML 1.1 numbers, keys given twice, fields that must not be
        [
            "joints:\n  - {type: R, theta: q1, d: 0, a: 1, alpha: 1:30}\n",
            "joints:\n  - {type: R, theta: q1, d: 0, a: 1, alpha: 0, a: 2}\n",
            "joints:\n  - {type: F, theta: 0, d: 0, a: 1, alpha: 0, q: q1}\n",
            "joints:\n  - {type: R, theta: q1, d: 0, a: 1, alpha: 0, limits: [a, b]}\n",
            "joints:\n  - {type: R, theta: q1, d: 0, a: 1, alpha: 0}\ntool: [{Tz: q1}]\n",
            "root_password: hunter2\napi_token: s3cr3t\n",
            "\ufeffstudent;q1\r\nalice;C1\r\n",
            "key: puma560\nkey: planar2r\nquestions: []\n",
        ]
    ),
    st.binary(max_size=3000),
    st.text(alphabet="[]{}&*:,-| ab1θ\n\t#!'\"?\\$^_=", max_size=400),
    st.builds(lambda n: "joints: " + "[" * n + "]" * n, st.integers(1, 6000)),
    st.builds(lambda n: "joints: [{type: R, theta: q1, d: " + "9" * n + "}]", st.integers(1, 6000)),
    st.builds(_bomb, st.integers(1, 9), st.integers(1, 12)),
    st.builds(_table_yaml, st.integers(1, 70), st.booleans()),
    st.builds(
        lambda s, n: " " * n + s,
        st.sampled_from(["| θ | d | a | α |\n|--|--|--|--|\n"]),
        st.integers(0, 120_000),
    ),
    st.builds(
        lambda qs: "key: puma560\nquestions:\n" + "".join(f"  - {q}\n" for q in qs),
        st.lists(
            st.builds(
                lambda i, a, p: f"{{id: {i}, ask: {a}, points: {p}}}",
                st.sampled_from(["q1", "q2", "'../x'", "student", "[1]"]),
                st.sampled_from(["table", "T0_2", "A9", "'T0_" + "9" * 50 + "'", "{a: 1}"]),
                st.sampled_from(["1", ".nan", ".inf", "-1", "[1]", "abc", "1e308"]),
            ),
            max_size=4,
        ),
    ),
)


def _write(path: Path, data: str | bytes) -> None:
    path.write_bytes(_bytes(data))


@contextlib.contextmanager
def _workspace():
    """A temporary folder with hostile files in it, as the working directory."""
    old = os.getcwd()
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        _write(root / "long.yaml", _table_yaml(60, twisted=True))
        _write(root / "bomb.yaml", _bomb(8, 10))
        _write(root / "deep.yaml", "joints: " + "[" * 5000 + "]" * 5000)
        os.mkfifo(root / "fifo.yaml")
        (root / "class").mkdir()
        for student in ("alice", "mallory"):
            (root / "class" / student).mkdir()
            for q in ("q1.md", "q5.txt"):
                src = HW / "submissions" / student / q
                if src.exists():
                    _write(root / "class" / student / q, src.read_bytes())
        os.chdir(root)
        try:
            yield root
        finally:
            os.chdir(old)


def _run(argv: list[str], stdin: bytes) -> tuple[int, str]:
    err, out = io.StringIO(), io.StringIO()
    old_stdin = sys.stdin
    sys.stdin = io.TextIOWrapper(io.BytesIO(stdin))
    try:
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
            with time_limit(PER_INPUT_SECONDS, Hang):
                try:
                    code = main(argv)
                except SystemExit as exit_:  # argparse: usage errors exit 2
                    code = exit_.code if isinstance(exit_.code, int) else 2
    finally:
        sys.stdin = old_stdin
    return code, err.getvalue()


FILES = ["long.yaml", "bomb.yaml", "deep.yaml", "fifo.yaml", "gen.yaml", "class", "nothing.yaml"]
ROBOTS = ["planar2r", "puma560", "stanford", "example1_rrp", "scara", "planar12r"]
junk = st.one_of(st.sampled_from(WORDS), st.text(max_size=12))
robot = st.one_of(st.sampled_from(ROBOTS), st.sampled_from(ROBOTS), st.sampled_from(FILES), junk)
number = st.one_of(
    st.integers(0, 12).map(str),
    st.integers(0, 12).map(str),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.sampled_from(["1e9", "99999999999", "100000000", "-5", "0", "inf", "nan", "1e300"]),
    junk,
)
joint_values = st.one_of(
    st.integers(1, 12).flatmap(
        lambda n: st.lists(st.floats(-10, 10), min_size=n, max_size=n).map(
            lambda v: ",".join(map(str, v))
        )
    ),
    st.sampled_from(["0,0", "0,0,0", "0,0,0,0,0,0", ",".join(["1"] * 12), ",".join(["0.1"] * 60)]),
    junk,
)
question = st.one_of(
    st.sampled_from(["table", "T0_2", "T0_6", "A1", "A3", "arm", "px", "T0_6[0,3]", "T2_0"]), junk
)
GRAMMAR = {  # command: (positional strategies, {option: value strategy or None for a flag})
    "list": ([], {}),
    "show": ([robot], {"--format": st.sampled_from(["markdown", "yaml"])}),
    "derive": (
        [robot],
        {
            "--format": st.sampled_from(["text", "markdown", "latex", "json"]),
            "--from": number,
            "--to": number,
            "--full": None,
            "-o": st.sampled_from(["out.txt", "out/d.tex"]),
        },
    ),
    "fk": ([robot], {"--q": joint_values, "--deg": None, "--json": None}),
    "check": (
        [],
        {
            "--key": robot,
            "--question": question,
            "--answer": st.sampled_from(["-", "-", "gen.yaml", "fifo.yaml", "/dev/zero"]),
            "--json": None,
            "--tool-free": None,
            "--timeout": number,
        },
    ),
    "grade": (
        [
            st.sampled_from([str(HW / "assignment.yaml"), "gen.yaml", "bomb.yaml"]),
            st.sampled_from(["class", "gen.yaml", str(HW / "class.csv"), "nothing"]),
        ],
        {
            "--timeout": number,
            "--quiet": None,
            "--dask": st.sampled_from(["garbage://x", "", "tcp://[::1", "x://"]),
        },
    ),
    "convert": (
        [robot],
        {
            "--to": st.sampled_from(["standard", "modified"]),
            "--samples": number,
            "-o": st.just("c.yaml"),
        },
    ),
    "handout": (
        [robot],
        {
            "-o": st.just("h.tex"),
            "--mode": st.sampled_from(["answers", "problems"]),
            "--full": None,
            "--numeric": None,
            "--title": junk,
        },
    ),
    "plot": (
        [robot],
        {
            "--q": joint_values,
            "--view": st.sampled_from(["2d", "3d"]),
            "--workspace": None,
            "--samples": number,
            "--dpi": number,
            "-o": st.sampled_from(["p.png", "p.svg"]),
        },
    ),
}
REQUIRED = {
    "fk": ["--q"],
    "check": ["--key", "--question", "--answer"],
    "convert": ["--to"],
    "handout": ["-o"],
    "plot": ["-o"],
}


@st.composite
def command_lines(draw: st.DrawFn) -> list[str]:
    """Mostly well-formed command lines with hostile values; now and then a stray option."""
    command = draw(st.sampled_from(sorted(GRAMMAR)))
    positional, options = GRAMMAR[command]
    argv = [command, *(draw(p) for p in positional)]
    if command == "grade":
        argv += ["-o", "report", "--workers", "0"]
    chosen = (
        draw(st.lists(st.sampled_from(sorted(options)), unique=True, max_size=4)) if options else []
    )
    for option in REQUIRED.get(command, []) + [
        o for o in chosen if o not in REQUIRED.get(command, [])
    ]:
        argv += [option] if options[option] is None else [option, draw(options[option])]
    if draw(st.integers(0, 9)) == 0:  # an option this command does not have
        argv += [draw(st.sampled_from(OPTIONS)), draw(junk)]
    return argv


def budget(examples: int) -> settings:
    """A fixed number of inputs, the same on every run (no deadline: hangs are timed above)."""
    return settings(
        max_examples=examples,
        deadline=None,
        derandomize=True,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
    )


def _bytes(data: str | bytes) -> bytes:
    return data if isinstance(data, bytes) else data.encode("utf-8", "surrogatepass")


@pytest.mark.slow
@budget(CLI_EXAMPLES)
@given(
    argv=command_lines(),
    stdin=st.one_of(st.binary(max_size=300), contents.map(_bytes)),
    gen=contents,
)
def test_any_command_line_is_answered_or_refused_in_one_line(argv, stdin, gen):
    with _workspace() as root:
        _write(root / "gen.yaml", gen)
        code, err = _run(argv, stdin)
    assert "Traceback" not in err and "internal error" not in err, (argv, err)
    assert code in (0, 1, 2), (argv, code, err)
    if code == 2 and err and not err.startswith("usage:"):
        assert err.startswith("dhsym: "), (argv, err)


def _load_all(root: Path, data: str | bytes) -> None:
    """Every loader on the same bytes: a result or a DHError, nothing else."""
    path = root / "input.yaml"
    _write(path, data)
    for load in (read_table, Assignment.load):
        try:
            load(path)
        except DHError as err:
            assert "\n" not in str(err).strip() or "not valid YAML" in str(err)
    folder = root / "subs"
    (folder / "eve").mkdir(parents=True, exist_ok=True)
    _write(folder / "eve" / "q1.md", data)
    _write(folder / "zoe.yaml", data)
    subs = read_submissions(folder, HOMEWORK)
    assert [s.student for s in subs] == ["eve", "zoe"]
    for key in KEYS:
        result = check_answer(key, _bytes(data))
        assert result.verdict.value in ("correct", "incorrect", "unreadable")


KEYS = [Key.load("planar2r", q) for q in ("table", "T0_2", "T0_2[0,3]")]
#: the homework's assignment (frozen), read once: the fuzzed bytes are the submissions
HOMEWORK = Assignment.load(HW / "assignment.yaml")


@pytest.mark.slow
@budget(FILE_EXAMPLES)
@given(data=contents)
def test_every_file_loader_gives_a_result_or_a_clear_error(data):
    with tempfile.TemporaryDirectory() as tmp, time_limit(PER_INPUT_SECONDS, Hang):
        _load_all(Path(tmp), data)
