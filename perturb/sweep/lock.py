"""One writer per sweep store: an exclusive lock on the store's folder (:class:`StoreLock`).

A driver holds the lock from the moment it creates or opens a store until it has written its
last chunk, so that two drivers (two ``--resume`` runs, a resume and a fresh run) never compute
the same points: the second is refused at once, in one line, before any work. The lock is
``flock`` on the folder itself (no file is added to the store); the system releases it when the
process ends, however it ends (``kill -9`` included), so a store is never left locked.
"""

from __future__ import annotations

import os
from pathlib import Path

from perturb.errors import InvalidParameterError

__all__ = ["StoreLock"]


class StoreLock:
    """An exclusive, non-blocking lock on the folder ``path`` (held until :meth:`release`)."""

    def __init__(self, path):
        self.path = Path(path)
        self.fd: int | None = None

    def acquire(self) -> StoreLock:
        """Take the lock, or raise at once if another process holds it.

        Raises
        ------
        perturb.errors.InvalidParameterError
            Another process (another perturb sweep) is writing the store now.
        """
        try:
            import fcntl
        except ImportError:  # pragma: no cover - not POSIX: one writer is the user's to keep
            return self
        fd = os.open(self.path, os.O_RDONLY)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(fd)
            raise InvalidParameterError(
                f"--output {str(self.path)!r}: another perturb sweep is writing this store now "
                "(it holds its lock); wait for it to end, then run again with --resume"
            ) from None
        self.fd = fd
        return self

    def release(self) -> None:
        if self.fd is not None:
            os.close(self.fd)  # closing the descriptor releases the lock
            self.fd = None

    def __enter__(self) -> StoreLock:
        return self.acquire()

    def __exit__(self, *exc) -> None:
        self.release()
