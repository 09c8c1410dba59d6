"""The sweep's results on disk: a Zarr store written chunk by chunk, resumable (:class:`SweepStore`).

Layout (Zarr format 3, consolidated metadata; ``xarray.open_zarr(path)`` reads it as a Dataset):
one coordinate per swept parameter, ``component`` (the state's names), ``time`` (the times asked
for), ``multiplier`` and ``check``; one variable per quantity
(:func:`perturb.sweep.quantities.variables`), chunked like the tasks, so that a task's results
are one write per variable. The group's attributes name the problem, its fixed parameters, the
order, the grid, the settings, the perturb version and the sweep's fingerprint.

A chunk's ``session`` is written last: it is the commit mark. ``--resume`` computes exactly the
chunks some of whose points still have session 0, or whose files are missing, unreadable or not
finite where the status promises a number (:meth:`SweepStore.sound`) — no point twice, none lost —
after checking that the store holds this very sweep (same fingerprint). Every chunk is written to
disk, even one of fill values, so that a missing file always means a lost chunk. One driver at a
time writes a store (:mod:`perturb.sweep.lock`); a store whose creation was cut short is marked
``creating`` and replaced by the same sweep. A store is never overwritten: a path that holds
anything else (another sweep, other data, a file) is refused.

Only this module (with :mod:`perturb.sweep.driver`) imports zarr and xarray.
"""

from __future__ import annotations

import contextlib
import json
import math
import warnings
from collections import Counter
from datetime import UTC, datetime
from pathlib import Path

import numpy as np

from perturb.errors import InvalidParameterError
from perturb.sweep.grid import Chunking
from perturb.sweep.quantities import TIMINGS, check_names, stored_name, variables
from perturb.sweep.spec import STORE_FORMAT, SweepJob
from perturb.sweep.status import PointStatus, code_of

__all__ = ["SweepStore", "check_new_store", "code_counts", "open_dataset", "write_dataset"]

#: The group attribute that marks a perturb sweep store (its value: the store format).
MARK = "perturb_sweep"
#: The group attribute saying whether the store's layout is complete: written first as
#: ``creating`` (with the mark and the fingerprint), ``ready`` once every array exists.
STATE, CREATING, READY = "store_state", "creating", "ready"


def _zarr():
    import zarr

    return zarr


def _consolidate(path: Path) -> None:
    zarr = _zarr()
    with warnings.catch_warnings():
        # consolidated metadata is an extension of Zarr format 3 (zarr-python says so on each
        # call); it is what lets ``xarray.open_zarr`` read the store without a warning
        warnings.simplefilter("ignore")
        zarr.consolidate_metadata(str(path))


def _refuse(path: Path, why: str, fix: str) -> InvalidParameterError:
    return InvalidParameterError(f"--output {str(path)!r}: {why}; {fix}")


def _not_a_chunk(path: Path, entry: str) -> InvalidParameterError:
    """The refusal of a store whose chunk place ``entry`` (``array/key``) holds a folder or a
    link: perturb writes only files there, and removes nothing it did not write."""
    return _refuse(
        path,
        f"is damaged: {entry} there is not a chunk file (a folder, a link)",
        "move it away (perturb removes nothing it did not write), then --resume",
    )


def _check_chunk_entries(path: Path) -> None:
    """Raise when a chunk's place in the store at ``path`` holds something perturb never writes
    there (a folder, a link): found from the arrays' metadata before any work (a cluster started,
    a solution derived), so the refusal is the run's one line.

    Arrays whose chunk keys are not the default ``c/i/j`` layout are left to the resume's own
    check (:meth:`SweepStore.sound`).
    """
    for array in sorted(path.iterdir()):
        meta = array / "zarr.json"
        if array.is_symlink() or not meta.is_file() or array == path:
            continue
        try:
            spec = json.loads(meta.read_text())
            ndim = len(spec["shape"])
            encoding = spec.get("chunk_key_encoding") or {}
            separator = (encoding.get("configuration") or {}).get("separator", "/")
        except (OSError, ValueError, KeyError, TypeError):
            continue  # unreadable metadata: the store is rebuilt on resume
        if encoding.get("name") != "default" or separator != "/" or ndim == 0:
            continue
        root = array / "c"
        if not root.exists() and not root.is_symlink():
            continue
        stack = [(root, 0)]
        while stack:
            place, depth = stack.pop()
            bad = place.is_symlink() or (
                not place.is_dir() if depth < ndim else not place.is_file()
            )
            if bad:
                raise _not_a_chunk(path, f"{array.name}/{place.relative_to(array).as_posix()}")
            if depth < ndim:
                stack.extend((child, depth + 1) for child in place.iterdir())


def _attrs_of(path: Path) -> dict | None:
    """The attributes of the sweep store at ``path``, None if it is not one."""
    zarr = _zarr()
    try:
        group = zarr.open_group(str(path), mode="r")
    except Exception:  # noqa: BLE001 - anything unreadable is "not a sweep store"
        return None
    attrs = dict(group.attrs)
    return attrs if MARK in attrs else None


class SweepStore:
    """An open sweep store (see the module docstring), locked for this process until
    :meth:`close`."""

    def __init__(self, path: Path, group, chunking: Chunking, swept, lock=None, validate=False):
        self.path = path
        self.group = group
        self.chunking = chunking
        self.swept = tuple(swept)
        self.lock = lock
        self.validate = validate
        with _writing_every_chunk():
            reopened = _zarr().open_group(str(path), mode="r+")
            self._arrays = {name: reopened[name] for name in reopened.array_keys()}

    # ------------------------------------------------------------------ opening
    @staticmethod
    def check(path, spec, *, resume: bool, version: str) -> bool | str:
        """Raise unless ``path`` can take this sweep: new (its folder exists), a store of this
        very sweep (with ``resume``), or this sweep's store whose creation was cut short (it is
        replaced: it holds no result). Returns False (new), True (to resume) or ``"replace"``.

        Raises
        ------
        perturb.errors.InvalidParameterError
            ``path`` holds something else than this sweep (another sweep, other data, a file),
            or a sweep without ``resume``, or nothing with ``resume``; its folder does not exist.
        """
        path = _through_link(Path(path))
        if path.exists() or path.is_symlink():
            attrs = _attrs_of(path) if path.is_dir() and not path.is_symlink() else None
            if attrs is None:
                raise _refuse(
                    path,
                    "exists and is not a perturb sweep store",
                    "choose a new path (a sweep never overwrites other data)",
                )
            if attrs.get(STATE) == CREATING:
                if attrs.get("fingerprint") != spec.fingerprint(version):
                    raise _refuse(
                        path,
                        "holds the unfinished creation of another sweep (it was cut short and "
                        "holds no result)",
                        "remove it or choose a new path",
                    )
                return "replace"
            if not resume:
                raise _refuse(
                    path,
                    f"already holds a sweep of {attrs.get('problem')!r}",
                    "pass --resume (resume=True in Python) to continue it, or choose a new path",
                )
            if attrs.get("fingerprint") != spec.fingerprint(version):
                raise _refuse(path, _difference(attrs, spec, version), "choose a new path")
            _check_chunk_entries(path)
            return True
        parent = path.parent if str(path.parent) else Path(".")
        if not parent.is_dir():
            raise _refuse(path, "its folder does not exist", "create the folder first")
        if resume:  # a path mistyped must not start a sweep afresh unasked
            raise _refuse(
                path,
                "holds no sweep to continue (--resume)",
                "check the path, or drop --resume (resume=False) to start the sweep",
            )
        return False

    @classmethod
    def prepare(
        cls, path, job: SweepJob, *, resume: bool, version: str, chunk_points, extra: dict
    ) -> SweepStore:
        """Create the store at ``path``, or open it to resume ``job`` (checked by :meth:`check`),
        and lock it (:class:`perturb.sweep.lock.StoreLock`) until :meth:`close`.

        ``chunk_points`` is called (with no argument) for the points per chunk only when the
        store is created; ``extra`` goes into the attributes (the problem as named, ...).

        Raises
        ------
        perturb.errors.InvalidParameterError
            As :meth:`check`; another process is writing the store now.
        """
        from perturb.sweep.lock import StoreLock

        path = _through_link(Path(path))
        created = cls.check(path, job.spec, resume=resume, version=version) is False
        if created:
            try:
                path.mkdir()
            except FileExistsError:
                raise _refuse(
                    path, "was created by another process just now", "choose a new path"
                ) from None
            except OSError as exc:
                raise _refuse(
                    path, f"cannot be created ({exc.strerror or exc})", "choose a writable path"
                ) from None
        lock = StoreLock(path).acquire()
        try:
            if created:
                return cls._create(path, job, version, chunk_points(), extra, lock)
            # checked again under the lock: another driver may have changed it meanwhile
            state = cls.check(path, job.spec, resume=resume, version=version)
            if state is True:
                return cls._open(path, lock, job)
            _empty_folder(path)  # this sweep's store, its creation cut short: made again
            return cls._create(path, job, version, chunk_points(), extra, lock)
        except BaseException:
            if created:  # nothing of it is a result: what this run made of it goes
                import shutil

                shutil.rmtree(path, ignore_errors=True)
            lock.release()
            raise

    @classmethod
    def _open(cls, path: Path, lock, job: SweepJob) -> SweepStore:
        """Open the store to resume ``job``: an array whose metadata is missing or unreadable
        (deleted, the whole array gone) is made again, of fill values, so that its chunks are
        computed again and the store opens as the Dataset it promises."""
        zarr = _zarr()
        group = zarr.open_group(str(path), mode="r+", use_consolidated=False)
        attrs = dict(group.attrs)
        grid = json.loads(attrs["grid"])
        shape = tuple(len(axis["values"]) for axis in grid)
        chunking = Chunking(shape, attrs["chunk"])
        names = tuple(axis["name"] for axis in grid)
        missing = [n for n in _expected_arrays(job) if not _array_metadata_ok(path / n)]
        if missing:
            for name in missing:
                if (path / name).is_symlink() or (
                    (path / name).exists() and not (path / name).is_dir()
                ):
                    raise _refuse(
                        path,
                        f"is damaged: {name} there is not a Zarr array perturb wrote",
                        "move it away (perturb removes nothing it did not write), then --resume",
                    )
            _layout(group, job, chunking, tuple(job.spec.model.state_names()), set(missing))
            group.attrs.update({"complete": False})
            _consolidate(path)
        return cls(path, group, chunking, names, lock, job.spec.validate)

    @classmethod
    def _create(cls, path, job, version, points, extra, lock) -> SweepStore:
        zarr = _zarr()
        spec = job.spec
        grid = spec.grid
        chunking = Chunking.of(grid.shape, points, job.fill_first())
        names = tuple(spec.model.state_names())
        attributes = {
            MARK: STORE_FORMAT,
            STATE: CREATING,  # until every array is made: a cut creation is recognised
            "fingerprint": job.key,
            "problem": spec.label,
        }
        try:
            group = zarr.open_group(str(path), mode="w-", attributes=attributes)
        except Exception as exc:  # noqa: BLE001 - any reason it cannot be created
            raise _refuse(path, f"cannot be created ({exc})", "choose a writable path") from None
        _layout(group, job, chunking, names)
        group.attrs.update(
            {
                "model_class": type(spec.model).__qualname__,
                "order": spec.order,
                "perturb_version": version,
                "fixed_parameters": json.dumps(spec.fixed_parameters()),
                "grid": json.dumps(grid.as_list()),
                "settings": json.dumps(spec.settings()),
                "derivation": job.derivation.mode.name.lower(),
                "derivation_reason": job.derivation.reason,
                "chunk": list(chunking.chunk),
                "created": datetime.now(UTC).isoformat(timespec="seconds"),
                "sessions": 0,
                "complete": False,
                **extra,
                STATE: READY,
            }
        )
        _consolidate(path)
        return cls(path, group, chunking, grid.names, lock, spec.validate)

    def close(self) -> None:
        """Release the store's lock (the results stay)."""
        if self.lock is not None:
            self.lock.release()
            self.lock = None

    # ------------------------------------------------------------------ progress of the sweep
    def pending(self, verify: bool = True) -> list[int]:
        """The chunks not written yet, in order: some point with session 0 — or, with
        ``verify``, a chunk of any variable missing, unreadable, or not finite where the point's
        status promises a number (:meth:`sound`). Such a chunk is computed again."""
        session = self._arrays[stored_name("session", self.swept)]
        out = []
        for number in self.chunking:
            region = self.chunking.region(number)
            try:
                written = bool(np.all(np.asarray(session[region]) > 0))
            except Exception:  # noqa: BLE001 - an unreadable session chunk: not written
                written = False
            if not written or (verify and not self.sound(number)):
                out.append(number)
        return out

    def sound(self, number: int) -> bool:
        """Whether every variable's chunk ``number`` is on disk, readable, and finite where the
        point's status is ``ok`` (ε, the period, the frequency; the verdict when validated)."""
        region = self.chunking.region(number)
        where = tuple(int(s.start // c) for s, c in zip(region, self.chunking.chunk, strict=True))
        values = {}
        for name, array in self._arrays.items():
            dims = tuple(array.metadata.dimension_names or ())
            if dims[: len(self.swept)] != self.swept or name in self.swept:
                continue  # a coordinate
            key = array.metadata.encode_chunk_key(where + (0,) * (array.ndim - len(where)))
            chunk = self.path / name / key
            if chunk.is_symlink() or (chunk.exists() and not chunk.is_file()):
                raise _not_a_chunk(self.path, f"{name}/{key}")
            if not chunk.is_file():
                return False
            try:
                values[name] = np.asarray(array[region])
            except Exception:  # noqa: BLE001 - corrupt: computed again
                return False
        try:
            status = values[stored_name("status", self.swept)]
        except KeyError:
            return False
        if np.any(status < 0):
            return False
        ok = status == code_of(PointStatus.OK)
        for name in ("epsilon", "period", "frequency"):
            array = values.get(stored_name(name, self.swept))
            if array is None or not np.all(np.isfinite(array[ok])):
                return False
        if self.validate:
            verdict = values.get(stored_name("verdict", self.swept))
            if verdict is None or np.any(verdict[ok] < 0):
                return False
        return True

    def begin_session(self) -> int:
        """Count a new run of the sweep; returns its number (1 for the first)."""
        session = int(self.group.attrs.get("sessions", 0)) + 1
        self.group.attrs.update({"sessions": session, "complete": False})
        _consolidate(self.path)
        return session

    def write(self, number: int, result: dict) -> None:
        """Write chunk ``number``'s results (``session`` last: the commit mark)."""
        region = self.chunking.region(number)
        block = tuple(s.stop - s.start for s in region)
        session_name = stored_name("session", self.swept)
        names = [n for n in result if n not in TIMINGS]
        names.sort(key=lambda n: stored_name(n, self.swept) == session_name)
        for name in names:
            array = self._arrays[stored_name(name, self.swept)]
            values = np.asarray(result[name])
            values = values.reshape(block + values.shape[1:])
            if values.dtype == object:
                values = values.astype(str)
            array[region + (slice(None),) * (values.ndim - len(block))] = values

    def points_written(self) -> int:
        """Points of the chunks written and sound (the store's own count)."""
        pending = self.pending()
        return math.prod(self.chunking.shape) - sum(_size(self.chunking, n) for n in pending)

    def finish(self) -> None:
        """Mark the store complete when every chunk is written."""
        if not self.pending():
            self.group.attrs.update({"complete": True})
            _consolidate(self.path)


def _size(chunking: Chunking, number: int) -> int:
    return math.prod(s.stop - s.start for s in chunking.region(number))


def _empty_folder(path: Path) -> None:
    """Remove what a cut creation of this sweep's store left in ``path`` (the folder stays)."""
    import shutil

    for child in path.iterdir():
        if child.is_dir() and not child.is_symlink():
            shutil.rmtree(child)
        else:
            child.unlink()


@contextlib.contextmanager
def _writing_every_chunk():
    """Arrays opened inside write every chunk, even one equal to the fill value: a chunk missing
    on disk then always means one not written (or lost), never one of fill values."""
    with _zarr().config.set({"array.write_empty_chunks": True}):
        yield


def _through_link(path: Path) -> Path:
    """``path``, or the folder a symbolic link there points to (a store named through a link is
    the store it links to; a link to nothing, or to a file, stays a link and is refused)."""
    if path.is_symlink():
        target = path.resolve()
        if target.is_dir() and not target.is_symlink():
            return target
    return path


def _layout(group, job: SweepJob, chunking: Chunking, names, only=None) -> None:
    """Make the store's arrays (every one, or those named in ``only``, made again over
    whatever is left of them): a coordinate per swept parameter and per dimension, a variable
    per quantity, of fill values."""
    spec = job.spec
    grid = spec.grid
    dims = {
        "component": np.array(names, dtype=str),
        "time": np.asarray(spec.times, dtype=float),
        "multiplier": np.arange(len(names)),
        "check": np.array(check_names(), dtype=str),
    }
    coordinates = {axis.name: np.asarray(axis.values, dtype=float) for axis in grid.axes}
    for name, values in {**coordinates, **dims}.items():
        if only is None or name in only:
            _coordinate(group, name, values, overwrite=only is not None)
    sizes = {name: len(values) for name, values in dims.items()}
    for var in variables(spec.validate):
        name = stored_name(var.name, grid.names)
        if only is not None and name not in only:
            continue
        group.create_array(
            name,
            shape=(*grid.shape, *(sizes[d] for d in var.dims)),
            chunks=(*chunking.chunk, *(sizes[d] for d in var.dims)),
            dtype=str if var.dtype == "str" else var.dtype,
            fill_value=var.fill,
            dimension_names=(*grid.names, *var.dims),
            attributes=dict(var.attrs),
            overwrite=only is not None,
        )


def _expected_arrays(job: SweepJob) -> list[str]:
    """The names of every array a store of ``job`` holds."""
    grid = job.spec.grid
    names = [axis.name for axis in grid.axes] + ["component", "time", "multiplier", "check"]
    return names + [stored_name(var.name, grid.names) for var in variables(job.spec.validate)]


def _array_metadata_ok(folder: Path) -> bool:
    """Whether ``folder`` holds the readable metadata of a Zarr array (format 3)."""
    meta = folder / "zarr.json"
    if folder.is_symlink() or not folder.is_dir() or meta.is_symlink() or not meta.is_file():
        return False
    try:
        data = json.loads(meta.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return False
    return isinstance(data, dict) and data.get("node_type") == "array"


def _coordinate(group, name: str, values: np.ndarray, overwrite: bool = False) -> None:
    array = group.create_array(
        name,
        shape=values.shape,
        chunks=values.shape,
        dtype=str if values.dtype.kind in "US" else values.dtype,
        dimension_names=(name,),
        overwrite=overwrite,
    )
    array[...] = values


def _difference(attrs: dict, spec, version: str) -> str:
    """What differs between the sweep in a store and ``spec`` (for the refusal)."""
    theirs = {
        "problem": attrs.get("problem"),
        "grid": attrs.get("grid"),
        "settings": attrs.get("settings"),
        "fixed parameters": attrs.get("fixed_parameters"),
        "perturb version": attrs.get("perturb_version"),
    }
    ours = {
        "problem": spec.label,
        "grid": json.dumps(spec.grid.as_list()),
        "settings": json.dumps(spec.settings()),
        "fixed parameters": json.dumps(spec.fixed_parameters()),
        "perturb version": version,
    }
    differ = [key for key in ours if theirs[key] != ours[key]]
    what = ", ".join(differ) if differ else "the problem's definition"
    return f"holds another sweep ({what} differ), so --resume cannot continue it there"


def check_new_store(path) -> None:
    """Raise unless ``path`` is free for a new store (checked before any work; nothing is ever
    written over what is there).

    Raises
    ------
    perturb.errors.InvalidParameterError
        ``path`` exists.
    """
    path = Path(path)
    if path.exists() or path.is_symlink():
        raise _refuse(path, "exists", "move it away or name another (a store is never overwritten)")


def write_dataset(dataset, path, attrs: dict | None = None) -> None:
    """Write a sweep's Dataset (kept in memory) as a new store at ``path`` (a report folder's
    ``sweep.zarr``), with ``attrs`` added to its attributes (the report's mark of its store).

    Raises
    ------
    perturb.errors.InvalidParameterError
        ``path`` exists (nothing is ever written over it).
    """
    check_new_store(path)
    path = Path(path)
    if attrs:
        dataset = dataset.copy()
        dataset.attrs.update(attrs)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # consolidated metadata in Zarr format 3 (see above)
        dataset.to_zarr(str(path), mode="w-", consolidated=True)


def open_dataset(path):
    """The store at ``path`` as an :class:`xarray.Dataset` (read lazily)."""
    import xarray as xr

    return xr.open_zarr(str(path))


def code_counts(variable) -> Counter:
    """How many points hold each code, counted chunk by chunk for a store read lazily (a store
    of 10^10 points is never loaded whole)."""
    data = variable.data
    if hasattr(data, "compute"):
        import dask
        import dask.array as da

        values, counts = dask.compute(*da.unique(data.ravel(), return_counts=True))
        return Counter({int(v): int(n) for v, n in zip(values, counts, strict=True)})
    return Counter(int(c) for c in data.ravel())
