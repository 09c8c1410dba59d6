"""The Zarr store of a sweep: created once, filled chunk by chunk, resumed, read as xarray.

One dimension per swept parameter (its values the coordinate), one variable per quantity, a
``done`` mask and the ``reason`` a point failed. The attributes say what was swept: the problem,
its fixed parameters, the order, whether points were validated, perturb's version, the grid, and
the meaning of the coded variables. Only the driver writes (one writer); a chunk's values and its
``done`` flags are written together, so an interrupted sweep resumes where it stopped, computing
no point twice and losing none.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from perturb.errors import InvalidParameterError, bad_value

__all__ = ["create_store", "open_store", "pending_points", "write_chunk"]

#: Characters kept of a failed point's reason (fixed-width strings in the store).
REASON_LENGTH = 200
#: Identifies a sweep store among other Zarr groups.
KIND = "perturb-sweep"


def _signature(attrs: dict) -> dict:
    keys = ("kind", "problem", "grid", "order", "validate", "fixed", "quantities")
    return {k: attrs.get(k) for k in keys}


def create_store(path, grid, quantities, attrs: dict, resume: bool):
    """Create the store, or check an existing one is this sweep's (``resume``).

    Raises
    ------
    InvalidParameterError
        When ``path`` exists and is not this sweep's store (never overwritten), or exists
        without ``resume``.
    """
    import xarray as xr
    import zarr

    path = Path(path)
    attrs = {**attrs, "kind": KIND, "grid": json.dumps(grid.describe()),
             "quantities": json.dumps(list(quantities))}  # fmt: skip
    if path.exists():
        try:
            existing = dict(zarr.open_group(str(path), mode="r").attrs)
        except Exception:  # noqa: BLE001 - any unreadable folder is "not a sweep store"
            existing = {}
        if existing.get("kind") != KIND:
            raise bad_value(
                "output", str(path),
                "it exists and is not a sweep store: choose a new path (nothing is overwritten)",
                InvalidParameterError,
            )  # fmt: skip
        if not resume:
            raise bad_value(
                "output", str(path),
                "a sweep store is already there: pass --resume to continue it, or choose a new "
                "path (nothing is overwritten)",
                InvalidParameterError,
            )  # fmt: skip
        if _signature(existing) != _signature(attrs):
            differing = sorted(
                k for k in _signature(attrs) if _signature(attrs)[k] != _signature(existing)[k]
            )
            raise bad_value(
                "output", str(path),
                f"it holds another sweep (its {', '.join(differing)} differ): --resume continues "
                "only the same problem, grid, order and options; choose a new path",
                InvalidParameterError,
            )  # fmt: skip
        return
    dims = grid.names
    coords = {a.name: np.asarray(a.values) for a in grid.axes}
    data = {q: (dims, np.full(grid.shape, np.nan)) for q in quantities}
    data["done"] = (dims, np.zeros(grid.shape, dtype=bool))
    data["reason"] = (dims, np.full(grid.shape, "", dtype=f"<U{REASON_LENGTH}"))
    dataset = xr.Dataset(data, coords=coords, attrs=attrs)
    dataset.to_zarr(str(path), mode="w-", zarr_format=2, consolidated=True)


def pending_points(path, grid) -> np.ndarray:
    """The flat indices of the points not yet done."""
    import zarr

    done = np.asarray(zarr.open_group(str(path), mode="r")["done"][...], dtype=bool)
    return np.flatnonzero(~done.ravel())


def write_chunk(path, grid, indices, columns: dict, reasons) -> None:
    """Write one finished chunk: its values, its reasons, then its ``done`` flags."""
    import zarr

    group = zarr.open_group(str(path), mode="r+")
    where = np.unravel_index(np.asarray(indices, dtype=np.int64), grid.shape)
    for name, values in columns.items():
        if name in group:
            group[name].vindex[where] = np.asarray(values, dtype=float)
    group["reason"].vindex[where] = np.array(
        [r[:REASON_LENGTH] for r in reasons], dtype=f"<U{REASON_LENGTH}"
    )
    group["done"].vindex[where] = True


def open_store(path):
    """The sweep as an :class:`xarray.Dataset` (lazily, from the store)."""
    import xarray as xr

    return xr.open_zarr(str(path), consolidated=True)
