"""Where the motion goes: basins of attraction, transients beside the slow flow, slow ramps.

Built on the steady states the series finds (:mod:`perturb.steady`) and the true motion
(:mod:`perturb.oracle`): :mod:`~perturb.dynamics.motion` (a driven problem's equations at its
values), :mod:`~perturb.dynamics.attractors` (the catalogue of proved steady states on a section),
:mod:`~perturb.dynamics.ensemble` (many states integrated together, their stroboscopic returns
only), :mod:`~perturb.dynamics.classify` (where each goes), :mod:`~perturb.dynamics.slowflow`
(the amplitude equations as ODEs, their separatrix), and the studies
:mod:`~perturb.dynamics.basins` (with :mod:`~perturb.dynamics.chunks`, on Dask, and
:mod:`~perturb.dynamics.mapping`, the map in memory or in a store),
:mod:`~perturb.dynamics.transient` and :mod:`~perturb.dynamics.ramp`, each returning a frozen
value object. Names resolve on first use (nothing is imported with the package).
"""

from __future__ import annotations

import importlib

__all__ = [
    "BasinMap",
    "Catalogue",
    "Ramp",
    "SlowFlow",
    "Transient",
    "basins",
    "catalogue",
    "ramp",
    "slow_flow_of",
    "transient",
]

_HOMES = {
    "BasinMap": "basins",
    "basins": "basins",
    "Catalogue": "attractors",
    "catalogue": "attractors",
    "Ramp": "ramp",
    "ramp": "ramp",
    "SlowFlow": "slowflow",
    "slow_flow_of": "slowflow",
    "Transient": "transient",
    "transient": "transient",
}


def __getattr__(name: str):
    if name in _HOMES:
        return getattr(importlib.import_module(f"perturb.dynamics.{_HOMES[name]}"), name)
    raise AttributeError(f"module 'perturb.dynamics' has no attribute {name!r}")
