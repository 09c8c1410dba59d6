"""The rule for expensive requests: estimate the work before it starts, ask above a threshold.

One rule for every command that can be asked for more than it should do unasked (a sweep's grid,
a response's values and order, the points shot against the true motion, a scene's sections): the
request's :class:`Cost` is estimated from its size before any work, and

* above :data:`~perturb._defaults.SWEEP_MAX_POINTS` points it is refused (a mistake, not a plan);
* above :data:`~perturb._defaults.SWEEP_CONFIRM_POINTS` points, or
  :data:`~perturb._defaults.CONFIRM_SECONDS` of estimated work on one core, it needs
  confirmation (``--yes``; ``yes=True`` in Python): the one-line refusal says how much was asked
  and how to confirm.

The estimates are coarse on purpose (the figures per unit are measured on the shipped problems,
``benchmarks/hostile_cli.md``): they tell a typing slip (an extra zero in N, an order of 12) from
a plan, not the run time. A confirmed run shows its progress on a terminal.

Examples
--------
>>> cost = response_cost(values=61, order=1, shots=2)
>>> cost.seconds < CONFIRM_SECONDS
True
>>> check_cost(response_cost(values=200_000, order=3, shots=0), yes=False)
Traceback (most recent call last):
...
perturb.errors.InvalidParameterError: this asks for about 3 h of work (200,000 response values at order 3); check the request and confirm with --yes (yes=True in Python)
"""

from __future__ import annotations

import math

from attrs import frozen

from perturb._defaults import (
    CENSUS_MODE_GROWTH,
    CENSUS_SECONDS,
    CONFIRM_SECONDS,
    NOTICE_SECONDS,
    RESPONSE_ALWAYS_SHOT,
    RESPONSE_DERIVE_SECONDS,
    RESPONSE_ORDER_GROWTH,
    RESPONSE_SECONDS_PER_VALUE,
    RESPONSE_TYPICAL_BRANCHES,
    SHOT_SECONDS,
    SWEEP_CONFIRM_POINTS,
    SWEEP_MAX_POINTS,
    SWEEP_POINT_SECONDS,
    SWEEP_STATE_SHARE,
    SWEEP_VALIDATION_SECONDS,
    TRUE_POINT_SECONDS,
    WORK_PRECISION_PERIOD_SECONDS,
)
from perturb.errors import InvalidParameterError

__all__ = [
    "Cost",
    "census_seconds",
    "check_cost",
    "modes_of",
    "notice",
    "response_cost",
    "sweep_cost",
    "work_precision_cost",
]


@frozen
class Cost:
    """What a request asks for: its points and the estimated seconds of work on one core.

    Attributes
    ----------
    what : str
        The request in words, for the message (``"40,000 validated sweep points at order 2"``).
    points : int
        Points whose results are kept (a sweep's grid; 0 when not a sweep).
    seconds : float
        Estimated work on one core.
    """

    what: str
    points: int
    seconds: float

    def __add__(self, other: Cost) -> Cost:
        return Cost(f"{self.what} and {other.what}", self.points + other.points,
                    self.seconds + other.seconds)  # fmt: skip


def _growth(order: int) -> float:
    try:
        return RESPONSE_ORDER_GROWTH ** (max(int(order), 1) - 1)
    except OverflowError:  # an order of thousands: past any estimate, past any confirmation
        return math.inf


def modes_of(problem) -> int:
    """The modes (coordinates) of ``problem``'s system (a problem or a
    :class:`~perturb.validation.Model`), the size the census grows with."""
    return len(problem.system().coordinates)


def census_seconds(modes: int) -> float:
    """The certified first-order census of a driven problem of ``modes`` modes (its steady
    states at one point, or the exact folds along a line): :data:`CENSUS_SECONDS` for one mode,
    :data:`CENSUS_MODE_GROWTH` times more for each further mode."""
    try:
        return CENSUS_SECONDS * CENSUS_MODE_GROWTH ** (max(int(modes), 1) - 1)
    except OverflowError:  # thousands of modes: past any estimate
        return math.inf


def response_cost(values: int, order: int, shots: int, true: int = 0, modes: int = 1) -> Cost:
    """A frequency response over ``values`` values at ``order``, ``shots`` points of each
    branch shot against the true motion, true curves of at most ``true`` points, of a problem
    of ``modes`` modes (:func:`perturb.response.model.problem_response`)."""
    modes = max(int(modes), 1)
    seconds = RESPONSE_DERIVE_SECONDS * _growth(order) * modes + census_seconds(modes)
    seconds += values * RESPONSE_SECONDS_PER_VALUE * max(int(order), 1) * modes
    if shots:
        seconds += (shots + RESPONSE_ALWAYS_SHOT) * RESPONSE_TYPICAL_BRANCHES * SHOT_SECONDS
    seconds += true * RESPONSE_TYPICAL_BRANCHES * TRUE_POINT_SECONDS
    what = f"{values:,} response values at order {order}"
    if modes > 1:
        what += f" of {modes} modes"
    if shots:
        what += f", {shots} shots per branch"
    if true:
        what += f", true curves of {true} points"
    return Cost(what, 0, seconds)


def work_precision_cost(periods: float, orders: int, repeat: int) -> Cost:
    """A work-precision run (:func:`perturb.workprecision.work_precision`): the derivations to
    ``orders``, then one untimed and ``repeat`` timed runs of every method over ``periods``
    periods."""
    seconds = RESPONSE_DERIVE_SECONDS * _growth(orders)
    seconds += (int(repeat) + 1) * float(periods) * WORK_PRECISION_PERIOD_SECONDS
    what = f"{periods:g} periods, orders 1..{orders}, {repeat} timed runs a method"
    return Cost(what, 0, seconds)


def sweep_cost(points: int, order: int, validate: bool, times: int = 1) -> Cost:
    """A sweep of ``points`` points at ``order`` (each validated when ``validate``), the state
    recorded at ``times`` times of each: past :data:`SWEEP_MAX_POINTS` values of the state it is
    refused as a grid of that many points would be."""
    per = SWEEP_VALIDATION_SECONDS if validate else SWEEP_POINT_SECONDS
    seconds = RESPONSE_DERIVE_SECONDS * _growth(order) + points * per
    seconds += points * max(int(times) - 1, 0) * SWEEP_POINT_SECONDS
    kind = "validated sweep points" if validate else "sweep points"
    what = f"{points:,} {kind} at order {order}"
    if times > 1:
        what += f", the state at {times:,} times of each"
    return Cost(what, max(points, points * int(times) // SWEEP_STATE_SHARE), seconds)


def _duration(seconds: float) -> str:
    if not math.isfinite(seconds):
        return "more time than can be estimated"
    if seconds < 90:
        return f"{seconds:.0f} s"
    if seconds < 5400:
        return f"{seconds / 60:.0f} min"
    if seconds < 3 * 86400:
        return f"{seconds / 3600:.0f} h"
    return f"{seconds / 86400:,.0f} days"


def notice(cost: Cost) -> str | None:
    """One line telling how long a request that may start will take, when it is past
    :data:`~perturb._defaults.NOTICE_SECONDS` (None below): a long run is never silent, even
    where no progress bar is drawn."""
    if not cost.seconds > NOTICE_SECONDS:
        return None
    return f"this asks for about {_duration(cost.seconds)} of work ({cost.what})"


def check_cost(cost: Cost, yes: bool) -> None:
    """Raise unless ``cost`` may start: at most :data:`SWEEP_MAX_POINTS` points, and, unless
    ``yes``, at most :data:`SWEEP_CONFIRM_POINTS` points and :data:`CONFIRM_SECONDS` of work.

    Raises
    ------
    perturb.errors.InvalidParameterError
        One line: how much was asked, and how to confirm (or that it is past any confirmation).
    """
    weighed = ", counting the recorded times" if "times of each" in cost.what else ""
    if cost.points > SWEEP_MAX_POINTS:
        raise InvalidParameterError(
            f"the grid has {cost.points:,} points{weighed}, more than {SWEEP_MAX_POINTS:,}; give "
            "fewer points per axis" + (" or fewer times" if weighed else "")
        )
    if yes:
        return
    if cost.points > SWEEP_CONFIRM_POINTS:
        raise InvalidParameterError(
            f"the grid has {cost.points:,} points{weighed} (more than "
            f"{SWEEP_CONFIRM_POINTS:,}); check the axes and confirm with --yes (yes=True in "
            "Python)"
        )
    if not cost.seconds <= CONFIRM_SECONDS or not math.isfinite(cost.seconds):
        raise InvalidParameterError(
            f"this asks for {'about ' if math.isfinite(cost.seconds) else ''}"
            f"{_duration(cost.seconds)} of work ({cost.what}); check the "
            "request and confirm with --yes (yes=True in Python)"
        )
