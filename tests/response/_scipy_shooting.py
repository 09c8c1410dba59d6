"""An independent true steady state of a driven system: plain scipy ``solve_ivp`` (DOP853) over
the forcing period and a Newton loop on the period map with a central-difference Jacobian.
Nothing of perturb's oracle is used; the tests compare perturb's branches with it."""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

#: The integration's tolerances: the period map to ~1e-11, far below the 1e-6 at which two true
#: orbits are told apart (distinct steady states of these problems differ by > 1e-3).
RTOL = 1e-11

#: Newton converged when the period map's residual is below this, relative to the state's size.
RESIDUAL = 1e-9

#: Newton steps allowed (quadratic convergence from a seed within the basin takes < 10).
STEPS = 20

#: Two true orbits are one when their initial states agree to this, relative to their size.
SAME_ORBIT = 1e-6

#: Newton has left the seed's neighbourhood (no orbit near it) when the state grows past this
#: multiple of the seed's size: the cubic terms then make the period map stiff and the integration
#: slow without telling anything.
ESCAPE = 10.0


def period_map(rhs, period: float, y) -> np.ndarray:
    sol = solve_ivp(rhs, (0.0, period), np.asarray(y, dtype=float), method="DOP853",
                    rtol=RTOL, atol=RTOL)  # fmt: skip
    return sol.y[:, -1]


def _jacobian(rhs, period: float, y) -> np.ndarray:
    n = len(y)
    out = np.empty((n, n))
    for i in range(n):
        step = np.zeros(n)
        step[i] = 1e-6 * max(1.0, abs(y[i]))
        out[:, i] = (period_map(rhs, period, y + step) - period_map(rhs, period, y - step)) / (
            2 * step[i]
        )
    return out


def shoot(rhs, period: float, seed):
    """``(state, largest |Floquet multiplier|)`` of the true orbit Newton reaches from ``seed``,
    or ``(None, nan)`` when it does not converge."""
    y = np.asarray(seed, dtype=float)
    bound = ESCAPE * max(1.0, float(np.max(np.abs(y))))
    for _ in range(STEPS):
        residual = period_map(rhs, period, y) - y
        jac = _jacobian(rhs, period, y)
        if np.max(np.abs(residual)) <= RESIDUAL * max(1.0, float(np.max(np.abs(y)))):
            return y, float(np.max(np.abs(np.linalg.eigvals(jac))))
        try:
            y = y - np.linalg.solve(jac - np.eye(len(y)), residual)
        except np.linalg.LinAlgError:
            return None, float("nan")
        if not np.all(np.isfinite(y)) or float(np.max(np.abs(y))) > bound:
            return None, float("nan")
    return None, float("nan")


def same_orbit(a, b) -> bool:
    size = max(1.0, float(np.max(np.abs(a))), float(np.max(np.abs(b))))
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b)))) <= SAME_ORBIT * size
