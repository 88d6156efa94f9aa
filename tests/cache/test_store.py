"""The disk cache: private folders and files, atomic writes, HMAC-verified reads
(dhsym.cache.store)."""

from __future__ import annotations

import os
import stat

import pytest

from dhsym.cache.store import Store, cache_enabled, cache_root, default_store

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
