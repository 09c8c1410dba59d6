"""The frequency response of a driven system: every branch, its stability, its folds.

For each value of the swept parameter (the detuning σ, the excitation frequency Ω, the forcing
level …) the response holds every branch of the **order-N** amplitude equations
(:func:`perturb.method.driven.amplitude_equations`, derived once with every parameter symbolic):
the first-order equations are solved for every real root with exact rational coefficients at the
window's ends (the count is proved), their exact folds found, and every branch is continued by
pseudo-arclength through its folds at order N (:mod:`perturb.steady.traced`,
:mod:`perturb.continuation`), then read at the grid values. Each point is judged stable or not by
its Floquet multipliers along the order-N orbit (:mod:`perturb.steady.floquet`), measured by
max ``|x|``, its first harmonic and its initial values (:mod:`perturb.steady.measures`).

The **folds** (saddle-node points, where a branch turns and the response jumps), branch points
and Neimark-Sacker points are located on the order-N curves, inside the sweep or just beside it.
The helpers below for the first-order folds (:func:`_folds`, :func:`continue_fold`) and the
grid-point tracing (:func:`trace_branches`) serve the responses built point by point.
"""

from __future__ import annotations

import math

from attrs import field, frozen

from perturb.steady.point import ResponsePoint, by_measure

__all__ = ["Fold", "FrequencyResponse", "ResponsePoint", "trace_branches"]


@frozen
class Fold:
    """A saddle-node point of the response: where two branches meet.

    ``value`` is the fold of the order-N response, located on its continued curve
    (``first_order``: the nearest fold of the first-order curve); ``note`` says when it could not
    be located to the tolerance; ``inside`` False for a fold just beside the sweep (in its
    window); ``peak`` max ``|x|`` of each coordinate there. ``uncertainty``: the series' own
    estimate of the fold's error in the swept parameter, the distance to the same fold one order
    lower (NaN where that order has none beside it: the series cannot tell where the fold is);
    within ±``uncertainty`` of ``value`` the branch set may change. ``true_value``: the true
    curve's fold it refines (``--true``; NaN without it, or none near).
    """

    value: float = field(converter=float)
    amplitudes: dict
    norms: dict
    first_order: float = field(default=math.nan, converter=float)
    note: str = ""
    inside: bool = True
    peak: dict = field(factory=dict)
    uncertainty: float = field(default=math.nan, converter=float)
    true_value: float = field(default=math.nan, converter=float)
    first_harmonic: dict = field(factory=dict)

    def amplitude(self, coordinate: str | None = None, measure: str = "initial") -> float:
        """``coordinate``'s amplitude by ``measure`` (``peak``, ``first-harmonic`` or
        ``initial``), as a response point's."""
        return by_measure(self, coordinate, measure)

    def band_note(self, parameter: str) -> str:
        """What a point within the fold's uncertainty says of it."""
        if not math.isfinite(self.uncertainty):
            return (
                f"the series cannot tell where the fold at {parameter} = {self.value:.8g} is (one "
                "order lower has no fold beside it): the branch set may change near it"
            )
        return (
            f"the branch set may change within ±{self.uncertainty:.2g} of the fold at "
            f"{parameter} = {self.value:.8g}"
        )

    def holds(self, value: float) -> bool:
        """Whether ``value`` lies within the fold's uncertainty band (an unknown one is not
        drawn as a band: it is said, by :meth:`band_note`, of the fold itself)."""
        width = self.uncertainty if math.isfinite(self.uncertainty) else 0.0
        return abs(float(value) - self.value) <= width


@frozen
class FrequencyResponse:
    """Every steady-state branch over a sweep (see the module docstring).

    Attributes
    ----------
    system : str
    parameter : str
        The swept parameter's name.
    order : int
    epsilon : float
    values : dict
        The other parameters' values.
    grid : tuple of float
        The swept values.
    points : tuple of ResponsePoint
        Every root at every grid value, in grid order.
    folds : tuple of Fold
        Inside the swept range, sorted.
    failures : tuple of str
        Grid values where the roots could not be enumerated, and curves that could not be
        followed, with the reason (never dropped silently).
    coordinates : tuple of str
    special : tuple
        Every located special point of the order-N curves (folds, branch points,
        Neimark-Sacker and period-doubling points), inside the sweep or just beside it
        (:class:`perturb.steady.continued.SpecialResponse`).
    curves : tuple
        The continued order-N curves, densely (:class:`perturb.steady.continued.ResponseCurve`).
    measure : str
        The amplitude measure the response is drawn and its branches named by.
    """

    system: str
    parameter: str
    order: int
    epsilon: float = field(converter=float)
    values: dict
    grid: tuple = field(converter=tuple)
    points: tuple = field(converter=tuple)
    folds: tuple = field(converter=tuple)
    failures: tuple = field(converter=tuple, factory=tuple)
    coordinates: tuple = field(converter=tuple, factory=tuple)
    special: tuple = field(converter=tuple, factory=tuple)
    curves: tuple = field(converter=tuple, factory=tuple, eq=False)
    measure: str = "initial"

    def at(self, value: float) -> tuple[ResponsePoint, ...]:
        """The responses at the grid value nearest ``value``."""
        nearest = min(self.grid, key=lambda g: abs(g - value))
        return tuple(p for p in self.points if p.value == nearest)

    def branches(self, coordinate: str | None = None) -> list[list[ResponsePoint]]:
        """The points traced into continuous branches (:func:`trace_branches`)."""
        return trace_branches(self.points, self.grid, coordinate)


def trace_branches(points, grid, coordinate: str | None = None) -> list[list[ResponsePoint]]:
    """Join the roots of neighbouring grid values into continuous branches.

    Between two folds the roots keep their order in amplitude (two roots of the response
    equations meet only at a fold), so equal counts are matched rank by rank. Where the count
    changes, a fold was crossed: the roots that appear (or disappear) are chosen among the
    adjacent pairs by the least total distance to the others' predicted amplitudes (linear
    extrapolation of each branch). A plotting aid: the points themselves are exact.
    """
    from itertools import combinations

    by_value: dict[float, list] = {}
    for p in points:
        by_value.setdefault(p.value, []).append(p)
    branches: list[list] = []
    open_: list[list] = []

    def predicted(branch, value):
        if len(branch) < 2:
            return branch[-1].norm(coordinate)
        (a, b) = branch[-2], branch[-1]
        if b.value == a.value:
            return b.norm(coordinate)
        slope = (b.norm(coordinate) - a.norm(coordinate)) / (b.value - a.value)
        return b.norm(coordinate) + slope * (value - b.value)

    for value in sorted(by_value):
        here = sorted(by_value[value], key=lambda p: p.norm(coordinate))
        guesses = [predicted(b, value) for b in open_]
        n, m = len(open_), len(here)
        best, best_cost = None, math.inf
        if m >= n:  # choose which of the current roots continue the open branches
            for kept in combinations(range(m), n):
                cost = sum(
                    abs(here[j].norm(coordinate) - g) for j, g in zip(kept, guesses, strict=True)
                )
                if cost < best_cost:
                    best, best_cost = [(i, j) for i, j in enumerate(kept)], cost
        else:  # choose which open branches end here
            for kept in combinations(range(n), m):
                cost = sum(abs(here[j].norm(coordinate) - guesses[i]) for j, i in enumerate(kept))
                if cost < best_cost:
                    best, best_cost = [(i, j) for j, i in enumerate(kept)], cost
        continued = dict(best or [])
        next_open = []
        taken = set(continued.values())
        for i, j in sorted(continued.items(), key=lambda item: item[1]):
            open_[i].append(here[j])
        for j, p in enumerate(here):
            if j in taken:
                continue
            branch = [p]
            branches.append(branch)
        for j, p in enumerate(here):
            owner = next((open_[i] for i, jj in continued.items() if jj == j), None)
            if owner is None:
                owner = next(b for b in branches if b[-1] is p)
            next_open.append(owner)
        open_ = next_open
    return branches
