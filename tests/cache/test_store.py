"""The disk cache: private folders and files, atomic writes, HMAC-verified reads
(dhsym.cache.store)."""

from __future__ import annotations

import os
import stat

import pytest

from dhsym.cache.store import (
    DEFAULT_LIMIT,
    Store,
    Trimmed,
    cache_enabled,
    cache_limit,
    cache_root,
    default_store,
    parse_size,
)
from dhsym.errors import DHError

NAME = "transform-" + "0123456789abcdef" * 4


@pytest.fixture
def store(tmp_path):
    return Store(tmp_path / "cache")


def test_write_and_read_back_private(store):
    assert store.read(NAME) is None
    assert store.write(NAME, b"data")
    assert store.read(NAME) == b"data"
    for folder in (store.root, store.entries):
        assert stat.S_IMODE(folder.stat().st_mode) == 0o700
    for path in (store.root / "key", store.entries / NAME, store.entries / f"{NAME}.hmac"):
        assert stat.S_IMODE(path.stat().st_mode) == 0o600
    assert len((store.root / "key").read_bytes()) == 32
    assert not [p for p in store.entries.iterdir() if p.name.startswith(".tmp-")]


def test_changed_entry_is_refused_and_deleted(store):
    store.write(NAME, b"data")
    (store.entries / NAME).write_bytes(b"evil")
    assert store.read(NAME) is None
    assert not (store.entries / NAME).exists()  # deleted: the caller rebuilds
    store.write(NAME, b"data")  # rebuilt
    assert store.read(NAME) == b"data"


def test_planted_entry_with_a_forged_hmac_is_refused(store):
    store.write(NAME, b"data")
    other = "transform-" + "f" * 64
    (store.entries / other).write_bytes(b"evil")
    os.chmod(store.entries / other, 0o600)
    # the HMAC of another entry, copied: it names the entry it was made for
    (store.entries / f"{other}.hmac").write_bytes((store.entries / f"{NAME}.hmac").read_bytes())
    os.chmod(store.entries / f"{other}.hmac", 0o600)
    assert store.read(other) is None


def test_key_changed_invalidates_every_entry(store):
    store.write(NAME, b"data")
    (store.root / "key").write_bytes(b"k" * 32)
    assert store.read(NAME) is None


@pytest.mark.parametrize("target", ["entry", "hmac", "key"])
def test_wrong_mode_is_refused(store, target):
    store.write(NAME, b"data")
    path = {
        "entry": store.entries / NAME,
        "hmac": store.entries / f"{NAME}.hmac",
        "key": store.root / "key",
    }[target]
    os.chmod(path, 0o644)
    assert store.read(NAME) is None


def test_open_folder_is_refused_on_read_and_made_private_on_write(store):
    store.write(NAME, b"data")
    os.chmod(store.entries, 0o777)
    assert store.read(NAME) is None
    assert store.write(NAME, b"data")
    assert stat.S_IMODE(store.entries.stat().st_mode) == 0o700
    assert store.read(NAME) == b"data"


def test_symbolic_link_is_refused(store, tmp_path):
    store.write(NAME, b"data")
    target = tmp_path / "elsewhere"
    target.write_bytes(b"data")
    os.chmod(target, 0o600)
    (store.entries / NAME).unlink()
    (store.entries / NAME).symlink_to(target)
    assert store.read(NAME) is None
    assert target.exists()  # the link is removed, never what it points to


@pytest.mark.skipif(os.getuid() != 0, reason="changing a file's owner needs root")
def test_wrong_owner_is_refused(store):
    store.write(NAME, b"data")
    os.chown(store.entries / NAME, 12345, 12345)
    assert store.read(NAME) is None


def test_folder_of_another_owner_is_not_used(store, monkeypatch):
    store.write(NAME, b"data")
    monkeypatch.setattr(os, "getuid", lambda: os.stat(store.root).st_uid + 1)
    assert store.read(NAME) is None
    assert not store.write(NAME, b"data")


def test_names_are_checked(store):
    with pytest.raises(ValueError):
        store.read("../key")
    with pytest.raises(ValueError):
        store.write("transform-xyz/../../evil", b"")


def test_info_and_clear(store):
    store.write(NAME, b"data")
    store.write("dynamics-" + "1" * 64, b"more")
    info = store.info()
    assert (info.root, info.entries, info.size) == (store.root, 2, 8)
    assert store.clear() == 2
    assert store.info().entries == 0 and not (store.root / "key").exists()


def test_root_and_switch(monkeypatch, tmp_path):
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "c"))
    monkeypatch.delenv("DHSYM_NO_CACHE", raising=False)
    assert cache_root() == tmp_path / "c" and default_store() == Store(tmp_path / "c")
    monkeypatch.setenv("DHSYM_NO_CACHE", "1")
    assert not cache_enabled() and default_store() is None
    monkeypatch.delenv("DHSYM_CACHE")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert cache_root() == tmp_path / "xdg" / "dhsym"  # through platformdirs


# -- the bound: least recently used entries trimmed -------------------------------------------


def _name(k):
    return f"rne-{k:064x}"


def _aged(store, name, seconds_ago):
    """Mark entry ``name`` last used ``seconds_ago`` (its modification time)."""
    import time

    when = time.time() - seconds_ago
    os.utime(store.entries / name, (when, when))


def _left(store):
    found = store.entries.iterdir()
    return sorted(p.name for p in found if p.name.startswith("rne-") and p.suffix != ".hmac")


def test_a_write_over_the_bound_deletes_the_least_recently_used(tmp_path):
    store = Store(tmp_path / "cache", limit=300, check_every=0)
    for k in range(3):
        assert store.write(_name(k), b"x" * 100)
        _aged(store, _name(k), 100 - k)  # 0 is the oldest
    assert store.read(_name(0)) == b"x" * 100  # read: used now, the newest
    assert store.write(_name(3), b"y" * 100)  # 400 bytes: one must go, the least recent
    assert _left(store) == [_name(0), _name(2), _name(3)]
    assert not (store.entries / f"{_name(1)}.hmac").exists()  # its HMAC with it
    assert store.info().size == 300 and store.read(_name(3)) == b"y" * 100


def test_the_entry_just_written_is_kept_even_alone_over_the_bound(tmp_path):
    store = Store(tmp_path / "cache", limit=50, check_every=0)
    store.write(_name(0), b"x" * 40)
    store.write(_name(1), b"y" * 80)
    assert _left(store) == [_name(1)] and store.read(_name(1)) == b"y" * 80


def test_trim_on_demand_and_stale_temporary_files(tmp_path):
    store = Store(tmp_path / "cache")
    for k in range(5):
        store.write(_name(k), b"x" * 10)
        _aged(store, _name(k), 100 - k)
    stale, fresh = store.entries / ".tmp-stale", store.entries / ".tmp-fresh"
    stale.write_bytes(b"half")
    fresh.write_bytes(b"half")  # another process is writing it
    os.utime(stale, (0, 0))
    assert store.trim(25) == Trimmed(entries=3, freed=30, size=20)
    assert _left(store) == [_name(3), _name(4)]
    assert not stale.exists() and fresh.exists()
    assert store.trim(25) == Trimmed(0, 0, 20)
    assert store.trim(0) == Trimmed(2, 20, 0) and store.info().entries == 0


def test_a_folder_of_another_user_is_not_trimmed(store, monkeypatch):
    for k in range(3):
        store.write(_name(k), b"x" * 10)
    monkeypatch.setattr(os, "getuid", lambda: os.stat(store.root).st_uid + 1)
    assert store.trim(0) == Trimmed(0, 0, 0)
    monkeypatch.undo()
    assert store.info().entries == 3


def test_a_symlink_among_the_entries_is_deleted_not_followed(store, tmp_path):
    outside = tmp_path / "outside"
    outside.write_bytes(b"precious" * 100)
    store.write(_name(0), b"x")
    (store.entries / _name(1)).symlink_to(outside)
    _aged(store, _name(0), 10)
    os.utime(store.entries / _name(1), (0, 0), follow_symlinks=False)
    store.trim(1)
    assert outside.read_bytes() == b"precious" * 100 and not (store.entries / _name(1)).is_symlink()


def test_the_bound_from_the_environment(monkeypatch, tmp_path):
    monkeypatch.delenv("DHSYM_CACHE_SIZE", raising=False)
    assert cache_limit() == DEFAULT_LIMIT == 512 * 2**20
    monkeypatch.setenv("DHSYM_CACHE_SIZE", "200")
    assert cache_limit() == 200 and Store(tmp_path).bound() == 200
    assert Store(tmp_path, limit=7).bound() == 7
    monkeypatch.setenv("DHSYM_CACHE", str(tmp_path / "c"))
    store = default_store()
    assert store is not None and store.info().limit == 200
    for k in range(4):
        store.write(_name(k), b"x" * 90)
    assert store.info().entries == 4  # checked on the first write only: within a minute
    os.utime(store.root / "trimmed", (0, 0))  # a minute later
    store.write(_name(4), b"x" * 90)
    assert store.info().entries == 2  # 180 of 200 bytes
    monkeypatch.setenv("DHSYM_CACHE_SIZE", "a lot")
    os.utime(store.root / "trimmed", (0, 0))
    with pytest.raises(DHError, match="DHSYM_CACHE_SIZE"):
        store.write(_name(9), b"x")


@pytest.mark.parametrize(
    ("text", "size"),
    [
        ("0", 0),
        ("1000", 1000),
        ("64k", 65536),
        ("64KB", 65536),
        ("200 MiB", 200 * 2**20),
        ("1.5g", 3 * 2**29),
        ("2T", 2 * 2**40),
    ],
)
def test_sizes(text, size):
    assert parse_size(text) == size


@pytest.mark.parametrize("text", ["", "-1", "1e6", "12 bytes", "M", "5P"])
def test_what_is_not_a_size(text):
    with pytest.raises(DHError, match="not a size"):
        parse_size(text)
