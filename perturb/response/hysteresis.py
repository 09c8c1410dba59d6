"""Slow up- and down-sweeps of the excitation frequency through the true motion: the jumps.

A driven system's response is multivalued between its folds; a slow sweep follows one branch
until it ends at a fold and then jumps to another. :func:`slow_sweep` integrates the original
equations with the phase :math:`\\theta' = \\Omega(t)` and :math:`\\Omega(t)` ramped linearly
(:math:`\\Omega' = \\pm r`), records the response's envelope (the largest |x| over each forcing
period) against Ω, and locates the jump: the largest change of the envelope between neighbouring
periods. Up and down sweeps give the two jump frequencies, which the analytic folds predict
(a finite rate delays a jump by :math:`O(r^{2/3})`: choose r small).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import sympy as sp
from attrs import field, frozen

from perturb._defaults import JUMP_WINDOW, SAMPLES_PER_FORCING_PERIOD, SETTLE_PERIODS
from perturb.errors import InvalidParameterError, bad_value
from perturb.oracle import SymbolicRHS, choose

__all__ = ["SweepRun", "slow_sweep"]


@frozen
class SweepRun:
    """One slow sweep of Ω through the true motion.

    Attributes
    ----------
    direction : str
        ``"up"`` or ``"down"``.
    omega : ndarray
        Ω at the end of each forcing period.
    envelope : ndarray
        max ``|x|`` over that forcing period.
    jump : float
        Ω where the envelope changes most from one period to the next.
    jump_size : float
        That change (positive: a jump up).
    """

    direction: str
    omega: np.ndarray = field(eq=False)
    envelope: np.ndarray = field(eq=False)
    jump: float
    jump_size: float


def slow_sweep(
    system,
    values: Mapping[str, float],
    epsilon: float,
    omega_start: float,
    omega_stop: float,
    rate: float,
    coordinate: str | None = None,
    start=None,
) -> SweepRun:
    """Integrate the driven ``system`` while Ω moves from ``omega_start`` to ``omega_stop``.

    Parameters
    ----------
    system : QuasilinearSystem
        Driven (``excitation`` set); its detuning is replaced by the ramp.
    values : mapping
        Values of its other parameters.
    epsilon : float
    omega_start, omega_stop : float
        The sweep (up when stop > start).
    rate : float
        |dΩ/dt| (> 0).
    coordinate : str, optional
        Whose envelope (default: the reference coordinate).
    start : array_like, optional
        Initial state (x, xdot); default at rest.

    Returns
    -------
    SweepRun
    """
    system.frame.require_driven("system", system.name, "give a driven system")
    if not (rate > 0 and math.isfinite(rate)):
        raise bad_value("rate", rate, "give a positive sweep rate", InvalidParameterError)
    if not (omega_start > 0 and omega_stop > 0 and omega_start != omega_stop):
        raise bad_value(
            "omega_stop", omega_stop, "give two different positive frequencies",
            InvalidParameterError,
        )  # fmt: skip
    drive = system.excitation
    omega = sp.Symbol("Omega_sweep")
    subs = {
        p: values[p.name] for p in system.parameters if p.name in values and p != drive.detuning
    }
    subs[system.parameter] = epsilon if system.regime.value == "small" else 1 / epsilon
    n = system.n
    state = system.state_symbols
    forces = [sp.sympify(f).subs(subs) for f in system.rhs]
    w2 = [sp.sympify(w**2).subs(subs) for w in system.frequencies]
    sign = 1.0 if omega_stop > omega_start else -1.0
    exprs = list(state[n:]) + [forces[i] - w2[i] * state[i] for i in range(n)]
    # settle at the start frequency, then ramp: Omega' = sign * rate
    rhs = SymbolicRHS((*state, drive.phase, omega), (*exprs, omega, sp.Float(sign * rate)))
    settle = SymbolicRHS((*state, drive.phase, omega), (*exprs, omega, sp.Integer(0)))
    solver = choose(None, rtol=1e-10, symbolic=True)
    y0 = np.zeros(2 * n) if start is None else np.asarray(start, dtype=float)
    period0 = 2 * math.pi / omega_start
    settled = solver.integrate(
        settle, (0.0, SETTLE_PERIODS * period0), np.concatenate((y0, [0.0, omega_start]))
    )
    settled.raise_for_status()
    duration = abs(omega_stop - omega_start) / rate
    mean_period = 4 * math.pi / (omega_start + omega_stop)
    periods = int(math.ceil(duration / mean_period))
    t = np.linspace(0.0, duration, periods * SAMPLES_PER_FORCING_PERIOD + 1)
    traj = solver.integrate(rhs, (0.0, duration), settled.y_final, t_eval=t)
    traj.raise_for_status()
    names = [c.name for c in system.coordinates]
    index = names.index(coordinate) if coordinate else system.reference_index
    x = np.abs(np.asarray(traj.y[index], dtype=float))
    w = np.asarray(traj.y[-1], dtype=float)
    blocks = len(x) // SAMPLES_PER_FORCING_PERIOD
    envelope = np.array(
        [
            x[k * SAMPLES_PER_FORCING_PERIOD : (k + 1) * SAMPLES_PER_FORCING_PERIOD].max()
            for k in range(blocks)
        ]
    )
    omegas = np.array(
        [w[min((k + 1) * SAMPLES_PER_FORCING_PERIOD, len(w) - 1)] for k in range(blocks)]
    )
    # the jump: the largest change over a window of periods (the response settles on the new
    # branch over many periods), placed where the envelope first crosses its midpoint
    window = max(1, int(JUMP_WINDOW * blocks))
    change = envelope[window:] - envelope[:-window]
    k = int(np.argmax(np.abs(change)))
    before, after = envelope[k], envelope[k + window]
    middle = 0.5 * (before + after)
    crossing = k + int(
        np.argmax((envelope[k : k + window + 1] - middle) * np.sign(before - middle) <= 0)
    )
    return SweepRun(
        direction="up" if sign > 0 else "down",
        omega=omegas,
        envelope=envelope,
        jump=float(omegas[crossing]),
        jump_size=float(after - before),
    )
