"""The disk cache: derived results and built libraries kept between processes, trusted only
when this user wrote them.

The folder is ``$DHSYM_CACHE`` when set, else the user cache folder of
:mod:`platformdirs` (``$XDG_CACHE_HOME/dhsym`` or ``~/.cache/dhsym`` on Linux);
``DHSYM_NO_CACHE=1`` (the command line's ``--no-cache``) turns it off, and it is off where
files have no POSIX owner and mode to check (Windows). Its rules:

- folders are created ``0700``, files ``0600``, each written to a temporary file in
  the same folder and moved in place with :func:`os.replace` (atomic);
- ``key`` is a 32-byte secret of this user (``0600``), made on first use; every entry
  ``<name>`` has a ``<name>.hmac``: the HMAC-SHA256 under that key of the entry's name and
  bytes, written by the process that wrote the entry;
- on reading, the folder, the key, the entry and its HMAC must be regular files (no
  symbolic links) owned by this user and unreadable and unwritable by others, and the
  HMAC must match (:func:`hmac.compare_digest`). Anything that fails is deleted and
  reads as absent: the caller derives or builds it again, never uses it.

A library planted under a predictable name therefore fails its HMAC (nobody else knows
the key) and is rebuilt before it is ever loaded.

Examples
--------
>>> import tempfile
>>> with tempfile.TemporaryDirectory() as tmp:
...     store = Store(Path(tmp) / "cache")
...     name = "transform-" + "ab" * 32
...     store.write(name, b"[1, 2]")
...     good = store.read(name)
...     _ = (store.root / "entries" / name).write_bytes(b"[6, 6]")  # changed behind its back
...     print(good, store.read(name), store.read(name))
True
b'[1, 2]' None None
"""

from __future__ import annotations

import hmac
import json
import os
import re
import secrets
import shutil
import stat
import tempfile
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import TypeVar

from dhsym.errors import DHError

__all__ = ["CacheInfo", "Store", "cache_enabled", "cache_root", "default_store", "derived_once"]

T = TypeVar("T")

_NAME = re.compile(r"[a-z][a-z0-9_]{0,31}-[0-9a-f]{16,64}(\.[a-z]{1,8})?")
_KEY_BYTES = 32


def cache_root() -> Path:
    """``$DHSYM_CACHE``, else the user cache folder of ``dhsym`` (:mod:`platformdirs`)."""
    root = os.environ.get("DHSYM_CACHE")
    if root:
        return Path(root).expanduser()
    import platformdirs

    return Path(platformdirs.user_cache_dir("dhsym", appauthor=False))


def cache_enabled() -> bool:
    """False when ``DHSYM_NO_CACHE`` is set to ``1``, ``true`` or ``yes``, and where files have
    no POSIX owner and mode to check (Windows: the memo of a process still works)."""
    if not hasattr(os, "getuid"):
        return False
    return os.environ.get("DHSYM_NO_CACHE", "").strip().lower() not in ("1", "true", "yes")


def default_store() -> Store | None:
    """The store of :func:`cache_root`, or ``None`` when the cache is turned off."""
    return Store(cache_root()) if cache_enabled() else None


def derived_once(
    name: Callable[[], str],
    derive: Callable[[], T],
    write: Callable[[T], bytes | None],
    read: Callable[[bytes], T | None],
    refusal: type[DHError],
) -> T:
    """``derive()``, kept in :func:`default_store` as entry ``name()``: a later process reads
    it back (verified) with ``read`` instead (``None`` from ``read``: not what this version
    writes, derived again and rewritten). ``write`` gives the bytes to keep (``None``:
    kept in this process only). A ``refusal`` that ``derive`` raises is kept too, as its
    message, and raised again without deriving. With the cache off: ``derive()``.

    >>> import tempfile
    >>> from dhsym.errors import TableError
    >>> def derive():
    ...     print("derived")
    ...     return 42
    >>> def once():
    ...     return derived_once(lambda: "answer-" + "0" * 16, derive, lambda v: b"%d" % v,
    ...                         lambda data: int(data), TableError)
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     os.environ["DHSYM_CACHE"] = tmp
    ...     try:
    ...         print(once(), once())
    ...     finally:
    ...         del os.environ["DHSYM_CACHE"]
    derived
    42 42
    """
    store = default_store()
    if store is None:
        return derive()
    entry = name()
    data = store.read(entry)
    if data is not None:
        refused = _refusal(data)
        if refused is not None:
            raise refusal(refused)
        found = read(data)
        if found is not None:
            return found
    try:
        value = derive()
    except refusal as err:  # a refusal found after seconds of work is kept too
        store.write(entry, json.dumps({"refused": err.message}).encode())
        raise
    kept = write(value)
    if kept is not None:
        store.write(entry, kept)
    return value


def _refusal(data: bytes) -> str | None:
    """The message of a kept refusal (``{"refused": message}``), else ``None``."""
    if not data.startswith(b'{"refused"'):
        return None
    try:
        doc = json.loads(data)
    except ValueError:
        return None
    refused = doc.get("refused") if isinstance(doc, dict) else None
    return refused if isinstance(refused, str) else None


@dataclass(frozen=True)
class CacheInfo:
    """What ``dhsym cache info`` prints: the folder, its entries and their size in bytes."""

    root: Path
    entries: int
    size: int
    enabled: bool


@dataclass(frozen=True)
class Store:
    """The disk cache in folder ``root`` (see the module's docstring)."""

    root: Path

    # -- the folder and the key ---------------------------------------------------------
    @property
    def entries(self) -> Path:
        """Where the entries are (``root/entries``)."""
        return self.root / "entries"

    def _folder(self, create: bool) -> Path | None:
        """The entries folder when it (and the root) are this user's and private; ``None``
        otherwise. ``create`` makes them ``0700`` (and makes an own folder private)."""
        if not hasattr(os, "getuid"):  # no POSIX owner to check: nothing is trusted
            return None
        for folder in (self.root, self.entries):
            try:
                st = folder.lstat()
            except FileNotFoundError:
                if not create:
                    return None
                try:
                    folder.mkdir(mode=0o700, parents=True, exist_ok=True)
                    st = folder.lstat()
                except OSError:
                    return None
            if not stat.S_ISDIR(st.st_mode) or st.st_uid != os.getuid():
                return None
            if st.st_mode & 0o077:
                if not create:
                    return None
                try:  # our own folder, too open: make it private (entries are MAC-checked)
                    os.chmod(folder, 0o700)
                except OSError:
                    return None
        return self.entries

    def _key(self, create: bool) -> bytes | None:
        """This user's secret, made on first use (``None`` when none can be trusted)."""
        path = self.root / "key"
        data = _read_private(path, _KEY_BYTES)
        if data is not None and len(data) == _KEY_BYTES:
            return data
        if not create:
            return None
        _remove(path)
        try:
            _write_atomic(path, secrets.token_bytes(_KEY_BYTES), exclusive=True)
        except FileExistsError:
            pass  # another process made it at the same moment: read theirs
        except OSError:
            return None
        data = _read_private(path, _KEY_BYTES)
        return data if data is not None and len(data) == _KEY_BYTES else None

    def _mac(self, key: bytes, name: str, data: bytes) -> bytes:
        return hmac.new(key, name.encode() + b"\0" + data, "sha256").hexdigest().encode()

    # -- entries --------------------------------------------------------------------------
    def read(self, name: str) -> bytes | None:
        """The bytes of entry ``name``, or ``None`` (absent, or refused and deleted)."""
        _check_name(name)
        folder = self._folder(create=False)
        key = self._key(create=False) if folder else None
        if folder is None or key is None:
            return None
        path, mac_path = folder / name, folder / f"{name}.hmac"
        if not path.exists() and not path.is_symlink():
            return None
        data, mac = _read_private(path), _read_private(mac_path, 256)
        if data is None or mac is None or not hmac.compare_digest(self._mac(key, name, data), mac):
            self.discard(name)
            return None
        return data

    def write(self, name: str, data: bytes) -> bool:
        """Store ``data`` as entry ``name`` (atomically, with its HMAC); False when the
        folder cannot be used (the result is simply not kept)."""
        _check_name(name)
        folder = self._folder(create=True)
        key = self._key(create=True) if folder else None
        if folder is None or key is None:
            return False
        try:
            _write_atomic(folder / f"{name}.hmac", self._mac(key, name, data))
            _write_atomic(folder / name, data)
        except OSError:
            return False
        return True

    def verified_file(self, name: str) -> Path | None:
        """The path of entry ``name`` when it passes every check (for a library to load
        by path); ``None`` when absent or refused (then deleted)."""
        return self.entries / name if self.read(name) is not None else None

    def put_file(self, name: str, source: Path) -> Path | None:
        """Move the file ``source`` (in a folder of this user) in as entry ``name``; its
        path, or ``None`` when the store cannot be used."""
        data = source.read_bytes()
        return self.entries / name if self.write(name, data) else None

    def discard(self, name: str) -> None:
        """Delete entry ``name`` and its HMAC (if this user may)."""
        _check_name(name)
        for path in (self.entries / name, self.entries / f"{name}.hmac"):
            _remove(path)

    def clear(self) -> int:
        """Delete every entry and the key; the number of entries deleted."""
        count = sum(1 for _ in self._names())
        if self._folder(create=False) is not None:
            shutil.rmtree(self.entries, ignore_errors=True)
            _remove(self.root / "key")
        return count

    def info(self) -> CacheInfo:
        """The folder, the number of entries and their size in bytes."""
        names = list(self._names())
        size = 0
        for name in names:
            try:
                size += (self.entries / name).lstat().st_size
            except OSError:
                pass
        return CacheInfo(self.root, len(names), size, cache_enabled())

    def _names(self) -> Iterator[str]:
        try:
            found = sorted(os.listdir(self.entries))
        except OSError:
            return
        for name in found:
            if _NAME.fullmatch(name) and not name.endswith(".hmac"):
                yield name


def _check_name(name: str) -> None:
    if not _NAME.fullmatch(name):
        raise ValueError(f"not a cache entry name: {name!r}")


def _read_private(path: Path, limit: int | None = None) -> bytes | None:
    """The bytes of a regular file owned by this user and private to them, else ``None``."""
    if not hasattr(os, "getuid"):
        return None
    try:
        fd = os.open(path, os.O_RDONLY | (os.O_NOFOLLOW if hasattr(os, "O_NOFOLLOW") else 0))
    except OSError:
        return None
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode) or st.st_uid != os.getuid() or st.st_mode & 0o077:
            return None
        if limit is not None and st.st_size > limit:
            return None
        with os.fdopen(fd, "rb", closefd=False) as f:
            return f.read()
    except OSError:
        return None
    finally:
        os.close(fd)


def _write_atomic(path: Path, data: bytes, *, exclusive: bool = False) -> None:
    """Write ``data`` to ``path`` as a ``0600`` file: a temporary file in the same folder,
    moved in place (``exclusive``: never replace an existing file)."""
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-")  # created 0600
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.chmod(tmp, 0o600)
        if exclusive:
            os.link(tmp, path)  # fails when it exists
        else:
            os.replace(tmp, path)
    finally:
        if os.path.lexists(tmp):
            os.unlink(tmp)


def _remove(path: Path) -> None:
    try:
        path.unlink()
    except OSError:
        pass
