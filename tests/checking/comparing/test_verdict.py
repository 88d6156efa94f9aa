"""Result values and their JSON."""

from __future__ import annotations

import json

from dhsym.checking import Key, check_answer
from dhsym.checking.comparing.verdict import CheckResult, Verdict


def test_exit_codes():
    assert [v.exit_code for v in Verdict] == [0, 1, 2]


def test_json_round_trip_and_schema_keys():
    r = check_answer(
        Key.load("planar2r", "T0_2"), "[[C12, S12, 0, 0], [S12, C12, 0, 0], [0,0,1,0]]"
    )
    data = json.loads(json.dumps(r.to_json()))
    assert set(data) == {
        "schema",
        "key",
        "question",
        "verdict",
        "message",
        "reason",
        "alternative",
        "diagnosis",
        "entries",
        "expected_table",
        "answer_table",
    }
    assert data["schema"] == 1 and data["verdict"] == "incorrect"
    assert set(data["entries"][0]) == {
        "row",
        "col",
        "verdict",
        "answer",
        "expected",
        "answer_latex",
        "expected_latex",
        "proof",
        "rounding",
    }
    assert CheckResult.from_json(data) == r
