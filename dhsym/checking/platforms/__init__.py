"""Where grading meets a platform: autograders, LMS gradebooks and notebooks.

- :mod:`~dhsym.checking.platforms.autograder`: Gradescope and PrairieLearn autograder zips;
- :mod:`~dhsym.checking.platforms.gradebooks`: Canvas, Moodle and generic gradebook imports;
- :mod:`~dhsym.checking.platforms.selfcheck`: ``dhsym.check`` in Jupyter, and
  ``assert_answer`` for otter-grader and nbgrader cells.
"""
