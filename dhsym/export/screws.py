r"""The screws part of the export: the product of exponentials (PoE) of a robot as code.

Lynch and Park, *Modern Robotics*, chapters 4 and 5.1: the tool pose in the space form
:math:`T(\theta) = e^{[\mathcal{S}_1]\theta_1} \cdots e^{[\mathcal{S}_n]\theta_n} M`
and the space and body Jacobians :math:`J_s`, :math:`J_b` with rows ``[ω; v]`` (the
angular part first, as the book writes a twist), read off the DH chain at home by
:func:`dhsym.screws.product.from_chain` (the space frame is the frame of ``fk``, the
tool frame its end). :func:`screw_programs` turns them into the same straight-line
:class:`~dhsym.export.program.Program` every language prints; ``what="screws"`` asks for
the three functions ``<prefix>_fk_space``, ``<prefix>_jacobian_space`` and
``<prefix>_jacobian_body`` (not among the default parts: an export without it is
unchanged), and the header of the files lists the screw axes and ``M``
(:func:`description_lines`).

Examples
--------
>>> import dhsym
>>> progs = screw_programs(dhsym.load("planar2r"))
>>> (progs.jacobian_space.rows, progs.jacobian_space.cols)
(6, 2)
>>> [str(o.expr) for o in progs.jacobian_space.outputs if o.row == 4]  # v_y: 0, -a1 cos q1
['0.0', '-c1']
>>> print(*description_lines(progs.poe), sep=chr(10))
Product of exponentials (Lynch and Park, Modern Robotics, ch. 4), twists as [w; v]:
T(theta) = e^([S1]*theta1) e^([S2]*theta2) M
Screw axes at home, in the frame of fk (S_i) and in the tool frame (B_i = Ad(M^-1) S_i):
  joint  S_i                  B_i
  1      (0, 0, 1, 0, 0, 0)    (0, 0, 1, 0, a1 + a2, 0)
  2      (0, 0, 1, 0, -a1, 0)  (0, 0, 1, 0, a2, 0)
Home configuration M (q = 0), by rows: (1, 0, 0, a1 + a2), (0, 1, 0, 0), (0, 0, 1, 0),
  (0, 0, 0, 1)
"""

from __future__ import annotations

import textwrap
from dataclasses import dataclass
from typing import TYPE_CHECKING

from dhsym.screws.product import ProductOfExponentials, from_chain

from .program import Program, _program

if TYPE_CHECKING:
    import sympy as sp

    from dhsym.kinematics.chain import KinematicChain

__all__ = ["ScrewPrograms", "description_lines", "screw_programs"]


@dataclass(frozen=True)
class ScrewPrograms:
    """The PoE of a robot as programs: ``fk_space`` (4×4, the pose of ``fk``),
    ``jacobian_space`` and ``jacobian_body`` (6×n, rows ``[ω; v]``), and the ``poe`` they
    were derived from."""

    poe: ProductOfExponentials
    fk_space: Program
    jacobian_space: Program
    jacobian_body: Program


def screw_programs(robot: KinematicChain, *, symbolic_lengths: bool = False) -> ScrewPrograms:
    r"""The space-form fk :math:`e^{[\mathcal{S}_1]\theta_1}\cdots M` and the Jacobians
    :math:`J_s`, :math:`J_b` of ``robot`` (exact, compact, from
    :class:`~dhsym.screws.product.ProductOfExponentials`) as programs in the joint values
    ``q1 … qn`` and, with ``symbolic_lengths``, the parameters ``p`` of
    :func:`~dhsym.export.program.fk_program`.

    >>> import dhsym
    >>> progs = screw_programs(dhsym.load("planar2r"), symbolic_lengths=True)
    >>> [p.name for p in progs.fk_space.parameters], str(progs.fk_space.outputs[3].expr)
    (['p_a1', 'p_a2'], 'c1*p_a1 + c12*p_a2')
    """
    poe = from_chain(robot)
    return ScrewPrograms(
        poe,
        _program(robot, poe.fk_space().matrix, symbolic_lengths),
        _program(robot, poe.jacobian_space().matrix, symbolic_lengths),
        _program(robot, poe.jacobian_body().matrix, symbolic_lengths),
    )


def _vector(entries: sp.MatrixBase) -> str:
    return "(" + ", ".join(str(e) for e in entries) + ")"


def description_lines(poe: ProductOfExponentials) -> list[str]:
    """What the header of an export with ``screws`` says of the PoE: the formula, the
    space and body screw axes and ``M`` (plain text; the languages make them comments)."""
    space = [_vector(s.vector) for s in poe.space]
    body = [_vector(b.vector) for b in poe.body]
    rows = [("joint", "S_i", "B_i")]
    rows += [(str(k), s, b) for k, (s, b) in enumerate(zip(space, body), start=1)]
    widths = [max(len(r[c]) for r in rows) for c in range(2)]
    home = ", ".join(_vector(poe.home.row(i)) for i in range(4))
    return [
        "Product of exponentials (Lynch and Park, Modern Robotics, ch. 4), twists as [w; v]:",
        poe.formula_text("space"),
        "Screw axes at home, in the frame of fk (S_i) and in the tool frame (B_i = Ad(M^-1) S_i):",
        *(f"  {r[0].ljust(widths[0])}  {r[1].ljust(widths[1])}  {r[2]}".rstrip() for r in rows),
        *textwrap.wrap(
            f"Home configuration M (q = 0), by rows: {home}",
            width=88,
            subsequent_indent="  ",
            break_on_hyphens=False,
        ),
    ]
