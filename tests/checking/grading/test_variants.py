"""A variant per student: the seeding, the class's draw without duplicates, the
assignment's ``variants:`` and its errors, grading each student against their own key."""

from __future__ import annotations

import hashlib
import hmac
from pathlib import Path

import pytest
import sympy as sp

from dhsym.checking.grading.assignment import Assignment
from dhsym.checking.grading.batch import grade
from dhsym.checking.grading.variants import (
    ClassList,
    VariantSpec,
    class_variants,
    list_variants,
    new_secret,
    variant_id,
)
from dhsym.errors import DHError

SECRET = b"0123456789abcdef0123"
HW = """title: HW variants
key: planar2r
secret: hw.secret
variants:
  a1: {from: 0.3, to: 0.5, step: 0.05}
  a2: [0.2, 0.25]
  q1: {values: [30, 45, 60], unit: deg}
questions:
  - {id: q1, ask: T0_2, points: 2}
  - {id: q2, ask: "ik@q1,0.5", points: 1}
"""


def right_t02(a1: str, a2: str) -> str:
    return (
        f"[[C12, -S12, 0, {a1}*C1 + {a2}*C12], [S12, C12, 0, {a1}*S1 + {a2}*S12], "
        "[0, 0, 1, 0], [0, 0, 0, 1]]"
    )


@pytest.fixture
def hw(tmp_path: Path) -> Path:
    (tmp_path / "hw.secret").write_text("s3cret-for-the-tests-0123456789\n")
    (tmp_path / "hw.yaml").write_text(HW)
    return tmp_path / "hw.yaml"


def test_values_are_exact_decimals_and_degrees():
    spec = VariantSpec.parse(
        {"a": {"from": 0.1, "to": 0.3, "step": 0.1}, "q": ["30°", "45 deg", "pi/3"]}, SECRET, "T"
    )
    a, q = spec.quantities
    assert a.values == (sp.Rational(1, 10), sp.Rational(2, 10), sp.Rational(3, 10))
    assert a.shown == ("0.1", "0.2", "0.3")  # no 0.30000000000000004
    assert q.values == (sp.pi / 6, sp.pi / 4, sp.pi / 3) and q.shown[:2] == ("30°", "45°")


def test_the_seed_is_the_keyed_hmac_of_the_normalised_id():
    spec = VariantSpec.parse({"a": list(range(1000))}, SECRET, "T")
    # NFC and case folding, as grading compares ids
    assert spec.draw("José") == spec.draw("jose\u0301") == spec.draw("JOSÉ")
    # reproducible: recomputed by hand from the documented message
    message = b"\0".join([b"dhsym-variant-v1", spec.label.encode(), b"alice", b"0"]) + b"\0a"
    index = int.from_bytes(hmac.new(SECRET, message, hashlib.sha256).digest()[:8], "big") % 1000
    assert dict(spec.draw("alice").values)["a"] == index
    # another secret gives other values: a student's values do not follow from the id
    other = VariantSpec.parse({"a": list(range(1000))}, b"another-secret-1234", "T")
    ids = [f"s{k}" for k in range(20)]
    assert [spec.draw(s).values for s in ids] != [other.draw(s).values for s in ids]


def test_no_duplicates_while_the_ranges_allow():
    spec = VariantSpec.parse({"a": [1, 2, 3], "b": [1, 2]}, SECRET, "T")
    six = class_variants(spec, [f"s{k}" for k in range(6)])
    assert len({v.values for v in six.values()}) == 6  # every combination once
    nine = class_variants(spec, [f"s{k}" for k in range(9)])
    counts: dict[object, int] = {}
    for v in nine.values():
        counts[v.values] = counts.get(v.values, 0) + 1
    assert sorted(counts.values()) == [1, 1, 1, 2, 2, 2]  # each once before any twice
    # deterministic, whatever the order of the class list
    assert class_variants(spec, [f"s{k}" for k in reversed(range(6))]) == six


def test_class_list(tmp_path: Path):
    p = tmp_path / "class.csv"
    p.write_text("Submission,Name\nalice,Alice\n\nJosé,\n")
    assert ClassList.load(p).students == (("alice", "Alice"), ("José", "José"))
    p.write_text("student\nalice\nALICE\n")
    with pytest.raises(DHError, match="row 3.*already"):
        ClassList.load(p)
    p.write_text("email\na@b\n")
    with pytest.raises(DHError, match="'submission' or 'student' column"):
        ClassList.load(p)


def test_listing_formats():
    spec = VariantSpec.parse({"a2": [0.4, 0.5], "q1": ["-30°", "30°"]}, SECRET, "HW")
    roster = ClassList((("=cmd()", "Eve"), ("bo", "Bo")))
    csv_text = list_variants(spec, roster, "csv")
    assert csv_text.splitlines()[0] == "student,name,a2,q1"
    assert csv_text.splitlines()[1].startswith("'=cmd()")  # a formula is neutralised
    assert '"students"' in list_variants(spec, roster, "json")
    assert list_variants(spec, roster).endswith("2 students, 2 distinct variants of 4\n")


@pytest.mark.parametrize(
    ("variants", "message", "field"),
    [
        ("[1, 2]", "mapping of names", "variants"),
        ("{a1: {from: 1, to: 0, step: 1}}", "from <= to", "variants.a1"),
        ("{a1: {from: 0, to: 1, step: 0.00001}}", "at most 10000", "variants.a1"),
        ("{a1: [0.1, 0.10]}", "listed twice", "variants.a1[2]"),
        ("{a1: [x + 1]}", "not a real number", "variants.a1[1]"),
        ("{a1: {values: [1], unit: grad}}", "deg or rad", "variants.a1.unit"),
        ("{q1: [0.5], zz: [1, 2]}", "used by no question", "variants.zz"),
    ],
)
def test_bad_variants_name_the_file_and_field(hw: Path, variants, message, field):
    text = HW.replace(HW[HW.index("variants:") : HW.index("questions:")], f"variants: {variants}\n")
    hw.write_text(text)
    with pytest.raises(DHError, match=message) as err:
        Assignment.load(hw)
    assert err.value.file == str(hw) and err.value.field == field


def test_variants_without_a_secret_are_refused(hw: Path):
    hw.write_text(HW.replace("secret: hw.secret\n", ""))
    with pytest.raises(DHError, match="secret only the instructor keeps") as err:
        Assignment.load(hw)
    assert err.value.field == "secret"
    hw.write_text(HW)
    (hw.parent / "hw.secret").write_text("short\n")
    with pytest.raises(DHError, match="at least 16"):
        Assignment.load(hw)


def test_new_secret_is_private_and_never_overwritten(tmp_path: Path):
    p = new_secret(tmp_path / "s")
    assert p.stat().st_mode & 0o777 == 0o600 and len(p.read_text().strip()) == 64
    with pytest.raises(DHError, match="exists already"):
        new_secret(p)


def test_for_variant_puts_the_values_into_the_keys(hw: Path):
    a = Assignment.load(hw)
    assert a.variants is not None and a.variants.names == ("a1", "a2", "q1")
    v = a.variants.draw("alice")
    mine = a.for_variant(v)
    values = dict(v.values)
    t02, ik = mine.questions
    assert not t02.key.table.constants  # the symbols replaced by the numbers
    assert t02.key.table.rows[0].a == values["a1"]
    assert ik.key.question.pose == pytest.approx((float(values["q1"]), 0.5))
    assert mine.fingerprint != a.fingerprint and mine.variant == v
    # an assignment without variants is untouched
    assert mine.questions[0].id == "q1" and a.questions[0].key.table.constants


def test_grade_checks_each_student_against_their_own_key(hw: Path, tmp_path: Path):
    roster = tmp_path / "class.csv"
    roster.write_text("student\nalice\nbob\ncarol\n")
    hw.write_text(  # the matrix question only: an IK key per variant takes long to prepare
        HW.replace("  q1: {values: [30, 45, 60], unit: deg}\n", "").replace(
            '  - {id: q2, ask: "ik@q1,0.5", points: 1}\n', ""
        )
    )
    a = Assignment.load(hw)
    assert a.variants is not None
    drawn = class_variants(a.variants, ["alice", "bob", "carol"])
    mine = dict(drawn[variant_id("alice")].shown)
    # a student whose lengths differ from alice's copies her answer
    copier = next(
        s
        for s in ("bob", "carol")
        if dict(drawn[s].shown)[("a1")] != mine["a1"] or dict(drawn[s].shown)["a2"] != mine["a2"]
    )
    subs = tmp_path / "subs"
    for who in ("alice", copier, "dan"):
        (subs / who).mkdir(parents=True)
        (subs / who / "q1.txt").write_text(right_t02(mine["a1"], mine["a2"]))
    with pytest.raises(DHError, match="--variants"):
        grade(hw, subs, tmp_path / "out", workers=0, progress=False)
    report = grade(hw, subs, tmp_path / "out", workers=0, progress=False, variants=roster)
    rec = {r.student: r for r in report.records}
    assert rec["alice"].verdicts["q1"] == "correct"
    assert rec[copier].verdicts["q1"] == "incorrect"
    assert rec["dan"].status.startswith("error: not on the class list")
    page = (tmp_path / "out" / "feedback" / "alice.md").read_text()
    assert f"**Your values:** {drawn[variant_id('alice')].text()}" in page
    # a rerun reuses the cache of each student's own key
    again = grade(hw, subs, tmp_path / "out", workers=0, progress=False, variants=roster)
    assert again.skipped == 2 and again.graded == 0


def test_feedback_without_variants_has_no_values_line(tmp_path: Path):
    ex = Path(__file__).resolve().parents[3] / "examples" / "homework"
    report = grade(
        ex / "assignment.yaml", ex / "submissions", tmp_path / "o", workers=0, progress=False
    )
    assert report.graded == 10
    assert "Your values" not in (tmp_path / "o" / "feedback" / "alice.md").read_text()


def test_a_profile_drawn_per_student_is_graded_against_their_own_values(tmp_path: Path):
    (tmp_path / "hw.secret").write_text("s3cret-for-the-tests-0123456789\n")
    (tmp_path / "hw.yaml").write_text(
        "title: HW profiles\nsecret: hw.secret\nvariants: {T: [2, 3, 4, 5], Q: [1, 2]}\n"
        "questions:\n"
        '  - {id: t1, ask: traj a2, key: "cubic(q0=0, qf=Q, tf=T)"}\n'
        '  - {id: t2, ask: "q@T/2", key: "quintic(q0=0, qf=Q, tf=T)"}\n'
    )
    a = Assignment.load(tmp_path / "hw.yaml")
    assert a.variants is not None and a.variants.names == ("T", "Q")
    roster = tmp_path / "class.csv"
    roster.write_text("student\nalice\nbob\ncarol\n")
    drawn = class_variants(a.variants, ["alice", "bob", "carol"])
    values = {s: {k: v for k, v in drawn[s].values} for s in ("alice", "bob", "carol")}
    mine = a.for_variant(drawn["alice"])
    assert (
        mine.questions[0].key.name
        == f"cubic(q0=0, qf={values['alice']['Q']}, tf={values['alice']['T']})"
    )
    a2 = {s: 3 * v["Q"] / v["T"] ** 2 for s, v in values.items()}
    copier = next(s for s in ("bob", "carol") if a2[s] != a2["alice"])
    subs = tmp_path / "subs"
    for who in ("alice", copier):
        (subs / who).mkdir(parents=True)
        (subs / who / "t1.txt").write_text(str(a2["alice"]))
        (subs / who / "t2.txt").write_text(f"{values[who]['Q']}/2")  # the midpoint, their own
    report = grade(
        tmp_path / "hw.yaml", subs, tmp_path / "out", workers=0, progress=False, variants=roster
    )
    rec = {r.student: r for r in report.records}
    assert rec["alice"].verdicts == {"t1": "correct", "t2": "correct"}
    assert rec[copier].verdicts == {"t1": "incorrect", "t2": "correct"}
    page = (tmp_path / "out" / "feedback" / "alice.md").read_text()
    assert f"**Your values:** {drawn['alice'].text()}" in page
