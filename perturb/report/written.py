"""What perturb wrote, so that it never removes or overwrites what it did not write.

Two kinds of output:

**A file** (``--output FILE`` of the commands that print, ``--plot FILE``). :func:`check_file`
runs before any work: the path is not empty, not a folder, its folder exists and can be written,
its plot format is known; an existing, non-empty file is refused (one line, exit 2) unless perturb
wrote it — or ``force`` is given. :func:`write_file` writes atomically (a temporary file in the
same folder moved into place) and records what it wrote in this user's record of outputs,
``outputs-written.json`` in perturb's cache folder (``PERTURB_CACHE_DIR``, kept private): the
resolved path, the size and the SHA-256 of the content. "Perturb wrote it" means the file now
holds exactly what perturb last wrote there; a file the user changed since is the user's again.
With the cache off (``PERTURB_CACHE_DIR=off``) there is no record, and every existing non-empty
file needs ``force``.

A report folder (``perturb report SCENE --output DIR``) is :mod:`perturb.report.folder`'s.
"""

from __future__ import annotations

import contextlib
import json
import os
import stat
from pathlib import Path

from perturb.errors import OutputError
from perturb.report.atomic import as_bytes, atomic_write, can_create, digest_bytes, digest_file

__all__ = ["check_file", "is_ours", "write_file"]

#: The record of single files written, in the cache folder.
RECORD = "outputs-written.json"
#: Entries kept in the record (the oldest are forgotten first: their files then need ``force``).
RECORD_ENTRIES = 4096

#: Plot formats by file extension (matplotlib's savefig formats that perturb's plots are drawn to).
PLOT_EXTENSIONS = ("png", "pdf", "svg", "eps", "ps", "jpg", "jpeg", "tif", "tiff", "webp")


# ---------------------------------------------------------------------------------- the record
def _record_path() -> Path | None:
    """The record of single files, when the cache folder is set, ours and private."""
    from perturb.cache import cache_dir

    folder = cache_dir()
    if folder is None:
        return None
    try:
        folder.mkdir(mode=0o700, parents=True, exist_ok=True)
        info = os.stat(folder)
    except OSError:
        return None
    if hasattr(os, "geteuid") and info.st_uid != os.geteuid():
        return None
    if info.st_mode & (stat.S_IWGRP | stat.S_IWOTH) and not info.st_mode & stat.S_ISVTX:
        return None
    return folder / RECORD


def _read_record(path: Path | None) -> dict:
    if path is None:
        return {}
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    files = data.get("files") if isinstance(data, dict) else None
    return files if isinstance(files, dict) else {}


@contextlib.contextmanager
def _locked(path: Path):
    """An exclusive lock beside ``path`` (two perturb processes update the record in turn)."""
    lock = path.with_name(path.name + ".lock")
    fd = os.open(lock, os.O_RDWR | os.O_CREAT, 0o600)
    try:
        try:
            import fcntl

            fcntl.flock(fd, fcntl.LOCK_EX)
        except ImportError:  # pragma: no cover - not POSIX: last writer wins
            pass
        yield
    finally:
        os.close(fd)


def _remember(path: Path, data: bytes) -> None:
    record = _record_path()
    if record is None:
        return
    with contextlib.suppress(OSError), _locked(record):
        files = _read_record(record)
        files.pop(str(path), None)
        files[str(path)] = {"sha256": digest_bytes(data), "size": len(data)}
        while len(files) > RECORD_ENTRIES:
            files.pop(next(iter(files)))
        atomic_write(record, json.dumps({"format": 1, "files": files}).encode())


def is_ours(path) -> bool:
    """Whether the file ``path`` holds exactly what perturb last wrote there (an empty file
    counts as ours: there is nothing in it to lose)."""
    path = Path(path).resolve()
    try:
        size = path.stat().st_size
    except OSError:
        return False
    if size == 0 and path.is_file():
        return True
    entry = _read_record(_record_path()).get(str(path))
    if not isinstance(entry, dict) or entry.get("size") != size:
        return False
    return digest_file(path) == entry.get("sha256")


# ---------------------------------------------------------------------------------- one file
def check_file(path, flag: str = "--output", *, force: bool = False, plot: bool = False) -> Path:
    """Check, before any work, that perturb may write the file ``path`` (see the module notes).

    Parameters
    ----------
    path : str or path-like
    flag : str
        The option named in messages (``--output``, ``--plot``).
    force : bool
        Overwrite an existing file that perturb did not write.
    plot : bool
        The file is a plot: its extension must name a format (:data:`PLOT_EXTENSIONS`).

    Returns
    -------
    pathlib.Path

    Raises
    ------
    perturb.errors.OutputError
        One line naming the option, the path and the fix.

    Examples
    --------
    >>> import tempfile
    >>> folder = tempfile.mkdtemp()
    >>> check_file(f"{folder}/out.json").name
    'out.json'
    >>> check_file(f"{folder}/plot.xyz", "--plot", plot=True)
    Traceback (most recent call last):
    ...
    perturb.errors.OutputError: --plot '.../plot.xyz': the format 'xyz' is unknown: give a file name ending in .png, .pdf, .svg, .eps, .ps, .jpg, .jpeg, .tif, .tiff or .webp
    """
    text = str(path)
    if not text.strip():
        raise OutputError(
            f"{flag} {text!r}: name a file, e.g. {flag} result{'.png' if plot else '.txt'}"
        )
    target = Path(text).expanduser()
    folder = target.parent
    if target.is_dir():
        raise OutputError(
            f"{flag} {text!r} is a folder: give a file path, e.g. {text.rstrip('/')}/out"
        )
    if plot:
        extension = target.suffix[1:].lower()
        if extension not in PLOT_EXTENSIONS:
            what = f"the format {extension!r} is unknown" if extension else "it has no extension"
            names = ", ".join(f".{e}" for e in PLOT_EXTENSIONS[:-1])
            raise OutputError(
                f"{flag} {text!r}: {what}: give a file name ending in {names} or "
                f".{PLOT_EXTENSIONS[-1]}"
            )
    if not folder.is_dir():
        raise OutputError(
            f"{flag} {text!r}: the folder {str(folder)!r} does not exist: create it first or "
            "give a path in an existing folder"
        )
    if not os.access(folder, os.W_OK) or not can_create(folder):
        raise OutputError(
            f"{flag} {text!r}: the folder {str(folder)!r} cannot be written: choose another"
        )
    if target.exists() or target.is_symlink():
        if not target.is_file():
            raise OutputError(
                f"{flag} {text!r} exists and is not a regular file: choose another path"
            )
        if not force and not is_ours(target):
            raise OutputError(
                f"{flag} {text!r} exists and was not written by perturb (or was changed since): "
                "perturb does not overwrite it; choose another path, or pass --force to replace it"
            )
    return target


def write_file(path, content: bytes | str) -> None:
    """Write ``content`` into ``path`` atomically and record it as written by perturb.

    Raises
    ------
    perturb.errors.OutputError
        The file cannot be written (the reason and the fix).
    """
    target = Path(path).expanduser()
    data = as_bytes(content)
    try:
        atomic_write(target, data)
    except OSError as exc:
        raise OutputError(
            f"{str(path)!r}: cannot be written ({exc.strerror or exc}); choose a writable path"
        ) from None
    _remember(target.resolve(), data)
