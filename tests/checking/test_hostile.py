"""Hostile answers: each is unreadable (or escaped), fast, executes nothing, writes nothing.

Fast is asserted by what bounds the work, never by a clock (a timed assertion fails on a
loaded machine): the checks run with no time limit of their own, so they end only because
the reader's counted limits (bytes, tokens, depth, exponents) refuse the answer or bound
what is left, and an answer too large or not text is refused before any of it is read.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import pytest

from dhsym.checking import check_answer
from dhsym.checking.reading import answers
from dhsym.checking.reading.limits import AnswerLimits

from ._keys import KEYS, load_key  # each key prepared once, as a grading worker does

CANARY = Path("/tmp/dhsym-hostile-canary")
HOSTILE = [
    f"__import__('os').system('touch {CANARY}')",
    f"exec(\"open('{CANARY}','w')\")",
    "eval('1+1')",
    "lambda: 1",
    "x.__class__.__bases__",
    "(" * 5000 + "x" + ")" * 5000,
    "x**9999999",
    "9" * 100_000,
    "1e999999999",
    "2^3^4^5^6^7",
    "((((x+1)^64+1)^64+1)^64)",
    "cos(" * 300 + "x" + ")" * 300,
    "\x00\x01\x02" * 1000,
    "a" * 200_000,
    r"\input{/etc/passwd}",
    r"\write18{touch /tmp/x}",
    r"\begin{bmatrix}\def\x{1}\x & 0 \\ 0 & 1\end{bmatrix}",
    "joints: &a [*a, *a, *a]\nname: &b [*a, *a]",
    "<script>alert(1)</script>",
    "{{7*7}} {% for x in range(9) %}",
    "x" * 10 + "+y" * 4000,
]


def _tree(root: Path) -> set[Path]:
    return set(root.rglob("*"))


@pytest.mark.parametrize("question", ["T0_2", "T0_2[0,3]", "table"])
@pytest.mark.parametrize("answer", HOSTILE, ids=range(len(HOSTILE)))
def test_hostile_answers_are_unreadable_fast(question, answer, tmp_path, monkeypatch):
    # the checked code gets a temporary folder of its own (and this test's folder as its
    # working directory), so the test watches folders nothing else on the machine writes to
    private = tmp_path / "tmp"
    private.mkdir()
    monkeypatch.setenv("TMPDIR", str(private))
    monkeypatch.setattr(tempfile, "tempdir", str(private))
    monkeypatch.chdir(tmp_path)
    before = _tree(tmp_path)
    # no deadline (seconds=0): the check ends because the counted limits bound its work
    key = load_key("planar2r", question)
    r = check_answer(key, answer, limits=AnswerLimits(seconds=0), keys=KEYS)
    assert r.verdict.value in ("unreadable", "incorrect")
    if r.verdict.value == "incorrect":  # readable but wrong: say so, never crash
        assert r.diagnoses
    assert not CANARY.exists()
    assert _tree(tmp_path) == before


def test_ten_megabytes_and_binary_junk(monkeypatch):
    px, table = load_key("puma560", "T0_6"), load_key("puma560", "table")

    # refused at the gate: the size and the bytes are looked at, the text never reaches
    # the normalisation that starts every reading (nor the parser after it)
    def read_past_the_gate(text: str) -> str:
        raise AssertionError(f"an answer of {len(text)} characters was read past the gate")

    monkeypatch.setattr(answers, "normalize_unicode", read_past_the_gate)
    big = check_answer(px, b"1" * 10_000_000, keys=KEYS)
    assert big.verdict.value == "unreadable"
    assert big.reason == "the answer is 10000000 bytes; at most 100000 are read"
    junk = check_answer(table, os.urandom(4096), keys=KEYS)
    assert junk.verdict.value == "unreadable"
    assert junk.reason in ("the answer is not text (binary data)", "the answer is not UTF-8 text")
