"""Set-up of the measurements: the integrator, the shooting section, the arguments."""

from __future__ import annotations

import math

import numpy as np

from perturb._defaults import AMPLITUDE_FLOOR, SECTION_ZERO, SLOW_COMPONENT
from perturb.errors import bad_value
from perturb.oracle import Integrator, TrajectoryStatus, choose
from perturb.validation.model import Equations, Model, ShootingSetup

__all__ = ["amplitudes", "check_positive", "derived_shooting_setup", "integrator_for"]


def check_positive(name: str, value, fix: str) -> float:
    """``value`` as a finite float > 0, else the one-line error naming ``name``."""
    if isinstance(value, bool):
        raise bad_value(name, value, fix)
    try:
        number = float(value)
    except (TypeError, ValueError, OverflowError):
        raise bad_value(name, value, fix) from None
    if not (math.isfinite(number) and number > 0):
        raise bad_value(name, value, fix)
    return number


def integrator_for(
    integrator, rtol: float, stiff: bool, symbolic: bool, max_steps: int | None = None
) -> Integrator:
    """The integrator to run (:func:`perturb.oracle.choose`, the one rule for that choice)."""
    return choose(integrator, rtol=rtol, stiff=stiff, symbolic=symbolic, max_steps=max_steps)


def amplitudes(values: np.ndarray) -> np.ndarray:
    """Per-component max |value| (rows), floored at :data:`AMPLITUDE_FLOOR` of the largest."""
    amp = np.max(np.abs(values), axis=1) if values.size else np.zeros(values.shape[0])
    top = float(np.max(amp)) if amp.size else 0.0
    return np.maximum(amp, AMPLITUDE_FLOOR * top if top > 0 else 1.0)


def derived_shooting_setup(
    model: Model, equations: Equations, y0: np.ndarray, n_integrals: int, samples: np.ndarray
) -> ShootingSetup:
    """Section, pinned components and trivial multipliers when the model gives no set-up.

    On the quasilinear state the section is the phase coordinate's velocity and the coordinates
    with user-fixed amplitudes are pinned.  On a physical state the components that stay constant
    to :data:`SLOW_COMPONENT` along the analytic period (family parameters) are pinned, the section
    passes through the seed on the most transversal free component, and further components at their
    extremes are pinned until there is one pin per first integral.
    """
    scale = max(float(np.max(np.abs(y0))), 1.0)
    amp = amplitudes(samples)
    pinned: list[int] = []
    section = None
    if equations.quasilinear:
        system = model.system()
        n = system.n
        options = model.method_options()
        fixed = [str(k) for k in options.get("amplitudes", {})]
        coords = [c.name for c in system.coordinates]
        phase = options.get("phase_coordinate") or (fixed[0] if len(fixed) == 1 else coords[0])
        section = n + coords.index(phase)
        pinned = [coords.index(a) for a in fixed if a in coords]
        n_trivial = 1 + max(len(pinned), n_integrals)
    else:
        spread = (np.max(samples, axis=1) - np.min(samples, axis=1)) / amp
        pinned = [i for i in range(len(y0)) if spread[i] < SLOW_COMPONENT]
        n_trivial = 1 + n_integrals
    velocity = np.asarray(equations.rhs(y0), dtype=float)
    section_value = 0.0
    if section is None or abs(y0[section]) > SECTION_ZERO * scale:
        # a section through the seed itself, on the most transversal free component: moving the
        # seed onto some "zero" section would break the first integrals it satisfies
        candidates = [i for i in range(len(y0)) if i not in pinned]
        section = max(candidates, key=lambda i: abs(velocity[i]) / amp[i])
        section_value = float(y0[section])
        if not equations.quasilinear:
            extra = sorted(
                (i for i in candidates if i != section), key=lambda i: -abs(y0[i]) / amp[i]
            )
            pinned += extra[: max(0, n_integrals - len(pinned))]
    crossing = float(velocity[section])
    direction = int(np.sign(crossing)) if abs(crossing) > SECTION_ZERO * amp[section] else 0
    return ShootingSetup(
        section_index=section,
        section_value=section_value,
        fixed_indices=tuple(sorted(pinned)),
        direction=direction,
        n_trivial=min(n_trivial, len(y0)),
    )


def cut_by_budget(traj) -> bool:
    """Whether ``traj`` stopped on its step budget (a deliberate cut, not a numerical failure)."""
    return traj.status is TrajectoryStatus.MAX_STEPS
