"""On-disk cache of derived symbolic objects (solutions, reductions): signed, self-checking entries.

Where
    The folder is ``$PERTURB_CACHE_DIR`` if set, else ``$XDG_CACHE_HOME/perturb`` or
    ``~/.cache/perturb``; ``PERTURB_CACHE_DIR=off`` disables the disk cache.  The folder must be
    private: one that other users can write (group/other write bit without the sticky bit) or that
    another user owns is refused with a :class:`~perturb.errors.CacheWarning`, and the run goes on
    without a disk cache.  So does a run whose folder cannot be written.

What an entry is
    ``MAGIC | tag | header length | header | payload``.  The payload is a pickle of the result; the
    header (JSON) names the format, the kind, the full key (SHA-256 of everything the result
    depends on: the inputs' ``srepr``, the perturb, sympy and Python versions and the engine's
    source), the perturb version, the engine fingerprint and the payload's SHA-256 and size.  The tag
    is an HMAC-SHA256 of everything after it under a per-user secret key kept *outside* the cache
    folder (``$PERTURB_CACHE_KEY_FILE``, else ``$XDG_CONFIG_HOME/perturb/cache.key`` or
    ``~/.config/perturb/cache.key``, 32 random bytes created with mode 0600 on first use).

Reading
    The tag is checked with ``hmac.compare_digest`` *before* anything is parsed or unpickled, so
    a file nobody holding the key wrote is never unpickled (unpickling runs code).  Then every header
    field must match what this call expects.  A truncated, corrupt, unsigned, foreign (another key),
    stale (another version, engine or format) or unloadable entry is discarded, recomputed and
    rewritten: it is never returned and never raises.  Each kind of trouble warns once per process.

Writing
    A temporary file in the folder (mode 0600) is moved into place by :func:`os.replace`, so
    concurrent writers of one key never leave a torn entry: the last complete one wins.  One left
    by a killed writer is removed, an hour old, by the next writer (``perturb/cache_files.py``).

Why pickle behind an HMAC rather than a code-free encoding: see ``benchmarks/bench_cache.py``.  A
results tree holds sympy expressions inside several attrs classes of the engine; a whitelisted tree
encoding must be kept in step with each of them, while the signature makes any pickle that this user's
perturb did not write unreadable, at a cost of microseconds.
"""

from __future__ import annotations

import contextlib
import contextvars
import enum
import functools
import hashlib
import hmac
import json
import os
import pickle
import platform
import re
import secrets
import stat
import struct
import tempfile
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

from perturb.cache_files import prune, read_entry, write_entry
from perturb.errors import CacheWarning, bad_value
from perturb.pickling import UNPICKLABLE, digest, dumps

__all__ = [
    "UNPICKLABLE",
    "Uncached",
    "active",
    "bypassed",
    "cache_dir",
    "cached",
    "digest",
    "held_warnings",
    "key_file",
]

T = TypeVar("T")

#: Environment variable naming the cache folder (``off`` disables the cache).
CACHE_ENV = "PERTURB_CACHE_DIR"
#: Environment variable naming the file of the secret signing key (tests point it elsewhere).
KEY_ENV = "PERTURB_CACHE_KEY_FILE"
#: Environment variable set (to ``1``) for the worker processes of a sweep's own local cluster: they
#: share its folder and key, whose trouble the sweep's process reports, so theirs is not reported
#: again (once per worker, in their own format); an entry they repair is still repaired.
QUIET_ENV = "PERTURB_CACHE_QUIET"
#: Bump when the layout of an entry or of the pickled objects changes.  Format 1 was a bare pickle;
#: format 2 pickled sympy's sums, products and powers by their constructors (re-evaluated on read).
CACHE_FORMAT = 3

#: First bytes of every entry: tells a perturb entry from any other file before the tag is checked.
_MAGIC = b"perturb-cache\n"
#: HMAC-SHA256 tag length in bytes.
_TAG_SIZE = hashlib.sha256().digest_size
#: Length prefix of the JSON header (unsigned 32-bit big-endian).
_LENGTH = struct.Struct(">I")
#: Bytes of the secret key: the HMAC-SHA256 block's worth of entropy (256 bits).
_SECRET_SIZE = 32
#: Permission bits that let users other than the owner write a folder.
_OTHERS_WRITE = stat.S_IWGRP | stat.S_IWOTH
#: Permission bits that let users other than the owner read or write the key file.
_OTHERS_ANY = stat.S_IRWXG | stat.S_IRWXO
#: A kind is a plain label: it becomes a file-name prefix, so no separators or dots.
_KIND = re.compile(r"[A-Za-z0-9_-]{1,40}")
#: Hex digits of an entry's key in its file name (SHA-256), and the pattern of one of them.
_KEY_DIGITS = 2 * hashlib.sha256().digest_size
_HEX = "[0-9a-f]"


class Rejection(enum.Enum):
    """Why an entry on disk was not used; the values are the messages shown to users."""

    NOT_A_FILE = "is not a regular file"
    TRUNCATED = "is truncated"
    NOT_AN_ENTRY = "is not a perturb cache entry"
    UNSIGNED = (
        "does not carry this user's signature (corrupt, or not written by this user's perturb)"
    )
    BAD_HEADER = "has an unreadable header"
    STALE = "was written by another perturb version, engine or cache format"
    FOREIGN = "holds the result of other inputs (another key)"
    BAD_CONTENT = "does not match its content hash"
    UNLOADABLE = "could not be unpickled"


# ---------------------------------------------------------------------------------- locations


def cache_dir() -> Path | None:
    """The cache folder, or ``None`` when caching on disk is disabled.

    Returns
    -------
    pathlib.Path or None
        ``$PERTURB_CACHE_DIR`` (``~`` expanded; ``off``, ``0``, ``none`` or empty: None), else
        ``$XDG_CACHE_HOME/perturb`` or ``~/.cache/perturb``.

    Examples
    --------
    >>> import os
    >>> from unittest import mock
    >>> from perturb.cache import cache_dir
    >>> with mock.patch.dict(os.environ, {"PERTURB_CACHE_DIR": "off"}):
    ...     cache_dir() is None
    True
    >>> with mock.patch.dict(os.environ, {"PERTURB_CACHE_DIR": "/scratch/perturb"}):
    ...     cache_dir().as_posix()
    '/scratch/perturb'
    """
    value = os.environ.get(CACHE_ENV)
    if value is not None:
        off = value.strip().lower() in ("off", "0", "none", "")
        return None if off else Path(value).expanduser()  # "~/..." quoted: the home folder
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "perturb"


def key_file() -> Path:
    """The file holding this user's secret signing key (outside the cache folder).

    Returns
    -------
    pathlib.Path
        ``$PERTURB_CACHE_KEY_FILE``, else ``$XDG_CONFIG_HOME/perturb/cache.key`` or
        ``~/.config/perturb/cache.key`` (made with mode 0600 on first use).

    Examples
    --------
    >>> import os
    >>> from unittest import mock
    >>> from perturb.cache import key_file
    >>> with mock.patch.dict(os.environ, {"PERTURB_CACHE_KEY_FILE": "/secure/perturb.key"}):
    ...     key_file().as_posix()
    '/secure/perturb.key'
    """
    value = os.environ.get(KEY_ENV, "").strip()
    if value:
        return Path(value).expanduser()
    base = os.environ.get("XDG_CONFIG_HOME") or os.path.join(os.path.expanduser("~"), ".config")
    return Path(base) / "perturb" / "cache.key"


def _uid() -> int | None:
    """The effective user id, or ``None`` where the platform has none (ownership is not checked)."""
    return os.geteuid() if hasattr(os, "geteuid") else None


# ---------------------------------------------------------------------------------- warnings

#: Kinds of trouble already reported in this process (each is reported once).
_WARNED: set[str] = set()


#: Inside :func:`held_warnings`: the cache's warnings given in the block, given when it ends.
_HELD: contextvars.ContextVar[list[str] | None] = contextvars.ContextVar(
    "perturb_cache_held", default=None
)


def _give(text: str, stacklevel: int) -> None:
    """Warn ``text`` now, or hold it for the innermost :func:`held_warnings` block."""
    held = _HELD.get()
    if held is not None:
        held.append(text)
    else:
        warnings.warn(text, CacheWarning, stacklevel=stacklevel + 1)


def _warn_once(topic: str, message: str) -> None:
    if topic not in _WARNED:
        _WARNED.add(topic)
        if os.environ.get(QUIET_ENV) == "1":
            return
        _give(f"perturb cache: {message}", stacklevel=4)


@contextlib.contextmanager
def held_warnings():
    """Hold the cache's warnings given inside the block and give them when it ends.

    A block that records the warnings of a computation as its result's own (a point's notes, a
    JSON's ``warnings``), or ignores them, holds the cache's: they concern the machine (a full
    or read-only folder, a damaged entry), not the result, and are given once per process, so a
    block that recorded or ignored one would change the result or lose the warning.  Put it
    before the recording ``warnings.catch_warnings`` in the same ``with``; nested blocks give
    their warnings to the outermost.

    Yields
    ------
    None
        The block runs with the cache's warnings held.

    Examples
    --------
    >>> import warnings
    >>> with held_warnings(), warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     value = cached("solution", ("demo",), lambda: 42)
    >>> caught
    []
    """
    held: list[str] = []
    token = _HELD.set(held)
    try:
        yield
    finally:
        _HELD.reset(token)
        for text in held:
            _give(text, stacklevel=4)


class _Unusable(Exception):
    """The folder or the key cannot be used safely; carries the (one-line) reason and fix."""


# ---------------------------------------------------------------------------------- the folder


def _check_folder(folder: Path) -> None:
    """Create ``folder`` (mode 0700) if needed; raise :class:`_Unusable` unless it is private."""
    try:
        folder.mkdir(mode=0o700, parents=True, exist_ok=True)
        info = os.stat(folder)
    except OSError as exc:
        raise _Unusable(f"cannot create the folder `{folder}` ({exc.strerror})") from None
    if not stat.S_ISDIR(info.st_mode):
        raise _Unusable(f"`{folder}` is not a folder")
    uid = _uid()
    if uid is not None and info.st_uid != uid:
        raise _Unusable(
            f"the folder `{folder}` belongs to user id {info.st_uid}, not to you: "
            f"set {CACHE_ENV} to a folder of your own"
        )
    if info.st_mode & _OTHERS_WRITE and not info.st_mode & stat.S_ISVTX:
        raise _Unusable(
            f"the folder `{folder}` can be written by other users "
            f"(mode {stat.S_IMODE(info.st_mode):04o}): run `chmod go-w {folder}`"
        )


# ---------------------------------------------------------------------------------- the key


def _read_secret(path: Path) -> bytes:
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise _Unusable(f"the key `{path}` is not a regular file: remove it")
        uid = _uid()
        if uid is not None and info.st_uid != uid:
            raise _Unusable(f"the key `{path}` belongs to user id {info.st_uid}: remove it")
        if uid is not None and info.st_mode & _OTHERS_ANY:
            raise _Unusable(
                f"the key `{path}` is open to other users "
                f"(mode {stat.S_IMODE(info.st_mode):04o}): run `chmod 600 {path}`"
            )
        secret = os.read(fd, _SECRET_SIZE + 1)
    finally:
        os.close(fd)
    if len(secret) != _SECRET_SIZE:
        raise _Unusable(f"the key `{path}` is damaged: remove it (a new one is made on next use)")
    return secret


def _create_secret(path: Path) -> None:
    """Write a new random key to ``path`` unless one appears there first (atomic, mode 0600)."""
    path.parent.mkdir(mode=0o700, parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".cache.key.")  # mkstemp: mode 0600
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(secrets.token_bytes(_SECRET_SIZE))
        try:
            os.link(tmp, path)  # fails if another process made the key meanwhile: use theirs
        except FileExistsError:
            pass
        except OSError:  # no hard links here: exclusive creation (a racing reader may see it short)
            try:
                fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
            except FileExistsError:
                return
            with os.fdopen(fd, "wb") as dst:
                dst.write(Path(tmp).read_bytes())
    finally:
        os.unlink(tmp)


def _secret(folder: Path) -> bytes:
    """This user's signing key, created on first use; :class:`_Unusable` if it cannot be trusted."""
    path = key_file()
    if Path(os.path.realpath(path)).is_relative_to(os.path.realpath(folder)):
        raise _Unusable(
            f"the key `{path}` lies inside the cache folder: set {KEY_ENV} to a path outside it"
        )
    try:
        try:
            return _read_secret(path)
        except FileNotFoundError:
            _create_secret(path)
            return _read_secret(path)
    except OSError as exc:
        raise _Unusable(f"cannot read or create the key `{path}` ({exc.strerror})") from None


# ---------------------------------------------------------------------------------- entries


@functools.cache
def _code_fingerprint() -> str:
    """Hash of the engine's source: an edited engine never reads results of an older one."""
    root = Path(__file__).parent
    digest = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        digest.update(path.relative_to(root).as_posix().encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()[:16]


@functools.cache
def _environment() -> dict:
    """What every entry must share with this process besides its key."""
    import sympy

    from perturb import __version__

    return {
        "format": CACHE_FORMAT,
        "perturb": __version__,
        "engine": _code_fingerprint(),
        "sympy": sympy.__version__,
        "python": platform.python_version(),
    }


def _key(kind: str, parts: tuple) -> str:
    """Full SHA-256 (hex) of everything the result depends on."""
    text = repr((sorted(_environment().items()), kind, *parts))
    return hashlib.sha256(text.encode()).hexdigest()


def _sign(secret: bytes, body: bytes) -> bytes:
    return hmac.new(secret, _MAGIC + body, hashlib.sha256).digest()


def encode(kind: str, key: str, value: object, secret: bytes) -> bytes:
    """The bytes of the entry holding ``value`` under ``key`` (raises if it cannot be pickled)."""
    payload = dumps(value)
    header = {
        **_environment(),
        "kind": kind,
        "key": key,
        "sha256": hashlib.sha256(payload).hexdigest(),
        "size": len(payload),
    }
    header_bytes = json.dumps(header, sort_keys=True).encode()
    body = _LENGTH.pack(len(header_bytes)) + header_bytes + payload
    return _MAGIC + _sign(secret, body) + body


def decode(blob: bytes, kind: str, key: str, secret: bytes) -> tuple[Rejection | None, object]:
    """``(None, value)`` for a valid entry of ``kind``/``key``, else ``(why, None)``.

    Nothing is parsed or unpickled before the signature is verified.
    """
    start = len(_MAGIC) + _TAG_SIZE
    head = blob[: len(_MAGIC)]
    if head != _MAGIC[: len(head)]:
        return Rejection.NOT_AN_ENTRY, None
    if len(blob) < start + _LENGTH.size:
        return Rejection.TRUNCATED, None
    tag, body = blob[len(_MAGIC) : start], blob[start:]
    if not hmac.compare_digest(tag, _sign(secret, body)):
        return Rejection.UNSIGNED, None
    # From here on the bytes are this user's perturb's own: the checks below catch stale or
    # misplaced entries, not forgeries.
    (size,) = _LENGTH.unpack_from(body)
    end = _LENGTH.size + size
    try:
        header = json.loads(body[_LENGTH.size : end])
    except ValueError:
        return Rejection.BAD_HEADER, None
    if not isinstance(header, dict):
        return Rejection.BAD_HEADER, None
    if any(header.get(name) != value for name, value in _environment().items()):
        return Rejection.STALE, None
    if header.get("kind") != kind or header.get("key") != key:
        return Rejection.FOREIGN, None
    payload = body[end:]
    if len(payload) != header.get("size") or hashlib.sha256(payload).hexdigest() != header.get(
        "sha256"
    ):
        return Rejection.BAD_CONTENT, None
    try:
        return None, pickle.loads(payload)
    except Exception:  # a signed entry of ours whose classes changed without a format bump
        return Rejection.UNLOADABLE, None


#: Set inside :func:`bypassed`: every :func:`cached` call computes afresh and writes nothing.
_BYPASS: contextvars.ContextVar[bool] = contextvars.ContextVar(
    "perturb_cache_bypass", default=False
)


@contextlib.contextmanager
def bypassed():
    """Compute everything afresh inside the block (to time a derivation), leaving the cache as it is.

    Yields
    ------
    None
        The block runs with the disk cache neither read nor written.

    Examples
    --------
    >>> with bypassed():
    ...     cached("solution", ("demo",), lambda: 42)
    42
    """
    token = _BYPASS.set(True)
    try:
        yield
    finally:
        _BYPASS.reset(token)


def active() -> bool:
    """Whether :func:`cached` uses the disk now (a folder is set and it is not bypassed).

    Returns
    -------
    bool

    Examples
    --------
    >>> import os
    >>> from unittest import mock
    >>> from perturb.cache import active, bypassed
    >>> with mock.patch.dict(os.environ, {"PERTURB_CACHE_DIR": "/scratch/perturb"}):
    ...     on = active()
    ...     with bypassed():
    ...         inside = active()
    >>> on, inside
    (True, False)
    """
    return cache_dir() is not None and not _BYPASS.get()


class Uncached:
    """A value :func:`cached` returns but does not keep: one that depends on this run, not on the
    key alone (a solve cut by its time budget, which a faster or idler machine would finish).

    Parameters
    ----------
    value : object
        What the computation gives this time.

    Examples
    --------
    >>> Uncached(([], "the budget was spent")).value
    ([], 'the budget was spent')
    """

    __slots__ = ("value",)

    def __init__(self, value) -> None:
        self.value = value

    @staticmethod
    def unwrap(value):
        """``value``, or the value it holds when it is :class:`Uncached`."""
        return value.value if isinstance(value, Uncached) else value


def cached(
    kind: str,
    parts: tuple | Callable[[], tuple],
    compute: Callable[[], T],
    *,
    keep: int | None = None,
) -> T:
    """Return ``compute()``, reading it from / writing it to the disk cache when enabled.

    Parameters
    ----------
    kind : str
        A label used as the file prefix (``solution``, ``reduction`` ...): letters, digits, ``-``, ``_``.
    parts : tuple or callable
        Everything the result depends on, as text-representable values (use ``sympy.srepr``), or
        a function returning that tuple: called only when the disk cache is in use, so that a run
        with the cache off or bypassed does not pay for a costly key (``srepr`` of a large system).
    compute : callable
        Builds the object when it is not cached.
    keep : int, optional
        Keep at most this many entries of ``kind``, the most recently written: for entries made
        anew at every point of a sweep.  Default: no bound.

    Returns
    -------
    The value of ``compute()``, or an equal one read from a valid entry.  Cache trouble never
    raises: it warns once (:class:`~perturb.errors.CacheWarning`) and computes.

    Examples
    --------
    The second call reads what the first wrote (a private folder of its own here):

    >>> import os, tempfile
    >>> from unittest import mock
    >>> from perturb.cache import cached
    >>> calls = []
    >>> def derive():
    ...     calls.append("derived")
    ...     return {"omega": 1.0}
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     with mock.patch.dict(os.environ, {"PERTURB_CACHE_DIR": folder}):
    ...         first = cached("demo", ("the inputs", 1), derive)
    ...         second = cached("demo", ("the inputs", 1), derive)
    >>> first == second, calls
    (True, ['derived'])
    """
    if not isinstance(kind, str) or not _KIND.fullmatch(kind):
        raise bad_value("kind", kind, "use a short label of letters, digits, '-' or '_'")
    if not active():
        return Uncached.unwrap(compute())
    folder = cache_dir()
    if callable(parts):
        parts = parts()
    try:
        _check_folder(folder)
        secret = _secret(folder)
    except _Unusable as reason:
        _warn_once("unusable", f"{reason}; running without the disk cache")
        return Uncached.unwrap(compute())
    key = _key(kind, parts)
    path = folder / f"{kind}-{key}.pkl"
    try:
        found = read_entry(path)
    except OSError:  # a link, not a regular file, or unreadable
        found = Rejection.NOT_A_FILE
    if isinstance(found, bytes):
        why, value = decode(found, kind, key, secret)
        if why is None:
            return value
        found = why
    if isinstance(found, Rejection):
        _warn_once("invalid", f"the entry `{path}` {found.value}: it was recomputed and rewritten")
    value = compute()
    if isinstance(value, Uncached):
        return value.value
    try:
        data = encode(kind, key, value, secret)
    except UNPICKLABLE:
        return value  # not picklable: it simply is not cached
    try:
        write_entry(folder, path, data)
    except OSError as exc:
        _warn_once(
            "unwritable", f"cannot write to `{folder}` ({exc.strerror}); results are not kept"
        )
    else:
        if keep is not None:
            prune(folder, f"{kind}-{_HEX * _KEY_DIGITS}.pkl", keep)  # not another kind's
    return value
