"""q1 (4 points): the DH table of the PUMA 560 (standard convention), checked by dhsym."""

from otter.test_files import test_case

OK_FORMAT = False

name = "q1"
points = 4


@test_case()
def test_q1(q1):
    from dhsym.checking import assert_answer

    assert_answer(q1, key="puma560", question="table")
