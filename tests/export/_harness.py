# ruff: noqa: E501
"""Drive exported code in each language: build it, feed it configurations and poses, read
back fk, Jacobians and IK solutions (all numbers printed with 17 digits).

The pieces every compile test shares (``test_languages``, ``test_rne``, ``test_motion``,
``test_screws``): :func:`build_c` and :func:`build_rust` write the files and a driver and
build them under the strict flags (:data:`C_FLAGS`, :data:`CPP_FLAGS`), :func:`numbers` runs
a program and reads the numbers it prints, :func:`octave` runs a driver script in GNU
Octave beside the files, :func:`load_python` imports the NumPy module."""

from __future__ import annotations

import importlib.util
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np


def rustc() -> str | None:
    """rustc on PATH, or the one rustup installs in ~/.cargo/bin."""
    found = shutil.which("rustc")
    if found:
        return found
    home = Path(os.environ.get("CARGO_HOME", Path.home() / ".cargo")) / "bin" / "rustc"
    return str(home) if home.is_file() else None


def _numbers(text: str) -> list[float]:
    return [float(t) for t in text.split()]


#: gcc's flags for exported C (warnings are errors)
C_FLAGS = ("-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-O2")
#: g++'s flags for exported C++
CPP_FLAGS = ("-std=c++17", "-Wall", "-Wextra", "-Werror", "-O2")


def _write(files: dict[str, str], folder: Path) -> None:
    for name, text in files.items():
        (folder / name).write_text(text)


def build_c(files: dict[str, str], folder: Path, main: str, cpp: bool = False) -> Path:
    """Write ``files`` and the driver ``main`` (``main.c`` or ``main.cpp``) into ``folder`` and
    build them with gcc (C99, with every ``.c`` file) or g++ (C++17); the program's path."""
    _write(files, folder)
    if cpp:
        (folder / "main.cpp").write_text(main)
        cmd = ["g++", *CPP_FLAGS, "main.cpp", "-o", "prog"]
    else:
        (folder / "main.c").write_text(main)
        sources = sorted(name for name in files if name.endswith(".c"))
        cmd = ["gcc", *C_FLAGS, "main.c", *sources, "-o", "prog", "-lm"]
    subprocess.run(cmd, cwd=folder, check=True, capture_output=True, text=True)
    return folder / "prog"


def rust_main(body: str, items: str = "", module: str = "arm") -> str:
    """A Rust driver of ``module``: ``items`` (constants, helpers), then ``main`` with the
    numbers on standard input in ``v: Vec<f64>`` and ``body`` (indented by four)."""
    return (
        f"mod {module};\nuse std::io::Read;\n{items}fn main() {{\n"
        "    let mut s = String::new();\n"
        "    std::io::stdin().read_to_string(&mut s).unwrap();\n"
        "    let v: Vec<f64> = s.split_whitespace().map(|x| x.parse().unwrap()).collect();\n"
        f"{body}}}\n"
    )


def build_rust(files: dict[str, str], folder: Path, main: str) -> Path:
    """Write ``files`` and the driver ``main.rs`` into ``folder`` and build them with rustc
    (edition 2021, ``-O``; functions the driver does not call are allowed); the program."""
    _write(files, folder)
    (folder / "main.rs").write_text(main)
    cmd = [rustc(), "--edition", "2021", "-O", "-A", "dead_code", "main.rs", "-o", "prog"]
    subprocess.run(cmd, cwd=folder, check=True, capture_output=True, text=True)
    return folder / "prog"


def numbers(cmd: list[str], folder: Path, text: str = "") -> np.ndarray:
    """Run ``cmd`` in ``folder`` with ``text`` on its standard input: the numbers it prints."""
    res = subprocess.run(cmd, cwd=folder, input=text, capture_output=True, text=True, check=True)
    return np.array(_numbers(res.stdout))


def octave(files: dict[str, str], folder: Path, script: str) -> np.ndarray:
    """Run the driver ``script`` in GNU Octave beside ``files``: the numbers it prints."""
    _write(files, folder)
    (folder / "drive.m").write_text(script)
    return numbers(["octave", "--no-gui", "--quiet", "--no-window-system", "drive.m"], folder)


def _input(q: np.ndarray, poses: np.ndarray) -> str:
    lines = [str(len(q))]
    lines += [" ".join(repr(float(v)) for v in row) for row in q]
    lines.append(str(len(poses)))
    lines += [" ".join(repr(float(v)) for v in T.ravel()) for T in poses]
    return "\n".join(lines) + "\n"


def _parse(out: list[float], m: int, k: int, n: int, jac: bool, ik: bool):
    at = 0
    fks, jacs, iks = [], [], []
    for _ in range(m):
        fks.append(np.array(out[at : at + 16]).reshape(4, 4))
        at += 16
        if jac:
            jacs.append(np.array(out[at : at + 6 * n]).reshape(6, n))
            at += 6 * n
    if ik:
        for _ in range(k):
            c = int(out[at])
            at += 1
            iks.append(np.array(out[at : at + c * n]).reshape(c, n))
            at += c * n
    assert at == len(out)
    return fks, jacs, iks


_C_MAIN = """
#include <stdio.h>
#include "{h}"
int main(void)
{{
    int m, k, i, j, c;
    double q[{N}_NJOINTS], T[16], J[6 * {N}_NJOINTS];
    {ikdecl}
    if (scanf("%d", &m) != 1) return 1;
    for (i = 0; i < m; ++i) {{
        for (j = 0; j < {N}_NJOINTS; ++j) if (scanf("%lf", &q[j]) != 1) return 1;
        {p}_fk(q, T{pa});
        for (j = 0; j < 16; ++j) printf("%.17g\\n", T[j]);
        {jac}
    }}
    if (scanf("%d", &k) != 1) return 1;
    for (i = 0; i < k; ++i) {{
        for (j = 0; j < 16; ++j) if (scanf("%lf", &T[j]) != 1) return 1;
        {ik}
    }}
    (void)c;
    return 0;
}}
"""


def run_c(files, prefix, q, poses, n, jac, ik, folder: Path, cpp: bool = False, params=None):
    """Compile with gcc/g++ under the issue's flags and run."""
    N = prefix.upper()
    ns = f"{prefix}::" if cpp else f"{prefix}_"
    cN = f"{prefix}::" if cpp else f"{N}_"
    pa = ""
    pdecl = ""
    if params is not None:
        pdecl = "static const double P[] = {" + ", ".join(repr(v) for v in params) + "};"
        pa = ", P"
    main = _C_MAIN.format(
        h=f"{prefix}.hpp" if cpp else f"{prefix}.h",
        N=N,
        p=prefix,
        pa=pa,
        ikdecl=(
            f"double S[{cN}MAX_IK_SOLUTIONS][{cN}NJOINTS], R[{cN}MAX_IK_SOLUTIONS];" if ik else ""
        )
        + pdecl,
        jac=(
            f'{ns}jacobian(q, J{pa}); for (j = 0; j < 6 * {cN}NJOINTS; ++j) printf("%.17g\\n", J[j]);'
            if jac
            else ""
        ),
        ik=(
            (f"c = {ns}ik(T, S, R{pa}); " if cpp else f"c = {ns}ik(T, 0.0, S, R{pa}); ")
            + 'printf("%d\\n", c); '
            f'for (j = 0; j < c * {cN}NJOINTS; ++j) printf("%.17g\\n", S[j / {cN}NJOINTS][j % {cN}NJOINTS]);'
            if ik
            else ""
        ),
    )
    if cpp:
        main = main.replace(f"{N}_NJOINTS", f"{prefix}::NJOINTS")
        main = main.replace(f"{prefix}_fk", f"{prefix}::fk")
    prog = build_c(files, folder, main, cpp)
    out = numbers([str(prog)], folder, _input(q, poses))
    return _parse(list(out), len(q), len(poses), n, jac, ik)


_RUST_MAIN = """
mod {p};
use std::io::Read;
fn main() {{
    let mut s = String::new();
    std::io::stdin().read_to_string(&mut s).unwrap();
    let v: Vec<f64> = s.split_whitespace().map(|x| x.parse().unwrap()).collect();
    let mut at = 0;
    let m = v[at] as usize; at += 1;
    for _ in 0..m {{
        let mut q = [0.0; {p}::NJOINTS];
        for j in 0..{p}::NJOINTS {{ q[j] = v[at]; at += 1; }}
        for x in {p}::fk(&q{pa}).iter() {{ println!("{{:e}}", x); }}
        {jac}
    }}
    let k = v[at] as usize; at += 1;
    for _ in 0..k {{
        let mut t = [0.0; 16];
        for j in 0..16 {{ t[j] = v[at]; at += 1; }}
        {ik}
    }}
    let _ = at;
}}
"""


def run_rust(files, prefix, q, poses, n, jac, ik, folder: Path, params=None):
    pa = ""
    if params is not None:
        pa = ", &[" + ", ".join(repr(float(v)) for v in params) + "]"
    main = _RUST_MAIN.format(
        p=prefix,
        pa=pa,
        jac=(
            f'for x in {prefix}::jacobian(&q{pa}).iter() {{ println!("{{:e}}", x); }}'
            if jac
            else ""
        ),
        ik=(
            f"let mut s = [[0.0; {prefix}::NJOINTS]; {prefix}::MAX_IK_SOLUTIONS]; "
            f"let mut r = [0.0; {prefix}::MAX_IK_SOLUTIONS]; "
            f'let c = {prefix}::ik(&t, None, &mut s, &mut r{pa}); println!("{{}}", c); '
            'for r in s[..c].iter() { for x in r.iter() { println!("{:e}", x); } }'
            if ik
            else "let _ = t;"
        ),
    )
    prog = build_rust(files, folder, main)
    out = numbers([str(prog)], folder, _input(q, poses))
    return _parse(list(out), len(q), len(poses), n, jac, ik)


def run_octave(files, prefix, q, poses, n, jac, ik, folder: Path):
    np.savetxt(folder / "q.txt", q, fmt="%.17g")
    np.savetxt(folder / "t.txt", poses.reshape(len(poses), 16), fmt="%.17g")
    lines = [
        "Qs = dlmread('q.txt');",
        "Ts = dlmread('t.txt');",
        "for i = 1:size(Qs, 1)",
        f"  T = {prefix}_fk(Qs(i, :)); fprintf('%.17g\\n', T.');",
    ]
    if jac:
        lines.append(f"  J = {prefix}_jacobian(Qs(i, :)); fprintf('%.17g\\n', J.');")
    lines.append("end")
    if ik:
        lines += [
            "for i = 1:size(Ts, 1)",
            "  T = reshape(Ts(i, :), 4, 4).';",
            f"  [Q, c] = {prefix}_ik(T); fprintf('%d\\n', c); fprintf('%.17g\\n', Q.');",
            "end",
        ]
    out = octave(files, folder, "\n".join(lines) + "\n")
    return _parse(list(out), len(q), len(poses) if ik else 0, n, jac, ik)


def load_python(files, prefix, folder: Path):
    _write(files, folder)
    spec = importlib.util.spec_from_file_location(f"exported_{prefix}", folder / f"{prefix}.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules.pop(spec.name, None)
    spec.loader.exec_module(module)
    return module


def run_python(files, prefix, q, poses, n, jac, ik, folder: Path, params=None):
    mod = load_python(files, prefix, folder)
    extra = () if params is None else (np.asarray(params),)
    fks = [mod.fk(row, *extra) for row in q]
    jacs = [mod.jacobian(row, *extra) for row in q] if jac else []
    iks = [mod.ik(T, *extra) for T in poses] if ik else []
    return fks, jacs, iks
