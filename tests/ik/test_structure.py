"""The family classifier: relations of consecutive axes, in either convention."""

from __future__ import annotations

import dhsym
from dhsym.ik import classify

from ._roundtrip import random_q, recovered


def test_the_classification_is_printed_from_the_axes_in_either_convention() -> None:
    ur5 = dhsym.load("ur5")
    assert str(classify(ur5)) == "axes 2, 3, 4 parallel"
    assert classify(ur5).family == "three parallel axes"
    modified = dhsym.Robot(dhsym.to_modified(ur5.table))
    assert str(classify(modified)) == "axes 2, 3, 4 parallel"
    assert str(classify(dhsym.load("puma560"))) == "axes 4, 5, 6 meet in a point"
    assert classify(dhsym.load("panda")).sentences == ("axes 1, 2, 3 meet in a point",)


def test_a_general_6r_is_solved_by_the_elimination() -> None:
    table = dhsym.load("puma560").table
    rows = list(table.rows)
    from dataclasses import replace

    rows[4] = replace(rows[4], a=0.05)
    rows[1] = replace(rows[1], alpha=0.3)
    r = dhsym.Robot(replace(table, rows=tuple(rows)))
    assert classify(r).family == "general 6R"
    assert r.inverse().family == "general 6R"
    assert recovered(r, random_q(r, 10)).all()
