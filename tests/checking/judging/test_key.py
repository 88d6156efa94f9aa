"""Key and PreparedKey: one frozen prepared part per kind of question, built once."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import dhsym
from dhsym.cache.memo import MEMO
from dhsym.checking import Key, check_answer
from dhsym.checking.judging.ik_key import IKPart
from dhsym.checking.judging.key import PREPARERS, PreparedKeys, TablePart, prepare
from dhsym.checking.judging.matrix_key import (
    DeterminantPart,
    DiagnosisSample,
    DynamicsPart,
    MatrixPart,
)

KEY = Key.load("planar2r", "T0_2")


def test_prepared_key_is_shared_by_a_workers_map_and_the_process_memo():
    keys = PreparedKeys()
    pk = keys.get(Key.load("planar2r", "T0_2"))
    assert keys.get(KEY) is pk and len(keys) == 1  # keyed by the frozen Key value
    assert prepare(KEY) is pk  # the process's memo: equal keys are prepared once
    assert PreparedKeys().get(KEY) is pk
    assert (
        check_answer(
            KEY,
            "[[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 + a2*S12], [0, 0, 1, 0]]",
            keys=keys,
        ).correct
        and len(keys) == 1
    )
    assert dhsym.load("planar2r").n == 2


@pytest.mark.parametrize(
    ("question", "kind"),
    [
        ("T0_2", MatrixPart),
        ("T0_2[0,3]", MatrixPart),
        ("J", MatrixPart),
        ("det J", DeterminantPart),
        ("M", DynamicsPart),
        ("ik", IKPart),
        ("table", TablePart),
    ],
)
def test_each_kind_has_its_own_frozen_part(question, kind):
    pk = prepare(Key.load("planar2r", question))
    assert type(pk.part) is kind
    assert PREPARERS[pk.key.question.kind] is not None
    with pytest.raises(dataclasses.FrozenInstanceError):
        pk.part = TablePart()  # type: ignore[misc]  # the prepared key is frozen too
    if dataclasses.fields(pk.part):
        name = dataclasses.fields(pk.part)[0].name
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(pk.part, name, None)


def test_matrix_parts_hold_typed_values():
    pk = PreparedKeys().get(Key.load("planar2r", "det J"))
    part = pk.part
    assert isinstance(part, DeterminantPart) and part.singularities.determinant == part.expected[0]
    assert isinstance(part.symbolic, DiagnosisSample) and isinstance(part.valued, DiagnosisSample)
    assert part.symbolic.key_values.shape == (part.symbolic.sample.size, 1, 1)
    dyn = prepare(Key.load("planar2r", "g")).part
    assert isinstance(dyn, DynamicsPart)
    assert {k for k, _, _ in dyn.variants} == {"gravity_direction", "l_for_lc"}
    assert prepare(Key.load("planar2r", "g")).names.symbol("qdot1") is not None


def test_ik_part_draws_its_diagnosis_poses_once():
    part = prepare(Key.load("planar2r", "ik")).part
    assert isinstance(part, IKPart) and part.pose is None
    assert set(part.diagnosis) == {False, True}  # planar2r's lengths have numbers
    assert part.diagnosis[True].sample.origin != part.diagnosis[False].sample.origin
    at = prepare(Key.load("planar2r", "ik@0.3,0.9")).part
    assert isinstance(at, IKPart) and at.pose is not None
    assert at.diagnosis[False].sample is at.pose and at.diagnosis[True].sample is at.pose
    assert np.allclose(at.pose.q, [[0.3, 0.9]])
    assert len(at.branch_names) == 2


def _count_builds(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """Every build of a mistake's variants from now on, by mistake kind (the builders of
    whole-matrix variants, whole-IK variants and one-step IK slips)."""
    from dhsym.checking.mistakes import _ik_mistakes, _mistake_base

    built: list[str] = []
    for owner, name in (
        (_mistake_base.Mistake, "build_variants"),
        (_ik_mistakes.IKStepEdit, "build_edits"),
        (_ik_mistakes.AtanForAtan2, "ik_variants"),
        (_ik_mistakes.WrongRootSign, "ik_variants"),
    ):
        original = getattr(owner, name)

        def counted(self, case, _original=original):  # type: ignore[no-untyped-def]
            built.append(self.kind)
            return _original(self, case)

        monkeypatch.setattr(owner, name, counted)
    return built


@pytest.mark.parametrize(
    ("robot", "question", "wrong"),
    [
        # the Jacobian of the 2R with a term of column 1 left out
        (
            "planar2r",
            "J",
            "[[-a2*S12, -a2*S12], [a2*C12, a2*C12], [0, 0], [0, 0], [0, 0], [1, 1]]",
        ),
        # the IK of the 2R with a slip in one step (a sign in theta1)
        (
            "planar2r",
            "ik",
            "D = (p_x**2 + p_y**2 - a1**2 - a2**2)/(2*a1*a2)\n"
            "theta2 = atan2(sqrt(1 - D**2), D)\n"
            "theta1 = atan2(p_y, p_x) + atan2(a2*sin(theta2), a1 + a2*cos(theta2))",
        ),
        (
            "puma560",
            "T0_2",
            "[[C1*C2, S1*C2, S2, 0], [-C1*S2, -S1*S2, C2, 0], [S1, -C1, 0, 0],"
            " [a2*C1*C2, a2*S1*C2, a2*S2, 1]]",
        ),
    ],
)
def test_a_prepared_key_diagnoses_its_first_wrong_answer_without_building(
    monkeypatch: pytest.MonkeyPatch, robot: str, question: str, wrong: str
) -> None:
    key = Key.load(robot, question)
    keys = PreparedKeys()
    pk = keys.get(key)  # before any answer's clock: everything the mistakes need is built
    built = _count_builds(monkeypatch)
    first = check_answer(key, wrong, keys=keys)
    assert first.verdict.value == "incorrect" and first.kinds
    assert first.kinds[0] != "unexplained"
    assert built == []  # the first wrong answer only compared with what was prepared
    # and a key prepared now (with the counters in place) does build them, once, here
    MEMO.clear()  # a new process, as far as the memo knows
    prepare(key)
    assert built, "the counters see the builders"
    del built[:]
    check_answer(key, wrong, keys=keys)
    assert built == [] and keys.get(key) is pk


def test_prepared_key_has_no_memo_to_fill():
    """A prepared key is frozen in fact: no mutable memo that answers fill."""
    pk = prepare(Key.load("planar2r", "ik"))
    assert not any(isinstance(v, dict) for v in vars(pk).values())
    with pytest.raises(dataclasses.FrozenInstanceError):
        pk.part = TablePart()  # type: ignore[misc]
    assert not hasattr(pk, "variant_values")


def test_a_key_unpickled_with_its_job_finds_the_prepared_key():
    """A sandbox child unpickles its jobs' assignment: the key objects are new and equal, and
    find the key prepared before the child forked (by value the first time, then by
    identity); many key objects later, a key is still found by value."""
    import pickle

    keys = PreparedKeys()
    pk = keys.get(KEY)
    copies = [pickle.loads(pickle.dumps(KEY)) for _ in range(100)]
    assert all(keys.get(k) is pk for k in copies) and len(keys) == 1
    assert all(keys.get(k) is pk for k in copies[:3])


def test_the_keys_mathml_is_converted_once_and_shown_for_wrong_entries():
    from dhsym.checking.grading.batch import warm_worker
    from dhsym.notation.mathml import latex_mathml

    keys = PreparedKeys()
    warm_worker((KEY,), keys)
    part = keys.get(KEY).part
    assert isinstance(part, MatrixPart) and part.expected_mathml.converted == 16
    r = check_answer(
        KEY,
        "[[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 - a2*S12],"
        " [0, 0, 1, 0], [0, 0, 0, 1]]",
        keys=keys,
    )
    wrong = [e for e in r.entries if not e.correct]
    assert [(e.row, e.col) for e in wrong] == [(2, 4)]
    assert wrong[0].expected_mathml == latex_mathml(wrong[0].expected_latex)
    assert all(e.expected_mathml == "" for e in r.entries if e.correct)


def test_a_key_is_prepared_once_per_process_for_equal_keys(monkeypatch):
    """Key.load prepares the key to check it; the check that follows, and a second
    Key.load of the same question (a notebook's next dhsym.check), find it prepared."""
    from dhsym.checking.judging import key as key_module

    MEMO.clear()
    built: list[str] = []
    original = key_module.PREPARERS["matrix"]

    def counted(*args, **kwargs):  # type: ignore[no-untyped-def]
        built.append("matrix")
        return original(*args, **kwargs)

    monkeypatch.setattr(key_module, "PREPARERS", {**key_module.PREPARERS, "matrix": counted})
    k = Key.load("planar2r", "T0_2")
    answer = "[[C12, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 + a2*S12], "
    answer += "[0, 0, 1, 0], [0, 0, 0, 1]]"
    assert check_answer(k, answer).correct
    assert prepare(Key.load("planar2r", "T0_2")) is prepare(k)
    assert built == ["matrix"]
    MEMO.clear()  # a new process, as far as the memo knows
    prepare(k)
    assert built == ["matrix", "matrix"]
