"""Bytes into files without tearing them, and their digests: what :mod:`perturb.report.written`
(single files) and :mod:`perturb.report.folder` (report folders) both write and compare.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import stat
import tempfile
from pathlib import Path

__all__ = ["as_bytes", "atomic_write", "can_create", "digest_bytes", "digest_file"]


def digest_file(path: Path) -> str | None:
    """The SHA-256 of the regular file ``path`` (None if it is not one or cannot be read)."""
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | os.O_NONBLOCK)
    except OSError:
        return None
    with os.fdopen(fd, "rb") as fh:
        if not stat.S_ISREG(os.fstat(fh.fileno()).st_mode):
            return None
        digest = hashlib.sha256()
        for block in iter(lambda: fh.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def digest_bytes(data: bytes) -> str:
    """The SHA-256 of ``data``, in hex."""
    return hashlib.sha256(data).hexdigest()


def as_bytes(content: bytes | str) -> bytes:
    """``content`` as bytes (text in UTF-8)."""
    return content.encode("utf-8") if isinstance(content, str) else bytes(content)


def atomic_write(path: Path, data: bytes) -> None:
    """``data`` into ``path`` by a temporary file in its folder moved into place (never torn)."""
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        mode = stat.S_IMODE(os.stat(path).st_mode) if path.exists() else 0o666 & ~_umask()
        os.chmod(tmp, mode)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def can_create(folder: Path) -> bool:
    """Whether a file can be created in ``folder`` (a probe with a fresh name, removed at once)."""
    try:
        with tempfile.NamedTemporaryFile(dir=folder, prefix=".perturb-probe-"):
            return True
    except OSError:
        return False
