"""A slow ramp of the drive frequency through the true motion: the jumps beside the folds.

:func:`ramp` moves a parameter of a driven problem that sets its drive frequency (Ω itself, or
the detuning) linearly in time between two values, at one or more rates, and integrates the
original equations with the phase :math:`\\theta = \\int \\Omega(t)\\,dt`
(:func:`perturb.response.hysteresis.slow_sweep`, settled first at the start value). Each run's
jump — where its envelope changes most, up or down — is set beside the fold of the order-N
response curve (:func:`perturb.response.model.problem_response`) at which the branch followed
ends: the last fold passed in the ramp's direction. A finite rate delays the jump past the fold
(by :math:`O(r^{2/3})` for a saddle-node); as the rate goes to zero the jump tends to the fold.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from attrs import field, frozen

from perturb._defaults import (
    DYNAMICS_PERIOD_SECONDS,
    RAMP_JUMP_PERIODS,
    RAMP_JUMP_SHARE,
    RAMP_MAX_PERIODS,
    SETTLE_PERIODS,
)
from perturb.errors import InvalidParameterError, bad_value
from perturb.validation.capabilities import label_of

__all__ = ["Ramp", "RampRun", "ramp"]

#: Values of the response curve computed between the ramp's ends for its folds.
FOLD_GRID = 81


@frozen
class RampRun:
    """One ramp at one rate.

    Attributes
    ----------
    direction : str
        ``"up"`` or ``"down"``.
    rate : float
        The absolute rate of change of the parameter, per unit of time.
    values : ndarray
        The parameter at the end of each drive period.
    envelope : ndarray
        The largest ``|x|`` over that drive period.
    jump : float
        The parameter's value at the jump.
    jump_size : float
        The envelope's change there (positive: a jump up).
    fold : float
        The fold the branch ends at (NaN: none on the ramp's side of the jump).
    delay : float
        ``jump - fold`` in the ramp's direction (positive: the jump comes after the fold).
    """

    direction: str
    rate: float
    values: np.ndarray = field(eq=False)
    envelope: np.ndarray = field(eq=False)
    jump: float
    jump_size: float
    fold: float
    delay: float


@frozen
class Ramp:
    """Ramps of a driven problem's drive frequency, up (and down), at one or more rates.

    Attributes
    ----------
    problem : str
    parameter : str
    start, stop : float
    order : int
        The response curve's order (its folds).
    folds : tuple of float
        The folds of the response curve between the ends (in the parameter).
    runs : tuple of RampRun
        By direction, then by rate (fastest first).
    coordinate : str
        Whose envelope.
    """

    problem: str
    parameter: str
    start: float
    stop: float
    order: int
    folds: tuple = field(converter=tuple)
    runs: tuple = field(converter=tuple)
    coordinate: str


def _rates(rate) -> tuple[float, ...]:
    values = [rate] if isinstance(rate, int | float) else list(rate)
    out = []
    for r in values:
        try:
            r = float(r)
        except (TypeError, ValueError):
            raise bad_value("rate", rate, "give a rate > 0", InvalidParameterError) from None
        if not (math.isfinite(r) and r > 0):
            raise bad_value("rate", r, "give a finite rate > 0 (the parameter's change per unit "
                            "of time), e.g. --rate 1e-4", InvalidParameterError)  # fmt: skip
        out.append(r)
    if not out:
        raise bad_value("rate", rate, "give at least one rate > 0", InvalidParameterError)
    return tuple(sorted(set(out), reverse=True))


def ramp(
    problem,
    parameter: str,
    start: float,
    stop: float,
    rate: float | Sequence[float],
    *,
    both_ways: bool = False,
    order: int = 1,
    coordinate: str | None = None,
    yes: bool = False,
) -> Ramp:
    """Ramp ``parameter`` of the driven ``problem`` from ``start`` to ``stop`` (see the module
    notes).

    Parameters
    ----------
    problem : problems.base.Problem
        A driven problem; its other parameters at their values.
    parameter : str
        A parameter that moves the drive frequency and nothing else (``Omega``, ``sigma``).
    start, stop : float
        The ramp's ends (up when stop > start).
    rate : float or sequence of float
        The absolute rate of change of the parameter per unit of time (> 0); several give
        the delay against the rate.
    both_ways : bool
        Also ramp back from ``stop`` to ``start``.
    order : int
        The response curve's order for the folds.
    coordinate : str, optional
        Whose envelope (default: the reference coordinate).
    yes : bool
        Confirm ramps past :func:`perturb.cost.check_cost`'s hour of work.

    Returns
    -------
    Ramp
        The response curve's folds between the ends, and each run (direction, rate) with its
        jump, the fold it left and the delay.

    Raises
    ------
    InvalidParameterError
        A rate of zero, a ramp that does not move (the same ends, or a parameter that does not
        move the drive frequency, or moves more than it), a problem that is not driven.

    Examples
    --------
    Up through the hysteresis band of a forced Duffing: the jump down comes just after the fold.

    >>> import perturb
    >>> from problems import get_problem
    >>> duffing = get_problem("forced-duffing").create(eps=0.02, F=0.5)
    >>> up = perturb.ramp(duffing, "Omega", 0.99, 1.06, 5e-6).runs[0]
    >>> round(up.fold, 4), 0 < up.delay < 0.005
    (1.0424, True)
    """
    from perturb.response.hysteresis import slow_sweep
    from perturb.steady.line import excitation_frequency

    rates = _rates(rate)
    for name, value in (("start", start), ("stop", stop)):
        if not (isinstance(value, int | float) and math.isfinite(value)):
            raise bad_value(name, value, "give a finite value", InvalidParameterError)
    if start == stop:
        raise bad_value("--sweep", f"{parameter}={start}:{stop}", "the ramp does not move: give "
                        "two different values START:STOP", InvalidParameterError)  # fmt: skip
    system = problem.system()
    system.frame.require_driven("problem", label_of(problem), "a ramp drives a driven problem")
    case = problem.case()
    if parameter not in case.map.user:
        raise bad_value("--sweep", parameter, f"not a parameter of {label_of(problem)}; give one "
                        f"of {', '.join(case.map.user)}", InvalidParameterError)  # fmt: skip
    ends = [case.at(**{parameter: float(v)}) for v in (start, stop)]  # checked by its rules
    symbols = [e.symbol_values for e in ends]
    epsilons = [float(e.epsilon) for e in ends]
    detuning = system.excitation.detuning
    moved = sorted(k for k in symbols[0] if symbols[0][k] != symbols[1][k])
    omegas = [excitation_frequency(system, s, e) for s, e in zip(symbols, epsilons, strict=True)]
    if omegas[0] == omegas[1]:
        raise bad_value("--sweep", parameter, "it does not move the drive frequency: the ramp "
                        "does not move; ramp the frequency (e.g. Omega)", InvalidParameterError)  # fmt: skip
    if epsilons[0] != epsilons[1] or any(k != str(detuning) for k in moved):
        raise bad_value("--sweep", parameter, "it moves more than the drive frequency "
                        f"({', '.join(moved) or 'eps'}); ramp the frequency (e.g. Omega)",
                        InvalidParameterError)  # fmt: skip
    slope = (omegas[1] - omegas[0]) / (stop - start)  # dOmega / d(parameter)
    mean = 4 * math.pi / (omegas[0] + omegas[1])  # a drive period in the middle of the ramp
    longest = abs(omegas[1] - omegas[0]) / (abs(slope) * rates[-1]) / mean
    if longest > RAMP_MAX_PERIODS:
        raise bad_value("rate", rates[-1], f"the ramp takes {longest:,.0f} drive periods at this "
                        f"rate, more than {RAMP_MAX_PERIODS:,}: give a faster rate or a shorter "
                        "ramp", InvalidParameterError)  # fmt: skip
    from perturb.cost import Cost, check_cost, response_cost

    legs = 2 if both_ways else 1
    total = legs * sum(abs(omegas[1] - omegas[0]) / (abs(slope) * r) / mean + SETTLE_PERIODS
                       for r in rates)  # fmt: skip
    work = Cost(f"{total:,.0f} drive periods of ramps", 0, total * DYNAMICS_PERIOD_SECONDS)
    check_cost(work + response_cost(FOLD_GRID, order, 0), yes)
    folds = _folds(problem, parameter, min(start, stop), max(start, stop), order)
    names = [c.name for c in system.coordinates]
    coordinate = coordinate or names[system.reference_index]
    if coordinate not in names:
        raise bad_value("coordinate", coordinate, f"give one of {names}", InvalidParameterError)
    legs = [(start, stop, omegas[0], omegas[1])]
    if both_ways:
        legs.append((stop, start, omegas[1], omegas[0]))
    runs = []
    values = symbols[0]
    from perturb.progress import notify

    done = 0
    notify("ramps", done, len(legs) * len(rates))
    for a, b, wa, wb in legs:
        for r in rates:
            run = slow_sweep(system, values, epsilons[0], wa, wb, abs(slope) * r, coordinate)
            done += 1
            notify("ramps", done, len(legs) * len(rates))
            along = a + (np.asarray(run.omega) - wa) / slope
            jump, size = _jump(along, np.asarray(run.envelope))
            fold = _passed(folds, jump, b > a)
            delay = (jump - fold) * (1 if b > a else -1)
            runs.append(RampRun("up" if b > a else "down", r, along, run.envelope, jump, size,
                                fold, delay))  # fmt: skip
    return Ramp(label_of(problem), parameter, float(start), float(stop), order, folds, runs,
                coordinate)  # fmt: skip


def _folds(problem, parameter: str, low: float, high: float, order: int) -> tuple:
    """The folds of the order-N response curve between ``low`` and ``high``."""
    from perturb.response.model import problem_response

    grid = np.linspace(low, high, FOLD_GRID)
    result = problem_response(problem, parameter, grid, order=order)
    return tuple(sorted(float(s.value) for s in result.response.special
                        if s.kind == "fold" and low <= s.value <= high))  # fmt: skip


def _jump(values: np.ndarray, envelope: np.ndarray) -> tuple[float, float]:
    """The first jump of the envelope and its size: the first run of windows of
    :data:`~perturb._defaults.RAMP_JUMP_PERIODS` drive periods over which the envelope changes
    by at least :data:`~perturb._defaults.RAMP_JUMP_SHARE` of its largest such change, one way;
    the jump is placed where the envelope crosses the middle of the largest change of that run.

    A window of periods (not a share of the ramp) shrinks in the parameter with the rate, so the
    jump it locates tends to where the branch ends as the rate goes to zero; the first run (not
    the largest change) is the departure, not the settling swings after it."""
    window = max(1, min(RAMP_JUMP_PERIODS, envelope.size - 1))
    change = envelope[window:] - envelope[:-window]
    size = np.abs(change)
    large = size >= RAMP_JUMP_SHARE * float(np.max(size))
    first = int(np.argmax(large))
    sign = np.sign(change[first])
    run = first
    while run + 1 < change.size and large[run + 1] and np.sign(change[run + 1]) == sign:
        run += 1
    k = first + int(np.argmax(size[first : run + 1]))
    before, after = envelope[k], envelope[k + window]
    middle = 0.5 * (before + after)
    crossing = k + int(
        np.argmax((envelope[k : k + window + 1] - middle) * np.sign(before - middle) <= 0)
    )
    return float(values[crossing]), float(after - before)


def _passed(folds: tuple, jump: float, up: bool) -> float:
    """The last fold passed before ``jump`` in the ramp's direction (NaN: none)."""
    behind = [f for f in folds if (f <= jump if up else f >= jump)]
    if not behind:
        return math.nan
    return max(behind) if up else min(behind)
