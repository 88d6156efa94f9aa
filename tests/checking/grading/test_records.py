"""GradeRecord: the dict of the grading cache both ways, pickling, malformed entries."""

from __future__ import annotations

import json
import pickle
from types import SimpleNamespace as NS

import pytest

from dhsym.checking.grading.batch import _cached_record
from dhsym.checking.grading.records import GradeRecord

GRADED = GradeRecord(
    uid="alice",
    student="alice",
    name="Alice",
    source="alice/",
    flags=("duplicate id: 2 submissions",),
    status="graded",
    scores={"q1": 4.0, "q2": 0.0},
    verdicts={"q1": "correct", "q2": "incorrect"},
    kinds=("wrong_sign",),
    score=4.0,
    max_score=6.0,
    wrong={"q1": (), "q2": (("(1,4)", "-a2*C1"),)},
    mistakes={"q1": (), "q2": ("wrong_sign",)},
    fingerprint="0123abcd",
    pages={"md": "# Feedback\n", "html": "<p>Feedback</p>"},
)
ASSIGNMENT = NS(questions=[NS(id="q1", points=4.0), NS(id="q2", points=2.0)], max_score=6.0)


def test_to_dict_is_the_cache_shape_and_from_dict_reads_it_back():
    d = GRADED.to_dict()
    assert d == {
        "uid": "alice",
        "student": "alice",
        "name": "Alice",
        "source": "alice/",
        "flags": ["duplicate id: 2 submissions"],
        "status": "graded",
        "scores": {"q1": 4.0, "q2": 0.0},
        "verdicts": {"q1": "correct", "q2": "incorrect"},
        "kinds": ["wrong_sign"],
        "wrong": {"q1": [], "q2": [["(1,4)", "-a2*C1"]]},
        "mistakes": {"q1": [], "q2": ["wrong_sign"]},
        "score": 4.0,
        "max": 6.0,
        "fingerprint": "0123abcd",
    }
    assert list(d) == list(json.loads(json.dumps(d)))  # the key order the cache is written in
    back = GradeRecord.from_dict(json.loads(json.dumps(d)))
    assert back == GRADED and back.pages == {}  # the pages are files, not cached
    assert json.dumps(back.to_dict()) == json.dumps(d)


def test_a_failed_record_round_trips_with_its_error():
    failed = GradeRecord(
        "bob",
        "bob",
        "Bob",
        "bob.yaml",
        (),
        "error: disk on fire",
        {"q1": 0.0},
        {"q1": "error"},
        ("error",),
        0.0,
        4.0,
        error="disk on fire",
    )
    d = failed.to_dict()
    assert d["error"] == "disk on fire" and "fingerprint" not in d
    assert "wrong" not in d and "mistakes" not in d  # the shape grade() has always had
    assert GradeRecord.from_dict(d) == failed


def test_a_record_pickles_with_its_pages():
    back = pickle.loads(pickle.dumps(GRADED))
    assert back == GRADED and back.pages == GRADED.pages


@pytest.mark.parametrize(
    "change",
    [
        {"scores": "all of them"},
        {"score": 1e999},
        {"score": "4"},
        {"max": None},
        {"flags": "duplicate id"},
        {"kinds": [1]},
        {"verdicts": {"q1": 1}},
        {"wrong": {"q2": 5}},
        {"wrong": {"q2": [["(1,4)"]]}},
        {"mistakes": {"q2": "wrong_sign"}},
        {"uid": None},
        {"fingerprint": 7},
    ],
)
def test_from_dict_refuses_a_malformed_entry(change):
    with pytest.raises(ValueError, match="a grade record needs"):
        GradeRecord.from_dict({**GRADED.to_dict(), **change})
    assert _cached_record({**GRADED.to_dict(), **change}, ASSIGNMENT) is None


def test_only_a_final_record_of_these_questions_is_taken_from_the_cache():
    assert _cached_record(GRADED.to_dict(), ASSIGNMENT) == GRADED
    for change in (
        {"status": "timeout"},
        {"verdicts": {"q1": "correct", "q2": "timeout"}},
        {"scores": {"q1": 4.0}},
        {"fingerprint": ""},
        # issue 25: scores outside [0, points], a total that is not their sum, another maximum
        {"scores": {"q1": 999.0, "q2": 0.0}, "score": 999.0},
        {"scores": {"q1": 1e308, "q2": 0.0}, "score": 1e308},
        {"scores": {"q1": -1.0, "q2": 0.0}, "score": -1.0},
        {"score": 10.0},
        {"max": 10.0},
    ):
        assert _cached_record({**GRADED.to_dict(), **change}, ASSIGNMENT) is None
    partial = GRADED.to_dict()
    del partial["fingerprint"]
    assert _cached_record(partial, ASSIGNMENT) is None
    assert _cached_record([], ASSIGNMENT) is None
