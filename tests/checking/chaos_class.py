"""A synthetic class for the chaos test: the honest example class plus one submission of
every hostile kind found so far (issue 15 and the hostile-answer tests).

:func:`build` writes it into a folder and returns the honest and the hostile
submission sources (``alice/``, ``deep.yaml`` …) so that a test can compare the
honest scores with a clean run and demand a status for every hostile one.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

from .test_hostile import CANARY, HOSTILE

HW = Path(__file__).resolve().parents[2] / "examples" / "homework"
QIDS = ("q1", "q2", "q3", "q4", "q5")
GOOD_TABLE = (HW / "submissions" / "bob" / "q1.md").read_text(encoding="utf-8")


def _alias_bomb(levels: int = 8) -> str:
    lines = ["l0: &l0 [x, x, x, x, x, x, x, x, x, x]"]
    for k in range(1, levels):
        lines.append(f"l{k}: &l{k} [" + ", ".join([f"*l{k - 1}"] * 10) + "]")
    return "\n".join(lines) + f"\nname: *l{levels - 1}\nanswers: {{q1: *l{levels - 1}}}\n"


def _folder(root: Path, name: str | bytes, answers: dict[str, str | bytes]) -> None:
    path = os.path.join(os.fsencode(root), os.fsencode(name))
    os.mkdir(path)
    for qid, text in answers.items():
        data = text if isinstance(text, bytes) else text.encode("utf-8", "surrogatepass")
        with open(os.path.join(path, os.fsencode(qid)), "wb") as fh:
            fh.write(data)


def build(root: Path) -> tuple[list[str], list[str]]:
    """Write the class into ``root``; return (honest sources, hostile sources)."""
    root.mkdir(parents=True, exist_ok=True)
    honest = []
    for student in sorted(p.name for p in (HW / "submissions").iterdir()):
        shutil.copytree(HW / "submissions" / student, root / student)
        honest.append(f"{student}/")
    hostile = []

    def add(source: str) -> None:
        hostile.append(source)

    # files that used to stop the whole run
    (root / "deep.yaml").write_text("answers: {q5: " + "[" * 5000 + "]" * 5000 + "}\n")
    add("deep.yaml")
    (root / "bigint.yaml").write_text("answers: {q5: " + "9" * 5000 + "}\n")
    add("bigint.yaml")
    _folder(root, b"caf\xe9", {"q5.txt": "a2*C1*C2"})
    add("caf\\xe9/")
    # an answer that made a separator regex run for 85 s (and Dask charge it to others)
    _folder(root, "spaces", {"q1.md": " " * 99_000 + "\n" + GOOD_TABLE})
    add("spaces/")
    _folder(root, "degrees", {"q1.md": "| θ ^" + " " * 99_000 + "x | d | a | α |\n|--|--|--|--|\n"})
    add("degrees/")
    # YAML that expands to gigabytes
    (root / "bomb.yaml").write_text(_alias_bomb())
    add("bomb.yaml")
    _folder(root, "tablebomb", {"q1.yaml": _alias_bomb().replace("answers", "joints")})
    add("tablebomb/")
    # a duplicate id (the honest alice/ keeps her score) and ids equal up to case
    (root / "alice.yaml").write_text("name: Not Alice\nanswers: {q5: '0'}\n")
    add("alice.yaml")
    shutil.copytree(root / "bob", root / "BOB")
    add("BOB/")
    # links, special and huge files, two answer files for one question
    secret = root.parent / "secret.txt"
    secret.write_text("TOPSECRET-4711\n")
    _folder(root, "linker", {})
    os.link(secret, root / "linker" / "q1.md")
    (root / "linker" / "q2.txt").symlink_to("/etc/passwd")
    (root / "linker" / "q3.txt").symlink_to("/dev/zero")
    os.mkfifo(root / "linker" / "q4.md")
    (root / "linker" / "q5.txt").write_bytes(b"1" * 10_000_000)
    add("linker/")
    _folder(root, "twofiles", {"q5.md": "0", "q5.txt": "a2*C1*C2"})
    add("twofiles/")
    _folder(root, "binary", {q + ".txt": os.urandom(3000) for q in QIDS})
    add("binary/")
    (root / "hostilename").mkdir()
    (root / "hostilename" / "name.txt").write_text(
        '=HYPERLINK("http://x") <script>alert(1)</script>'
    )
    (root / "hostilename" / "q5.txt").write_text("{{7*7}} | `x` $$ \\input{/etc/passwd}")
    add("hostilename/")
    (root / "shapes.yaml").write_text("name: [1, 2]\nanswers: {q1: [a, b], q2: {x: 1}, q5: 3.5}\n")
    add("shapes.yaml")
    # every hostile answer of the single-answer tests, to every question
    for k, text in enumerate(HOSTILE):
        _folder(root, f"hostile{k:02d}", {f"{q}.txt": text for q in QIDS})
        add(f"hostile{k:02d}/")
    return honest, hostile


__all__ = ["CANARY", "QIDS", "build"]
