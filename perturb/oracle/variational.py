"""The shooting's set-up shared by both shooters: the variational equations and their integrator.

:func:`variational_rhs` is the right-hand side of the state and its fundamental matrix,
:math:`\\Phi' = J(y)\\Phi` (symbolic when the field is: heyoka then integrates it),
:func:`shooting_integrator` the integrator of that augmented state, and
:func:`finite_difference_jacobian` the Jacobian of a field given as a plain function.
"""

from __future__ import annotations

import math

import attrs
import numpy as np

from perturb._defaults import FD_REL_STEP, SHOOTING_INTEGRATOR_RTOL
from perturb.oracle.base import RHS, Integrator
from perturb.oracle.registry import choose
from perturb.oracle.scipy import Scipy
from perturb.oracle.symbolic import SymbolicRHS

__all__ = ["finite_difference_jacobian", "shooting_integrator", "variational_rhs"]


def finite_difference_jacobian(rhs: RHS, y: np.ndarray) -> np.ndarray:
    """Centred finite-difference Jacobian of ``rhs`` at ``y`` (accuracy ~1e-10 relative).

    Parameters
    ----------
    rhs : callable
        ``rhs(y) -> dy/dt``.
    y : ndarray, shape (n,)

    Returns
    -------
    ndarray, shape (n, n)

    Examples
    --------
    >>> import numpy as np
    >>> from perturb.oracle import finite_difference_jacobian
    >>> finite_difference_jacobian(lambda y: np.array([y[1], -y[0] ** 3]), np.array([2.0, 0.0])).round(6)
    array([[  0.,   1.],
           [-12.,   0.]])
    """
    y = np.asarray(y, dtype=float)
    n = y.size
    jac = np.empty((n, n))
    scale = max(1.0, float(np.max(np.abs(y))))
    for j in range(n):
        h = FD_REL_STEP * max(abs(y[j]), scale)
        e = np.zeros(n)
        e[j] = h
        jac[:, j] = (np.asarray(rhs(y + e)) - np.asarray(rhs(y - e))) / (2.0 * h)
    return jac


def variational_rhs(rhs, jac):
    """The rhs of (y, Phi) with Phi' = J(y) Phi; symbolic if ``rhs`` is symbolic."""
    if isinstance(rhs, SymbolicRHS) and jac is None:
        return rhs.variational
    n_holder = {}

    def jacobian(y):
        if jac is not None:
            return np.asarray(jac(y), dtype=float)
        if isinstance(rhs, SymbolicRHS):
            return rhs.jacobian(y)
        return finite_difference_jacobian(rhs, y)

    def augmented(z):
        n = n_holder.get("n")
        if n is None:
            n = int(round((math.sqrt(1 + 4 * z.size) - 1) / 2))  # z.size = n + n**2
            n_holder["n"] = n
        y = z[:n]
        phi = z[n:].reshape(n, n)
        return np.concatenate((np.asarray(rhs(y), dtype=float), (jacobian(y) @ phi).ravel()))

    return augmented


def shooting_integrator(integrator, aug_rhs, n: int) -> Integrator:
    """Resolve the integrator argument and adapt per-component tolerances to the augmented state."""
    symbolic = isinstance(aug_rhs, SymbolicRHS)
    if integrator is None:
        return choose(None, rtol=SHOOTING_INTEGRATOR_RTOL, symbolic=symbolic)
    integrator = choose(integrator, symbolic=symbolic)
    if isinstance(integrator, Scipy):
        # per-component options given for the n-dimensional state: extend them to the n + n**2
        # augmented state (Phi entries are O(1) near the identity)
        if integrator.atol is not None and np.ndim(integrator.atol) == 1:
            if np.size(integrator.atol) == n:
                atol = np.concatenate((integrator.atol, np.full(n * n, integrator.rtol)))
                integrator = attrs.evolve(integrator, atol=atol)
        if integrator.y_scale is not None and np.size(integrator.y_scale) == n:
            y_scale = np.concatenate((np.abs(integrator.y_scale), np.ones(n * n)))
            integrator = attrs.evolve(integrator, y_scale=y_scale)
    return integrator
