"""Dynamics benchmarks: symbolic equations of motion and compiled ``rne``, against references
run in the same process.

Run ``python benchmarks/bench_dynamics.py`` (``--symbolic`` also derives the PUMA 560 with
fully symbolic inertial parameters, which takes minutes). Prints:

0. the PUMA 560 (and with ``--arms`` the Stanford arm and the UR5) in the compact form with
   grouped constants (``compact_dynamics``: goal ≤ 15 s), the terms of M11 (goal ≤ 30), the
   operation counts (``sympy.count_ops``) of M, C, g; the command ``dhsym derive puma560
   --what dynamics`` in a fresh process (Markdown and LaTeX, goal ≤ 60 s); the exported
   ``rne``'s multiplications and additions against Corke's 224 + 174; the first ``rne`` in a
   fresh process with an empty disk cache (goal ≤ 2 s);
1. the PUMA 560's symbolic M, C and g (Lagrange–Euler) with its published numeric inertial
   parameters (goal: under 30 s), and the Newton–Euler τ;
2. dhsym's Lagrange–Euler against ``sympy.physics.mechanics.LagrangesMethod`` on a planar
   2R and 3R arm with symbolic masses, lengths and inertias (same arm, same results);
3. the numeric ``rne`` (the recursion on numbers) of the PUMA 560 for a batch of 10⁵
   states and for one state, against pinocchio's ``rnea`` called from Python (when ``pin``
   is installed);
4. one state after the switch to the compiled program (``COMPILE_AFTER`` small calls):
   ``rne``, ``inertia``, ``gravload``, ``coriolis``, ``accel`` of the PUMA 560 in CPU time
   per call (``time.process_time``, best of 7 runs of 2000 calls, the load printed), through
   the C program (when a compiler is there; goal ≤ 5 µs per ``rne``) against the same
   program for Python floats (the NumPy path without a compiler) and against pinocchio's
   ``rnea``, ``crba``, ``computeCoriolisMatrix`` and ``aba`` in the same run (``pin``, a
   test extra; said when it is absent); and the first ``rne`` in a fresh process with an
   empty and with a warm disk cache.

``--only-numbers`` runs parts 3's one-state figures, 4 and the first calls only (a minute).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
import sympy as sp

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import dhsym  # noqa: E402
from dhsym.dynamics import lagrange, newton_euler  # noqa: E402
from dhsym.kinematics.simplification import prove_equal  # noqa: E402
from dhsym.model.tablefile import read_table_text  # noqa: E402
from dhsym.robot import Robot  # noqa: E402


def timed(f, *a, **k):
    t0 = time.perf_counter()
    out = f(*a, **k)
    return out, time.perf_counter() - t0


def planar(n: int) -> Robot:
    rows = "\n".join(
        f"  - {{type: R, theta: q{i}, d: 0, a: l{i}, alpha: 0, m: m{i}, "
        f"r: [lc{i} - l{i}, 0, 0], I: [0, I{i}, I{i}]}}"
        for i in range(1, n + 1)
    )
    return Robot(read_table_text(f"gravity: [0, -g, 0]\njoints:\n{rows}"))


def mechanics_planar(n: int) -> sp.Matrix:
    """The same planar arm with sympy.physics.mechanics: M from LagrangesMethod."""
    from sympy.physics import mechanics as me

    q = me.dynamicsymbols(f"q1:{n + 1}")
    g = sp.Symbol("g", real=True)
    N = me.ReferenceFrame("N")
    origin = me.Point("O")
    origin.set_vel(N, 0)
    joint = origin
    bodies, angle = [], 0
    for i in range(1, n + 1):
        m, ln, lc, inertia = (sp.Symbol(f"{s}{i}", real=True) for s in ("m", "l", "lc", "I"))
        angle = angle + q[i - 1]
        F = me.ReferenceFrame(f"F{i}")
        F.orient_axis(N, N.z, angle)
        F.set_ang_vel(N, sum(qq.diff() for qq in q[:i]) * N.z)
        C = joint.locatenew(f"C{i}", lc * F.x)
        C.v2pt_theory(joint, N, F)
        body = me.RigidBody(f"B{i}", C, F, m, (me.inertia(F, 0, inertia, inertia), C))
        body.potential_energy = m * g * C.pos_from(origin).dot(N.y)
        bodies.append(body)
        previous, joint = joint, joint.locatenew(f"J{i}", ln * F.x)
        joint.v2pt_theory(previous, N, F)  # both ends of link i are fixed in F_i
    L = me.Lagrangian(N, *bodies)
    lm = me.LagrangesMethod(L, q)
    lm.form_lagranges_equations()
    return lm.mass_matrix


def fresh(code: str, env: dict[str, str] | None = None) -> tuple[float, float]:
    """Wall time and CPU time (user + system) of ``code`` in a fresh Python process
    (imports included). On a shared machine the CPU time is the figure that carries over."""
    import os
    import resource
    import subprocess

    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", code], check=True, env={**os.environ, **(env or {})})
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def cpu_timed(f, *a, **k):
    """``(result, wall seconds, CPU seconds of this process)``."""
    w0, c0 = time.perf_counter(), time.process_time()
    out = f(*a, **k)
    return out, time.perf_counter() - w0, time.process_time() - c0


def op_counts(exprs: list[sp.Expr]) -> dict[str, int]:
    """``sympy.count_ops`` of ``exprs`` by kind (``MUL``, ``ADD``, ``POW``, ``NEG``, ``SIN``…)."""
    total = sp.Add(*(sp.count_ops(e, visual=True) for e in exprs))
    return {str(s): int(total.coeff(s)) for s in total.free_symbols} if total != 0 else {}


def flops_line(label: str, robot: dhsym.Robot) -> str:
    """The exported ``rne``'s floating-point operations: multiplications (squares counted as
    one each), additions and subtractions, negations; sines, cosines and the Coulomb
    friction's sign tests apart (they are no flops)."""
    from dhsym.export.program import rne_program

    prog = rne_program(robot)
    c = op_counts([a.expr for a in prog.body] + [o.expr for o in prog.outputs])
    mul = c.get("MUL", 0) + c.get("DIV", 0) + c.get("POW", 0)
    add = c.get("ADD", 0) + c.get("SUB", 0)
    flops = mul + add + c.get("NEG", 0)
    rest = ", ".join(f"{c[k]} {k.lower()}" for k in ("SIN", "COS", "COULOMB") if c.get(k))
    return (
        f"{label}: {mul} multiplications (squares included), {add} additions, "
        f"{c.get('NEG', 0)} negations: {flops} flops [goal <= 400]; also {rest}"
    )


def compact_figures(arms: list[str]) -> None:
    """Part 0: the compact form, the command line, the exported rne, the first call."""
    import tempfile

    from dhsym.dynamics.compact_form import compact_dynamics

    for name in arms:
        cd, t, cpu = cpu_timed(compact_dynamics, dhsym.load(name))
        ops = {part: sum(sp.count_ops(e) for e in getattr(cd, part)) for part in "MCg"}
        print(
            f"{name}: compact M, C, g (symbolic lengths and inertias) in {t:.1f} s wall, "
            f"{cpu:.1f} s CPU [goal <= 15 s]; M11 has {cd.terms(1, 1)} terms [goal <= 30]; "
            f"{len(cd.constants)} grouped constants; count_ops M {ops['M']}, C {ops['C']}, "
            f"g {ops['g']}"
        )
    for fmt in ("markdown", "latex"):
        with tempfile.TemporaryDirectory() as out:
            code = (
                "import sys; from dhsym.cli.main import main; sys.exit(main(['derive', "
                f"'puma560', '--what', 'dynamics', '--format', '{fmt}', '-o', "
                f"'{out}/puma.out']))"
            )
            t, cpu = fresh(code)
        print(
            f"dhsym derive puma560 --what dynamics --format {fmt}: {t:.1f} s wall, "
            f"{cpu:.1f} s CPU [goal <= 60 s]"
        )
    import dataclasses

    puma = dhsym.load("puma560")
    print(flops_line("exported rne of the PUMA 560 (friction and motor inertia)", puma))
    rigid = dataclasses.replace(
        puma.table,
        rows=tuple(
            dataclasses.replace(r, inertia=dataclasses.replace(r.inertia, Jm=0, B=0, Tc=(0, 0)))
            if r.inertia is not None
            else r
            for r in puma.table.rows
        ),
    )
    print(
        flops_line(
            "the same, rigid links only (Corke's simplified PUMA: 224 + 174)", dhsym.Robot(rigid)
        )
    )
    first_call_figures()


def first_call_figures() -> None:
    """The first ``rne`` of the PUMA 560 in a fresh process (imports included), with an
    empty disk cache and then with the cache that run left (warm)."""
    import tempfile

    code = "import dhsym; p = dhsym.load('puma560'); p.rne([0.1] * 6, [0.2] * 6, [0.3] * 6)"
    with tempfile.TemporaryDirectory() as cache:
        for state in ("empty", "warm"):
            t, cpu = fresh(code, {"DHSYM_CACHE": cache})
            print(
                f"first rne of the PUMA 560 in a fresh process, {state} disk cache: {t:.1f} s "
                f"wall, {cpu:.1f} s CPU [goal <= 2 s]"
            )


def per_call(fn, number: int = 2000, repeat: int = 7) -> float:
    """CPU seconds of one call of ``fn()``: the best of ``repeat`` runs of ``number``
    calls, timed with ``time.process_time`` (on a loaded machine the CPU time is the
    figure that carries over; the load is printed beside it)."""
    best = float("inf")
    for _ in range(repeat):
        t0 = time.process_time()
        for _ in range(number):
            fn()
        best = min(best, (time.process_time() - t0) / number)
    return best


def load_text() -> str:
    import os

    return "load average {:.2f} {:.2f} {:.2f} (uptime), 2 cores".format(*os.getloadavg())


def state_figures() -> None:
    """Part 4: one state after the switch, through C, the Python floats program and
    pinocchio, CPU µs per call."""
    from dhsym.dynamics import compiled_dynamics as cd
    from dhsym.export.shared_library import native_compiler

    puma = dhsym.load("puma560")
    rng = np.random.default_rng(1)
    q, v, a = rng.uniform(-1, 1, (3, 6))
    paths = {
        "C": puma.dynamics_functions(),  # the facade passes the C compiler when there is one
        "NumPy": cd.dynamics_functions(puma),  # no compiler: the program for Python floats
    }
    import resource

    def cpu_with_children() -> float:
        mine = time.process_time()
        kids = resource.getrusage(resource.RUSAGE_CHILDREN)
        return mine + kids.ru_utime + kids.ru_stime

    for path, f in paths.items():
        t0 = cpu_with_children()
        for _ in range(cd.COMPILE_AFTER + 1):  # past the switch, as a simulation gets there
            f.gravload(q)
        print(
            f"PUMA 560, {path} path: {cd.COMPILE_AFTER} small calls on the recursion and the "
            f"switch (the program; on the C path its build too; disk cache as found) "
            f"{cpu_with_children() - t0:.1f} s CPU with the compiler's"
        )
    if paths["C"]._native is None:
        why = (
            "no C compiler (DHSYM_NO_COMPILE or none found)"
            if native_compiler() is None
            else "C build failed"
        )
        print(f"PUMA 560 one state: {why}; the C path is the NumPy path here")
    tau = paths["NumPy"].rne(q, v, a)
    calls = {
        "rne": lambda f: f.rne(q, v, a),
        "inertia": lambda f: f.inertia(q),
        "gravload": lambda f: f.gravload(q),
        "coriolis": lambda f: f.coriolis(q, v),
        "accel": lambda f: f.accel(q, v, tau),
    }
    for name, call in calls.items():  # the paths agree
        ref, got = call(paths["NumPy"]), call(paths["C"])
        assert np.allclose(got, ref, rtol=1e-10, atol=1e-10 * max(1.0, np.abs(ref).max())), name
    times = {
        (name, path): per_call(lambda c=call, f=f: c(f))
        for name, call in calls.items()
        for path, f in paths.items()
    }
    pin_times: dict[str, float] = {}
    try:
        import pinocchio as pin

        from tests.dynamics.test_compiled_dynamics import pin_model
    except ImportError:
        pin = None
        print("pinocchio: absent (pip install pin, a test extra); no pinocchio figures")
    if pin is not None:
        model = pin_model(puma)
        data = model.createData()
        C = paths["C"]
        M = pin.crba(model, data, q)
        M = np.triu(M) + np.triu(M, 1).T
        agree = {
            "rne": np.allclose(pin.rnea(model, data, q, v, a), C.rne(q, v, a, friction=False)),
            "inertia": np.allclose(M, C.inertia(q)),
            "coriolis": np.allclose(
                pin.computeCoriolisMatrix(model, data, q, v) @ v, C.coriolis(q, v) @ v
            ),
        }
        print(f"pinocchio {pin.__version__} agrees with dhsym (no friction): {agree}")
        pin_calls = {
            "rne": ("rnea", lambda: pin.rnea(model, data, q, v, a)),
            "inertia": ("crba", lambda: pin.crba(model, data, q)),
            "gravload": (
                "computeGeneralizedGravity",
                lambda: pin.computeGeneralizedGravity(model, data, q),
            ),
            "coriolis": (
                "computeCoriolisMatrix",
                lambda: pin.computeCoriolisMatrix(model, data, q, v),
            ),
            "accel": ("aba", lambda: pin.aba(model, data, q, v, tau)),
        }
        pin_times = {name: per_call(call) for name, (_, call) in pin_calls.items()}
    print(
        f"PUMA 560, one state after the switch, CPU us per call (best of 7 x 2000; {load_text()}):"
    )
    for name in calls:
        c_us, np_us = times[name, "C"] * 1e6, times[name, "NumPy"] * 1e6
        line = (
            f"  {name:9s} C {c_us:7.2f}   NumPy path {np_us:8.2f} (C {np_us / c_us:5.1f}x faster)"
        )
        if name in pin_times:
            p_us = pin_times[name] * 1e6
            line += (
                f"   pinocchio {pin_calls[name][0]} {p_us:6.2f} (C / pinocchio {c_us / p_us:4.2f})"
            )
        print(line + ("   [goal <= 5 us]" if name == "rne" else ""))


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--symbolic", action="store_true", help="also the fully symbolic PUMA 560")
    p.add_argument("--batch", type=int, default=100_000, help="states in the rne batch")
    p.add_argument("--arms", action="store_true", help="part 0 also for the Stanford arm and UR5")
    p.add_argument("--only-compact", action="store_true", help="part 0 only")
    p.add_argument("--only-numbers", action="store_true", help="part 4 and the first calls only")
    args = p.parse_args()
    if args.only_numbers:
        state_figures()
        first_call_figures()
        return 0
    compact_figures(["puma560", *(["stanford", "ur5"] if args.arms else [])])
    if args.only_compact:
        return 0

    puma = dhsym.load("puma560")
    numeric = Robot(puma.table.substituted())
    eom, t = timed(lagrange, numeric)
    ops = sum(sp.count_ops(e) for e in (*eom.M, *eom.C, *eom.g))
    verdict = "ok" if t < 30 else "over"
    print(f"PUMA 560, numeric inertias: Lagrange M, C, g in {t:.1f} s [{verdict}: goal < 30 s]")
    print(f"  M, C, g: {ops} operations in all")
    _, t = timed(newton_euler, numeric)
    print(f"PUMA 560, numeric inertias: Newton-Euler tau with its steps in {t:.1f} s")
    if args.symbolic:
        symbolic = Robot(
            read_table_text(
                "joints:\n"
                + "\n".join(
                    f"  - {{type: R, theta: theta{i}, d: {d}, a: {a}, alpha: {al}}}"
                    for i, (d, a, al) in enumerate(
                        [(0, 0, "pi/2"), (0, "a2", 0), ("d3", "a3", "-pi/2"),
                         ("d4", 0, "pi/2"), (0, 0, "-pi/2"), (0, 0, 0)], start=1)
                )
            )
        )  # fmt: skip
        _, t = timed(lagrange, symbolic)
        print(f"PUMA 560, symbolic inertias and lengths: Lagrange M, C, g in {t:.1f} s")

    # the sympy.physics.mechanics reference runs on planar arms (the PUMA 560 in
    # LagrangesMethod is not attempted here)
    for n in (2, 3):
        arm = planar(n)
        ours, t_ours = timed(lagrange, arm)
        theirs, t_them = timed(mechanics_planar, n)
        from sympy.physics.mechanics import dynamicsymbols

        subs = dict(zip(dynamicsymbols(f"q1:{n + 1}"), arm.variables))
        same = prove_equal(theirs.subs(subs), ours.M)
        print(
            f"planar {n}R, symbolic: dhsym Lagrange {t_ours:.2f} s, sympy.physics.mechanics "
            f"LagrangesMethod {t_them:.2f} s (ratio {t_them / t_ours:.2f}; same M: {same})"
        )

    f = puma.dynamics_functions()
    rng = np.random.default_rng(0)
    Q, V, A = (rng.uniform(-1, 1, (args.batch, 6)) for _ in range(3))
    from dhsym.dynamics.compiled_dynamics import COMPILE_AFTER

    _, t_recursion = timed(f.rne, Q, V, A)  # before the switch: the recursion on numbers
    for k in range(COMPILE_AFTER + 1):  # past the switch to the compiled program
        f.rne(Q[k], V[k], A[k])
    _, t_batch = timed(f.rne, Q, V, A)
    reps = 2000
    t0 = time.perf_counter()
    for k in range(reps):
        f.rne(Q[k], V[k], A[k])
    t_one = (time.perf_counter() - t0) / reps
    print(
        f"PUMA 560 rne, batch of {args.batch}: the recursion on numbers (before the switch) "
        f"{t_recursion * 1e3:.1f} ms ({t_recursion / args.batch * 1e6:.2f} us/state); the "
        f"compiled program (after it) {t_batch * 1e3:.1f} ms "
        f"({t_batch / args.batch * 1e6:.2f} us/state); one state {t_one * 1e6:.1f} us"
    )
    try:
        import pinocchio as pin

        from tests.dynamics.test_compiled_dynamics import pin_model
    except ImportError:
        print("pinocchio: not installed (pip install pin)")
        state_figures()
        return 0
    model = pin_model(puma)
    data = model.createData()
    fr = f.friction(V)
    pin.rnea(model, data, Q[0], V[0], A[0])
    t0 = time.perf_counter()
    out = np.empty_like(Q)
    for k in range(args.batch):
        out[k] = pin.rnea(model, data, Q[k], V[k], A[k])
    t_pin = time.perf_counter() - t0
    agree = np.allclose(out, f.rne(Q, V, A) - fr, atol=1e-8)
    print(
        f"pinocchio rnea from Python: {args.batch} states in {t_pin * 1e3:.1f} ms "
        f"({t_pin / args.batch * 1e6:.2f} us/state); batched dhsym is {t_pin / t_batch:.1f}x "
        f"faster; one state: pinocchio {t_pin / args.batch * 1e6:.1f} us vs dhsym "
        f"{t_one * 1e6:.1f} us (ratio {t_one / (t_pin / args.batch):.1f}); agree: {agree}"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
