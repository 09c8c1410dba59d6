"""Poincaré's construction, split by concern.

* :mod:`perturb.method.poincare` — :class:`PoincareMethod` (options) and the order-by-order template;
* :mod:`perturb.method.expansion` — the forcing of each order, the given initial values in ε;
* :mod:`perturb.method.conditions` — solving the periodicity conditions, choosing a branch;
* :mod:`perturb.method.steps` — :class:`GeneratingSolution`, :class:`OrderStep`,
  :class:`PeriodicityCondition` (printable, LaTeX);
* :mod:`perturb.method.exact` — zero tests and exact roots.
"""

from perturb.method.poincare import PoincareMethod, solve
from perturb.method.steps import (
    Condition,
    GeneratingSolution,
    OrderStep,
    PeriodicityCondition,
)

__all__ = [
    "Condition",
    "GeneratingSolution",
    "OrderStep",
    "PeriodicityCondition",
    "PoincareMethod",
    "solve",
]
