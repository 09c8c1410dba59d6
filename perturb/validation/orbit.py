"""Existence and accuracy: the true periodic orbit near the analytic one, and the distance between
them at equal phase over one period."""

from __future__ import annotations

import math

import numpy as np

from perturb._defaults import (
    FLOQUET_TOL,
    MULTIPLIER_FLOOR,
    ORBIT_RESOLUTION_LIMIT,
    SAMPLES_PER_PERIOD,
    SHOOTING_ITERATIONS,
    SHOOTING_PRECISION,
    SHOOTING_TOL,
    STIFF_SHOOTING_RTOL,
    STIFF_SHOOTING_TOL,
)
from perturb.errors import PerturbError
from perturb.oracle import PeriodicOrbit, Scipy, find_periodic_orbit
from perturb.validation.capabilities import own_true_orbit
from perturb.validation.checks import analytic_states, component_errors
from perturb.validation.model import Equations, Model, ShootingSetup
from perturb.validation.report import OrbitCheck
from perturb.validation.setup import amplitudes, integrator_for

__all__ = ["orbit_check", "with_model_true_orbit"]


def _failed(setup: ShootingSetup, names, message: str, status=None, **found) -> OrbitCheck:
    nan = math.nan
    return OrbitCheck(
        success=False,
        period=found.get("period", nan),
        initial_state=found.get("initial_state", {}),
        floquet=found.get("floquet", ()),
        n_trivial=setup.n_trivial,
        trivial_multiplier_error=found.get("trivial_multiplier_error", nan),
        trivial_ok=False,
        period_error=nan,
        initial_state_error=nan,
        orbit_error=nan,
        message=message,
        status=status,
        integrator=found.get("integrator", ""),
        resolution_limit=ORBIT_RESOLUTION_LIMIT,
    )


def orbit_check(
    model: Model,
    solution,
    equations: Equations,
    y0: np.ndarray,
    period: float,
    setup: ShootingSetup,
    integrator,
    rtol: float,
    stiff: bool,
    max_steps: int | None,
) -> OrbitCheck:
    """Shoot for the true orbit seeded by the analytic one, and measure the analytic orbit's error.

    The shooting pins ``setup.fixed_indices`` (one per family parameter), expects
    ``setup.n_trivial`` multipliers at 1 and estimates its own resolution: the periodicity defect
    over the distance of the first non-trivial multiplier from 1.
    """
    names = model.state_names()
    shooter = setup.integrator
    if shooter is None and stiff:
        shooter = Scipy("Radau", rtol=STIFF_SHOOTING_RTOL)
    elif shooter is None and max_steps is not None:
        shooter = integrator_for(None, rtol, False, equations.symbolic, max_steps)
    try:
        orbit = find_periodic_orbit(
            equations.rhs,
            y0,
            period,
            section_index=setup.section_index,
            section_value=setup.section_value,
            fixed_indices=setup.fixed_indices,
            direction=setup.direction,
            n_trivial=setup.n_trivial,
            max_iter=SHOOTING_ITERATIONS,
            integrator=shooter,
            tol=STIFF_SHOOTING_TOL if stiff else SHOOTING_TOL,
        )
    except PerturbError as exc:  # the seed itself was refused: reported, not raised
        return _failed(setup, names, f"the shooting refused its seed: {exc}")
    found = dict(
        period=orbit.period,
        initial_state=dict(zip(names, map(float, orbit.initial_state), strict=True)),
        floquet=tuple(complex(z) for z in orbit.multipliers),
        trivial_multiplier_error=orbit.trivial_multiplier_error,
        integrator=orbit.integrator,
    )
    if not orbit.success:
        return _failed(setup, names, orbit.message, orbit.status, **found)
    init_error, orbit_error = errors_against_orbit(
        model, solution, equations, y0, period, orbit.initial_state, orbit.period, integrator, rtol,
        stiff,
    )  # fmt: skip
    multipliers = list(orbit.multipliers)
    n_trivial = setup.n_trivial
    gap = abs(complex(multipliers[n_trivial]) - 1) if len(multipliers) > n_trivial else 1.0
    defect = max(float(orbit.residual), SHOOTING_PRECISION)
    # below MULTIPLIER_FLOOR the gap itself is round-off: the orbit cannot be certified at all
    resolution = math.inf if gap < MULTIPLIER_FLOOR else defect / gap
    message = orbit.message
    if resolution > ORBIT_RESOLUTION_LIMIT:
        message += (
            f" Not resolved: the first non-trivial Floquet multiplier is {gap:.1e} from 1 (floor "
            f"{MULTIPLIER_FLOOR:g}), so a periodicity defect of {defect:.1e} leaves the orbit "
            f"uncertain by ~{resolution:.1e} of its amplitude."
        )
    return OrbitCheck(
        success=True,
        period=orbit.period,
        initial_state=found["initial_state"],
        floquet=found["floquet"],
        n_trivial=n_trivial,
        trivial_multiplier_error=orbit.trivial_multiplier_error,
        trivial_ok=orbit.trivial_multiplier_error <= FLOQUET_TOL,
        period_error=(period - orbit.period) / orbit.period,
        initial_state_error=init_error,
        orbit_error=orbit_error,
        message=message,
        status=orbit.status,
        integrator=orbit.integrator,
        resolution=resolution,
        resolution_limit=ORBIT_RESOLUTION_LIMIT,
    )


def errors_against_orbit(
    model, solution, equations, y0, period, true_y0, true_period, integrator, rtol, stiff
) -> tuple[float, float]:
    """(initial-state error, orbit error) of the analytic solution against a true periodic orbit.

    Both orbits are sampled at the same phases of their own periods, from their own states on the
    common section; each component's error is relative to its amplitude on the true orbit.
    """
    names = model.state_names()
    true_y0 = np.asarray(true_y0, dtype=float)
    phases = np.linspace(0.0, 1.0, SAMPLES_PER_PERIOD + 1)
    analytic = analytic_states(model, solution, phases * period)
    solver = integrator_for(integrator, rtol, stiff, equations.symbolic)
    traj = solver.integrate(equations.rhs, (0.0, true_period), true_y0, t_eval=phases * true_period)
    if traj.success:
        true = np.asarray(traj.y, dtype=float)
        _, _, orbit_error = component_errors(names, analytic, true)
        amp = amplitudes(true)
    else:
        orbit_error, amp = math.nan, amplitudes(analytic)
    return float(np.max(np.abs(y0 - true_y0) / amp)), orbit_error


def with_model_true_orbit(
    model: Model, solution, equations, y0, period, unresolved: OrbitCheck, integrator, rtol, stiff
) -> OrbitCheck:
    """The model's own true orbit (:class:`~perturb.validation.capabilities.OwnTrueOrbit`) in
    place of an unresolved shooting.

    Asked for only when the double-precision shooting converged but could not resolve the orbit
    (the model's method, e.g. the disk's conditioned extended-precision shooting, is dearer and
    specific).  If the model has none, or it fails (e.g. no extended precision available), the
    unresolved check is kept with the reason appended.
    """
    try:
        true: PeriodicOrbit | None = own_true_orbit(model, solution)
    except PerturbError as exc:
        return _append(unresolved, f"The model's own true-orbit finder failed: {exc}")
    if true is None:
        return _append(unresolved, "The model offers no true-orbit finder of its own.")
    if not true.success:
        return _append(
            unresolved, f"The model's own true-orbit finder did not run or failed: {true.message}"
        )
    init_error, orbit_error = errors_against_orbit(
        model, solution, equations, y0, period, true.initial_state, true.period, integrator, rtol,
        stiff,
    )  # fmt: skip
    n_trivial = unresolved.n_trivial if true.n_trivial_expected is None else true.n_trivial_expected
    return OrbitCheck(
        success=True,
        period=true.period,
        initial_state=dict(zip(model.state_names(), map(float, true.initial_state), strict=True)),
        floquet=tuple(complex(z) for z in true.multipliers),
        n_trivial=n_trivial,
        trivial_multiplier_error=true.trivial_multiplier_error,
        trivial_ok=true.trivial_multiplier_error <= FLOQUET_TOL,
        period_error=(period - true.period) / true.period,
        initial_state_error=init_error,
        orbit_error=orbit_error,
        message=(
            f"Double-precision shooting could not resolve the orbit (resolution "
            f"{unresolved.resolution:.1e}); the problem's own true-orbit finder ran instead: "
            f"{true.message}"
        ),
        status=unresolved.status,
        integrator=true.integrator,
        resolution=true.resolution,
        resolution_limit=ORBIT_RESOLUTION_LIMIT,
    )


def _append(check: OrbitCheck, sentence: str) -> OrbitCheck:
    from attrs import evolve

    return evolve(check, message=f"{check.message} {sentence}")
