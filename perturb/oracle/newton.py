"""The one Newton loop of the shooting: damped steps down to the precision floor.

Both shooters — the autonomous one (:func:`perturb.oracle.find_periodic_orbit`: the period among
the unknowns, a section, pinned integrals) and the driven one
(:func:`perturb.oracle.find_forced_orbit`: the period given) — solve "the period map returns the
state" by the same iteration, written here once. A shooter is a :class:`PeriodMap`: its unknowns
``x``, a shot over one period (:class:`Shot`), the residual, the Newton system and how a step
moves ``x``. :func:`damped_newton` then

1. shoots from ``x0``, and stops when the residual is below ``max(tol, floor)``, where the floor
   is the smallest residual the working precision can show (:func:`precision_floor`);
2. takes the least-squares Newton step, halving it until the residual falls (a line search);
3. when no step helps, measures the integration noise (the same shot with a loosened
   integrator) and, unless the residual is already at that floor, retries with a step that leaves
   out the directions whose target is within the noise;
4. reports a status whose value is the message: converged, at most ``max_iter`` iterations,
   stalled (no step helps, or the step is below :data:`SHOOTING_STALL_STEP`), or the first
   integration failed.
"""

from __future__ import annotations

import enum
import math
from abc import ABC, abstractmethod

import numpy as np
from attrs import frozen

from perturb._defaults import (
    FLOOR_SAFETY,
    NOISE_PROBE_FACTOR,
    ROUNDING_ULPS,
    SHOOTING_MAX_HALVINGS,
    SHOOTING_RANK_RTOL,
    SHOOTING_STALL_STEP,
)
from perturb.oracle._noise import solve_noise

__all__ = [
    "NewtonOutcome",
    "NewtonResult",
    "PeriodMap",
    "Shot",
    "damped_newton",
    "defect_noise",
    "newton_step",
    "precision_floor",
]


@frozen(eq=False)
class Shot:
    """One shot over a period: the trajectory, ``y(T) - y(0)``, the monodromy and ``f(y(T))``
    (``defect`` None when the integration failed)."""

    trajectory: object
    defect: np.ndarray | None
    monodromy: np.ndarray | None
    velocity: np.ndarray | None = None


class NewtonOutcome(enum.Enum):
    """How the loop ended (the shooter words its message)."""

    CONVERGED = "converged"
    MAX_ITER = "max_iter"
    STALLED = "stalled"
    STALLED_STEP = "stalled: step below the floor"
    INTEGRATION_FAILED = "integration of the initial guess failed"


@frozen(eq=False)
class NewtonResult:
    """The end of :func:`damped_newton`: the outcome, the last iterate and its shot."""

    outcome: NewtonOutcome
    x: np.ndarray
    shot: Shot
    residual: float
    iterations: int
    floor: float
    step_size: float = math.nan
    rank: int | None = None
    columns: int | None = None


class PeriodMap(ABC):
    """A shooter as the Newton loop sees it (see the module docstring).

    Attributes a subclass sets: ``tol``, ``max_iter``, ``scale`` (the state's size, for relative
    residuals) and ``solver`` (the integrator, :meth:`loosened` for the noise probe).
    """

    tol: float
    max_iter: int
    scale: float
    solver: object

    @abstractmethod
    def shoot(self, x: np.ndarray, integrator=None) -> Shot:
        """State and variational equations over one period from the unknowns ``x``."""

    @abstractmethod
    def state(self, x: np.ndarray) -> np.ndarray:
        """The initial state held by ``x`` (what the precision floor is measured on)."""

    @abstractmethod
    def residual(self, x: np.ndarray, shot: Shot) -> float:
        """The relative defect of the shot (and of any pinned condition)."""

    @abstractmethod
    def linearised(self, x: np.ndarray, shot: Shot) -> tuple[np.ndarray, np.ndarray]:
        """The Newton matrix and target at ``x``."""

    @abstractmethod
    def moved(self, x: np.ndarray, step: np.ndarray, lam: float) -> np.ndarray | None:
        """``x`` moved by ``lam * step`` (None where that leaves the admissible set)."""

    def step_size(self, x: np.ndarray, step: np.ndarray) -> float:
        """The relative size of a Newton step (compared with :data:`SHOOTING_STALL_STEP`)."""
        return float(np.max(np.abs(step), initial=0.0)) / self.scale


def defect_noise(y_start, defect, noise=None) -> np.ndarray:
    """The absolute noise of each component of the defect ``y(T) - y(0)``.

    Both states are float64 numbers however precisely they were integrated, so each component of
    the difference carries :data:`ROUNDING_ULPS` of their spacing, plus the integration error
    ``noise`` when it was measured (:func:`integration_noise`, absolute).
    """
    size = np.maximum(np.abs(y_start), np.abs(y_start + defect))
    rounding = ROUNDING_ULPS * np.spacing(size)
    return rounding if noise is None else rounding + noise


def precision_floor(y_start, defect, scale: float, tol: float, noise=None) -> float:
    """The smallest residual the working precision can show at ``y_start``, relative to ``scale``.

    The largest :func:`defect_noise` among the components whose defect is still above ``tol``: a
    large component that returns exactly (a constant, a pinned coordinate) limits nothing. Far
    below ``tol`` for states of the size of ``scale``; not for a conditioned state whose origin is
    off the orbit (``|u| >> 1``).
    """
    floor = defect_noise(y_start, defect, noise) / scale
    limiting = np.abs(defect) / scale > tol
    return float(np.max(floor[limiting], initial=0.0))


def integration_noise(problem: PeriodMap, x, defect):
    """The integration error of each component of the defect at ``x`` (absolute).

    The same shot with an integrator whose error is :data:`NOISE_PROBE_FACTOR` times larger
    (:meth:`~perturb.oracle.base.IntegratorBase.loosened`) differs by about ``factor - 1`` times
    this integrator's error (both errors are proportional to the tolerance). None when the
    integrator cannot be loosened or the probe fails: the floor is then round-off alone.
    """
    # an Integrator given by the user need not derive from IntegratorBase: no loosened() then
    loosen = getattr(problem.solver, "loosened", None)
    probe = loosen(NOISE_PROBE_FACTOR) if loosen is not None else None
    if probe is None:
        return None
    probe_defect = problem.shoot(x, probe).defect
    if probe_defect is None or not np.all(np.isfinite(probe_defect)):
        return None
    return np.abs(probe_defect - defect) / (NOISE_PROBE_FACTOR - 1.0)


def newton_step(newton: np.ndarray, target: np.ndarray, noise=None):
    """The least-squares Newton step and the rank of the Newton matrix.

    Without ``noise``: the minimum-norm least-squares step (singular values below
    :data:`SHOOTING_RANK_RTOL` of the largest cut). With ``noise`` (the absolute noise of each row of
    ``target``), a truncated-SVD step that also leaves out every direction whose component of the
    target is within the noise (a discrepancy rule): near a rank-deficient matrix those directions
    carry only noise, amplified by a small singular value, and a step along them wrecks the
    directions that can still converge.
    """
    if noise is None:
        step, _, rank, _ = np.linalg.lstsq(newton, target, rcond=SHOOTING_RANK_RTOL)
        return solve_noise(step, newton, target), int(rank)
    u, sv, vt = np.linalg.svd(newton, full_matrices=False)
    components = u.T @ target
    kept = sv > SHOOTING_RANK_RTOL * sv[0]
    keep = kept & (np.abs(components) > float(np.linalg.norm(noise)))
    step = vt[keep].T @ (components[keep] / sv[keep])
    return solve_noise(step, newton, target), int(np.count_nonzero(kept))


def damped_newton(problem: PeriodMap, x0: np.ndarray) -> NewtonResult:
    """The damped Newton iteration of ``problem`` from ``x0`` (see the module docstring)."""
    x = np.array(x0, dtype=float)
    shot = problem.shoot(x)
    if shot.defect is None:
        return NewtonResult(NewtonOutcome.INTEGRATION_FAILED, x, shot, math.inf, 0, math.inf)
    residual = problem.residual(x, shot)
    floor = precision_floor(problem.state(x), shot.defect, problem.scale, problem.tol)
    iterations, rank, columns = 0, None, None
    measured = None  # the integration noise, once measured at the current point

    def at_floor() -> bool:
        """Whether the residual is at the precision floor, measured now that Newton stopped."""
        nonlocal floor, measured
        measured = integration_noise(problem, x, shot.defect)
        floor = precision_floor(problem.state(x), shot.defect, problem.scale, problem.tol, measured)
        return residual <= FLOOR_SAFETY * floor

    def line_search(step):
        """The first damped step that reduces the residual: (x, shot, residual) or None."""
        lam = 1.0
        for _ in range(SHOOTING_MAX_HALVINGS + 1):
            x_try = problem.moved(x, step, lam)
            if x_try is not None:
                trial = problem.shoot(x_try)
                if trial.defect is not None:
                    residual_try = problem.residual(x_try, trial)
                    if residual_try < residual:
                        return x_try, trial, residual_try
            lam *= 0.5
        return None

    def ended(outcome, step_size=math.nan) -> NewtonResult:
        return NewtonResult(outcome, x, shot, residual, iterations, floor, step_size, rank, columns)

    while residual > max(problem.tol, floor):
        if iterations >= problem.max_iter:
            if at_floor():
                break
            return ended(NewtonOutcome.MAX_ITER)
        iterations += 1
        matrix, target = problem.linearised(x, shot)
        step, rank = newton_step(matrix, target)
        columns = matrix.shape[1]
        found = line_search(step)
        if found is None and not at_floor():
            # near the floor, the directions whose target is within the noise carry only noise:
            # a step along them (amplified by a small singular value) wrecks the others
            rows = defect_noise(problem.state(x), shot.defect, measured)
            noise = np.concatenate((rows, np.zeros(len(target) - len(rows))))
            step, _ = newton_step(matrix, target, noise)
            found = line_search(step)
        step_size = problem.step_size(x, step)
        if found is None:
            if residual <= FLOOR_SAFETY * floor:  # at_floor() measured it above
                break
            return ended(NewtonOutcome.STALLED, step_size)
        x, shot, residual = found
        floor = precision_floor(problem.state(x), shot.defect, problem.scale, problem.tol)
        if step_size < SHOOTING_STALL_STEP and residual > max(problem.tol, floor):
            if at_floor():
                break
            return ended(NewtonOutcome.STALLED_STEP, step_size)
    return ended(NewtonOutcome.CONVERGED)
