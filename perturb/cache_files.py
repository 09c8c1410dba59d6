"""The disk cache's files: an entry read without following a link, written whole, pruned; the
temporary files a killed writer left behind removed (for :mod:`perturb.cache`, which decides what
an entry holds and whether it can be trusted)."""

from __future__ import annotations

import contextlib
import os
import stat
import tempfile
import time
from pathlib import Path

from perturb._defaults import CACHE_LEFTOVER_SECONDS

__all__ = ["prune", "read_entry", "sweep_leftovers", "write_entry"]

#: A writer's temporary file (:func:`write_entry`): ``tempfile.mkstemp``'s prefix and our suffix.
TEMPORARY = "tmp*.tmp"

#: The folders whose leftovers this process has swept (once each).
_SWEPT: set[Path] = set()


class NotARegularFile(OSError):
    """The entry's path names something else than a regular file (a folder, a device)."""


def read_entry(path: Path) -> bytes | None:
    """The bytes at ``path``, or None if there is no entry.

    Raises
    ------
    OSError
        ``path`` is a symbolic link (never followed), not a regular file
        (:class:`NotARegularFile`), or unreadable.
    """
    try:
        fd = os.open(
            path, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0)
        )
    except FileNotFoundError:
        return None
    with os.fdopen(fd, "rb") as fh:
        if not stat.S_ISREG(os.fstat(fh.fileno()).st_mode):
            raise NotARegularFile(f"{path} is not a regular file")
        return fh.read()


def write_entry(folder: Path, path: Path, data: bytes) -> None:
    """Atomically put ``data`` at ``path``: a temporary file in ``folder`` (mode 0600) moved into
    place by :func:`os.replace`, so concurrent writers never leave a torn entry."""
    sweep_leftovers(folder)
    fd, tmp = tempfile.mkstemp(dir=folder, suffix=".tmp")  # mode 0600
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def sweep_leftovers(folder: Path) -> None:
    """Remove the temporary files a killed writer left in ``folder`` (older than
    ``CACHE_LEFTOVER_SECONDS``: a live writer's is milliseconds old), once per process and
    folder. A file already gone, or not ours to remove, is skipped; a link is left alone."""
    if folder in _SWEPT:
        return
    _SWEPT.add(folder)
    now = time.time()
    for path in folder.glob(TEMPORARY):
        with contextlib.suppress(OSError):
            info = path.lstat()
            if stat.S_ISREG(info.st_mode) and now - info.st_mtime > CACHE_LEFTOVER_SECONDS:
                path.unlink()


def prune(folder: Path, pattern: str, keep: int) -> None:
    """Remove the entries matching ``pattern`` in ``folder`` beyond the ``keep`` most recently
    written.

    By the time written, not read: a read leaves its entry as it is (a warm run writes nothing).
    Concurrent runs may prune together: an entry already gone is skipped.
    """
    entries = []
    for path in folder.glob(pattern):
        with contextlib.suppress(OSError):
            entries.append((path.stat().st_mtime_ns, path))
    entries.sort(reverse=True)
    for _, path in entries[keep:]:
        with contextlib.suppress(OSError):
            path.unlink()
