"""A sweep's results kept in memory (no store given): the arrays, then an :class:`xarray.Dataset`
with the layout of the Zarr store (:mod:`perturb.sweep.store`)."""

from __future__ import annotations

import json

import numpy as np

from perturb._defaults import SWEEP_MEMORY_BYTES, SWEEP_TEXT_BYTES
from perturb.errors import InvalidParameterError
from perturb.sweep.grid import Chunking
from perturb.sweep.quantities import check_names, stored_name, variables
from perturb.sweep.spec import STORE_FORMAT, SweepJob

__all__ = ["MemoryResult", "check_memory", "dataset_of", "result_bytes"]


def dataset_of(coords: dict, data: dict, attrs: dict):
    """An :class:`xarray.Dataset` of plain arrays: ``data`` maps a name to ``(dims, array,
    attributes)`` (a phase diagram's maps and special points)."""
    import xarray as xr

    variables = {name: xr.Variable(dims, values, attributes) for name, (dims, values, attributes)
                 in data.items()}  # fmt: skip
    return xr.Dataset(variables, coords=coords, attrs=attrs)


def result_bytes(spec) -> int:
    """Bytes the results of ``spec``'s sweep take in memory: every variable's values (a text
    value counted at :data:`SWEEP_TEXT_BYTES`), for every point."""
    names = len(spec.model.state_names())
    sizes = {"component": names, "time": len(spec.times), "multiplier": names,
             "check": len(check_names())}  # fmt: skip
    per_point = 0
    for var in variables(spec.validate):
        count = int(np.prod([sizes[d] for d in var.dims])) if var.dims else 1
        width = SWEEP_TEXT_BYTES if var.dtype == "str" else np.dtype(var.dtype).itemsize
        per_point += count * width
    return per_point * spec.grid.size


def check_memory(spec) -> None:
    """Raise unless the results of ``spec``'s sweep fit in memory (:data:`SWEEP_MEMORY_BYTES`):
    a larger sweep writes a Zarr store instead.

    Raises
    ------
    perturb.errors.InvalidParameterError
        One line: the points, the memory they would take, the fix.
    """
    need = result_bytes(spec)
    if need > SWEEP_MEMORY_BYTES:
        raise InvalidParameterError(
            f"the grid's {spec.grid.size:,} points would take about {need / 2**30:,.3g} GiB in "
            f"memory (more than {SWEEP_MEMORY_BYTES / 2**30:g} GiB): write them to a store, "
            "--format zarr --output STORE (output= in Python), which holds one chunk at a time"
        )


class MemoryResult:
    """The arrays of every variable, filled chunk by chunk (:meth:`write`)."""

    def __init__(self, job: SweepJob, chunking: Chunking, attrs: dict):
        spec = job.spec
        self.job = job
        self.chunking = chunking
        self.attrs = attrs
        names = tuple(spec.model.state_names())
        self.dims = {
            "component": np.array(names, dtype=str),
            "time": np.asarray(spec.times, dtype=float),
            "multiplier": np.arange(len(names)),
            "check": np.array(check_names(), dtype=str),
        }
        sizes = {name: len(values) for name, values in self.dims.items()}
        self.variables = variables(spec.validate)
        self.arrays = {}
        for var in self.variables:
            shape = (*spec.grid.shape, *(sizes[d] for d in var.dims))
            dtype = object if var.dtype == "str" else var.dtype
            self.arrays[var.name] = np.full(shape, var.fill, dtype=dtype)

    def pending(self) -> list[int]:
        return list(self.chunking)

    def write(self, number: int, result: dict) -> None:
        region = self.chunking.region(number)
        block = tuple(s.stop - s.start for s in region)
        for name, array in self.arrays.items():
            values = np.asarray(result[name])
            array[region] = values.reshape(block + values.shape[1:])

    def dataset(self):
        """The results as an :class:`xarray.Dataset` (the store's layout and attributes)."""
        import xarray as xr

        spec = self.job.spec
        grid = spec.grid
        coords = {axis.name: np.asarray(axis.values, dtype=float) for axis in grid.axes}
        coords.update(self.dims)
        data = {}
        for var in self.variables:
            values = self.arrays[var.name]
            if values.dtype == object:
                values = values.astype(str)
            name = stored_name(var.name, grid.names)
            data[name] = ((*grid.names, *var.dims), values, dict(var.attrs))
        attrs = {
            "perturb_sweep": STORE_FORMAT,
            "problem": spec.label,
            "model_class": type(spec.model).__qualname__,
            "order": spec.order,
            "fixed_parameters": json.dumps(spec.fixed_parameters()),
            "grid": json.dumps(grid.as_list()),
            "settings": json.dumps(spec.settings()),
            "derivation": self.job.derivation.mode.name.lower(),
            "derivation_reason": self.job.derivation.reason,
            "complete": bool(np.all(self.arrays["session"] > 0)),
            **self.attrs,
        }
        return xr.Dataset(data, coords=coords, attrs=attrs)
