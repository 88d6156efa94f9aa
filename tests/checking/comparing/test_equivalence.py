"""Numeric comparison at random points, then exact proof under limits."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from dhsym.checking.comparing.equivalence import (
    Sample,
    cancellation,
    close,
    prove_entry,
    values,
)

x, y = sp.symbols("x y", real=True)


def test_values_and_close():
    s = Sample.random([x, y], size=16)
    assert close(values(sp.sin(x) ** 2 + sp.cos(x) ** 2, s), np.ones(16))
    assert not close(values(sp.sin(x), s), values(sp.cos(x), s))
    M = values(sp.Matrix([[x, y]]), s)
    assert M.shape == (16, 1, 2)
    assert not close(values(sp.zoo, s), np.ones(16))  # non-finite is never equal


def test_sample_fixed_and_extended():
    s = Sample.random([x, y], fixed={y: 0.5})
    assert (s.env[y] == 0.5).all()
    z = sp.Symbol("z")
    assert z in s.extended([z]).env and s.extended([x]) is s


def test_prove_entry_exact_false_and_skipped():
    assert prove_entry(sp.cos(x + y), sp.cos(x) * sp.cos(y) - sp.sin(x) * sp.sin(y)) is True
    assert prove_entry(sp.cos(x), sp.cos(x) + sp.Rational(1, 10**30)) is False
    huge = (sp.cos(x) ** 2 + sp.sin(x) ** 2 + sp.cos(y) ** 2 + sp.sin(y) ** 2 - 1) ** 60
    assert prove_entry(huge, sp.Integer(1)) is None  # too large to expand: numbers decide
    assert prove_entry(sp.tan(x) * sp.cos(x), sp.sin(x)) is None  # not a trig polynomial


def test_sample_points_are_fresh_for_every_draw():
    first, second = Sample.random([x, y]), Sample.random([x, y])
    assert first.size == 64 and not np.allclose(first.table, second.table)
    assert first.origin != second.origin
    assert Sample.random([x], seed=5).table.tolist() == Sample.random([x], seed=5).table.tolist()
    z = sp.Symbol("z")
    assert first.extended([z]).origin == first.origin  # key symbols keep their values


def test_every_check_draws_its_own_points(monkeypatch):
    from dhsym.checking import Key, PreparedKeys, check_answer
    from dhsym.checking.comparing import equivalence

    drawn = []
    real = equivalence.Sample.random

    def spy(*args, **kwargs):
        drawn.append(real(*args, **kwargs))
        return drawn[-1]

    key, keys = Key.load("planar2r", "T0_2[0,3]"), PreparedKeys()
    check_answer(key, "a1 C1 + a2 C12", keys=keys)  # prepares the key (its diagnosis samples)
    monkeypatch.setattr(equivalence.Sample, "random", spy)
    assert check_answer(key, "a1 C1 + a2 C12", keys=keys).correct  # the worker's prepared key
    assert check_answer(key, "a1 C1 + a2 C12", keys=keys).correct
    assert len(drawn) == 2 and not np.allclose(drawn[0].table, drawn[1].table)


# The points the checker used before: numpy's default_rng(20240), 24 points in [-2.5, 2.5],
# rows in the order of the sorted symbols (planar 2R: a1, a2, theta1, theta2).
OLD_POINTS = np.random.default_rng(20240).uniform(-2.5, 2.5, size=(4, 24))


def vanishing(name: str, row: np.ndarray) -> str:
    """A product that is zero at every old point: (name - t_1)(name - t_2)…"""
    return "".join(f"({name} - ({float(v)!r}))" for v in row)


def test_crafted_term_vanishes_on_the_old_points():
    from dhsym.model.parsing import parse_expression

    term = parse_expression(vanishing("theta1", OLD_POINTS[2]))
    t1 = sp.Symbol("theta1", real=True)
    old = Sample((t1,), OLD_POINTS[2:3])
    assert np.abs(values(term, old)).max() == 0.0  # exactly zero in double precision
    assert np.abs(values(term, Sample.random([t1]))).max() > 1e-3


@pytest.mark.parametrize(
    ("question", "answer"),
    [
        ("T0_2[0,0]", "C12 + " + vanishing("theta1", OLD_POINTS[2])),
        ("T0_2[0,3]", "a1 C1 + a2 C12 + a1*a2*" + vanishing("theta1", OLD_POINTS[2])),
        ("T0_2[1,0]", "S12 - 3" + vanishing("theta2", OLD_POINTS[3])),
        (
            "T0_2",
            "[[C12 + {t}, -S12, 0, a1*C1 + a2*C12], [S12, C12, 0, a1*S1 + a2*S12 - {t}],"
            " [0, 0, 1, 0]]".format(t=vanishing("theta1", OLD_POINTS[2])),
        ),
    ],
)
def test_answers_crafted_to_vanish_on_the_old_fixed_points_are_graded_wrong(question, answer):
    from dhsym.checking import Key, check_answer

    result = check_answer(Key.load("planar2r", question), answer)
    assert result.verdict.value == "incorrect"


@pytest.mark.parametrize(
    ("answer", "key"),
    [
        (1 - 2 * sp.sin((x + y) / 2) ** 2, sp.cos(x + y)),
        (sp.cos(x / 2) ** 2 - sp.sin(x / 2) ** 2, sp.cos(x)),
        (2 * sp.sin(x / 2) * sp.cos(x / 2), sp.sin(x)),
        (4 * sp.cos(x / 3) ** 3 - 3 * sp.cos(x / 3), sp.cos(x)),
        ((sp.cos(x - y) + sp.cos(x + y)) / 2, sp.cos(x) * sp.cos(y)),
        (sp.sin(x + sp.pi / 2), sp.cos(x)),
    ],
)
def test_other_identities_are_proven_exactly(answer, key):
    assert prove_entry(answer, key) is True


def test_wrong_identities_are_disproven():
    assert prove_entry(1 - 2 * sp.sin(x) ** 2, sp.cos(x)) is False
    assert prove_entry(2 * sp.sin(x / 2) * sp.cos(x / 2), sp.cos(x)) is False


def test_cancellation_with_the_walks_memo_decides_as_without():
    """The sizes of an answer's sums taken from the values its walk computed (the memo of
    the answer and its key at the sample) decide as the sizes computed again."""
    x, y = sp.symbols("x y", real=True)
    key = sp.Matrix([[sp.cos(x), sp.sin(x) * y, x**2 + 1]])
    answers = [
        sp.Matrix([[(sp.cos(x) ** 2 + sp.sin(x) ** 2 - 1) * 10**13 + sp.cos(x), y, x**2]]),
        sp.Matrix([[sp.cos(x) + sp.Rational(1, 10**3), sp.sin(x) * y * (1 + 10**-14), 2]]),
        sp.Matrix([[sp.cos(90) * x, sp.sin(sp.pi / 180 * x) * 10**15 - 10**15, x**2 + 1]]),
    ]
    decided = set()
    for answer in answers:
        sample = Sample.random({x, y})
        memo: dict[object, np.ndarray] = {}
        diff = values(answer, sample, memo) - values(key, sample, memo)
        for j in range(3):
            plain = cancellation(answer[0, j], sample, diff[:, 0, j])
            assert cancellation(answer[0, j], sample, diff[:, 0, j], memo) == plain
            decided.add(plain)
    assert decided == {True, False}


def test_sample_symbols_keep_sympys_canonical_order():
    """Sample.random orders plain symbols by name: the order default_sort_key gives
    (seeded samples draw the same values per symbol as before)."""
    import random

    from dhsym.checking.comparing.equivalence import Sample, _ordered

    rng = random.Random(3)
    names = ["theta1", "theta10", "theta2", "a_1", "A", "a1", "Z", "lc2", "d_3", "alpha_im1"]
    for _ in range(200):
        picked = rng.sample(names, rng.randint(1, len(names)))
        syms = {sp.Symbol(n, real=rng.random() < 0.5) for n in picked}
        assert _ordered(syms) == tuple(sorted(syms, key=sp.default_sort_key))
    mixed = {sp.Symbol("x"), sp.Dummy("n"), sp.Symbol("b")}
    assert _ordered(mixed) == tuple(sorted(mixed, key=sp.default_sort_key))
    assert Sample.random(mixed, seed=5).symbols == tuple(sorted(mixed, key=sp.default_sort_key))
