"""Numerical oracle: integrators behind one protocol and periodic orbits by shooting.

Problem-independent: everything works on an autonomous ODE ``y' = f(y)`` given as a numpy callable
``rhs(y)`` or as a :class:`SymbolicRHS` (sympy expressions, needed by the Taylor integrator heyoka).

Layout: :mod:`~perturb.oracle.base` (the result, its status and the template every integrator
follows), one module per backend (:mod:`~perturb.oracle.rk4`, :mod:`~perturb.oracle.scipy`,
:mod:`~perturb.oracle.heyoka`), :mod:`~perturb.oracle.registry` (names and :func:`choose`),
:mod:`~perturb.oracle.symbolic` (sympy rhs and the heyoka translation),
:mod:`~perturb.oracle.orbit`, :mod:`~perturb.oracle.shooting` (periodic orbits),
:mod:`~perturb.oracle.forced` (the periodic responses of driven systems, period given),
:mod:`~perturb.oracle.driven_family` (those responses along a parameter: the fixed-period shooting
map with its monodromy and sensitivity, for continuation) and :mod:`~perturb.oracle.bifurcation`
(the Floquet test functions: fold, period doubling, Neimark–Sacker).  Code outside
the oracle imports from this package only.
"""

import importlib

from perturb.oracle.base import Integrator, IntegratorBase, Trajectory, TrajectoryStatus
from perturb.oracle.floquet import expected_trivial_multipliers
from perturb.oracle.heyoka import Heyoka, heyoka_available
from perturb.oracle.orbit import OrbitRoute, OrbitStatus, PeriodicOrbit
from perturb.oracle.registry import INTEGRATORS, choose, default_integrator, get_integrator
from perturb.oracle.rk4 import RK4
from perturb.oracle.scipy import Scipy, scaled_atol
from perturb.oracle.shooting import find_periodic_orbit, finite_difference_jacobian
from perturb.oracle.symbolic import SymbolicRHS
from perturb.oracle.translate import to_heyoka

__all__ = [
    "INTEGRATORS",
    "RK4",
    "DrivenFamily",
    "Heyoka",
    "Integrator",
    "IntegratorBase",
    "OrbitRoute",
    "OrbitStatus",
    "PeriodicOrbit",
    "Scipy",
    "Shot",
    "SymbolicRHS",
    "Trajectory",
    "TrajectoryStatus",
    "choose",
    "critical_multiplier",
    "default_integrator",
    "expected_trivial_multipliers",
    "find_forced_orbit",
    "find_periodic_orbit",
    "finite_difference_jacobian",
    "fold_test",
    "get_integrator",
    "heyoka_available",
    "is_neimark_sacker",
    "neimark_sacker_test",
    "period_doubling_test",
    "scaled_atol",
    "to_heyoka",
]

#: Names of the driven and bifurcation modules, imported on first access (PEP 562): a free
#: system's validation never loads them.
_LAZY = {
    "DrivenFamily": "perturb.oracle.driven_family",
    "Shot": "perturb.oracle.driven_family",
    "critical_multiplier": "perturb.oracle.bifurcation",
    "find_forced_orbit": "perturb.oracle.forced",
    "fold_test": "perturb.oracle.bifurcation",
    "is_neimark_sacker": "perturb.oracle.bifurcation",
    "neimark_sacker_test": "perturb.oracle.bifurcation",
    "period_doubling_test": "perturb.oracle.bifurcation",
}


def __getattr__(name: str):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'perturb.oracle' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value  # later lookups skip this hook
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
