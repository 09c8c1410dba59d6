"""Numerical references used by several tests (scipy only, tight tolerances)."""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import fsolve

#: Tolerances of reference integrations: far below the smallest error the tests resolve (~1e-9).
REF_RTOL, REF_ATOL = 1e-13, 1e-14

#: The spacing of the doubles at 1 (2.2e-16).
EPS64 = float(np.finfo(float).eps)
#: What one float64 operation may be off by, in EPS64, on any IEEE machine: a basic operation is
#: correctly rounded (1/2), an elementary function (a libm's, numpy's SIMD loops) within 4 ulps.
ULPS_PER_OPERATION = 4


def roundings(operations: int) -> float:
    """Relative tolerance of a float64 number computed by two routes of ``operations`` each.

    Where nothing cancels (the terms are of the result's size), each route is within
    ``operations * ULPS_PER_OPERATION`` ulps of the exact value on any IEEE machine, so two routes,
    or two machines, differ by at most twice that. A result that cancels takes it relative to the
    terms' size. Never the bits: a tolerance below this is a test of this machine's rounding.

    >>> roundings(8)  # 64 EPS64
    1.4210854715202004e-14
    """
    return 2 * operations * ULPS_PER_OPERATION * EPS64


def integrate(rhs, y0, t):
    """Reference trajectory at times ``t`` (DOP853 at REF_RTOL)."""
    t = np.asarray(t, float)
    sol = solve_ivp(
        rhs,
        (0.0, float(t[-1])),
        np.asarray(y0, float),
        method="DOP853",
        t_eval=t,
        rtol=REF_RTOL,
        atol=REF_ATOL,
    )
    assert sol.success, sol.message
    return sol.y


def shoot_1dof(rhs, x0_guess, period_guess):
    """Periodic orbit of a 1-DOF autonomous oscillator through xdot(0) = 0: returns (x0, T)."""

    def residual(u):
        x0, T = u
        y = integrate(rhs, [x0, 0.0], [0.0, T])[:, -1]
        return [y[0] - x0, y[1]]

    (x0, T), info, ier, msg = fsolve(
        residual, [x0_guess, period_guess], xtol=1e-13, full_output=True
    )
    assert ier == 1, msg
    return x0, T


def fitted_slope(x, y):
    """Least-squares slope of log(y) against log(x)."""
    return float(np.polyfit(np.log(x), np.log(y), 1)[0])
