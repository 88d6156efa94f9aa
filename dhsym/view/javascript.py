"""The robot's functions in JavaScript, for the view: printed from the export room's
programs (:func:`dhsym.export.program.links_program`, :func:`~dhsym.export.program.fk_program`)
with sympy's JavaScript printer, as the C and Rust are printed from them.

:func:`robot_script` is one expression statement, ``const DHSYM_ROBOT = (() => {…})();``,
whose value has ``n``, ``fk(q)`` (world to tool, 16 numbers row by row: ``robot.fk``),
``jacobian(q)`` (the geometric Jacobian of ``robot.jacobian(q)``, 6 × n row by row) and
``links(q)`` (for each link its matrix ``^{i-1}T_i``, 12 numbers, and the bend point of its
row, 3 numbers). Only the name ``DHSYM_ROBOT`` is declared at the top level, so it can follow
the bundled view in one script.

Examples
--------
>>> import dhsym
>>> text = robot_script(dhsym.load("planar2r"))
>>> text.splitlines()[0]
'const DHSYM_ROBOT = (() => {'
>>> print([line for line in text.splitlines() if "c12 =" in line][0].strip())
const c12 = Math.cos(q1 + q2);
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import sympy as sp
from sympy.printing.jscode import JavascriptCodePrinter

from dhsym.export.program import Program, fk_program, jacobian_program, links_program

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = ["JavaScriptPrinter", "robot_script"]


class JavaScriptPrinter(JavascriptCodePrinter):
    """sympy's JavaScript printer, numbers to 17 digits (as the programs give them)."""

    def _print_Float(self, expr: sp.Float) -> str:
        return repr(float(expr))


def _function(name: str, program: Program, printer: JavaScriptPrinter, out: str) -> list[str]:
    lines = [f"  function {name}(q) {{"]
    lines += [f"    const {j} = q[{k}];" for k, j in enumerate(program.joints)]
    lines += [f"    const {a.name} = {printer.doprint(a.expr)};" for a in program.body]
    values = ", ".join(printer.doprint(o.expr) for o in program.outputs)
    lines += [f"    {out.format(values=values)}", "  }"]
    return lines


def robot_script(robot: KinematicChain) -> str:
    """``const DHSYM_ROBOT = …;``: the robot's ``n``, ``fk`` and ``links`` in JavaScript.

    The table needs values for its lengths (``table.with_values``); a symbol without one is
    a :class:`~dhsym.errors.DHError` naming it.
    """
    printer = JavaScriptPrinter()
    links = links_program(robot)
    lines = ["const DHSYM_ROBOT = (() => {", '  "use strict";']
    lines += _function("fk", fk_program(robot), printer, "return [{values}];")
    lines += _function("jacobian", jacobian_program(robot), printer, "return [{values}];")
    lines += _function("links", links, printer, "const v = [{values}];")[:-1]
    lines += [
        "    const out = [];",
        f"    for (let i = 0; i < {robot.n}; i++) {{",
        "      out.push(v.slice(16 * i, 16 * i + 15));",
        "    }",
        "    return out;",
        "  }",
        f"  return {{ n: {robot.n}, fk, jacobian, links }};",
        "})();",
    ]
    return "\n".join(lines) + "\n"
