"""The rigid body's equations as fast numeric functions (compiled from the derived expressions).

:mod:`problems.rigid_body.equations` derives the Euler–Poisson system, its first integrals and their
dimensionless form symbolically; this module compiles them, once a process and only when asked for,
into numeric right-hand sides, Jacobians and integrals for the integrators (the dimensional
expressions, which do not depend on the body, are also kept on disk).
"""

from __future__ import annotations

from collections.abc import Callable
from functools import cache

import numpy as np
import sympy as sp

from perturb._lambdify import numpy_lambdify
from perturb.errors import bad_value
from perturb.system import EPS
from problems.rigid_body import equations as _equations
from problems.rigid_body._stored import stored
from problems.rigid_body.equations import (
    DIMENSIONAL_STATE,
    NONDIMENSIONAL_STATE,
    A,
    B,
    C,
    M,
    NondimensionalParameters,
    R,
    RigidBodyParameters,
    a,
    b,
    euler_poisson_equations,
    first_integrals,
    g,
    k,
    nondimensional_equations,
    nondimensional_integrals,
    x0,
    x0p,
    y0,
    y0p,
    z0,
    z0p,
)

__all__ = [
    "full_jacobian",
    "full_rhs",
    "integrals_function",
    "nondimensional_integrals_function",
    "nondimensional_jacobian",
    "nondimensional_rhs",
]

_KAPPA = sp.Symbol("kappa")  # 3 g / R, so that R = inf is the number 0
_DIM_ARGS = (A, B, C, x0, y0, z0, M, g, _KAPPA)
_NONDIM_ARGS = (a, b, k, x0p, y0p, z0p, EPS)


#: Which of the three numeric functions: right-hand side, Jacobian, first integrals.
_RHS, _JACOBIAN, _INTEGRALS = range(3)
_INTEGRAL_NAMES = ("energy", "area", "geometric")


@cache
def _dimensional_expressions() -> tuple:
    """(rhs list, Jacobian matrix, integrals list) with R = 3g/kappa (on disk: body-independent)."""
    return stored("body-dimensional", ("equations.py", "numeric.py"), (), _derive_dimensional)


def _derive_dimensional() -> tuple:
    rhs = euler_poisson_equations(R).subs(R, 3 * g / _KAPPA)
    jac = rhs.jacobian(DIMENSIONAL_STATE)
    ints = [first_integrals(R)[name].subs(R, 3 * g / _KAPPA) for name in _INTEGRAL_NAMES]
    return list(rhs), jac, ints


@cache
def _nondimensional_expressions() -> tuple:
    rhs = nondimensional_equations(True, ratios=False)
    jac = rhs.jacobian(NONDIMENSIONAL_STATE)
    ints = [nondimensional_integrals(True)[name] for name in _INTEGRAL_NAMES]
    return list(rhs), jac, ints


@cache
def _dimensional_function(which: int) -> Callable:
    """One of the numeric dimensional functions, compiled only when asked for."""
    return numpy_lambdify(
        (DIMENSIONAL_STATE, _DIM_ARGS), _dimensional_expressions()[which], cse=True
    )


@cache
def _nondimensional_function(which: int) -> Callable:
    """One of the numeric dimensionless functions, compiled only when asked for."""
    expr = _nondimensional_expressions()[which]
    return numpy_lambdify((NONDIMENSIONAL_STATE, _NONDIM_ARGS), expr, cse=True)


def _dim_args(params: RigidBodyParameters) -> tuple[float, ...]:
    if not isinstance(params, RigidBodyParameters):
        raise bad_value("params", params, "pass a RigidBodyParameters instance")
    return (
        params.A,
        params.B,
        params.C,
        params.x0,
        params.y0,
        params.z0,
        params.M,
        params.g,
        params.gradient,
    )


def _nondim_args(params: NondimensionalParameters) -> tuple[float, ...]:
    if not isinstance(params, NondimensionalParameters):
        raise bad_value("params", params, "pass a NondimensionalParameters instance")
    return (params.a, params.b, params.k, params.x0p, params.y0p, params.z0p, params.eps)


def full_rhs(params: RigidBodyParameters) -> Callable[[float, np.ndarray], np.ndarray]:
    """Numeric right-hand side ``f(t, y)`` of the dimensional 6-D Euler–Poisson system.

    ``y = (p, q, r, gamma1, gamma2, gamma3)``; suitable for :func:`scipy.integrate.solve_ivp`.
    """
    f = _dimensional_function(_RHS)
    args = _dim_args(params)
    return lambda t_, y: np.array(f(y, args), dtype=float)


def full_jacobian(params: RigidBodyParameters) -> Callable[[float, np.ndarray], np.ndarray]:
    """Numeric Jacobian ``J(t, y)`` (6x6) of :func:`full_rhs`."""
    jf = _dimensional_function(_JACOBIAN)
    args = _dim_args(params)
    return lambda t_, y: np.array(jf(y, args), dtype=float)


def integrals_function(params: RigidBodyParameters) -> Callable[[np.ndarray], np.ndarray]:
    """Numeric ``(energy, area, geometric)`` of a state ``y`` of shape (6,) or (6, n)."""
    hf = _dimensional_function(_INTEGRALS)
    args = _dim_args(params)
    return lambda y: np.array(np.broadcast_arrays(*hf(np.asarray(y, dtype=float), args)))


def nondimensional_rhs(
    params: NondimensionalParameters,
) -> Callable[[float, np.ndarray], np.ndarray]:
    """Numeric ``f(tau, y)`` of the dimensionless system, ``y = (p1, q1, r1, gamma1..3)``."""
    f = _nondimensional_function(_RHS)
    args = _nondim_args(params)
    return lambda t_, y: np.array(f(y, args), dtype=float)


def nondimensional_jacobian(
    params: NondimensionalParameters,
) -> Callable[[float, np.ndarray], np.ndarray]:
    """Numeric Jacobian of :func:`nondimensional_rhs`."""
    jf = _nondimensional_function(_JACOBIAN)
    args = _nondim_args(params)
    return lambda t_, y: np.array(jf(y, args), dtype=float)


def nondimensional_integrals_function(
    params: NondimensionalParameters,
) -> Callable[[np.ndarray], np.ndarray]:
    """Numeric dimensionless ``(energy, area, geometric)`` of ``y`` (shape (6,) or (6, n))."""
    hf = _nondimensional_function(_INTEGRALS)
    args = _nondim_args(params)
    return lambda y: np.array(np.broadcast_arrays(*hf(np.asarray(y, dtype=float), args)))


# These functions lived in :mod:`problems.rigid_body.equations` before; users' ``from
# problems.rigid_body.equations import full_rhs`` still works because this module hands them to
# it (the package imports this module first), so equations never imports numeric: no circle.
for _name in __all__:
    setattr(_equations, _name, globals()[_name])
