# ruff: noqa: E501
"""The exported product of exponentials (``--what screws``: ``<prefix>_fk_space``,
``<prefix>_jacobian_space``, ``<prefix>_jacobian_body``) in every language, built and run
(gcc, g++, rustc, Octave, NumPy) against ``robot.fk``, ``robot.jacobian_space`` and
``robot.jacobian_body`` at random configurations (≤ 1e-12) for the UR5 and the PUMA 560,
and against the numbers of ``modern_robotics`` recorded in ``tests/screws`` for the UR5 of
Lynch and Park's Example 4.5 (its PoE file)."""

from __future__ import annotations

import functools
import shutil
from importlib import resources
from pathlib import Path

import numpy as np
import pytest

import dhsym
from dhsym.export import DEFAULT_PARTS, export_languages

from ..conftest import _need
from ..screws.test_poefile import MR_FK, MR_JB, MR_JS, THETA
from . import _harness as h

LANGS = ("c", "cpp", "matlab", "rust", "python")
NAMES = ["ur5", "puma560"]


def _lynch_park_ur5() -> dhsym.Robot:
    ref = resources.files("dhsym.screws") / "robots" / "lynch_park_ur5.poe.yaml"
    with resources.as_file(ref) as p:
        return dhsym.load(str(p))


@functools.cache
def _case(name: str, symbolic: bool = False) -> tuple[dhsym.Robot, dict[str, dict[str, str]]]:
    """The robot and its screws export in every language (the programs derived once)."""
    robot = _lynch_park_ur5() if name == "lynch_park_ur5" else dhsym.load(name)
    files = export_languages(robot, LANGS, "screws", "arm", symbolic, command="test")
    return robot, files


def _configurations(n: int) -> np.ndarray:
    rng = np.random.default_rng(36)
    return np.vstack([np.zeros(n), rng.uniform(-np.pi, np.pi, (5, n))])


def _check(robot: dhsym.Robot, q: np.ndarray, out: np.ndarray) -> None:
    """``out``: for each row of ``q`` the 16 entries of fk_space, then J_s and J_b row-major."""
    n = robot.n
    per = 16 + 12 * n
    assert out.shape == (len(q) * per,)
    for k, row in enumerate(q):
        got = out[k * per : (k + 1) * per]
        np.testing.assert_allclose(got[:16].reshape(4, 4), robot.fk(row), rtol=0, atol=1e-12)
        js, jb = got[16 : 16 + 6 * n], got[16 + 6 * n :]
        np.testing.assert_allclose(js.reshape(6, n), robot.jacobian_space(row), atol=1e-12)
        np.testing.assert_allclose(jb.reshape(6, n), robot.jacobian_body(row), atol=1e-12)


def _stdin(q: np.ndarray) -> str:
    return "\n".join([str(len(q)), *(" ".join(repr(float(v)) for v in row) for row in q)]) + "\n"


_C_MAIN = """
#include <stdio.h>
#include "arm.{ext}"
#define N {n}
static void put(const double *x, int k)
{{
    int j;
    for (j = 0; j < k; ++j) printf("%.17g\\n", x[j]);
}}
int main(void)
{{
    int m, i, j;
    double q[N], T[16], J[6 * N];
    if (scanf("%d", &m) != 1) return 1;
    for (i = 0; i < m; ++i) {{
        for (j = 0; j < N; ++j) if (scanf("%lf", &q[j]) != 1) return 1;
        {ns}fk_space(q, T{pa}); put(T, 16);
        {ns}jacobian_space(q, J{pa}); put(J, 6 * N);
        {ns}jacobian_body(q, J{pa}); put(J, 6 * N);
    }}
    return 0;
}}
"""

_RUST_MAIN = h.rust_main("""\
    let n = arm::NJOINTS;
    for i in 0..(v[0] as usize) {
        let mut q = [0.0; arm::NJOINTS];
        q.copy_from_slice(&v[1 + n * i..1 + n * (i + 1)]);
        for x in arm::fk_space(&q).iter() { println!("{:e}", x); }
        for x in arm::jacobian_space(&q).iter() { println!("{:e}", x); }
        for x in arm::jacobian_body(&q).iter() { println!("{:e}", x); }
    }
""")

_OCTAVE = """
Q = dlmread('q.txt');
for i = 1:rows(Q)
  printf('%.17g\\n', arm_fk_space(Q(i, :)).');
  printf('%.17g\\n', arm_jacobian_space(Q(i, :)).');
  printf('%.17g\\n', arm_jacobian_body(Q(i, :)).');
end
"""


def _run(lang: str, robot: dhsym.Robot, files: dict[str, str], q: np.ndarray, folder: Path):
    """fk_space, J_s and J_b at each row of ``q`` from the exported ``lang``, one flat array."""
    if lang in ("c", "cpp"):
        cpp = lang == "cpp"
        main = _C_MAIN.format(
            ext="hpp" if cpp else "h", n=robot.n, ns="arm::" if cpp else "arm_", pa=""
        )
        prog = h.build_c(files, folder, main, cpp)
        return h.numbers([str(prog)], folder, _stdin(q))
    if lang == "rust":
        return h.numbers([str(h.build_rust(files, folder, _RUST_MAIN))], folder, _stdin(q))
    if lang == "matlab":
        np.savetxt(folder / "q.txt", np.atleast_2d(q), fmt="%.17g")
        return h.octave(files, folder, _OCTAVE)
    module = h.load_python(files, "arm", folder)
    parts = [(module.fk_space(r), module.jacobian_space(r), module.jacobian_body(r)) for r in q]
    return np.concatenate([np.ravel(x) for triple in parts for x in triple])


def _need_tool(lang: str) -> None:
    if lang == "rust":
        _need("rustc", h.rustc() is not None, "apt-get install rustc (or rustup)")
    elif lang != "python":
        tool = {"c": "gcc", "cpp": "g++", "matlab": "octave"}[lang]
        _need(tool, shutil.which(tool) is not None, f"apt-get install {tool}")


@pytest.mark.slow
@pytest.mark.parametrize("lang", LANGS)
@pytest.mark.parametrize("name", NAMES)
def test_every_language_gives_dhsyms_numbers(name: str, lang: str, tmp_path: Path) -> None:
    _need_tool(lang)
    robot, files = _case(name)
    q = _configurations(robot.n)
    _check(robot, q, _run(lang, robot, files[lang], q, tmp_path))


@pytest.mark.slow
@pytest.mark.parametrize("lang", LANGS)
def test_lynch_park_ur5_gives_modern_robotics_numbers(lang: str, tmp_path: Path) -> None:
    """The UR5 of Lynch and Park's Example 4.5, loaded from its PoE file: the exported code
    gives ``FKinSpace``, ``JacobianSpace`` and ``JacobianBody`` of ``modern_robotics``."""
    _need_tool(lang)
    robot, files = _case("lynch_park_ur5")
    out = _run(lang, robot, files[lang], np.array([THETA]), tmp_path)
    np.testing.assert_allclose(out[:16].reshape(4, 4), MR_FK, atol=1e-12)
    np.testing.assert_allclose(out[16:52].reshape(6, 6), MR_JS, atol=1e-12)
    np.testing.assert_allclose(out[52:].reshape(6, 6), MR_JB, atol=1e-12)


@pytest.mark.slow
def test_python_takes_a_batch_and_the_lengths_as_parameters(tmp_path: Path) -> None:
    robot, files = _case("lynch_park_ur5", symbolic=True)
    module = h.load_python(files["python"], "arm", tmp_path)
    values = {s.name: float(v) for s, v in robot.table.values}
    names = _parameter_names(files["python"]["arm.py"])
    assert module.NPARAMS == len(names) > 0 and set(names) <= set(values)
    p = np.array([values[name] for name in names])
    q = _configurations(robot.n)
    np.testing.assert_allclose(module.fk_space(q, p), robot.fk(q), atol=1e-12)
    np.testing.assert_allclose(module.jacobian_space(q, p), robot.jacobian_space(q), atol=1e-12)
    np.testing.assert_allclose(module.jacobian_body(q, p), robot.jacobian_body(q), atol=1e-12)
    # and at the book's lengths changed: the parameters are read, not baked in
    longer = module.fk_space(THETA, 2 * p)
    assert not np.allclose(longer, MR_FK)


def _parameter_names(text: str) -> list[str]:
    """The table names of ``p``'s entries, in order, from the module's comment line."""
    line = next(x for x in text.splitlines() if x.startswith("# Lengths and offsets"))
    return [part.split(" = ")[1] for part in line.split(": ", 1)[1].split(", ")]


def test_the_header_lists_the_screw_axes_and_m() -> None:
    _, files = _case("lynch_park_ur5")
    text = files["c"]["arm.h"]
    assert " * T(theta) = e^([S1]*theta1) e^([S2]*theta2)" in text
    assert " *   joint  S_i" in text
    # the book's S_2 = (0, 1, 0, -H1, 0, 0) and B_6 = (0, 0, 1, 0, 0, 0)
    assert " *   2      (0, 1, 0, -H1, 0, 0)" in text
    assert "(0, 0, 1, 0, 0, 0)\n" in text
    assert " * Home configuration M (q = 0), by rows: (-1, 0, 0, L1 + L2)," in text
    assert "void arm_fk_space(const double q[ARM_NJOINTS], double T[16]);" in text
    assert "void arm_jacobian_body(const double q[ARM_NJOINTS], double J[6 * ARM_NJOINTS]);" in text


def test_screws_is_a_part_of_its_own() -> None:
    robot = dhsym.load("planar2r")
    assert "screws" not in DEFAULT_PARTS
    plain = dhsym.export(robot, "c", prefix="arm", command="x")
    with_screws = dhsym.export(robot, "c", what="fk,jacobian,ik,screws", prefix="arm", command="x")
    assert "fk_space" not in plain["arm.c"] and "Product of exponentials" not in plain["arm.h"]
    # the other functions are the same lines: the part adds, it changes nothing
    for name in ("arm.c", "arm.h"):
        kept = [line for line in with_screws[name].splitlines() if "made by" not in line]
        assert all(line in kept for line in plain[name].splitlines() if "made by" not in line)
    assert sorted(dhsym.export(robot, "matlab", what="screws", prefix="arm")) == [
        "arm_fk.m",
        "arm_fk_space.m",
        "arm_jacobian_body.m",
        "arm_jacobian_space.m",
        "arm_njoints.m",
    ]
    rust = dhsym.export(robot, "rust", what="screws", prefix="arm")["arm.rs"]
    assert "pub fn jacobian_space(q: &[f64; NJOINTS]) -> [f64; 6 * NJOINTS] {" in rust
    assert "pub fn jacobian(" not in rust


def test_cli_exports_the_screws(tmp_path: Path) -> None:
    from dhsym.cli.main import main

    args = ["export", "planar2r", "--lang", "python", "--what", "screws", "--prefix", "arm"]
    assert main([*args, "-o", str(tmp_path)]) == 0
    text = (tmp_path / "arm.py").read_text()
    assert "made by: dhsym export planar2r --lang python --what screws --prefix arm" in text
    module = h.load_python({}, "arm", tmp_path)
    robot = dhsym.load("planar2r")
    q = _configurations(2)
    np.testing.assert_allclose(module.jacobian_body(q), robot.jacobian_body(q), atol=1e-12)
