"""A transient: the true motion from one initial state beside the slow flow's prediction.

:func:`transient` integrates the original equations from the given state (at drive phase φ) for
P drive periods, sampled :data:`~perturb._defaults.TRANSIENT_SAMPLES` times a period, and reads
its slow amplitudes by the variation of constants of the first-order solution
(:meth:`perturb.dynamics.slowflow.SlowFlow.from_section` at the phase of each sample): the
envelope :math:`\\sqrt{a^2 + b^2}` and the phase :math:`\\arctan(b/a)` of each resonant
coordinate. Beside it, the slow flow of the chosen order integrated from the same amplitudes.
Which steady state the motion settles on and after how long is the basin classification of its
stroboscopic returns (:func:`perturb.dynamics.classify.classify`): the time at which it entered
the state's capture radius for good.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
from attrs import field, frozen

from perturb._defaults import (
    BASIN_CAPTURE_RETURNS,
    DEFAULT_RTOL,
    DYNAMICS_PERIOD_SECONDS,
    TRANSIENT_MAX_PERIODS,
    TRANSIENT_SAMPLES,
)
from perturb.errors import InvalidParameterError, bad_value

__all__ = ["Transient", "transient"]


@frozen
class Transient:
    """A transient of the true motion and of the slow flow.

    Attributes
    ----------
    problem : str
    start : dict
        The initial state, by name.
    phase : float
        The drive phase φ at t = 0.
    order : int
        The slow flow's order (1: averaging).
    times : ndarray, shape (K,)
    state : ndarray, shape (K, m)
        The true motion.
    names : tuple of str
        The state's components.
    coordinates : tuple of str
        The resonant coordinates (the envelopes' and phases').
    true_amplitudes, slow_amplitudes : ndarray, shape (K, 2r)
        (a₁, b₁, …) read from the true motion, and the slow flow's.
    settled : str
        The steady state the true motion settles on (its name), or an outcome's words.
    settle_time : float
        When it entered that state's capture radius for good (NaN: it did not settle).
    slow_settled : str
        The catalogued state nearest the slow flow's end, and how near.
    catalogue : Catalogue
    """

    problem: str
    start: dict
    phase: float
    order: int
    times: np.ndarray = field(eq=False)
    state: np.ndarray = field(eq=False)
    names: tuple = field(converter=tuple)
    coordinates: tuple = field(converter=tuple)
    true_amplitudes: np.ndarray = field(eq=False)
    slow_amplitudes: np.ndarray = field(eq=False)
    settled: str
    settle_time: float
    slow_settled: str
    catalogue: object = field(eq=False)

    @property
    def success(self) -> bool:
        """Whether the true motion settled on a steady state within the periods."""
        return math.isfinite(self.settle_time)

    def envelope(self, slow: bool = False) -> np.ndarray:
        """Shape (K, r): :math:`\\sqrt{a^2 + b^2}` of each resonant coordinate."""
        u = self.slow_amplitudes if slow else self.true_amplitudes
        return np.hypot(u[:, 0::2], u[:, 1::2])

    def phase_of(self, slow: bool = False) -> np.ndarray:
        """Shape (K, r): :math:`\\arctan2(b, a)` of each resonant coordinate (radians)."""
        u = self.slow_amplitudes if slow else self.true_amplitudes
        return np.arctan2(u[:, 1::2], u[:, 0::2])


def _periods(periods) -> int:
    if isinstance(periods, bool) or not isinstance(periods, int | np.integer) or periods < 1:
        raise bad_value("periods", periods, "give the drive periods to follow, a whole number "
                        ">= 1 (--periods 300)", InvalidParameterError)  # fmt: skip
    if periods > TRANSIENT_MAX_PERIODS:
        raise bad_value("periods", periods, f"give at most {TRANSIENT_MAX_PERIODS:,} drive "
                        "periods (each is sampled; a basin study follows more states for less)",
                        InvalidParameterError)  # fmt: skip
    return int(periods)


def transient(
    problem, start: Mapping, periods: int, *, order: int = 1, phase: float = 0.0,
    yes: bool = False,
) -> Transient:  # fmt: skip
    """The true motion of the driven ``problem`` from ``start`` beside its slow flow.

    Parameters
    ----------
    problem : problems.base.Problem or perturb.validation.Model
    start : mapping
        ``{component: value}`` of the initial state (unnamed components 0).
    periods : int
        Drive periods to follow (>= 1).
    order : int
        The slow flow's order (1: averaging; N: the displacement function to ε^N) and the
        series' order of the catalogue's seeds.
    phase : float
        The drive phase at t = 0 (radians).
    yes : bool
        Confirm a request past :func:`perturb.cost.check_cost`'s hour of work (a high order).

    Returns
    -------
    Transient

    Raises
    ------
    InvalidParameterError
        A component not in the state, a value not finite, periods below 1, a problem that is not
        driven.

    Examples
    --------
    From rest the bistable forced Duffing settles on its small response:

    >>> import perturb
    >>> from problems import get_problem
    >>> duffing = get_problem("forced-duffing").create(Omega=1.05)
    >>> result = perturb.transient(duffing, {"x": 0.0, "xdot": 0.0}, 200)
    >>> result.settled, result.success
    ('lower', True)
    """
    from perturb.dynamics.attractors import catalogue as make_catalogue
    from perturb.dynamics.classify import Outcome, classify
    from perturb.dynamics.ensemble import ensemble
    from perturb.dynamics.motion import motion_of
    from perturb.dynamics.slowflow import slow_flow_of
    from perturb.oracle import choose

    count = _periods(periods)
    if not (isinstance(phase, int | float) and math.isfinite(phase)):
        raise bad_value("phase", phase, "give a finite drive phase (radians)",
                        InvalidParameterError)  # fmt: skip
    from perturb.cost import Cost, check_cost, response_cost

    work = Cost(f"{count:,} drive periods", 0, count * DYNAMICS_PERIOD_SECONDS)
    check_cost(work + response_cost(1, order, 0), yes)
    motion = motion_of(problem)
    y0 = motion.state(start, "--from")
    flow = slow_flow_of(problem, order)
    from perturb.progress import stage

    with stage("transient: the steady states, shot"):
        chart = make_catalogue(problem, order, float(phase), motion)
    t = motion.drive_period * np.arange(count * TRANSIENT_SAMPLES + 1) / TRANSIENT_SAMPLES
    solver = choose(None, rtol=DEFAULT_RTOL, symbolic=True)
    with stage(f"transient: the true motion over {count:,} drive periods"):
        traj = solver.integrate(motion.rhs, (0.0, float(t[-1])), np.append(y0, phase), t_eval=t)
    traj.raise_for_status()
    y = np.asarray(traj.y, dtype=float)
    state, theta = y[: motion.m].T, y[motion.m]
    true_u = flow.from_section(state, theta)
    slow_u = flow.integrate(flow.from_section(y0, phase), t)
    if chart.status.success:
        result = classify(ensemble(motion, phase), chart, y0[None, :], count)
        code = int(result.codes[0])
        attractors = chart.with_found(result.found).attractors
        if code >= 0:
            settled = attractors[code].name
            entered = max(int(result.periods[0]) - BASIN_CAPTURE_RETURNS + 1, 0)
            settle_time = entered * motion.drive_period
        else:
            settled = next(o.value for o in Outcome if o.code == code)
            settle_time = math.nan
    else:
        settled, settle_time = chart.message, math.nan
    end = flow.to_section(slow_u[-1], phase + motion.omega * t[-1])
    slow_settled = _nearest(chart, end, phase + motion.omega * t[-1], motion)
    return Transient(
        problem=motion.label, start=dict(zip(motion.names, y0.tolist(), strict=True)),
        phase=float(phase), order=order, times=t, state=state, names=motion.names,
        coordinates=flow.coordinates, true_amplitudes=true_u, slow_amplitudes=slow_u,
        settled=settled, settle_time=settle_time, slow_settled=slow_settled, catalogue=chart,
    )  # fmt: skip


def _nearest(chart, end: np.ndarray, theta: float, motion) -> str:
    """The catalogued state whose orbit passes nearest the slow flow's end (the orbit is
    compared at the end's drive phase), with the distance."""
    if not np.all(np.isfinite(end)) or not chart.states:
        return "the slow flow did not stay finite"
    from perturb.dynamics.attractors import orbit_points

    best, gap = "", math.inf
    for state in chart.states:
        start = _back_to_zero(state, chart.phase, motion)
        points = orbit_points(motion, start, theta)
        d = float(np.min(np.linalg.norm(points - end[None, :], axis=1)))
        if d < gap:
            best, gap = state.name, d
    return f"{best} (the slow flow ends {gap:.3g} from its true orbit)"


def _back_to_zero(state, phase: float, motion) -> np.ndarray:
    """The state's orbit at θ = 0, from its point at the section's phase."""
    from perturb.oracle import choose

    back = (phase % (2 * math.pi)) / motion.omega
    if back == 0.0:
        return state.points[0]
    solver = choose(None, rtol=DEFAULT_RTOL, symbolic=True)
    traj = solver.integrate(
        motion.rhs, (0.0, motion.drive_period - back), np.append(state.points[0], phase)
    )
    traj.raise_for_status()
    return np.asarray(traj.y_final, dtype=float)[: motion.m]
