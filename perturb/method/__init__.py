"""Poincaré's construction, split by concern.

* :mod:`perturb.method.poincare` — :class:`PoincareMethod` (options) and the order-by-order template;
* :mod:`perturb.method.expansion` — the forcing of each order, the given initial values in ε;
* :mod:`perturb.method.conditions` — solving the periodicity conditions, choosing a branch;
* :mod:`perturb.steps` — :class:`GeneratingSolution`, :class:`OrderStep`,
  :class:`PeriodicityCondition` (printable, LaTeX);
* :mod:`perturb.method.exact` — zero tests and exact roots.
"""

from __future__ import annotations

import importlib

#: Public name -> defining module, imported on first access (PEP 562): ``perturb.steps`` can
#: then be imported (by :mod:`perturb.solution`) without loading the construction.
_LAZY = {
    "PoincareMethod": "perturb.method.poincare",
    "solve": "perturb.method.poincare",
    "Condition": "perturb.steps",
    "GeneratingSolution": "perturb.steps",
    "OrderStep": "perturb.steps",
    "PeriodicityCondition": "perturb.steps",
}

__all__ = [
    "Condition",
    "GeneratingSolution",
    "OrderStep",
    "PeriodicityCondition",
    "PoincareMethod",
    "solve",
]


def __getattr__(name: str):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'perturb.method' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value
