"""``dhsym derive --what jacobian|singularities|screws|ik|dynamics --format json``: as JSON.

Each object has ``schema``, ``dhsym`` (version), ``robot``, ``convention``, ``what`` and
``variables``; every formula comes three ways: ``compact`` (C/S notation), ``full``
(cos/sin, ``atan2``, ``sqrt``: readable back by the parser) and ``latex``. docs/reference/json.md
documents the fields.

Examples
--------
>>> from dhsym import load
>>> d = jacobian_json(load("planar2r"))
>>> d["what"], d["compact"][0], d["columns"][1]["axis"]
('jacobian', ['-a1*S1 - a2*S12', '-a2*S12'], ['0', '0', '1'])
>>> s = singularities_json(load("planar2r"))
>>> s["measure"], s["determinant"]["compact"], [f["kind"] for f in s["factors"]]
('det J_v', 'a1*a2*S2', ['constant', 'constant', 'elbow'])
>>> ik = ik_json(load("planar2r"))
>>> ik["count"], ik["steps"][-1]["lhs"], ik["steps"][-1]["rhs"]["full"]
(2, 'theta1', 'atan2(p_y, p_x) - atan2(a2*sin(theta2), a1 + a2*cos(theta2))')
"""

from __future__ import annotations

from collections.abc import Callable

import sympy as sp

from dhsym.kinematics.jacobian import geometric_jacobian
from dhsym.kinematics.singularities import singularities
from dhsym.notation.layout import Math
from dhsym.notation.printers import Notation
from dhsym.robot import Robot

from .common import JSON_SCHEMA_VERSION, json_head

__all__ = [
    "JSON_SCHEMA_VERSION",
    "derivation_json",
    "dynamics_json",
    "ik_json",
    "jacobian_json",
    "control_json",
    "screws_json",
    "singularities_json",
    "trajectory_json",
]


def _formula(robot: Robot, expr: object) -> dict[str, str]:
    """One formula three ways: compact, full (parser-readable) and LaTeX."""
    full = Notation(robot.notation.labels, compact=False)
    return {
        "compact": robot.notation.text(expr),
        "full": full.text(expr),
        "latex": robot.notation.latex(expr),
    }


def _head(robot: Robot, what: str) -> dict[str, object]:
    return {**json_head(robot), "what": what, "variables": [str(v) for v in robot.variables]}


def _grid(fn: Callable[[sp.Expr], str], M: sp.MatrixBase) -> list[list[str]]:
    return [[fn(M[r, c]) for c in range(M.cols)] for r in range(M.rows)]


def _legend(robot: Robot, exprs: list[sp.Expr]) -> list[dict[str, str]]:
    return [{"abbrev": e.text, "meaning": e.meaning_text} for e in robot.notation.legend(exprs)]


def jacobian_json(
    robot: Robot, frame: int | str = "base", point: int | str = "tool"
) -> dict[str, object]:
    """The geometric Jacobian: ``frame``, ``point``, ``columns`` (each ``index``, ``joint``,
    ``variable``, ``axis_frame``, ``axis``, ``lever`` (null for a prismatic joint),
    ``column``), ``compact``/``matrix``/``latex`` (6×n) and ``legend``."""
    J = geometric_jacobian(robot, frame, point)
    full = Notation(robot.notation.labels, compact=False)
    text = robot.notation.text
    columns = [
        {
            "index": i,
            "joint": c.joint.value,
            "variable": str(c.variable),
            "axis_frame": c.axis_frame,
            "axis": [text(x) for x in c.axis],
            "lever": [text(x) for x in c.lever] if c.joint.value == "R" else None,
            "column": [text(x) for x in (*c.linear, *c.angular)],
        }
        for i, c in enumerate(J.columns, start=1)
    ]
    return {
        **_head(robot, "jacobian"),
        "frame": J.frame,
        "point": J.point,
        "columns": columns,
        "compact": _grid(text, J.matrix),
        "matrix": _grid(full.text, J.matrix),
        "latex": _grid(robot.notation.latex, J.matrix),
        "legend": _legend(robot, list(J.matrix)),
    }


def singularities_json(robot: Robot) -> dict[str, object]:
    """The factored determinant: ``measure``, ``method``, ``determinant`` (a formula),
    ``blocks`` (``name``, ``frame``, ``determinant``) and ``factors`` (``kind``, ``name``,
    ``description``, ``factor``, ``power``, ``zeros``: ``[{variable, value}]``)."""
    s = singularities(robot)
    return {
        **_head(robot, "singularities"),
        "measure": s.measure,
        "method": s.method,
        "determinant": _formula(robot, s.determinant),
        "blocks": [
            {"name": b.name, "frame": b.frame, "determinant": _formula(robot, b.determinant)}
            for b in s.blocks
        ],
        "factors": [
            {
                "kind": f.kind,
                "name": f.name,
                "description": f.description,
                "factor": _formula(robot, f.expr),
                "power": f.power,
                "zeros": [
                    {"variable": str(v), "value": _formula(robot, z)} for v, z in f.solutions
                ],
            }
            for f in s.factors
        ],
        "legend": _legend(robot, [s.determinant]),
    }


def ik_json(robot: Robot) -> dict[str, object]:
    """The closed-form inverse kinematics: ``structure``, ``pose`` (the 4×4 pose symbols),
    ``branches`` (``symbol``, ``role``, ``joint``, ``meaning``), ``count`` and ``steps``
    (``part``, ``sentence``, ``lhs``, ``rhs``, ``equation`` (``{lhs, rhs}`` or null),
    ``branch`` (the sign it introduces, or null), ``singular`` (or null))."""
    ik = robot.inverse()
    steps = []
    for st in ik.steps:
        steps.append(
            {
                "part": st.part,
                "sentence": st.sentence.text(robot.notation),
                "lhs": str(st.lhs),
                "rhs": _formula(robot, st.rhs),
                "equation": (
                    {
                        "lhs": _formula(robot, st.equation.lhs),
                        "rhs": _formula(robot, st.equation.rhs),
                    }
                    if st.equation is not None
                    else None
                ),
                "branch": str(st.branch.symbol) if st.branch is not None else None,
                "singular": _formula(robot, st.singular) if st.singular is not None else None,
            }
        )
    return {
        **_head(robot, "ik"),
        "structure": ik.structure,
        "pose": [[str(x) for x in row] for row in ik.pose.tolist()],
        "branches": [
            {
                "symbol": str(b.symbol),
                "role": b.role,
                "joint": b.joint,
                "meaning": b.sentence.text(robot.notation),
            }
            for b in ik.branches
        ],
        "count": ik.count,
        "steps": steps,
        "legend": _legend(robot, [st.rhs for st in ik.steps]),
    }


def dynamics_json(robot: Robot) -> dict[str, object]:
    """The equations of motion: ``rates``, ``accelerations``, ``gravity``, ``energies``
    (``link``, ``kinetic``, ``potential``), ``links`` (``link``, ``m``, ``r``, ``I``: each
    link's mass, centre of mass and inertia), ``M`` and ``C`` (n×n formulas), ``christoffel`` (the
    nonzero ``c_ijk``, ``i ≤ j``: ``i``, ``j``, ``k`` (1-based), ``value``), ``g``, ``tau``
    and ``newton_euler`` (``sweep``, ``name``, ``link``, ``rule``, ``value``: formulas).

    >>> from dhsym import load
    >>> d = dynamics_json(load("planar2r"))
    >>> d["M"][1][1]["compact"], [c["i"] * 100 + c["j"] * 10 + c["k"] for c in d["christoffel"]]
    ('Izz2 + m2*(a2**2 + rx2**2 + ry2**2 + 2*a2*rx2)', [112, 121, 221])
    >>> d["links"][1]["m"]["compact"], d["C"][1][0]["compact"][:40]
    ('m2', 'm2*(a1*thetadot1*ry2*C2 + a1*thetadot1*a')
    """
    lag = robot.dynamics()
    ne = robot.dynamics(method="newton-euler")
    n = lag.M.rows
    f = lambda e: _formula(robot, e)  # noqa: E731
    return {
        **_head(robot, "dynamics"),
        "rates": [str(v) for v in lag.rates],
        "accelerations": [str(v) for v in lag.accelerations],
        "gravity": [f(x) for x in lag.model.gravity],
        "energies": [
            {"link": i, "kinetic": f(k), "potential": f(p)}
            for i, (k, p) in enumerate(zip(lag.kinetic, lag.potential, strict=True), start=1)
        ],
        "links": [
            {
                "link": i,
                "m": f(L.m),
                "r": [f(x) for x in L.r],
                "I": [[f(L.I[a, b]) for b in range(3)] for a in range(3)],
            }
            for i, L in enumerate(lag.model.links, start=1)
        ],
        "M": [[f(lag.M[i, j]) for j in range(n)] for i in range(n)],
        "C": [[f(lag.C[i, j]) for j in range(n)] for i in range(n)],
        "christoffel": [
            {"i": i + 1, "j": j + 1, "k": k + 1, "value": f(lag.christoffel[i][j][k])}
            for i in range(n)
            for j in range(i, n)
            for k in range(n)
            if lag.christoffel[i][j][k] != 0
        ],
        "g": [f(x) for x in lag.g],
        "tau": [f(x) for x in lag.tau],
        "newton_euler": [
            {
                "sweep": s.sweep,
                "name": s.name,
                "link": s.link,
                "rule": s.equation,
                "value": [f(x) for x in s.value],
            }
            for s in ne.steps
        ],
        "legend": _legend(robot, [*lag.M, *lag.g]),
    }


def trajectory_json(robot: Robot) -> dict[str, object]:
    """The profiles of a joint derived (:func:`dhsym.explain.trajectories.derive_trajectory`):
    per profile its conditions, linear system, assumptions, solution and ``q(t)``, each
    formula as text and LaTeX."""
    from dhsym.explain.trajectories import derive_trajectory

    d = derive_trajectory(robot)

    def both(m: Math) -> dict[str, str]:
        return {"text": m.text, "latex": str(m.latex)}

    return {
        **_head(robot, "trajectory"),
        "profiles": [
            {
                "key": s.key,
                "title": s.title,
                "source": s.source,
                "conditions": [both(c) for c in s.conditions],
                "system": None if s.system is None else both(s.system),
                "assumptions": [both(a) for a in s.assumptions],
                "solution": [both(x) for x in s.solution],
                "position": both(s.position),
            }
            for s in d.sections
        ],
    }


def control_json(robot: Robot) -> dict[str, object]:
    """The computed-torque closed loop derived (:func:`dhsym.explain.trajectories.derive_control`):
    its steps and the gains, each formula as text and LaTeX."""
    from dhsym.explain.trajectories import derive_control

    d = derive_control(robot)
    return {
        **_head(robot, "control"),
        "steps": [{"label": label, "text": m.text, "latex": str(m.latex)} for label, m in d.steps],
        "gains": [{"text": m.text, "latex": str(m.latex)} for m in d.gains],
    }


def screws_json(robot: Robot) -> dict[str, object]:
    """The screw axes (Lynch and Park, *Modern Robotics*; rows ``[ω; v]``): ``space`` and
    ``body`` (6×n) and ``home`` (M, 4×4), each ``compact``/``full``/``latex``; ``axes``
    (each ``index``, ``joint``, ``variable``, ``frame``, ``omega``, ``point``, ``v``), the
    ``formula`` (space and body) and ``legend``.

    >>> from dhsym import load
    >>> d = screws_json(load("planar2r"))
    >>> d["what"], d["space"]["compact"][4], d["axes"][1]["v"]
    ('screws', ['0', '-a1'], ['0', '-a1', '0'])
    """
    poe = robot.poe()
    text = robot.notation.text
    full = Notation(robot.notation.labels, compact=False)
    S, B = poe.screw_matrix("space"), poe.screw_matrix("body")

    def three(M: sp.MatrixBase) -> dict[str, list[list[str]]]:
        return {
            "compact": _grid(text, M),
            "full": _grid(full.text, M),
            "latex": _grid(robot.notation.latex, M),
        }

    axes = [
        {
            "index": s.joint,
            "joint": s.kind.value,
            "variable": str(s.variable),
            "frame": s.frame,
            "omega": [text(x) for x in s.omega * s.rate],
            "point": [text(x) for x in s.point] if s.kind.value == "R" else None,
            "v": [text(x) for x in s.v],
        }
        for s in poe.steps
    ]
    return {
        **_head(robot, "screws"),
        "space_frame": poe.frames[0],
        "tool_frame": poe.frames[1],
        "axes": axes,
        "home": three(poe.home),
        "space": three(S),
        "body": three(B),
        "formula": {"space": poe.formula_text("space"), "body": poe.formula_text("body")},
        "legend": _legend(robot, [*poe.home, *S, *B]),
    }


def derivation_json(robot: Robot, what: str) -> dict[str, object]:
    """The JSON of ``what`` (``jacobian``, ``singularities``, ``screws``, ``ik``,
    ``dynamics``, ``trajectory`` or ``control``)."""
    build = {
        "jacobian": jacobian_json,
        "singularities": singularities_json,
        "screws": screws_json,
        "ik": ik_json,
        "dynamics": dynamics_json,
        "trajectory": trajectory_json,
        "control": control_json,
    }
    return build[what](robot)
