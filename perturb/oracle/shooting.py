"""Periodic orbits of autonomous ODEs by Newton shooting on a Poincaré section.

The unknowns are the period :math:`T` and the initial state :math:`y_0` restricted to a Poincaré
section :math:`y_s = c` (``section_index`` = s, ``section_value`` = c) with some further components
pinned (``fixed_indices``), which removes the neutral directions along families of orbits created
by first integrals (energy, momenta) or by a free amplitude.  The residual is the periodicity defect

.. math:: F(y_0, T) = \\varphi_T(y_0) - y_0 ,

and its Jacobian comes from the variational equations :math:`\\dot\\Phi = J(y)\\Phi`, :math:`\\Phi(0) = I`,
integrated together with the state:

.. math:: \\partial F / \\partial y_0 = \\Phi(T) - I,\\qquad \\partial F / \\partial T = f(\\varphi_T(y_0)).

The system is square only without first integrals; in general it has more equations than unknowns
(the integrals make some rows dependent), so each Newton step is a least-squares (Gauss–Newton)
step, which converges quadratically because the residual vanishes at the solution.  A backtracking
line search damps steps that would increase the residual.

At convergence :math:`\\Phi(T)` is the monodromy matrix; its eigenvalues are the Floquet multipliers.
Autonomy gives one trivial multiplier 1 (eigenvector :math:`f(y_0)`) and each first integral another;
their distance from 1 is an accuracy check of the whole computation (as in AUTO).
"""

from __future__ import annotations

import enum
import math
from collections.abc import Sequence
from typing import Any

import attrs
import numpy as np
from attrs import field, frozen

from perturb.errors import PerturbError, bad_value
from perturb.oracle._settings import (
    EQUILIBRIUM_MOTION,
    FD_REL_STEP,
    SHOOTING_INTEGRATOR_RTOL,
    SHOOTING_MAX_HALVINGS,
    SHOOTING_MAX_ITER,
    SHOOTING_STALL_STEP,
    SHOOTING_TOL,
)
from perturb.oracle.integrators import (
    RHS,
    Heyoka,
    Integrator,
    Scipy,
    get_integrator,
    heyoka_available,
)
from perturb.oracle.symbolic import SymbolicRHS

__all__ = ["OrbitStatus", "PeriodicOrbit", "find_periodic_orbit", "finite_difference_jacobian"]


class OrbitStatus(enum.Enum):
    """How a shooting search ended; the values are the user-facing messages.

    :attr:`PeriodicOrbit.message` gives the numbers of the particular run.
    """

    CONVERGED = "The shooting converged to a periodic orbit."
    MAX_ITER = "The Newton iteration did not converge within `max_iter` iterations."
    INTEGRATION_FAILED = "An integration of the state and variational equations failed."
    STALLED = "The Newton iteration stalled: no step reduces the residual (integrator accuracy limits it)."
    WRONG_DIRECTION = "Converged, but the orbit crosses the section in the wrong direction."
    EQUILIBRIUM = (
        "Converged onto an equilibrium, not a periodic orbit (a family parameter was not pinned)."
    )

    @property
    def success(self) -> bool:
        """True only for :attr:`CONVERGED`."""
        return self is OrbitStatus.CONVERGED

    @property
    def code(self) -> int:
        """The legacy integer code (0 converged, negative failure), for integer JSON fields."""
        return _ORBIT_CODES[self]


_ORBIT_CODES = {
    OrbitStatus.CONVERGED: 0,
    OrbitStatus.MAX_ITER: -1,
    OrbitStatus.INTEGRATION_FAILED: -2,
    OrbitStatus.STALLED: -3,
    OrbitStatus.WRONG_DIRECTION: -4,
    OrbitStatus.EQUILIBRIUM: -5,
}

#: Singular values below this fraction of the largest count as zero in the rank of the Newton matrix.
_RANK_RTOL = 1e-9


def _readonly(value: Any) -> np.ndarray:
    array = np.array(value)
    array.setflags(write=False)
    return array


_array_eq = attrs.cmp_using(eq=np.array_equal)


@frozen
class PeriodicOrbit:
    """A periodic orbit found by shooting, with its Floquet multipliers and how the search ended.

    Attributes
    ----------
    period : float
        The period :math:`T`.
    initial_state : ndarray, shape (n,)
        :math:`y(0)`, on the section.
    floquet_multipliers : ndarray, shape (n,), complex
        Eigenvalues of :attr:`monodromy`, sorted by distance from 1 (the trivial ones first).
    monodromy : ndarray, shape (n, n)
        :math:`\\Phi(T)`, the linearised flow over one period.
    residual : float
        Relative periodicity defect :math:`\\|y(T) - y(0)\\|_\\infty / s`, ``s`` the state scale.
    iterations : int
        Newton iterations performed.
    status : OrbitStatus
        :attr:`OrbitStatus.CONVERGED`, or why the search failed: ``MAX_ITER``,
        ``INTEGRATION_FAILED``, ``STALLED`` (no step reduces the residual: integrator accuracy limits
        it), ``WRONG_DIRECTION`` (converged but crossing the section in the wrong direction) or
        ``EQUILIBRIUM`` (a fixed point is "periodic" with any period, typically because a family
        parameter was not pinned).
    message : str
        What happened, with the numbers.
    trivial_multiplier_error : float
        Largest distance from 1 among the ``n_trivial`` multipliers closest to 1.  For a double
        multiplier (a Jordan block, e.g. a conservative family) it scales like the square root of the
        integration error, so expect ~1e-7 there rather than ~1e-13.
    integrator : str
        The integrator that ran.
    """

    period: float = field(converter=float)
    initial_state: np.ndarray = field(converter=_readonly, eq=_array_eq)
    floquet_multipliers: np.ndarray = field(converter=_readonly, eq=_array_eq)
    monodromy: np.ndarray = field(converter=_readonly, eq=_array_eq)
    residual: float = field(converter=float)
    iterations: int
    status: OrbitStatus = field(validator=attrs.validators.instance_of(OrbitStatus))
    message: str
    trivial_multiplier_error: float = math.nan
    integrator: str = ""

    @property
    def success(self) -> bool:
        """True if the iteration converged to an orbit crossing the section as requested."""
        return self.status.success

    def raise_for_status(self) -> PeriodicOrbit:
        """Return ``self`` if successful, else raise :class:`perturb.errors.PerturbError`."""
        if not self.success:
            raise PerturbError(f"shooting failed ({self.status.name}): {self.message}")
        return self


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


def _variational_rhs(rhs, jac):
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


def _shooting_integrator(integrator, aug_rhs, n: int) -> Integrator:
    """Resolve the integrator argument and adapt per-component tolerances to the augmented state."""
    if integrator is None:
        if heyoka_available() and isinstance(aug_rhs, SymbolicRHS):
            return Heyoka()
        return Scipy("DOP853", rtol=SHOOTING_INTEGRATOR_RTOL)
    if isinstance(integrator, str):
        integrator = get_integrator(integrator)
    if not isinstance(integrator, Integrator):
        raise bad_value(
            "integrator", integrator, "pass an integrator object, a registry name or None"
        )
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


def _as_index_tuple(name: str, value, n: int) -> tuple[int, ...]:
    values = (value,) if isinstance(value, int | np.integer) else tuple(value)
    for v in values:
        if not isinstance(v, int | np.integer) or not -n <= v < n:
            raise bad_value(name, value, f"indices must be integers in [0, {n})")
    return tuple(sorted({int(v) % n for v in values}))


def find_periodic_orbit(
    rhs: RHS,
    y0_guess: Sequence[float],
    period_guess: float,
    *,
    section_index: int,
    section_value: float = 0.0,
    direction: int = 0,
    fixed_indices: int | Sequence[int] = (),
    jac=None,
    integrator: Integrator | str | None = None,
    tol: float = SHOOTING_TOL,
    max_iter: int = SHOOTING_MAX_ITER,
    n_trivial: int = 1,
    y_scale: float | None = None,
) -> PeriodicOrbit:
    """Find a periodic orbit of ``y' = rhs(y)`` by Newton shooting on a Poincaré section.

    Parameters
    ----------
    rhs : callable or SymbolicRHS
        ``rhs(y) -> dy/dt`` for a state of shape ``(n,)``.
    y0_guess : array_like, shape (n,)
        Initial guess of the state at the section crossing.
    period_guess : float
        Initial guess of the period (> 0).
    section_index : int
        Component defining the section ``y[section_index] = section_value``; it is pinned.
    section_value : float, optional
        Value of the section (0 by default).
    direction : {0, 1, -1}, optional
        Required sign of ``dy[section_index]/dt`` at the crossing; 0 accepts either.  Checked at
        convergence (``OrbitStatus.WRONG_DIRECTION`` if violated).
    fixed_indices : int or sequence of int, optional
        Further components held at their guessed values, one per neutral direction (e.g. the energy
        of a conservative family: pin the amplitude).
    jac : callable, optional
        ``jac(y) -> (n, n)`` Jacobian of ``rhs``.  Default: the symbolic Jacobian of a
        :class:`SymbolicRHS`, else centred finite differences of ``rhs``.
    integrator : Integrator or str, optional
        Integrator of the state + variational equations (``n + n**2`` components).  Default: heyoka
        at machine precision for a symbolic rhs when heyoka is installed, else DOP853 at
        ``rtol = SHOOTING_INTEGRATOR_RTOL``.  Must be markedly more accurate than ``tol``.
    tol : float, optional
        Convergence tolerance on the relative residual ``||y(T) - y(0)||_inf / scale``.
    max_iter : int, optional
        Maximum number of Newton iterations.
    n_trivial : int, optional
        Number of multipliers expected at 1: one for autonomy plus one per independent first
        integral; used for :attr:`PeriodicOrbit.trivial_multiplier_error`.
    y_scale : float, optional
        State scale of the relative residual; default ``max |y0_guess|`` (1 if that is zero).

    Returns
    -------
    PeriodicOrbit
        Always returned; failure to converge is reported through ``status`` and ``message``.

    Raises
    ------
    perturb.errors.InvalidParameterError
        For invalid input (bad indices, non-positive period or tolerance, non-finite guess).

    Examples
    --------
    Van der Pol limit cycle, x'' - eps (1 - x**2) x' + x = 0, on the section x' = 0:

    >>> import numpy as np
    >>> eps = 0.1
    >>> rhs = lambda y: np.array([y[1], eps * (1 - y[0] ** 2) * y[1] - y[0]])
    >>> orbit = find_periodic_orbit(rhs, [2.0, 0.0], 2 * np.pi, section_index=1)
    >>> bool(orbit.success), round(orbit.period, 6)
    (True, 6.287111)
    """
    y0 = np.array(y0_guess, dtype=float)
    if y0.ndim != 1 or y0.size == 0 or not np.all(np.isfinite(y0)):
        raise bad_value("y0_guess", y0_guess, "pass a finite, non-empty 1-D state vector")
    n = y0.size
    if not (isinstance(period_guess, int | float | np.number) and math.isfinite(period_guess)):
        raise bad_value("period_guess", period_guess, "pass a finite positive number")
    if period_guess <= 0:
        raise bad_value("period_guess", period_guess, "the period must be positive")
    if not (tol > 0 and math.isfinite(tol)):
        raise bad_value("tol", tol, "pass a positive tolerance such as 1e-12")
    if not isinstance(max_iter, int | np.integer) or max_iter < 1:
        raise bad_value("max_iter", max_iter, "pass an integer >= 1")
    if direction not in (-1, 0, 1):
        raise bad_value("direction", direction, "use +1, -1 or 0 (either direction)")
    if not isinstance(n_trivial, int | np.integer) or not 0 <= n_trivial <= n:
        raise bad_value("n_trivial", n_trivial, f"pass an integer in [0, {n}]")
    (section,) = _as_index_tuple("section_index", section_index, n)
    fixed = _as_index_tuple("fixed_indices", fixed_indices, n)
    free = [i for i in range(n) if i != section and i not in fixed]
    if isinstance(rhs, SymbolicRHS) and rhs.n != n:
        raise bad_value("y0_guess", f"{n} components", f"the symbolic rhs has {rhs.n}")
    scale = float(np.max(np.abs(y0))) if y_scale is None else float(y_scale)
    if y_scale is not None and not (scale > 0 and math.isfinite(scale)):
        raise bad_value("y_scale", y_scale, "pass a positive state scale")
    scale = scale if scale > 0 else 1.0

    y0[section] = section_value
    aug_rhs = _variational_rhs(rhs, jac)
    solver = _shooting_integrator(integrator, aug_rhs, n)
    identity = np.eye(n)

    def shoot(y_start, period):
        """Integrate state + variational equations over one period: (F, Phi, f(y(T))) or error."""
        traj = solver.integrate(aug_rhs, (0.0, period), np.concatenate((y_start, identity.ravel())))
        if not traj.success:
            return traj, None, None, None
        z = np.asarray(traj.y_final, dtype=float)
        y_end, phi = z[:n], z[n:].reshape(n, n)
        return traj, y_end - y_start, phi, np.asarray(rhs(y_end), dtype=float)

    def failed(status, message, iterations, y_now, period, residual, phi=None):
        phi = np.full((n, n), np.nan) if phi is None else phi
        finite = bool(np.all(np.isfinite(phi)))
        return PeriodicOrbit(
            period=period,
            initial_state=y_now,
            floquet_multipliers=_multipliers(phi) if finite else np.full(n, np.nan, dtype=complex),
            monodromy=phi,
            residual=residual,
            iterations=iterations,
            status=status,
            message=message,
            integrator=solver.name,
        )

    y, period = y0, float(period_guess)
    traj, defect, phi, f_end = shoot(y, period)
    if defect is None:
        return failed(
            OrbitStatus.INTEGRATION_FAILED,
            f"integration of the initial guess failed: {traj.message} (t = {traj.t_reached})",
            0,
            y,
            period,
            math.inf,
        )
    residual = float(np.max(np.abs(defect))) / scale
    iterations = 0
    rank_note = ""
    while residual > tol:
        if iterations >= max_iter:
            return failed(
                OrbitStatus.MAX_ITER,
                f"no convergence in max_iter = {max_iter} Newton iterations: residual "
                f"{residual:.3e} > tol = {tol:.1e}; improve the guess or raise `max_iter`",
                iterations,
                y,
                period,
                residual,
                phi,
            )
        iterations += 1
        # Newton matrix: d(phi_T(y0) - y0)/d(free y0, T) = [(Phi - I)[:, free], f(y(T))]
        newton = np.column_stack(((phi - identity)[:, free], f_end))
        step, _, rank, _ = np.linalg.lstsq(newton, -defect, rcond=_RANK_RTOL)
        if rank < newton.shape[1]:
            rank_note = (
                f" The Newton matrix has rank {rank} < {newton.shape[1]} unknowns: the orbit is "
                "not isolated; pin more components with `fixed_indices`."
            )
        lam, accepted = 1.0, False
        for _ in range(SHOOTING_MAX_HALVINGS + 1):
            y_try = y.copy()
            y_try[free] += lam * step[:-1]
            period_try = period + lam * step[-1]
            if period_try > 0:
                trial = shoot(y_try, period_try)
                if trial[1] is not None:
                    residual_try = float(np.max(np.abs(trial[1]))) / scale
                    if residual_try < residual:
                        accepted = True
                        break
            lam *= 0.5
        step_size = float(np.max(np.abs(step[:-1]), initial=0.0)) / scale
        step_size = max(step_size, abs(step[-1]) / period)
        if not accepted:
            return failed(
                OrbitStatus.STALLED,
                f"stalled after {iterations} iterations at residual {residual:.3e} > tol = "
                f"{tol:.1e}: no damped Newton step reduces it (relative step {step_size:.1e}); "
                "the integrator error probably dominates: tighten its tolerance or loosen `tol`."
                + rank_note,
                iterations,
                y,
                period,
                residual,
                phi,
            )
        y, period = y_try, period_try
        traj, defect, phi, f_end = trial
        residual = residual_try
        if step_size < SHOOTING_STALL_STEP and residual > tol:
            return failed(
                OrbitStatus.STALLED,
                f"stalled after {iterations} iterations at residual {residual:.3e} > tol = "
                f"{tol:.1e}: the Newton step is below {SHOOTING_STALL_STEP:g}." + rank_note,
                iterations,
                y,
                period,
                residual,
                phi,
            )

    multipliers = _multipliers(phi)
    distances = np.sort(np.abs(multipliers - 1.0))
    trivial_error = float(distances[n_trivial - 1]) if n_trivial > 0 else 0.0
    status, message = (
        OrbitStatus.CONVERGED,
        f"converged in {iterations} iterations: residual {residual:.2e}, period {float(period)!r}, "
        f"trivial multiplier error {trivial_error:.1e}." + rank_note,
    )
    velocity = np.asarray(rhs(y), dtype=float)
    crossing = float(velocity[section])
    if float(np.max(np.abs(velocity))) * period <= EQUILIBRIUM_MOTION * scale:
        status = OrbitStatus.EQUILIBRIUM
        message = (
            f"converged onto an equilibrium (|f(y0)| * T = {np.max(np.abs(velocity)) * period:.1e}),"
            " not a periodic orbit; pin the amplitude or energy with `fixed_indices`, or start "
            "closer to the orbit."
        )
    elif direction != 0 and np.sign(crossing) != direction:
        status = OrbitStatus.WRONG_DIRECTION
        message = (
            f"converged, but the orbit crosses the section with dy[{section}]/dt = {crossing:.3e}, "
            f"not in the requested direction {direction:+d}; start from the other crossing."
        )
    return PeriodicOrbit(
        period=period,
        initial_state=y,
        floquet_multipliers=multipliers,
        monodromy=phi,
        residual=residual,
        iterations=iterations,
        status=status,
        message=message,
        trivial_multiplier_error=trivial_error,
        integrator=solver.name,
    )


def _multipliers(phi: np.ndarray) -> np.ndarray:
    """Eigenvalues of the monodromy matrix sorted by distance from 1."""
    values = np.linalg.eigvals(phi).astype(complex)
    return values[np.argsort(np.abs(values - 1.0), kind="stable")]
