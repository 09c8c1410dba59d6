"""Reading a user's input file (a scene, ``--times @FILE``) safely: only a regular file is opened,
without blocking, and never more than a size cap is read.

A FIFO with no writer would block the ``open`` for ever, ``/dev/zero`` would be read into memory
without end, a folder gives an ``IsADirectoryError``: each is refused in one line before anything
is read.
"""

from __future__ import annotations

import os
import stat

__all__ = ["UnreadableFile", "read_capped"]


class UnreadableFile(Exception):
    """The file cannot be read as an input; the message is the reason, in words."""


def _kind(mode: int) -> str | None:
    """What a non-regular file is, in words (None for a regular file)."""
    if stat.S_ISREG(mode):
        return None
    if stat.S_ISDIR(mode):
        return "a folder, not a file"
    if stat.S_ISFIFO(mode):
        return "a FIFO (named pipe), not a regular file"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device, not a regular file"
    if stat.S_ISSOCK(mode):
        return "a socket, not a regular file"
    return "not a regular file"


def _size(count: int) -> str:
    return f"{count / 2**20:.1f} MB" if count >= 2**20 else f"{count:,} bytes"


def read_capped(path, limit: int) -> bytes:
    """The bytes of the regular file ``path``, at most ``limit`` of them.

    Raises
    ------
    UnreadableFile
        The path does not exist, is a folder, a FIFO, a device or a socket, cannot be opened, or
        holds more than ``limit`` bytes (the message says which).
    """
    try:
        info = os.stat(path)
    except (OSError, ValueError) as exc:
        raise UnreadableFile(_reason(exc)) from None
    kind = _kind(info.st_mode)
    if kind is not None:
        raise UnreadableFile(kind)
    if info.st_size > limit:
        raise UnreadableFile(f"it holds {_size(info.st_size)}, more than {_size(limit)}")
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0)
    try:
        fd = os.open(path, flags)
    except OSError as exc:
        raise UnreadableFile(_reason(exc)) from None
    try:
        kind = _kind(os.fstat(fd).st_mode)  # replaced between the two looks: looked at again
        if kind is not None:
            raise UnreadableFile(kind)
        chunks, total = [], 0
        while total <= limit:
            chunk = os.read(fd, min(limit + 1 - total, 1 << 20))
            if not chunk:
                break
            chunks.append(chunk)
            total += len(chunk)
    except OSError as exc:
        raise UnreadableFile(_reason(exc)) from None
    finally:
        os.close(fd)
    if total > limit:
        raise UnreadableFile(f"it holds more than {_size(limit)}")
    return b"".join(chunks)


def _reason(exc: BaseException) -> str:
    if isinstance(exc, OSError) and exc.strerror:
        return exc.strerror
    return " ".join(str(exc).split()) or type(exc).__name__
