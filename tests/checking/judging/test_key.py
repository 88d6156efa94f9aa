"""Key and PreparedKey: one frozen prepared part per kind of question, built once."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import dhsym
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


def test_prepared_key_is_shared_by_a_workers_map_and_nothing_else():
    keys = PreparedKeys()
    pk = keys.get(Key.load("planar2r", "T0_2"))
    assert keys.get(KEY) is pk and len(keys) == 1  # keyed by the frozen Key value
    assert prepare(KEY) is not pk  # no process-wide memo: another worker prepares its own
    assert PreparedKeys().get(KEY) is not pk
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
    assert set(part.diagnosis_poses) == {False, True}  # planar2r's lengths have numbers
    assert part.diagnosis_poses[True].origin != part.diagnosis_poses[False].origin
    at = prepare(Key.load("planar2r", "ik@0.3,0.9")).part
    assert isinstance(at, IKPart) and at.pose is not None and not at.diagnosis_poses
    assert np.allclose(at.pose.q, [[0.3, 0.9]])
    assert len(at.branch_names) == 2
