"""Sweeps and validity maps at scale, on Dask: :func:`sweep`.

Derive once, evaluate (and validate) everywhere: a problem over a grid of its own parameters, the
points computed by ``dask.distributed`` workers (a LocalCluster, or an existing cluster by
address) and written to a Zarr store chunk by chunk as they finish, read back as an
:class:`xarray.Dataset`. Needs the extra ``perturb[sweep]`` (dask[distributed], xarray, zarr);
nothing else in perturb imports this room.

Modules: :mod:`.grid` (axes, points, limits), :mod:`.points` (what a worker computes),
:mod:`.store` (the Zarr store: create, resume, write, read), :mod:`.run` (the driver).
"""

from perturb.sweep.grid import CONFIRM_POINTS, Grid, GridAxis, parse_axis
from perturb.sweep.run import sweep

__all__ = ["CONFIRM_POINTS", "Grid", "GridAxis", "parse_axis", "sweep"]
