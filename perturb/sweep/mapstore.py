"""A map over a grid whose arrays its caller lays out, on disk: :class:`MapStore`.

A basin map (:mod:`perturb.dynamics.basins`) is a grid like a sweep's, with other variables: codes,
periods, states. :class:`MapStore` is :class:`~perturb.sweep.store.SweepStore` with the layout
given by the caller instead of derived from a sweep's spec, under the same rules — a fingerprint
names what the store holds, one writer (:class:`~perturb.sweep.lock.StoreLock`), every chunk
written to disk and ``session`` written last as the commit mark, ``resume`` computing exactly the
chunks not committed or not sound — and the same helpers (the store module's, which alone talk
to Zarr).
"""

from __future__ import annotations

import json
from datetime import UTC, datetime
from pathlib import Path

import numpy as np

from perturb.sweep.grid import Chunking
from perturb.sweep.spec import STORE_FORMAT
from perturb.sweep.store import (
    CREATING,
    MARK,
    READY,
    STATE,
    SweepStore,
    _attrs_of,
    _check_chunk_entries,
    _consolidate,
    _coordinate,
    _empty_folder,
    _refuse,
    _zarr,
)

__all__ = ["MapStore"]


class MapStore(SweepStore):
    """A map over a grid whose arrays its caller lays out (a basin map: codes, periods, final
    states), written chunk by chunk under the sweep store's rules: a fingerprint names what it
    holds, one writer (:class:`~perturb.sweep.lock.StoreLock`), every chunk written to disk and
    ``session`` written last as the commit mark, ``--resume`` computing exactly the chunks not
    committed or not sound (:meth:`sound`). ``arrays`` maps a name to ``(dtype, fill, attributes,
    extra)``: ``extra`` a trailing ``(dimension, values)`` or None."""

    @classmethod
    def prepare_map(
        cls, path, *, fingerprint: str, label: str, axes: list[tuple[str, np.ndarray]],
        arrays: dict, chunk: tuple, attrs: dict, resume: bool,
    ) -> MapStore:  # fmt: skip
        """Create the store at ``path`` (new), or open it to resume (``resume``: it must hold
        this ``fingerprint``); locked until :meth:`close`.

        Raises
        ------
        perturb.errors.InvalidParameterError
            As :meth:`SweepStore.check`: ``path`` holds anything else, a map of another request,
            nothing to resume, a folder that does not exist; another process writes it now.
        """
        from perturb.sweep.lock import StoreLock

        path = Path(path)
        state = cls.check_map(path, fingerprint, resume)
        if state is False:
            try:
                path.mkdir()
            except OSError as exc:
                raise _refuse(path, f"cannot be created ({exc.strerror or exc})",
                              "choose a new, writable path") from None  # fmt: skip
        lock = StoreLock(path).acquire()
        try:
            if state is True and cls.check_map(path, fingerprint, resume) is True:
                return cls._reopen(path, lock)
            if state == "replace":
                _empty_folder(path)
            return cls._create_map(path, fingerprint, label, axes, arrays, chunk, attrs, lock)
        except BaseException:
            if state is False:
                import shutil

                shutil.rmtree(path, ignore_errors=True)
            lock.release()
            raise

    @staticmethod
    def check_map(path, fingerprint: str, resume: bool) -> bool | str:
        """Raise unless ``path`` can take the map ``fingerprint`` names (as
        :meth:`SweepStore.check`); False (new), True (to resume) or ``"replace"`` (its creation
        was cut short)."""
        path = Path(path)
        if path.exists() or path.is_symlink():
            attrs = _attrs_of(path) if path.is_dir() and not path.is_symlink() else None
            if attrs is None:
                raise _refuse(path, "exists and is not a perturb store",
                              "choose a new path (a store never overwrites other data)")  # fmt: skip
            if attrs.get("fingerprint") != fingerprint:
                raise _refuse(path, f"holds another request ({attrs.get('problem')!r}, "
                              f"{attrs.get('kind', 'a sweep')}), so it cannot be continued",
                              "choose a new path")  # fmt: skip
            if attrs.get(STATE) == CREATING:
                return "replace"
            if not resume:
                raise _refuse(path, "already holds this very request",
                              "pass --resume (resume=True in Python) to continue it, or choose "
                              "a new path")  # fmt: skip
            _check_chunk_entries(path)
            return True
        parent = path.parent if str(path.parent) else Path(".")
        if not parent.is_dir():
            raise _refuse(path, "its folder does not exist", "create the folder first")
        if resume:
            raise _refuse(path, "holds nothing to continue (--resume)",
                          "check the path, or drop --resume (resume=False) to start")  # fmt: skip
        return False

    @classmethod
    def _reopen(cls, path: Path, lock) -> MapStore:
        """The store at ``path``, to resume (its grid and chunks read from its attributes)."""
        group = _zarr().open_group(str(path), mode="r+")
        attrs = dict(group.attrs)
        grid = json.loads(attrs["grid"])
        shape = tuple(len(axis["values"]) for axis in grid)
        names = tuple(axis["name"] for axis in grid)
        return cls(path, group, Chunking(shape, attrs["chunk"]), names, lock, False)

    @classmethod
    def _create_map(cls, path, fingerprint, label, axes, arrays, chunk, attrs, lock) -> MapStore:
        zarr = _zarr()
        group = zarr.open_group(
            str(path), mode="w-",
            attributes={MARK: STORE_FORMAT, STATE: CREATING, "fingerprint": fingerprint,
                        "problem": label},
        )  # fmt: skip
        names = tuple(name for name, _ in axes)
        shape = tuple(len(values) for _, values in axes)
        for name, values in axes:
            _coordinate(group, name, np.asarray(values))
        extras = {}
        for name, (dtype, fill, attributes, extra) in {
            **arrays,
            "session": ("int32", 0, {"long_name": "run that wrote the point"}, None),
        }.items():
            dims, sizes = names, shape
            if extra is not None:
                extras[extra[0]] = np.asarray(extra[1])
                dims, sizes = (*names, extra[0]), (*shape, len(extra[1]))
            group.create_array(
                name, shape=sizes, chunks=(*chunk, *sizes[len(shape):]), dtype=dtype,
                fill_value=fill, dimension_names=dims, attributes=dict(attributes),
            )  # fmt: skip
        for name, values in extras.items():
            _coordinate(group, name, values)
        grid = [{"name": n, "values": np.asarray(v, dtype=float).tolist()} for n, v in axes]
        group.attrs.update({
            **attrs, "grid": json.dumps(grid), "chunk": list(chunk), "sessions": 0,
            "complete": False, "created": datetime.now(UTC).isoformat(timespec="seconds"),
            STATE: READY,
        })  # fmt: skip
        _consolidate(path)
        return cls(path, group, Chunking(shape, chunk), names, lock, False)

    def sound(self, number: int) -> bool:
        """Whether every array's chunk ``number`` is on disk (a file) and readable."""
        region = self.chunking.region(number)
        where = tuple(int(s.start // c) for s, c in zip(region, self.chunking.chunk, strict=True))
        for name, array in self._arrays.items():
            dims = tuple(array.metadata.dimension_names or ())
            if dims[: len(self.swept)] != self.swept or name in self.swept:
                continue  # a coordinate
            key = array.metadata.encode_chunk_key(where + (0,) * (array.ndim - len(where)))
            chunk = self.path / name / key
            if chunk.is_symlink() or not chunk.is_file():
                return False
            try:
                np.asarray(array[region])
            except Exception:  # noqa: BLE001 - corrupt: computed again
                return False
        return True

    def attributes(self) -> dict:
        """The store's attributes."""
        return dict(self.group.attrs)

    def update(self, attrs: dict) -> None:
        """Add ``attrs`` to the store's attributes (written at once)."""
        self.group.attrs.update(attrs)
        _consolidate(self.path)
