"""q3 (1 point): link matrix 3 of Example 4 (the 6-DOF arm with an offset), checked by dhsym."""

from otter.test_files import test_case

OK_FORMAT = False

name = "q3"
points = 1


@test_case()
def test_q3(q3):
    from dhsym.checking import assert_answer

    assert_answer(q3, key="example4_6dof", question="T2_3")
