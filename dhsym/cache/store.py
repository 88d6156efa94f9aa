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

The folder is bounded: its entries take at most :data:`DEFAULT_LIMIT` bytes (512 MiB;
``$DHSYM_CACHE_SIZE`` sets another bound, as ``200M``, ``2G``, ``64k`` or a number of bytes;
the HMAC files, 64 bytes each, are not counted). A write checks the size (a scan of the
folder) when the last check is a minute old or more (the file ``trimmed`` in the folder
records when), and if the entries exceed the bound deletes the least recently used ones
(by modification time: a read that passes the checks marks its entry used) until they
fit, never the entry just written. The folder may thus exceed the bound by what a minute
of writing adds, until the next write; :meth:`Store.trim` (``dhsym cache trim``) trims at
once.

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
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import TypeVar

from dhsym.errors import DHError

__all__ = [
    "DEFAULT_LIMIT",
    "CacheInfo",
    "Store",
    "Trimmed",
    "cache_enabled",
    "cache_limit",
    "cache_root",
    "default_store",
    "derived_once",
    "parse_size",
]

T = TypeVar("T")

_NAME = re.compile(r"[a-z][a-z0-9_]{0,31}-[0-9a-f]{16,64}(\.[a-z]{1,8})?")
_KEY_BYTES = 32

#: The bound of the entries' size in bytes when ``$DHSYM_CACHE_SIZE`` sets none (512 MiB).
DEFAULT_LIMIT = 512 * 2**20
#: A temporary file a write left behind (a process killed mid-write) older than this many
#: seconds is deleted by :meth:`Store.trim`.
_STALE_SECONDS = 3600
_SIZE = re.compile(r"(\d+(?:\.\d+)?)\s*([kmgt]?)(?:i?b)?", re.IGNORECASE)


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


def parse_size(text: str, field: str = "size") -> int:
    """A size in bytes from ``text``: a number of bytes, or with ``k``, ``M``, ``G`` or
    ``T`` (powers of 1024; ``KB``, ``MiB`` … read alike). ``field`` names it in the error.

    >>> parse_size("512M"), parse_size("64k"), parse_size("1.5G"), parse_size("1000")
    (536870912, 65536, 1610612736, 1000)
    >>> parse_size("lots", "DHSYM_CACHE_SIZE")
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: field DHSYM_CACHE_SIZE: not a size: 'lots' (a number of bytes, ...
    """
    found = _SIZE.fullmatch(text.strip())
    if found is None:
        raise DHError(
            f"not a size: {text!r} (a number of bytes, or with k, M, G or T: 200M)", field=field
        )
    number, unit = found.groups()
    return int(float(number) * 1024 ** " kmgt".index(unit.lower() or " "))


def cache_limit() -> int:
    """The bound of the entries' size in bytes: ``$DHSYM_CACHE_SIZE``, else
    :data:`DEFAULT_LIMIT`.

    Raises
    ------
    DHError
        When ``$DHSYM_CACHE_SIZE`` is not a size (naming the variable).
    """
    given = os.environ.get("DHSYM_CACHE_SIZE", "").strip()
    return parse_size(given, "DHSYM_CACHE_SIZE") if given else DEFAULT_LIMIT


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
    >>> before = os.environ.get("DHSYM_CACHE")
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     os.environ["DHSYM_CACHE"] = tmp
    ...     try:
    ...         print(once(), once())
    ...     finally:
    ...         if before is None:
    ...             del os.environ["DHSYM_CACHE"]
    ...         else:
    ...             os.environ["DHSYM_CACHE"] = before
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
    """What ``dhsym cache info`` prints: the folder, its entries and their size in bytes,
    whether the cache is on, and the bound of the size (:func:`cache_limit`)."""

    root: Path
    entries: int
    size: int
    enabled: bool
    limit: int = DEFAULT_LIMIT


@dataclass(frozen=True)
class Trimmed:
    """What :meth:`Store.trim` did: the entries deleted, the bytes they took, and the size
    of the entries left."""

    entries: int
    freed: int
    size: int


@dataclass(frozen=True)
class Store:
    """The disk cache in folder ``root`` (see the module's docstring). ``limit`` bounds the
    entries' size in bytes (``None``: :func:`cache_limit`, read when a write needs it);
    a write checks it when the last check is ``check_every`` seconds old or more."""

    root: Path
    limit: int | None = None
    check_every: float = 60.0

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
        try:  # used now: the last entry a trim deletes
            os.utime(path)
        except OSError:
            pass
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
        if self._check_due():
            self._fit(keep=name)
        return True

    def _check_due(self) -> bool:
        """Whether a write should check the size now: the last check (the modification time
        of ``root/trimmed``) is ``check_every`` seconds old or more; if so it is now."""
        marker = self.root / "trimmed"
        try:
            if time.time() - marker.lstat().st_mtime < self.check_every:
                return False
        except OSError:
            pass  # never checked
        try:
            _write_atomic(marker, b"")
        except OSError:
            return False
        return True

    def trim(self, limit: int | None = None) -> Trimmed:
        """Delete the least recently used entries (oldest modification time first; a read
        marks its entry used) until the entries take at most ``limit`` bytes (default: this
        store's bound), and temporary files a killed write left (older than an hour).

        >>> import tempfile
        >>> with tempfile.TemporaryDirectory() as tmp:
        ...     store = Store(Path(tmp) / "cache")
        ...     for k in range(4):
        ...         _ = store.write(f"rne-{k:064x}", b"x" * 100)
        ...     print(store.trim(250), store.info().entries)
        Trimmed(entries=2, freed=200, size=200) 2
        """
        return self._fit(limit=limit)

    def bound(self) -> int:
        """The bound of the entries' size in bytes: ``limit``, else :func:`cache_limit`."""
        return self.limit if self.limit is not None else cache_limit()

    def _fit(self, keep: str | None = None, limit: int | None = None) -> Trimmed:
        """:meth:`trim` to ``limit`` (default :meth:`bound`), never deleting entry ``keep``
        (the one just written)."""
        if self._folder(create=False) is None:  # not this user's: nothing is deleted
            return Trimmed(0, 0, 0)
        bound = self.bound() if limit is None else limit
        used: list[tuple[int, str, int]] = []  # (modification time, name, size)
        stale = []
        now = time.time()
        try:
            with os.scandir(self.entries) as found:
                for item in found:
                    try:
                        st = item.stat(follow_symlinks=False)
                    except OSError:
                        continue
                    if item.name.startswith(".tmp-"):
                        if now - st.st_mtime > _STALE_SECONDS:
                            stale.append(item.name)
                    elif _NAME.fullmatch(item.name) and not item.name.endswith(".hmac"):
                        used.append((st.st_mtime_ns, item.name, st.st_size))
        except OSError:
            return Trimmed(0, 0, 0)
        for name in stale:
            _remove(self.entries / name)
        size = sum(s for _, _, s in used)
        removed = freed = 0
        for _, name, bytes_ in sorted(used):
            if size <= bound:
                break
            if name == keep:
                continue
            self.discard(name)
            size -= bytes_
            freed += bytes_
            removed += 1
        return Trimmed(removed, freed, size)

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
        return CacheInfo(self.root, len(names), size, cache_enabled(), self.bound())

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
