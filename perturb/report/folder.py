"""A report folder (``perturb report SCENE --output DIR``): perturb replaces or removes in it only
what it wrote there.

The folder holds a marker, ``.perturb-report.json``, naming the scene it reports and, for each file perturb wrote there, its
SHA-256 (a Zarr store: a token also kept in the store's attributes, and its fingerprint,
:func:`store_fingerprint`: the names and sizes of its files and the bytes of its metadata). The
marker is a claim, not a licence: a file or store counts as perturb's only while its current
content matches what the marker records; a missing, malformed or null record, or one claimed
and not yet written (a report killed while it wrote), protects whatever is there, and every file
is looked at again just before it is replaced or removed. :func:`claim_folder` runs
before any work: a new or empty folder is taken; a folder holding an earlier report of the same
scene file is taken; the report of another scene needs ``force``; and in every case a file the
report would write or remove that perturb did not write (or that changed since) is a clash — one
line naming it, exit 2 — which ``force`` does not override: ``force`` replaces perturb's own files
only. Files of other names are never touched.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import stat
import uuid
from collections.abc import Iterable
from pathlib import Path

from perturb.errors import OutputError
from perturb.report.atomic import as_bytes, atomic_write, can_create, digest_bytes, digest_file

__all__ = ["MARKER", "STORE_TOKEN", "ReportFolder", "claim_folder", "store_fingerprint"]

#: The marker file of a report folder.
MARKER = ".perturb-report.json"
#: The marker's format (bump when its layout changes).
MARKER_FORMAT = 1
#: The attribute of a report's Zarr store holding its token.
STORE_TOKEN = "perturb_report_token"


def _digests_of(record) -> tuple[str, ...]:
    """The digests a marker's record of one file allows: a SHA-256 string, or a list of them
    (the old and the new content while a file is replaced); anything else allows none."""
    items = record if isinstance(record, list) else [record]
    return tuple(d for d in items if isinstance(d, str) and len(d) == _DIGEST_LENGTH)


#: Hex digits of a SHA-256.
_DIGEST_LENGTH = 64

#: Files of a Zarr store whose content is its metadata (formats 2 and 3): the store's fingerprint
#: holds their bytes, and the names and sizes of all its other files (the chunks).
_ZARR_METADATA = ("zarr.json", ".zarray", ".zattrs", ".zgroup", ".zmetadata")


def store_fingerprint(path) -> str | None:
    """What "a store's content matches" means for a report's Zarr store: the SHA-256 of every
    file's relative path and size, and of the metadata files' bytes (a chunk or an array added,
    removed or resized, an attribute changed: another fingerprint). None when ``path`` is not a
    real folder (a symbolic link, a file) or cannot be read whole."""
    root = Path(path)
    if root.is_symlink() or not root.is_dir():
        return None
    digest = hashlib.sha256()
    try:
        entries = []
        for folder, dirs, files in os.walk(root, onerror=_raise):
            dirs.sort()
            for name in sorted(files):
                entries.append(Path(folder, name))
            for name in dirs:
                if Path(folder, name).is_symlink():
                    return None
        for file in entries:
            info = os.lstat(file)
            if not stat.S_ISREG(info.st_mode):
                return None
            relative = file.relative_to(root).as_posix()
            digest.update(f"{relative}\0{info.st_size}\0".encode())
            if file.name in _ZARR_METADATA:
                content = digest_file(file)
                if content is None:
                    return None
                digest.update(content.encode())
    except OSError:
        return None
    return digest.hexdigest()


def _raise(exc: OSError) -> None:
    raise exc


class ReportFolder:
    """A report folder claimed by :func:`claim_folder`: writes its files and keeps the marker.

    Every file is replaced or removed only while its content is still what the marker records
    (it is looked at again just before: a file the user saved there while the report was
    computed is theirs); a digest is recorded before the file is moved into place, so that a
    report killed in between leaves a marker that still knows the file.
    """

    def __init__(self, folder: Path, scene: str, files: dict, stores: dict, prints=None):
        self.folder = folder
        self.scene = scene
        self.files = dict(files)  # name -> sha256 (None: claimed, not yet written)
        self.stores = dict(stores)  # name -> token
        self.prints = dict(prints or {})  # store name -> its fingerprint once written
        self.stale: list[str] = []  # perturb's files of an earlier report not written this time

    def _save(self) -> None:
        marker = {
            "perturb_report": MARKER_FORMAT,
            "scene": self.scene,
            "files": self.files,
            "stores": self.stores,
            "store_fingerprints": self.prints,
        }
        atomic_write(self.folder / MARKER, json.dumps(marker, indent=1).encode())

    def begin(self, names: Iterable[str], stale: Iterable[str] = ()) -> None:
        """Claim ``names`` in the marker (before writing them), remove ``stale`` ones (ours)."""
        for name in stale:
            self._remove(name)
        for name in names:
            self.files.setdefault(name, None)
        self._save()

    def _clash(self, name: str) -> OutputError:
        return OutputError(
            f"--output {str(self.folder)!r}: {name} there was changed or put there while the "
            "report was computed; perturb never overwrites it: move it away and run again"
        )

    def _check_file(self, name: str) -> None:
        """Raise unless the file ``name`` is missing or holds what the marker records."""
        path = self.folder / name
        if not (path.exists() or path.is_symlink()):
            return
        if digest_file(path) not in _digests_of(self.files.get(name)):
            raise self._clash(name)

    def _check_store(self, name: str) -> None:
        path = self.folder / name
        if not (path.exists() or path.is_symlink()):
            return
        if name not in self.stores or not _is_ours_store(
            path, self.stores[name], self.prints.get(name)
        ):
            raise self._clash(name)

    def _remove(self, name: str) -> None:
        path = self.folder / name
        if name in self.stores:
            self._check_store(name)
            if path.is_dir():
                import shutil

                shutil.rmtree(path)
            self.stores.pop(name)
            self.prints.pop(name, None)
        else:
            self._check_file(name)
            with contextlib.suppress(FileNotFoundError):
                path.unlink()
            self.files.pop(name, None)

    def write(self, name: str, content: bytes | str) -> None:
        data = as_bytes(content)
        self._check_file(name)
        new = digest_bytes(data)
        before = _digests_of(self.files.get(name))
        self.files[name] = [*before, new] if before else new  # either is ours meanwhile
        self._save()
        atomic_write(self.folder / name, data)
        self.files[name] = new
        self._save()

    def store_token(self, name: str) -> str:
        """A fresh token for the store ``name`` (kept in its attributes and in the marker)."""
        if (self.folder / name).exists() or (self.folder / name).is_symlink():
            self._remove(name)
        token = uuid.uuid4().hex
        self.stores[name] = token
        self.prints.pop(name, None)
        self.files.pop(name, None)
        self._save()
        return token

    def store_written(self, name: str) -> None:
        """Record the fingerprint of the store ``name`` just written (:func:`store_fingerprint`):
        from now on it is replaced only while it still has it."""
        self.prints[name] = store_fingerprint(self.folder / name)
        self._save()


def _is_ours_store(path: Path, token, fingerprint) -> bool:
    """Whether the store at ``path`` is the one a marker records: a real folder whose
    attributes hold the marker's token and whose fingerprint is the one recorded (a store
    recorded without one, being written when the report stopped, is not known to be ours)."""
    if not (isinstance(token, str) and token and isinstance(fingerprint, str)):
        return False
    if path.is_symlink() or not path.is_dir() or _store_token(path) != token:
        return False
    return store_fingerprint(path) == fingerprint


def _read_marker(folder: Path) -> dict | None:
    try:
        data = json.loads(_read_small(folder / MARKER))
    except (OSError, ValueError):
        return None
    if not (isinstance(data, dict) and data.get("perturb_report") == MARKER_FORMAT):
        return None
    files, stores = data.get("files"), data.get("stores", {})
    prints = data.get("store_fingerprints", {})
    if not (isinstance(files, dict) and isinstance(stores, dict) and isinstance(prints, dict)):
        return None
    return data


#: Largest marker read (one is a few hundred bytes a file): a larger one is not perturb's.
_MARKER_MAX_BYTES = 1 << 20


def _read_small(path: Path) -> str:
    """The text of the regular file ``path`` (not a link, FIFO or device; at most
    :data:`_MARKER_MAX_BYTES`), or OSError/ValueError."""
    from perturb._files import UnreadableFile, read_capped

    if path.is_symlink():
        raise ValueError("a symbolic link")
    try:
        return read_capped(path, _MARKER_MAX_BYTES).decode("utf-8")
    except UnreadableFile as exc:
        raise ValueError(str(exc)) from None


def _store_token(path: Path) -> str | None:
    """The token in the attributes of the Zarr store at ``path`` (format 2 or 3), if any."""
    for meta, key in (("zarr.json", "attributes"), (".zattrs", None)):
        try:
            data = json.loads(_read_small(path / meta))
        except (OSError, ValueError):
            continue
        attrs = data.get(key, {}) if key and isinstance(data, dict) else data
        if isinstance(attrs, dict):
            token = attrs.get(STORE_TOKEN)
            return token if isinstance(token, str) and token else None
    return None


def claim_folder(
    folder,
    names: Iterable[str],
    scene: str,
    *,
    known: Iterable[str] = (),
    force: bool = False,
) -> ReportFolder:
    """Check, before any work, that a report may be written into ``folder``; create it.

    Parameters
    ----------
    folder : str or path-like
    names : iterable of str
        The files (and stores) this report writes.
    scene : str
        What the report is of (the scene file's resolved path): a folder holding the report of
        another needs ``force``.
    known : iterable of str
        Every name a report may write: those of an earlier report of ours not written this time
        are removed (only if perturb wrote them and they are unchanged).
    force : bool
        Replace perturb's own files from the report of another scene.

    Returns
    -------
    ReportFolder

    Raises
    ------
    perturb.errors.OutputError
        The path is empty, a file, cannot be created or written; a file to be written or
        removed was not written by perturb (or changed since); the report of another scene
        without ``force``.
    """
    text = str(folder)
    if not text.strip():
        raise OutputError(f"--output {text!r}: name a folder, e.g. --output report")
    path = Path(text).expanduser()
    if path.exists() and not path.is_dir():
        raise OutputError(f"--output {text!r} is an existing file: name a folder")
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(
            f"--output {text!r}: cannot write there (the folder cannot be created: "
            f"{exc.strerror or exc}); choose a writable folder"
        ) from None
    if not os.access(path, os.W_OK) or not can_create(path):
        raise OutputError(
            f"--output {text!r}: cannot write there (the folder is not writable); choose a writable folder"
        )
    names = list(names)
    marker = _read_marker(path)
    if (path / MARKER).exists() and marker is None:
        raise OutputError(
            f"--output {text!r}: {MARKER} there is not a marker perturb wrote; move it away or "
            "choose another folder"
        )
    ours_files, ours_stores, prints = {}, {}, {}
    if marker is not None:
        # a claim, not a licence: a file is perturb's only while it holds a content the marker
        # records (a null, missing or malformed record, or "claimed, not yet written", is none)
        for name, digest in marker["files"].items():
            if not _plain_name(name):
                continue
            current = digest_file(path / name)
            if current is not None and current in _digests_of(digest):
                ours_files[name] = current
        for name, token in marker["stores"].items():
            fingerprint = marker.get("store_fingerprints", {}).get(name)
            if _plain_name(name) and _is_ours_store(path / name, token, fingerprint):
                ours_stores[name], prints[name] = token, fingerprint
        if marker.get("scene") != scene and not force:
            raise OutputError(
                f"--output {text!r} holds the report of another scene ({marker.get('scene')}): "
                "choose another folder, or pass --force to replace perturb's files there"
            )
    ours = set(ours_files) | set(ours_stores)
    stale = [n for n in known if n not in names and n in ours]
    for name in names:
        target = path / name
        if (target.exists() or target.is_symlink()) and name not in ours:
            raise OutputError(
                f"--output {text!r}: {name} there was not written by perturb (or was changed "
                "since); perturb never overwrites it: move it away or choose another folder"
            )
    claimed = ReportFolder(path, scene, ours_files, ours_stores, prints)
    claimed.stale = stale
    return claimed


def _plain_name(name) -> bool:
    """A file name of the folder itself (not a path out of it)."""
    return (
        isinstance(name, str)
        and name not in ("", ".", "..")
        and "/" not in name
        and (os.sep not in name and "\0" not in name)
    )
