"""Periodic orbits of driven systems: Newton shooting with the period given by the forcing.

A driven system :math:`y' = F(y, \\theta)`, :math:`\\theta = \\Omega t`, is integrated as the
autonomous system of ``(y, θ)`` with :math:`\\theta' = \\Omega` (so heyoka and the symbolic
Jacobians serve it as any other). Its periodic response of period T (``p`` forcing periods) is a
fixed point of the period map: the unknowns are the initial state only — the period is known and
the time origin is fixed by the forcing (θ(0) = 0), so there is no section and **no trivial
multiplier**. The residual and Newton matrix are

.. math:: F(y_0) = \\varphi_T(y_0) - y_0, \\qquad \\partial F/\\partial y_0 = \\Phi(T) - I

on the state block of the variational equations; the Floquet multipliers are the eigenvalues of
that block of :math:`\\Phi(T)` (asymptotically stable when all lie inside the unit circle). The
stopping rule is the autonomous shooting's: the tolerance or the precision floor measured at the
orbit (:mod:`perturb.oracle.shooting`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from perturb._defaults import (
    FLOOR_SAFETY,
    SHOOTING_MAX_HALVINGS,
    SHOOTING_MAX_ITER,
    SHOOTING_TOL,
)
from perturb.errors import bad_value
from perturb.oracle.orbit import OrbitStatus, PeriodicOrbit, multipliers_of
from perturb.oracle.shooting import (
    _integration_noise,
    _newton_step,
    _precision_floor,
    _shooting_integrator,
    _variational_rhs,
)
from perturb.oracle.symbolic import SymbolicRHS

__all__ = ["find_forced_orbit"]


def find_forced_orbit(
    rhs: SymbolicRHS,
    y0_guess: Sequence[float],
    period: float,
    *,
    integrator=None,
    tol: float = SHOOTING_TOL,
    max_iter: int = SHOOTING_MAX_ITER,
) -> PeriodicOrbit:
    """The periodic response of period ``period`` of a driven system.

    Parameters
    ----------
    rhs : SymbolicRHS
        The autonomous form: state ``(y_1..y_m, theta)`` with ``theta' = Omega`` last.
    y0_guess : array_like, shape (m,)
        Guess of the state at t = 0 (θ = 0), e.g. the analytic response's.
    period : float
        The response's period (p forcing periods), fixed.
    integrator : Integrator or str, optional
        As for :func:`perturb.oracle.find_periodic_orbit`.
    tol : float
        Relative residual ``max|y(T) - y(0)| / max|y(0)|`` to reach (or the precision floor).
    max_iter : int

    Returns
    -------
    PeriodicOrbit
        ``n_trivial_expected = 0``; ``floquet_multipliers`` of the state block, sorted by distance
        from 1; failures as a status with the reason.

    Examples
    --------
    The linear oscillator x'' + 0.2 x' + x = cos(t): its response is x = 5 sin t.

    >>> import sympy as sp
    >>> x, v, th = sp.symbols("x v theta")
    >>> rhs = SymbolicRHS((x, v, th), (v, -0.2 * v - x + sp.cos(th), 1))
    >>> orbit = find_forced_orbit(rhs, [0.0, 4.0], 2 * 3.141592653589793)
    >>> bool(orbit.success), round(float(orbit.initial_state[1]), 6)
    (True, 5.0)
    """
    y0 = np.array(y0_guess, dtype=float)
    if not isinstance(rhs, SymbolicRHS):
        raise bad_value("rhs", rhs, "give a SymbolicRHS of (state..., theta)")
    m = rhs.n - 1
    if y0.shape != (m,) or not np.all(np.isfinite(y0)):
        raise bad_value("y0_guess", y0_guess, f"give {m} finite numbers (the state without theta)")
    if not (isinstance(period, int | float | np.number) and math.isfinite(period) and period > 0):
        raise bad_value("period", period, "give the positive period of the response")
    aug = _variational_rhs(rhs, None)
    solver = _shooting_integrator(integrator, aug, rhs.n)
    identity = np.eye(rhs.n)
    scale = max(float(np.max(np.abs(y0))), 1.0)

    def shoot(y_state, _period=period, using=solver):
        start = np.concatenate((y_state, [0.0], identity.ravel()))
        traj = using.integrate(aug, (0.0, period), start)
        if not traj.success:
            return traj, None, None, None
        z = np.asarray(traj.y_final, dtype=float)
        phi = z[rhs.n :].reshape(rhs.n, rhs.n)[:m, :m]
        return traj, z[:m] - y_state, phi, None

    def failed(status, message, iterations, y, residual, phi=None):
        phi = np.full((m, m), np.nan) if phi is None else phi
        finite = bool(np.all(np.isfinite(phi)))
        return PeriodicOrbit(
            period=period,
            initial_state=y,
            floquet_multipliers=multipliers_of(phi) if finite else np.full(m, np.nan, complex),
            monodromy=phi,
            residual=residual,
            iterations=iterations,
            status=status,
            message=message,
            integrator=solver.name,
        )

    y = y0
    traj, defect, phi, _ = shoot(y)
    if defect is None:
        return failed(
            OrbitStatus.INTEGRATION_FAILED,
            f"integration of the initial guess failed: {traj.message}",
            0, y, math.inf,
        )  # fmt: skip
    residual = float(np.max(np.abs(defect))) / scale
    floor = _precision_floor(y, defect, scale, tol)
    iterations = 0
    while residual > max(tol, floor):
        if iterations >= max_iter:
            return failed(
                OrbitStatus.MAX_ITER,
                f"no convergence in {max_iter} Newton iterations: residual {residual:.3e}",
                iterations, y, residual, phi,
            )  # fmt: skip
        iterations += 1
        step, _ = _newton_step(phi - np.eye(m), -defect)
        accepted = None
        lam = 1.0
        for _ in range(SHOOTING_MAX_HALVINGS + 1):
            trial = shoot(y + lam * step)
            if trial[1] is not None:
                trial_residual = float(np.max(np.abs(trial[1]))) / scale
                if trial_residual < residual:
                    accepted = (y + lam * step, trial, trial_residual)
                    break
            lam *= 0.5
        if accepted is None:
            noise = _integration_noise(solver, shoot, y, period, defect)
            floor = _precision_floor(y, defect, scale, tol, noise)
            if residual <= FLOOR_SAFETY * floor:
                break
            return failed(
                OrbitStatus.STALLED,
                f"stalled after {iterations} iterations at residual {residual:.3e} > tol = "
                f"{tol:.1e} and above {FLOOR_SAFETY:g} x the precision floor {floor:.1e}",
                iterations, y, residual, phi,
            )  # fmt: skip
        y, (traj, defect, phi, _), residual = accepted
        floor = _precision_floor(y, defect, scale, tol)
    multipliers = multipliers_of(phi)
    largest = float(np.max(np.abs(multipliers)))
    where = f"residual {residual:.2e}" + ("" if residual <= tol else f" at the floor {floor:.1e}")
    return PeriodicOrbit(
        period=period,
        initial_state=y,
        floquet_multipliers=multipliers,
        monodromy=phi,
        residual=residual,
        iterations=iterations,
        status=OrbitStatus.CONVERGED,
        message=(
            f"converged in {iterations} iterations: {where}, period {period!r} (given); largest "
            f"|Floquet multiplier| {largest:.6f} ({'stable' if largest < 1 else 'unstable'})"
        ),
        integrator=solver.name,
        precision_floor=floor,
    )
