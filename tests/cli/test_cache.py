"""``dhsym cache info|clear|trim`` and ``--no-cache`` (dhsym.cli.cache)."""

from __future__ import annotations

import os

import numpy as np

import dhsym
from dhsym.cache.store import Store
from dhsym.cli.main import main


def _fill(tmp_path, monkeypatch):
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "c"))
    monkeypatch.delenv("DHSYM_NO_CACHE", raising=False)
    Store(tmp_path / "c").write("rne-" + "a" * 64, b"12345")


def test_info_and_clear(tmp_path, monkeypatch, capsys):
    _fill(tmp_path, monkeypatch)
    assert main(["cache", "info"]) == 0
    out = capsys.readouterr().out
    assert str(tmp_path / "c") in out and "entries: 1" in out and "5 bytes" in out
    assert main(["cache", "clear"]) == 0
    assert "removed 1 entry" in capsys.readouterr().out
    assert main(["cache", "info"]) == 0
    assert "entries: 0" in capsys.readouterr().out


def test_trim_to_a_size(tmp_path, monkeypatch, capsys):
    _fill(tmp_path, monkeypatch)
    Store(tmp_path / "c").write("rne-" + "b" * 64, b"678")
    old = tmp_path / "c" / "entries" / ("rne-" + "a" * 64)
    os.utime(old, (0, 0))  # the least recently used
    assert main(["cache", "info"]) == 0
    assert "limit:   536,870,912 bytes" in capsys.readouterr().out
    assert main(["cache", "trim"]) == 0  # within the limit: nothing to do
    assert "removed 0 entries" in capsys.readouterr().out
    assert main(["cache", "trim", "--max-size", "4"]) == 0
    out = capsys.readouterr().out
    assert "removed 1 entry (5 bytes)" in out and "3 bytes left (at most 4)" in out
    assert not old.exists() and (tmp_path / "c" / "entries" / ("rne-" + "b" * 64)).exists()
    assert main(["cache", "trim", "--max-size", "lots"]) == 2
    assert "--max-size: not a size: 'lots'" in capsys.readouterr().err


def test_the_limit_from_the_environment(tmp_path, monkeypatch, capsys):
    _fill(tmp_path, monkeypatch)
    monkeypatch.setenv("DHSYM_CACHE_SIZE", "1k")
    assert main(["cache", "info"]) == 0
    assert "limit:   1,024 bytes" in capsys.readouterr().out


def test_no_cache_turns_the_store_off_for_the_command_only(tmp_path, monkeypatch, capsys):
    _fill(tmp_path, monkeypatch)
    assert main(["--no-cache", "cache", "info"]) == 0
    assert "turned off" in capsys.readouterr().out
    assert "DHSYM_NO_CACHE" not in os.environ  # left as found


def test_no_cache_writes_nothing(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "empty"))
    monkeypatch.setenv("DHSYM_NO_CACHE", "1")
    from dhsym.model.tablefile import read_table_text

    arm = dhsym.Robot(read_table_text(PENDULUM))
    assert arm.gravload(np.zeros(1)).shape == (1,)
    assert not (tmp_path / "empty").exists()


def test_dynamics_kept_and_read_back(tmp_path, monkeypatch):
    from dhsym.dynamics.compiled_dynamics import dynamics_functions
    from dhsym.model.tablefile import read_table_text

    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "c"))
    monkeypatch.delenv("DHSYM_NO_CACHE", raising=False)
    import dhsym.dynamics.compiled_dynamics as cd

    # the compiled τ is what a long simulation switches to: at once here
    monkeypatch.setattr(cd, "COMPILE_AFTER", 0)
    arm = dhsym.Robot(read_table_text(PENDULUM))
    x = np.array([0.3])
    first = dynamics_functions(arm).rne(x, x, x)
    assert len(list(_entries(Store(tmp_path / "c"), "rne"))) == 1
    monkeypatch.setattr(cd, "rne_expressions", None)  # read back, not derived again
    assert np.array_equal(dynamics_functions(arm).rne(x, x, x), first)


PENDULUM = """
joints: [{type: R, theta: q1, d: 0, a: 1, alpha: 0, m: 2, r: [-0.5, 0, 0], I: [0, 0.1, 0.1]}]
"""


def _entries(store, kind):
    """The entries of one kind (their HMAC files left out)."""
    return [p for p in store.entries.glob(f"{kind}-*") if not p.name.endswith(".hmac")]
