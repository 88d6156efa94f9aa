"""Comparing: the tools every judge and every mistake share, below both.

- :mod:`~dhsym.checking.comparing.equivalence`: exact, then numeric sampling, equality of
  entries (:class:`~dhsym.checking.comparing.equivalence.Sample`);
- :mod:`~dhsym.checking.comparing.table_match`: two DH tables that give the same kinematics;
- :mod:`~dhsym.checking.comparing.verdict`: the result
  (:class:`~dhsym.checking.comparing.verdict.CheckResult`, ``Diagnosis``);
- :mod:`~dhsym.checking.comparing.tolerances`: the numeric tolerances and sample ranges;
- the key's values at sample points: :mod:`~dhsym.checking.comparing.sampled_frames` (DH
  frames), :mod:`~dhsym.checking.comparing.ik_values` (closed-form IK branches),
  :mod:`~dhsym.checking.comparing.dynamics_values` (the dynamics questions' keys).

Imports the reading room only: the judging room and the mistakes room build on it.
"""
