"""Numerical oracle: integrators behind one protocol and periodic orbits by shooting.

Problem-independent: everything works on an autonomous ODE ``y' = f(y)`` given as a numpy callable
``rhs(y)`` or as a :class:`SymbolicRHS` (sympy expressions, needed by the Taylor integrator heyoka).
"""

from perturb.oracle.integrators import (
    INTEGRATORS,
    RK4,
    Heyoka,
    Integrator,
    Scipy,
    Trajectory,
    TrajectoryStatus,
    default_integrator,
    get_integrator,
    heyoka_available,
    scaled_atol,
)
from perturb.oracle.registry import choose
from perturb.oracle.shooting import (
    OrbitStatus,
    PeriodicOrbit,
    find_periodic_orbit,
    finite_difference_jacobian,
)
from perturb.oracle.symbolic import SymbolicRHS, to_heyoka

__all__ = [
    "INTEGRATORS",
    "RK4",
    "Heyoka",
    "Integrator",
    "OrbitStatus",
    "PeriodicOrbit",
    "Scipy",
    "SymbolicRHS",
    "Trajectory",
    "TrajectoryStatus",
    "choose",
    "default_integrator",
    "find_periodic_orbit",
    "finite_difference_jacobian",
    "get_integrator",
    "heyoka_available",
    "scaled_atol",
    "to_heyoka",
]
