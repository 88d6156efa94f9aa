"""q4 (2 points): the generic link matrix ^{i-1}T_i (modified convention), checked by dhsym."""

from otter.test_files import test_case

OK_FORMAT = False

name = "q4"
points = 2


@test_case()
def test_q4(q4):
    from dhsym.checking import assert_answer

    assert_answer(q4, key="generic_modified_link.yaml", question="A1")
