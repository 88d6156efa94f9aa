"""Judging answers: is what the student wrote the key, and if not, which entries differ.

- :mod:`~dhsym.checking.judging.key`: :class:`~dhsym.checking.judging.key.Key` and the key
  prepared once (:class:`~dhsym.checking.judging.key.PreparedKey`), one part per kind of
  question, each built by its kind's preparer: :mod:`~dhsym.checking.judging.matrix_key`
  (matrices, ``det J``, dynamics), :mod:`~dhsym.checking.judging.ik_key` (inverse kinematics);
- :mod:`~dhsym.checking.judging.checker`: :func:`~dhsym.checking.judging.checker.check_answer`,
  the one entry point, which reads the answer and hands it to its kind's judge:
  :mod:`~dhsym.checking.judging.matrix_judge`, :mod:`~dhsym.checking.judging.table_judge`,
  :mod:`~dhsym.checking.judging.ik_check` (inverse-kinematics answers, branch by branch);
- :mod:`~dhsym.checking.judging.rounding`: what rounding of decimals is accepted.

The tools judges share with the mistakes (equivalence, table matching, the verdict, the
key's sampled values) are the comparing room's (:mod:`dhsym.checking.comparing`); which
mistake explains a wrong answer is the mistakes room's (:mod:`dhsym.checking.mistakes`).
"""
