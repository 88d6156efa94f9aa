"""Judging answers: is what the student wrote the key, and if not, which entries differ.

- :mod:`~dhsym.checking.judging.checker`: :class:`~dhsym.checking.judging.checker.Key` and
  :func:`~dhsym.checking.judging.checker.check_answer`, the one entry point;
- :mod:`~dhsym.checking.judging.equivalence`: exact, then numeric sampling, equality of entries;
- :mod:`~dhsym.checking.judging.table_match`: two DH tables that give the same kinematics;
- :mod:`~dhsym.checking.judging.ik_check`: inverse-kinematics answers, branch by branch;
- :mod:`~dhsym.checking.judging.rounding`, :mod:`~dhsym.checking.judging.tolerances`: what
  rounding of decimals is accepted, and the numeric tolerances;
- :mod:`~dhsym.checking.judging.verdict`: the result
  (:class:`~dhsym.checking.judging.verdict.CheckResult`).

Which mistake explains a wrong answer is the mistakes room's (:mod:`dhsym.checking.mistakes`).
"""
