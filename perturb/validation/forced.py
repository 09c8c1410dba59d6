"""The measurements of a driven model: its forced orbit, and its stability against Floquet's.

A driven model's true response is found by shooting with the period **given**
(:func:`perturb.oracle.find_forced_orbit`: no section, no trivial multiplier). Its period error is
zero by construction, so the verdict's fourth measurement is instead **stability**: the analytic
stability of the branch (the Floquet multipliers along the order-N orbit,
:mod:`perturb.steady.floquet`) against the true orbit's Floquet multipliers (stable when all lie inside the unit circle).
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from perturb._defaults import (
    ORBIT_RESOLUTION_LIMIT,
    SHOOTING_ITERATIONS,
    SHOOTING_TOL,
    STIFF_SHOOTING_TOL,
)
from perturb.errors import PerturbError
from perturb.oracle import find_forced_orbit
from perturb.validation.model import Equations, Model
from perturb.validation.orbit import errors_against_orbit
from perturb.validation.report import Check, OrbitCheck

__all__ = ["analytic_stability", "forced_orbit_check", "stability_check"]


def forced_orbit_check(
    model: Model, solution, equations: Equations, y0, period: float, integrator, rtol, stiff
) -> OrbitCheck:
    """Shoot for the driven model's response (period given), seeded by the analytic one.

    The resolution is the residual over the smallest singular value of the Newton matrix
    :math:`\\Phi(T) - I` (how far the state can move for that residual).
    """
    names = model.state_names()
    state_y0 = np.asarray(y0, dtype=float)[:-1]  # theta(0) = 0 is fixed by the forcing
    try:
        orbit = find_forced_orbit(
            equations.rhs, state_y0, period, max_iter=SHOOTING_ITERATIONS,
            tol=STIFF_SHOOTING_TOL if stiff else SHOOTING_TOL,
        )  # fmt: skip
    except PerturbError as exc:
        return _failed(names, f"the forced shooting refused its seed: {exc}")
    if not orbit.success:
        return _failed(names, orbit.message, orbit.status, orbit.integrator)
    true_y0 = np.append(orbit.initial_state, 0.0)
    init_error, orbit_error = errors_against_orbit(
        model, solution, equations, np.asarray(y0, dtype=float), period, true_y0, period,
        integrator, rtol, stiff,
    )  # fmt: skip
    newton = np.asarray(orbit.monodromy) - np.eye(len(orbit.initial_state))
    smallest = float(np.min(np.linalg.svd(newton, compute_uv=False)))
    resolution = math.inf if smallest == 0 else max(orbit.residual, 1e-16) / smallest
    return OrbitCheck(
        success=True,
        period=period,
        initial_state=dict(zip(names, map(float, true_y0), strict=True)),
        floquet=tuple(complex(z) for z in orbit.multipliers),
        n_trivial=0,
        trivial_multiplier_error=0.0,
        trivial_ok=True,
        period_error=0.0,
        initial_state_error=init_error,
        orbit_error=orbit_error,
        message=orbit.message,
        status=orbit.status,
        integrator=orbit.integrator,
        resolution=resolution,
        resolution_limit=ORBIT_RESOLUTION_LIMIT,
    )


def _failed(names, message, status=None, integrator="") -> OrbitCheck:
    nan = math.nan
    return OrbitCheck(
        success=False, period=nan, initial_state={n: nan for n in names}, floquet=(),
        n_trivial=0, trivial_multiplier_error=nan, trivial_ok=False, period_error=nan,
        initial_state_error=nan, orbit_error=nan, message=message, status=status,
        integrator=integrator, resolution=nan, resolution_limit=ORBIT_RESOLUTION_LIMIT,
    )  # fmt: skip


def analytic_stability(model: Model, solution) -> bool | None:
    """The analytic verdict on ``solution``'s branch: the Floquet multipliers of the variational
    equation along the order-N orbit (:mod:`perturb.steady.floquet`, the response's own)."""
    from perturb.method.driven import amplitude_equations
    from perturb.steady.evaluate import PointEvaluator
    from perturb.steady.line import line_of_values

    system = model.system()
    equations = amplitude_equations(system, max(int(solution.order), 1))
    generating = solution.generating
    u = []
    for name in equations.coordinates:
        i = generating.coordinates.index(name)
        u += [float(sp.sympify(generating.cos_amplitudes[i])),
              float(sp.sympify(generating.sin_amplitudes[i]))]  # fmt: skip
    values = model.symbol_values()
    names = [p.name for p in system.parameters]
    swept = names[0] if names else None
    if swept is None:
        return None
    line = line_of_values(names, values, float(model.epsilon()), swept)
    at = PointEvaluator(equations, line).evaluate([u], [float(values[swept])], check_lower=False)
    return at["stability"].stable[0]


def stability_check(orbit: OrbitCheck | None, analytic: bool | None, why_missing: str) -> Check:
    """The analytic stability against the true orbit's Floquet multipliers."""
    if orbit is None or not orbit.success:
        return Check("stability", math.nan, 1.0, None, why_missing)
    largest = max((abs(z) for z in orbit.floquet), default=math.nan)
    true_stable = largest < 1.0
    if analytic is None:
        return Check(
            "stability", largest, 1.0, None,
            f"the order-N multipliers are marginal here (a fold or no damping); the true orbit's "
            f"largest "
            f"|Floquet multiplier| is {largest:.6g}",
        )  # fmt: skip
    agree = analytic == true_stable
    words = {True: "stable", False: "unstable"}
    return Check(
        "stability",
        largest,
        1.0,
        agree,
        f"the order-N Floquet multipliers say {words[analytic]}, the true orbit's largest "
        f"|Floquet multiplier| "
        f"{largest:.6g} says {words[true_stable]}" + ("" if agree else ": they disagree"),
    )
