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
iteration is the autonomous shooting's own (:func:`perturb.oracle.newton.damped_newton`): the
tolerance or the precision floor measured at the orbit.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from perturb._defaults import (
    FLOOR_SAFETY,
    SHOOTING_MAX_ITER,
    SHOOTING_STALL_STEP,
    SHOOTING_TOL,
)
from perturb.errors import bad_value
from perturb.oracle.newton import NewtonOutcome, PeriodMap, Shot, damped_newton
from perturb.oracle.orbit import OrbitRoute, OrbitStatus, PeriodicOrbit, multipliers_of
from perturb.oracle.symbolic import SymbolicRHS
from perturb.oracle.variational import shooting_integrator, variational_rhs

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
        ``n_trivial_expected = 0``; ``multipliers`` of the state block, sorted by distance
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
    aug = variational_rhs(rhs, None)
    solver = shooting_integrator(integrator, aug, rhs.n)
    result = damped_newton(_ForcedMap(rhs, aug, solver, period, m, y0, tol, max_iter), y0)
    phi = result.shot.monodromy
    if phi is None:
        phi = np.full((m, m), np.nan)
    finite = bool(np.all(np.isfinite(phi)))
    multipliers = multipliers_of(phi) if finite else np.full(m, np.nan, complex)
    status, message = _outcome(result, tol, max_iter, period, multipliers)
    return PeriodicOrbit(
        period=period,
        initial_state=result.x,
        multipliers=multipliers,
        monodromy=phi,
        residual=result.residual,
        iterations=result.iterations,
        status=status,
        message=message,
        integrator=solver.name,
        precision_floor=result.floor,
        defect=result.shot.defect,
        found_by=OrbitRoute.FORCED,
    )


class _ForcedMap(PeriodMap):
    """The period map of a driven system (:class:`~perturb.oracle.newton.PeriodMap`): the
    unknowns are the initial state, θ(0) = 0 and the period fixed."""

    def __init__(self, rhs, aug, solver, period, m, y0, tol, max_iter):
        self.rhs, self.aug, self.solver, self.period, self.m = rhs, aug, solver, period, m
        self.identity = np.eye(rhs.n)
        self.scale = max(float(np.max(np.abs(y0))), 1.0)
        self.tol, self.max_iter = tol, max_iter

    def shoot(self, x, integrator=None) -> Shot:
        start = np.concatenate((x, [0.0], self.identity.ravel()))
        traj = (integrator or self.solver).integrate(self.aug, (0.0, self.period), start)
        if not traj.success:
            return Shot(traj, None, None)
        z = np.asarray(traj.y_final, dtype=float)
        phi = z[self.rhs.n :].reshape(self.rhs.n, self.rhs.n)[: self.m, : self.m]
        return Shot(traj, z[: self.m] - x, phi)

    def state(self, x):
        return x

    def residual(self, x, shot) -> float:
        return float(np.max(np.abs(shot.defect))) / self.scale

    def linearised(self, x, shot):
        return shot.monodromy - np.eye(self.m), -shot.defect

    def moved(self, x, step, lam):
        return x + lam * step


def _outcome(result, tol, max_iter, period, multipliers) -> tuple[OrbitStatus, str]:
    """The orbit's status and message from the loop's outcome."""
    iterations, residual, floor = result.iterations, result.residual, result.floor
    if result.outcome is NewtonOutcome.INTEGRATION_FAILED:
        return OrbitStatus.INTEGRATION_FAILED, (
            f"integration of the initial guess failed: {result.shot.trajectory.message}"
        )
    if result.outcome is NewtonOutcome.MAX_ITER:
        return OrbitStatus.MAX_ITER, (
            f"no convergence in max_iter = {max_iter} Newton iterations: residual "
            f"{residual:.3e} > tol = {tol:.1e}; improve the guess or raise `max_iter`"
        )
    if result.outcome in (NewtonOutcome.STALLED, NewtonOutcome.STALLED_STEP):
        return OrbitStatus.STALLED, (
            f"stalled after {iterations} iterations at residual {residual:.3e} > tol = "
            f"{tol:.1e} and above {FLOOR_SAFETY:g} x the precision floor {floor:.1e}: "
            + (
                "no damped Newton step reduces it"
                if result.outcome is NewtonOutcome.STALLED
                else f"the Newton step is below {SHOOTING_STALL_STEP:g}"
            )
        )
    largest = float(np.max(np.abs(multipliers)))
    where = f"residual {residual:.2e}" + ("" if residual <= tol else f" at the floor {floor:.1e}")
    return OrbitStatus.CONVERGED, (
        f"converged in {iterations} iterations: {where}, period {period!r} (given); largest "
        f"|Floquet multiplier| {largest:.6f} ({'stable' if largest < 1 else 'unstable'})"
    )
