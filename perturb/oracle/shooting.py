"""Periodic orbits of autonomous ODEs by Newton shooting on a Poincaré section.

The unknowns are the period :math:`T` and the initial state :math:`y_0` restricted to a Poincaré
section :math:`y_s = c` (``section_index`` = s, ``section_value`` = c) with some further components
pinned (``fixed_indices``) or some first integrals held at their values at the guess
(``integrals``), which removes the neutral directions along families of orbits created by first
integrals (energy, momenta) or by a free amplitude.  Without either, Newton drifts along the family
(minimum-norm steps in the neutral direction), often down to the equilibrium at its end.  The
residual is the periodicity defect

.. math:: F(y_0, T) = \\varphi_T(y_0) - y_0 ,

and its Jacobian comes from the variational equations :math:`\\dot\\Phi = J(y)\\Phi`, :math:`\\Phi(0) = I`,
integrated together with the state:

.. math:: \\partial F / \\partial y_0 = \\Phi(T) - I,\\qquad \\partial F / \\partial T = f(\\varphi_T(y_0)).

to which each pinned integral adds one row :math:`g(y_0) - g(y_{\text{guess}})`, with gradient
:math:`\nabla g(y_0)`.  The system is square only without first integrals; in general it has more
equations than unknowns (the integrals make some rows dependent), so each Newton step is a least-squares (Gauss–Newton)
step, which converges quadratically because the residual vanishes at the solution.  A backtracking
line search damps steps that would increase the residual.

At convergence :math:`\\Phi(T)` is the monodromy matrix; its eigenvalues are the Floquet multipliers.
Autonomy gives one trivial multiplier 1 (eigenvector :math:`f(y_0)`) and each first integral
another, two per integral in involution for a Hamiltonian system (see :mod:`perturb.oracle.floquet`);
their distance from 1 is an accuracy check of the whole computation (as in AUTO).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np
import sympy as sp
from attrs import frozen

from perturb._defaults import (
    EQUILIBRIUM_MOTION,
    FLOOR_SAFETY,
    SHOOTING_MAX_ITER,
    SHOOTING_STALL_STEP,
    SHOOTING_TOL,
    TRIVIAL_MULTIPLIER_TOL,
)
from perturb._lambdify import numpy_lambdify
from perturb.errors import bad_value
from perturb.oracle.base import RHS, Integrator
from perturb.oracle.floquet import count_near_one, expected_trivial_multipliers
from perturb.oracle.newton import NewtonOutcome, PeriodMap, Shot, damped_newton, rounding_norm
from perturb.oracle.orbit import OrbitStatus, PeriodicOrbit, multipliers_of
from perturb.oracle.symbolic import SymbolicRHS
from perturb.oracle.variational import (
    finite_difference_jacobian,
    shooting_integrator,
    variational_rhs,
)

__all__ = ["find_periodic_orbit", "finite_difference_jacobian"]


@frozen
class _Integral:
    """A first integral held at its value at the guess: g(y) and its gradient."""

    value: Callable[[np.ndarray], float]
    gradient: Callable[[np.ndarray], np.ndarray]


def _integral_conditions(integrals, rhs, n: int) -> list[_Integral]:
    """Numeric value and gradient of each integral (sympy: exact gradient; callable: centred FD)."""
    items = [integrals] if callable(integrals) or isinstance(integrals, sp.Basic) else integrals
    try:
        items = list(items)
    except TypeError:
        raise bad_value(
            "integrals", integrals, "pass a sequence of callables g(y) or sympy expressions"
        ) from None
    conditions = []
    for g in items:
        if isinstance(g, sp.Basic):
            if not isinstance(rhs, SymbolicRHS):
                raise bad_value(
                    "integrals",
                    g,
                    "a sympy integral needs a SymbolicRHS (its state symbols); pass a callable "
                    "g(y) -> float instead",
                )
            stray = g.free_symbols - set(rhs.state)
            if stray:
                raise bad_value(
                    "integrals", g, f"it depends on {sorted(map(str, stray))}, not state symbols"
                )
            value_fn = numpy_lambdify(rhs.state, g)
            grad_fn = numpy_lambdify(rhs.state, [sp.diff(g, x) for x in rhs.state])
            conditions.append(
                _Integral(
                    value=lambda y, f=value_fn: float(f(*y)),
                    gradient=lambda y, f=grad_fn: np.array(f(*y), dtype=float).reshape(n),
                )
            )
        elif callable(g):
            conditions.append(
                _Integral(
                    value=lambda y, g=g: float(g(y)),
                    gradient=lambda y, g=g: finite_difference_jacobian(
                        lambda z: np.atleast_1d(np.asarray(g(z), dtype=float)), y
                    )[0],
                )
            )
        else:
            raise bad_value(
                "integrals", g, "pass callables g(y) -> float or sympy expressions of the state"
            )
    return conditions


class _AutonomousMap(PeriodMap):
    """The period map of an autonomous system on a section (:class:`~perturb.oracle.newton.PeriodMap`):
    the unknowns are the free components of the initial state and the period; pinned first
    integrals add rows to the Newton system and to the residual."""

    def __init__(self, rhs, aug, solver, free, conditions, targets, scale, tol, max_iter):
        self.rhs, self.aug, self.solver, self.free = rhs, aug, solver, list(free)
        self.conditions, self.targets = conditions, targets
        self.scale, self.tol, self.max_iter = scale, tol, max_iter
        self.identity = None

    def _split(self, x):
        return x[:-1], float(x[-1])

    def shoot(self, x, integrator=None) -> Shot:
        """State + variational equations over one period: (F, Phi, f(y(T))) or a failed shot."""
        y_start, period = self._split(x)
        n = y_start.size
        if self.identity is None or self.identity.shape[0] != n:
            self.identity = np.eye(n)
        start = np.concatenate((y_start, self.identity.ravel()))
        traj = (integrator or self.solver).integrate(self.aug, (0.0, period), start)
        if not traj.success:
            return Shot(traj, None, None)
        z = np.asarray(traj.y_final, dtype=float)
        y_end, phi = z[:n], z[n:].reshape(n, n)
        return Shot(traj, y_end - y_start, phi, np.asarray(self.rhs(y_end), dtype=float))

    def state(self, x):
        return x[:-1]

    def residual(self, x, shot) -> float:
        """Relative periodicity defect, and relative defect of each pinned integral."""
        y_now = x[:-1]
        residual = float(np.max(np.abs(shot.defect))) / self.scale
        for condition, (value, size) in zip(self.conditions, self.targets, strict=True):
            residual = max(residual, abs(condition.value(y_now) - value) / size)
        return residual

    def linearised(self, x, shot):
        # d(phi_T(y0) - y0)/d(free y0, T) = [(Phi - I)[:, free], f(y(T))]
        y = x[:-1]
        newton = np.column_stack(((shot.monodromy - self.identity)[:, self.free], shot.velocity))
        target = -shot.defect
        if self.conditions:
            # one row per pinned integral, scaled to state units: (scale / s) grad g . dy0 = ...
            pairs = list(zip(self.conditions, self.targets, strict=True))
            rows = [
                np.append(condition.gradient(y)[self.free] * (self.scale / size), 0.0)
                for condition, (_, size) in pairs
            ]
            misses = [
                -(condition.value(y) - value) * (self.scale / size)
                for condition, (value, size) in pairs
            ]
            newton = np.vstack((newton, rows))
            target = np.concatenate((target, misses))
        return newton, target

    def matrix_noise(self, shot) -> float:
        # the matrix's columns: the free ones of the monodromy and the velocity (the pinned
        # integrals' rows are gradients at the guess, of their own size: no rounding near zero)
        return rounding_norm(np.column_stack((shot.monodromy[:, self.free], shot.velocity)))

    def moved(self, x, step, lam):
        y_try = x[:-1].copy()
        y_try[self.free] += lam * step[:-1]
        period_try = x[-1] + lam * step[-1]
        return np.append(y_try, period_try) if period_try > 0 else None

    def step_size(self, x, step) -> float:
        size = float(np.max(np.abs(step[:-1]), initial=0.0)) / self.scale
        return max(size, abs(step[-1]) / x[-1])


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
    n_trivial: int | None = None,
    y_scale: float | None = None,
    integrals: Sequence[Callable[[np.ndarray], float] | sp.Expr] = (),
    hamiltonian: bool = False,
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
        of a conservative family: pin the amplitude).  See also ``integrals``.
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
        Number of multipliers expected at 1, used for :attr:`PeriodicOrbit.trivial_multiplier_error`.
        Default: derived from ``integrals`` and ``hamiltonian`` by
        :func:`~perturb.oracle.floquet.expected_trivial_multipliers` (1 for autonomy alone).
    y_scale : float, optional
        State scale of the relative residual; default ``max |y0_guess|`` (1 if that is zero).
    integrals : sequence of callable or sympy.Expr, optional
        First integrals ``g(y)`` held at their values at the guess (after the section is applied):
        they pin the member of a family of orbits, as the energy does for a conservative
        oscillator, without choosing which component to fix.  A sympy expression (in the state
        symbols of a :class:`SymbolicRHS`) gets its exact gradient, a callable centred differences.
        The relative defect ``|g(y0) - g(guess)| / s`` (``s`` the size of ``g`` or of its change
        over the state scale) is part of the residual.
    hamiltonian : bool, optional
        The system is Hamiltonian and ``integrals`` are in involution (energy included; it is
        implied if none is given): two trivial multipliers per integral instead of one.

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
    if isinstance(tol, bool) or not isinstance(tol, int | float | np.number):
        raise bad_value("tol", tol, "pass a positive tolerance such as 1e-12")
    if not (tol > 0 and math.isfinite(tol)):
        raise bad_value("tol", tol, "pass a positive tolerance such as 1e-12")
    if not isinstance(max_iter, int | np.integer) or max_iter < 1:
        raise bad_value("max_iter", max_iter, "pass an integer >= 1")
    if direction not in (-1, 0, 1):
        raise bad_value("direction", direction, "use +1, -1 or 0 (either direction)")
    if not isinstance(hamiltonian, bool | np.bool_):
        raise bad_value("hamiltonian", hamiltonian, "pass True or False")
    conditions = _integral_conditions(integrals, rhs, n)
    if n_trivial is None:
        n_trivial = expected_trivial_multipliers(len(conditions), bool(hamiltonian))
        if n_trivial > n:
            raise bad_value(
                "integrals",
                f"{len(conditions)} integrals",
                f"they imply {n_trivial} trivial multipliers for {n} state components; pass "
                "only independent ones, or `n_trivial`",
            )
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
    targets = []
    for k, condition in enumerate(conditions):
        value, gradient = condition.value(y0), condition.gradient(y0)
        size = max(abs(value), float(np.max(np.abs(gradient))) * scale)
        if not (math.isfinite(size) and size > 0):
            raise bad_value(
                "integrals",
                f"integral {k} = {value!r} with gradient {gradient!r} at the guess",
                "an integral must be finite and not stationary at the guess to pin a family",
            )
        targets.append((value, size))
    aug_rhs = variational_rhs(rhs, jac)
    solver = shooting_integrator(integrator, aug_rhs, n)
    period_map = _AutonomousMap(
        rhs, aug_rhs, solver, free, conditions, targets, scale, tol, max_iter
    )
    result = damped_newton(period_map, np.append(y0, float(period_guess)))
    y, period = result.x[:n], float(result.x[n])
    phi, residual, iterations, floor = (
        result.shot.monodromy,
        result.residual,
        result.iterations,
        result.floor,
    )
    rank_note = ""
    if result.rank is not None and result.rank < result.columns:
        rank_note = (
            f" The Newton matrix has rank {result.rank} < {result.columns} unknowns: the steps "
            "are the least-squares ones of minimum norm (what the matrix does not determine "
            "is left alone); if the orbit is a member of a family, pin it with "
            "`fixed_indices` or `integrals`."
        )

    def failed(status, message):
        matrix = np.full((n, n), np.nan) if phi is None else phi
        finite = bool(np.all(np.isfinite(matrix)))
        return PeriodicOrbit(
            n_trivial_expected=n_trivial,
            n_trivial_found=count_near_one(multipliers_of(matrix)) if finite else 0,
            period=period,
            initial_state=y,
            multipliers=multipliers_of(matrix) if finite else np.full(n, np.nan, dtype=complex),
            monodromy=matrix,
            residual=residual,
            iterations=iterations,
            status=status,
            message=message,
            integrator=solver.name,
            defect=result.shot.defect,
        )

    if result.outcome is NewtonOutcome.INTEGRATION_FAILED:
        traj = result.shot.trajectory
        return failed(
            OrbitStatus.INTEGRATION_FAILED,
            f"integration of the initial guess failed: {traj.message} (t = {traj.t_reached})",
        )
    if result.outcome is NewtonOutcome.MAX_ITER:
        return failed(
            OrbitStatus.MAX_ITER,
            f"no convergence in max_iter = {max_iter} Newton iterations: residual "
            f"{residual:.3e} > tol = {tol:.1e}; improve the guess or raise `max_iter`",
        )
    if result.outcome is NewtonOutcome.STALLED:
        return failed(
            OrbitStatus.STALLED,
            f"stalled after {iterations} iterations at residual {residual:.3e} > tol = "
            f"{tol:.1e}: no damped Newton step reduces it (relative step "
            f"{result.step_size:.1e}), and it is above {FLOOR_SAFETY:g} x the precision floor "
            f"{floor:.1e} measured there; improve the guess, or tighten the integrator."
            + rank_note,
        )
    if result.outcome is NewtonOutcome.STALLED_STEP:
        return failed(
            OrbitStatus.STALLED,
            f"stalled after {iterations} iterations at residual {residual:.3e} > tol = "
            f"{tol:.1e} and above {FLOOR_SAFETY:g} x the precision floor {floor:.1e}: the "
            f"Newton step is below {SHOOTING_STALL_STEP:g}." + rank_note,
        )

    multipliers = multipliers_of(phi)
    distances = np.sort(np.abs(multipliers - 1.0))
    trivial_error = float(distances[n_trivial - 1]) if n_trivial > 0 else 0.0
    n_found = count_near_one(multipliers)
    where = (
        f"residual {residual:.2e}"
        if residual <= tol
        else f"residual {residual:.2e} at the precision floor {floor:.1e} (> tol = {tol:.1e})"
    )
    status, message = (
        OrbitStatus.CONVERGED,
        f"converged in {iterations} iterations: {where}, period {float(period)!r}, "
        f"trivial multiplier error {trivial_error:.1e}; {n_found} multipliers within "
        f"{TRIVIAL_MULTIPLIER_TOL:g} of 1, {n_trivial} expected." + rank_note,
    )
    velocity = np.asarray(rhs(y), dtype=float)
    crossing = float(velocity[section])
    if float(np.max(np.abs(velocity))) * period <= EQUILIBRIUM_MOTION * scale:
        status = OrbitStatus.EQUILIBRIUM
        message = (
            f"converged onto an equilibrium (|f(y0)| * T = {np.max(np.abs(velocity)) * period:.1e}),"
            " not a periodic orbit; pin the amplitude with `fixed_indices` or the energy with "
            "`integrals`, or start closer to the orbit."
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
        multipliers=multipliers,
        monodromy=phi,
        residual=residual,
        iterations=iterations,
        status=status,
        message=message,
        trivial_multiplier_error=trivial_error,
        n_trivial_expected=n_trivial,
        n_trivial_found=n_found,
        integrator=solver.name,
        precision_floor=floor,
        defect=result.shot.defect,
    )
