"""Sweeps and validity maps: a problem's solution over a grid of its parameters, on Dask.

``perturb.sweep(problem, grid, ...)`` (this module is callable: it is ``sweep``) derives
the solution once, evaluates — and with ``validate=True`` shoots and judges — every point in
chunks on a ``dask.distributed`` cluster, and returns an ``xarray.Dataset`` (written to a
resumable Zarr store when ``output`` is given). ``perturb sweep`` is the same from the command line.

Rooms: ``grid`` (axes, points, chunks), ``spec`` (what a sweep computes),
``derive`` (derive once), ``quantities`` (the variables), ``status`` (coded
statuses), ``evaluate`` and ``task`` (the work of a task, on a worker), ``driver``
(Dask), ``store`` (Zarr, resume), ``memory`` (results without a store), ``api``
(the front door). Only ``driver``, ``store`` and ``memory`` import the extra
``perturb[sweep]`` (dask, distributed, xarray, zarr), and only when a sweep runs; importing this
package (or ``grid``, which scenes use to read a ``[sweep]`` section) loads none of them.

Examples
--------
>>> import perturb
>>> from problems import get_problem
>>> ds = perturb.sweep(get_problem("duffing").create(), ["eps=0.05:0.1:3"], workers=1)  # doctest: +SKIP
>>> ds.period.sel(eps=0.1).item()  # doctest: +SKIP
6.0533...
"""

from __future__ import annotations

import importlib
import sys
import types

__all__ = ["Axis", "Grid", "PointStatus", "parse_axis", "sweep"]

#: Public name -> the module defining it (imported on first use: PEP 562).
_LAZY = {
    "sweep": "perturb.sweep.api",
    "Axis": "perturb.sweep.grid",
    "Grid": "perturb.sweep.grid",
    "parse_axis": "perturb.sweep.grid",
    "PointStatus": "perturb.sweep.status",
}


def __getattr__(name: str):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'perturb.sweep' has no attribute {name!r}")
    return getattr(importlib.import_module(module), name)


class _CallableModule(types.ModuleType):
    """``perturb.sweep`` is both this package and its front door: ``perturb.sweep(...)`` calls
    :func:`perturb.sweep.api.sweep`."""

    def __call__(self, *args, **kwargs):
        from perturb.sweep.api import sweep

        return sweep(*args, **kwargs)


sys.modules[__name__].__class__ = _CallableModule
