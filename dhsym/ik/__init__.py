"""Inverse kinematics: one module per family (the general 6R in :mod:`.general6r`).

May import :mod:`dhsym.model`, :mod:`dhsym.notation` and :mod:`dhsym.kinematics`.
"""
