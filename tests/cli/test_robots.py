"""``dhsym ik`` as complete as ``robot.ik`` (issue 32, item 3): branch names on every line,
``--free``, ``--limits``, ``--near``/``--one``, JSON alone on stdout with branch, q, residual
and reason, exit status 0 with solutions, 1 with none, 2 on bad input."""

from __future__ import annotations

import json

import numpy as np
import pytest

import dhsym
from dhsym.cli.main import main

_Q = "0.3,-0.5,0.4,0.2,0.7,-1.1"
_PANDA_Q = [0.3, -0.5, 0.4, -2.0, 0.2, 1.6, 0.7]


def test_every_line_names_its_branch_and_its_residual(capsys):
    assert main(["ik", "puma560", "--pose-of", _Q]) == 0
    lines = capsys.readouterr().out.splitlines()[1:]  # after the note on --pose-of's unit
    assert lines[0].startswith("8 closed-form solution(s)") and "| branch | residual" in lines[0]
    names = dhsym.load("puma560").ik(dhsym.load("puma560").fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1]))
    assert [line.split(" | ")[1] for line in lines[1:]] == list(names.branches)


def test_json_carries_branch_signs_q_residual_and_reason(capsys):
    assert main(["ik", "ur5", "--pose-of", _Q, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["method"] == "closed form" and out["reason"] is None
    assert len(out["solutions"]) == 8 == len(out["q"])
    first = out["solutions"][0]
    assert set(first) == {"branch", "signs", "q", "residual", "singular"}
    assert first["branch"] == "right arm, wrist not flipped, elbow up"
    assert first["signs"] == [1, 1, 1] and first["residual"] < 1e-12
    assert first["q"] == pytest.approx([0.3, -0.5, 0.4, 0.2, 0.7, -1.1], abs=1e-9)


def test_no_solution_exits_1_with_the_reason_in_json_and_on_stderr(capsys):
    pose = "1,0,0,5,0,1,0,0,0,0,1,0"  # 5 m away: beyond the UR5's reach
    assert main(["ik", "ur5", "--pose", pose, "--json"]) == 1
    captured = capsys.readouterr()
    out = json.loads(captured.out)
    assert out["q"] == [] and out["solutions"] == []
    assert "theta3" in out["reason"] and "out of reach" in out["reason"]
    assert "the wrist centre is 5 from the origin of frame 0" in out["reason"]
    assert "this arm reaches at most about 0.9" in out["reason"]
    assert "dhsym: no solution:" in captured.err


@pytest.mark.parametrize("k", range(1, 8))
def test_any_joint_of_the_panda_given_on_the_command_line(k, capsys):
    # issue 32, done when: dhsym ik panda --pose-of … --free k=… --json | python -m json.tool
    q = ",".join(map(str, _PANDA_Q))
    assert main(["ik", "panda", "--pose-of", q, "--free", f"{k}={_PANDA_Q[k - 1]}", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["free"] == {str(k): _PANDA_Q[k - 1]}
    assert out["method"] in ("closed form", "general 6R", "numeric") and out["solutions"]
    r = dhsym.load("panda")
    T = r.fk(_PANDA_Q)
    for sol in out["solutions"]:
        assert sol["q"][k - 1] == _PANDA_Q[k - 1] and sol["residual"] <= 1e-9
        assert np.abs(r.fk(sol["q"]) - T).max() <= 1e-9
    if out["method"] == "numeric":
        assert out["converged"] is True and out["iterations"] > 0


def test_several_free_choices_are_solved_in_turn(capsys):
    q = ",".join(map(str, _PANDA_Q))
    argv = ["ik", "panda", "--pose-of", q, "--free", "7=0.7", "--free", "4=-2", "--one"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "closed-form solution(s) with theta7 = 0.7 given" in out
    assert "numeric solution(s) with theta4 = -2 given" in out
    assert "Levenberg–Marquardt from several starts, converged" in out
    assert main([*argv, "--json"]) == 0
    results = json.loads(capsys.readouterr().out)["results"]
    assert [r["free"] for r in results] == [{"7": 0.7}, {"4": -2.0}]
    assert [len(r["solutions"]) for r in results] == [1, 1]


def test_free_takes_the_unit_of_q(capsys):
    q = ",".join(str(np.degrees(v)) for v in _PANDA_Q)
    argv = ["ik", "panda", "--deg", "--pose-of", q, "--free", f"7={np.degrees(0.7)}", "--json"]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert all(s["q"][6] == pytest.approx(0.7, abs=1e-12) for s in out["solutions"])


def test_near_orders_the_solutions_and_one_keeps_the_nearest(capsys):
    r = dhsym.load("puma560")
    sols = r.ik(r.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1]))
    far = sols.q[-1]
    near = ",".join(repr(float(v)) for v in far + 0.01)
    assert main(["ik", "puma560", "--pose-of", _Q, "--near", near, "--one", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert len(out["solutions"]) == 1
    assert out["solutions"][0]["q"] == pytest.approx(far.tolist(), abs=1e-9)
    assert out["solutions"][0]["branch"] == sols.branches[-1]


def test_limits_keep_only_solutions_within_the_joint_limits(capsys):
    r = dhsym.load("puma560")
    q = [0.3, -0.5, 0.4, 0.2, 0.7, -1.1]
    assert main(["ik", "puma560", "--pose-of", _Q, "--limits", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    kept = r.ik(r.fk(q), limits=True)
    assert 0 < len(out["solutions"]) == len(kept) < 8
    assert [s["branch"] for s in out["solutions"]] == list(kept.branches)


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (["--free", "9=0.1"], "--free 9=0.1: joint 9 is not a joint of Franka Emika Panda"),
        (["--free", "x"], "--free: expected JOINT=VALUE"),
        (["--free", "4=y"], "--free 4="),
        (["--near", "1,2"], "--near needs 7 values"),
        (["--free", "4=-2", "--numeric"], "--numeric finds one solution"),
    ],
)
def test_bad_options_exit_2_naming_the_option(extra, message, capsys):
    q = ",".join(map(str, _PANDA_Q))
    assert main(["ik", "panda", "--pose-of", q, *extra]) == 2
    assert message in capsys.readouterr().err


def test_a_singular_wrist_names_its_family_in_text_and_json(capsys):
    q = "0.3,-0.5,0.4,0.2,0,-1.1"
    assert main(["ik", "puma560", "--pose-of", q, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert "θ4 + θ6 = -0.9 is all that is determined" in out["note"]
    assert main(["ik", "puma560", "--pose-of", q]) == 0
    assert "  note: θ5 = 0: the wrist is singular" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("name", "q", "says"),
    [
        ("puma560", "0.3,-0.5,0.4,0.2,0,-1.1", "θ4 + θ6 = -0.9 is all that is determined"),
        # the Stanford table is in degrees: so is --pose-of (θ4 + θ6 = −40° = −0.6981 rad)
        ("stanford", "10,-30,0.4,20,0,-60", "θ4 + θ6 = -0.6981 is all that is determined"),
        ("ur5", "0.3,-1.1,1.4,-0.6,0,0.4", "θ2 + θ3 + θ4 + θ6 = 0.1 is all that is determined"),
    ],
)
def test_a_singular_pose_names_its_family_in_text_and_json_on_each_arm(name, q, says, capsys):
    # issue 32, done when: singular poses on PUMA, UR5 and Stanford, Python, CLI and JSON
    assert main(["ik", name, "--pose-of", q, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert says in out["note"] and out["note"].startswith("θ5 = 0: the wrist is singular")
    assert any(s["singular"] == ["wrist"] for s in out["solutions"])
    assert main(["ik", name, "--pose-of", q]) == 0
    assert "  note: θ5 = 0: the wrist is singular" in capsys.readouterr().out
    r = dhsym.load(name)
    values = np.array([float(x) for x in q.split(",")])
    if name == "stanford":
        values[[0, 1, 3, 4, 5]] = np.radians(values[[0, 1, 3, 4, 5]])
    assert says in r.ik(r.fk(values)).note


@pytest.mark.parametrize(
    ("name", "where", "step"),
    [
        ("puma560", "5", "theta3"),
        ("ur5", "5", "theta3"),
        ("stanford", "axis", "theta1"),
    ],
)
def test_an_unreachable_pose_names_the_step_in_python_text_and_json(name, where, step, capsys):
    r = dhsym.load(name)
    T = r.fk([0.3, -0.5, 0.4, 0.2, 0.7, -1.1])
    if where == "axis":  # the Stanford arm reaches out to any distance (d3 unlimited) but
        T[:3, 3] = [0.0, 0.0, 0.3]  # never within its shoulder offset of the axis of joint 1
    else:
        T[:3, 3] *= 5
    said = f"no real value of {step} on any branch"
    sol = r.ik(T)
    assert len(sol) == 0 and said in sol.reason
    pose = ",".join(f"{x:.12g}" for x in T[:3].ravel())
    assert main(["ik", name, "--pose", pose, "--json"]) == 1
    captured = capsys.readouterr()
    out = json.loads(captured.out)
    assert out["solutions"] == [] and said in out["reason"]
    assert "dhsym: no solution:" in captured.err and said in captured.err
    assert main(["ik", name, "--pose", pose]) == 1
    assert said in capsys.readouterr().err
