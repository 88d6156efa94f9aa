"""q2 (2 points): the matrix ^0T_2 of the PUMA 560, checked by dhsym."""

from otter.test_files import test_case

OK_FORMAT = False

name = "q2"
points = 2


@test_case()
def test_q2(q2):
    from dhsym.checking import assert_answer

    assert_answer(q2, key="puma560", question="T0_2")
