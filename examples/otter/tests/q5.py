"""q5 (1 point): p_x of the PUMA 560, checked by dhsym."""

from otter.test_files import test_case

OK_FORMAT = False

name = "q5"
points = 1


@test_case()
def test_q5(q5):
    from dhsym.checking import assert_answer

    assert_answer(q5, key="puma560", question="T0_6[0,3]")
