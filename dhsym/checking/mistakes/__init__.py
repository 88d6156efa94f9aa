"""Mistakes: the classic ways a DH answer goes wrong, each recognised by recomputing the key.

:mod:`~dhsym.checking.mistakes.registry` lists them per kind of question and finds the one
that explains a wrong answer; the plug-ins hold the mistakes by family (table rows, matrix
entries, Jacobians, inverse kinematics, dynamics) on the base classes of
:mod:`~dhsym.checking.mistakes._mistake_base`.
"""
