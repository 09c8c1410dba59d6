"""Numerical oracle: integrators behind one protocol and periodic orbits by shooting.

Problem-independent: everything works on an autonomous ODE ``y' = f(y)`` given as a numpy callable
``rhs(y)`` or as a :class:`SymbolicRHS` (sympy expressions, needed by the Taylor integrator heyoka).

Layout: :mod:`~perturb.oracle.base` (the result, its status and the template every integrator
follows), one module per backend (:mod:`~perturb.oracle.rk4`, :mod:`~perturb.oracle.scipy`,
:mod:`~perturb.oracle.heyoka`), :mod:`~perturb.oracle.registry` (names and :func:`choose`),
:mod:`~perturb.oracle.symbolic` (sympy rhs and the heyoka translation),
:mod:`~perturb.oracle.orbit`, :mod:`~perturb.oracle.shooting` (periodic orbits) and
:mod:`~perturb.oracle.forced` (the periodic responses of driven systems, period given).  Code outside
the oracle imports from this package only.
"""

from perturb.oracle.base import Integrator, IntegratorBase, Trajectory, TrajectoryStatus
from perturb.oracle.floquet import expected_trivial_multipliers
from perturb.oracle.forced import find_forced_orbit
from perturb.oracle.heyoka import Heyoka, heyoka_available
from perturb.oracle.orbit import OrbitStatus, PeriodicOrbit
from perturb.oracle.registry import INTEGRATORS, choose, default_integrator, get_integrator
from perturb.oracle.rk4 import RK4
from perturb.oracle.scipy import Scipy, scaled_atol
from perturb.oracle.shooting import find_periodic_orbit, finite_difference_jacobian
from perturb.oracle.symbolic import SymbolicRHS
from perturb.oracle.translate import to_heyoka

__all__ = [
    "INTEGRATORS",
    "RK4",
    "Heyoka",
    "Integrator",
    "IntegratorBase",
    "OrbitStatus",
    "PeriodicOrbit",
    "Scipy",
    "SymbolicRHS",
    "Trajectory",
    "TrajectoryStatus",
    "choose",
    "default_integrator",
    "expected_trivial_multipliers",
    "find_forced_orbit",
    "find_periodic_orbit",
    "finite_difference_jacobian",
    "get_integrator",
    "heyoka_available",
    "scaled_atol",
    "to_heyoka",
]
